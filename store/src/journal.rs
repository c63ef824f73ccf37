//! The checkpoint journal: `results/journal.csv`, one `runs.csv` row appended (and flushed) as
//! each run finishes, its trace written beside it at once. A run that is interrupted (SIGINT,
//! SIGKILL, a pre-empted job) loses only the runs that were in flight: the next start folds the
//! journal into `runs.csv` (atomically) and skips the runs it holds. Only rows of the current
//! code revision are folded: a row of another revision (an old journal, or one copied in) is
//! not, and the start says so run by run; those runs are run again. A normal end merges
//! everything into `runs.csv` and removes the journal. A line cut short by a kill (the last
//! one) is dropped; any other bad line, a name that cannot name a file, or a run listed twice
//! is an error naming the file and the line (a journal this program wrote has each run once).
//!
//! **The seal.** The integrity manifest (crate::integrity) is saved only at the end of a step,
//! so a killed run never records the traces it checkpointed. The journal seals them itself:
//! `results/journal-traces.sha256` gets the line `<sha256>  <trace path>` (the format of
//! `sha256sum`) once the trace is written and before its row is appended. Folding a row
//! records its trace in the manifest only if the trace still hashes to its seal; a row whose
//! trace is missing, changed since, or was never sealed (a journal of an older version) is not
//! folded, is said, and is run again. So a resumed directory's manifest covers every row and
//! trace it holds, and a resumed shard merges.
use crate::error::{IoAction, IoError};
use crate::owned_dir::PathError;
use crate::results_dir::{ResultsDir, JOURNAL};
use crate::tracked_dir::TrackedError;
use records::table::{self, TableError};
use records::RowsError;
use records::TracePoint;
use records::{check_run_names, RunRow};
use spec::RunKey;
use std::collections::HashMap;
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The seal of the journal's traces (see the module doc).
pub const SEAL: &str = "journal-traces.sha256";

/// The journal of the results directory `dir`.
pub fn path(dir: &Path) -> PathBuf {
    dir.join(JOURNAL)
}

/// The seal of the journal of `dir`.
pub fn seal_path(dir: &Path) -> PathBuf {
    dir.join(SEAL)
}

/// Why the journal of an interrupted run cannot be opened, written or read back.
#[derive(Debug, thiserror::Error)]
pub enum JournalError {
    /// A file operation on the journal or its seal failed.
    #[error(transparent)]
    Io(#[from] IoError),
    /// The journal's path under the results directory was refused.
    #[error(transparent)]
    Path(#[from] PathError),
    /// A trace could not be written into the results directory.
    #[error(transparent)]
    Results(#[from] crate::results_dir::ResultsError),
    /// The existing journal's header is not this run's.
    #[error("{}: its header is not that of this run (more joints, or another version); fold it in by running the same selection again, or remove it", path.display())]
    Header {
        /// The journal.
        path: PathBuf,
    },
    /// A row could not be appended to the journal.
    #[error("{}: {source}", path.display())]
    Csv {
        /// The journal.
        path: PathBuf,
        /// The CSV error.
        source: csv::Error,
    },
    /// A thread panicked while holding the journal's lock.
    #[error("journal lock poisoned")]
    Poisoned,
    /// The journal does not read as a table of run rows.
    #[error(transparent)]
    Table(#[from] TableError),
    /// The journal's rows are not usable (a name that cannot name a file, a run listed twice).
    #[error("{}: {error}; this is not a journal this program wrote: remove it (its runs are run again)", path.display())]
    Rows {
        /// The journal.
        path: PathBuf,
        /// Which row and why.
        error: RowsError,
    },
    /// A recovered trace could not be recorded in the results directory's manifest.
    #[error(transparent)]
    Tracked(#[from] TrackedError),
    /// A line of the traces' seal is not `<sha256>  <trace path>`.
    #[error("{}: line {line}: not `<sha256>  <trace path>`, so not a seal this program wrote: remove it and the journal beside it (their runs are run again)", path.display())]
    Seal {
        /// The seal file.
        path: PathBuf,
        /// The line, from 1.
        line: usize,
    },
}

/// An open journal, shared by the worker threads.
pub struct Journal<'a> {
    results: &'a ResultsDir,
    /// Per-joint columns of its header (the most joints among the runs it will hold).
    joints: usize,
    /// The journal and its seal, appended together.
    files: Mutex<(File, File)>,
}

/// Opens `path` for appending, creating it.
fn append(path: &Path) -> Result<File, IoError> {
    OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
        .map_err(IoError::at(path, IoAction::Open))
}

impl<'a> Journal<'a> {
    /// Opens (creating, with the header) the journal of `results` for appending rows of arms
    /// with at most `joints` joints. An existing journal keeps its header: a run resumed with
    /// arms of more joints than it was started with starts a new journal.
    pub fn open(results: &'a ResultsDir, joints: usize) -> Result<Self, JournalError> {
        let path = results.tracked().resolve(Path::new(JOURNAL))?;
        let seal = append(&results.tracked().resolve(Path::new(SEAL))?)?;
        let mut file = append(&path)?;
        let empty = file.metadata().map(|m| m.len() == 0).unwrap_or(true);
        let header = table::header::<RunRow>(joints);
        if empty {
            writeln!(file, "{}", header.join(",")).map_err(IoError::at(&path, IoAction::Write))?;
        } else {
            let text =
                crate::owned_dir::read_text(&path).map_err(IoError::at(&path, IoAction::Read))?;
            if text.lines().next() != Some(header.join(",").as_str()) {
                return Err(JournalError::Header { path });
            }
        }
        Ok(Self {
            results,
            joints,
            files: Mutex::new((file, seal)),
        })
    }

    /// Checkpoints one finished run: its trace, then its seal, then its row (one write each,
    /// flushed); a run whose trace is not kept (`trace` `None`: its sweep's `traces` chose so)
    /// its row alone.
    pub fn record(&self, row: &RunRow, trace: Option<&[TracePoint]>) -> Result<(), JournalError> {
        let seal_line = match trace {
            Some(trace) => {
                let sealed = self.results.write_trace(&row.key(), trace)?;
                format!(
                    "{}  {}\n",
                    sealed.sha256,
                    trace_name(&ResultsDir::trace_rel(&row.key()))
                )
            }
            None => String::new(),
        };
        let journal = path(self.results.path());
        let csv_error = |source| JournalError::Csv {
            path: journal.clone(),
            source,
        };
        let mut w = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(Vec::new());
        w.write_record(table::record(row, self.joints).map_err(csv_error)?)
            .map_err(csv_error)?;
        let line = w
            .into_inner()
            .map_err(|e| csv_error(csv::Error::from(e.into_error())))?;
        let mut files = self.files.lock().map_err(|_| JournalError::Poisoned)?;
        let (file, seal) = &mut *files;
        if !seal_line.is_empty() {
            seal.write_all(seal_line.as_bytes())
                .and_then(|()| seal.flush())
                .map_err(IoError::at(seal_path(self.results.path()), IoAction::Write))?;
            crate::kill_point::passed();
        }
        file.write_all(&line)
            .and_then(|()| file.flush())
            .map_err(IoError::at(journal, IoAction::Write))?;
        crate::kill_point::passed();
        Ok(())
    }
}

/// A trace's path as the seal names it: relative, with `/`.
fn trace_name(rel: &Path) -> String {
    rel.to_string_lossy().replace('\\', "/")
}

/// What an interrupted run's journal holds, by run key (its rows stay in the journal, read
/// back one at a time by [`Recovered::rows`]: O(bytes of a key) per run in memory).
#[derive(Debug, Default)]
pub struct Recovered {
    /// Rows of the current code revision whose traces match their seal (now recorded in the
    /// results directory's manifest), in key order: folded into `runs.csv`, not run again.
    pub current: Vec<Entry>,
    /// Rows of another revision (with that revision): not folded (run again).
    pub other_revision: Vec<(RunKey, String)>,
    /// Rows of the current revision whose trace is missing, changed since it was sealed, or
    /// was never sealed: not folded (run again).
    pub unsealed: Vec<RunKey>,
    /// The per-joint columns of the journal's header.
    pub joints: usize,
}

/// A row of the journal: its run key and where it starts.
#[derive(Debug)]
pub struct Entry {
    /// The run key.
    pub key: RunKey,
    /// The row's start in the journal.
    at: csv::Position,
}

impl Recovered {
    /// The rows of [`Recovered::current`] read back from the journal of `dir`, in key order,
    /// one at a time (the journal is read at each row's start).
    pub fn rows<'a>(
        &'a self,
        dir: &Path,
    ) -> Result<impl Iterator<Item = Result<RunRow, JournalError>> + 'a, JournalError> {
        let journal = path(dir);
        let mut rows = open_rows(&journal)?;
        let mut entries = self.current.iter();
        Ok(std::iter::from_fn(move || {
            let entry = entries.next()?;
            let table_error = |e: TableError| TableError {
                path: Some(journal.clone()),
                ..e
            };
            let read = rows
                .seek(entry.at.clone())
                .map_err(table_error)
                .and_then(|()| match rows.next() {
                    Some(row) => row.map_err(table_error),
                    None => Err(table_error(TableError {
                        path: None,
                        line: entry.at.line(),
                        what: "the row read before is gone".to_string(),
                    })),
                });
            Some(read.map_err(JournalError::from))
        }))
    }
}

/// The journal at `journal` opened to be read row by row.
fn open_rows(journal: &Path) -> Result<table::Rows<RunRow, inputs::Capped>, JournalError> {
    let file =
        crate::owned_dir::open_file(journal).map_err(IoError::at(journal, IoAction::Read))?;
    table::rows(file).map_err(|e| {
        TableError {
            path: Some(journal.to_path_buf()),
            ..e
        }
        .into()
    })
}

/// The rows of an interrupted run's journal in `results` (none without one), split by code
/// revision (`git_rev`: the current one) and by whether their traces match the seal; the
/// traces of [`Recovered::current`] are recorded in the manifest of `results` (saved by the
/// caller). A last line cut short by a kill is dropped, in the journal and in the seal. The
/// journal is read row by row: what is kept per run is its key and its place. A row whose run
/// keeps no trace by choice (`traced` false for its key) needs no seal.
pub fn recover(
    results: &ResultsDir,
    git_rev: &str,
    traced: impl Fn(&RunKey) -> bool,
) -> Result<Recovered, JournalError> {
    let journal = path(results.path());
    if !journal.exists() {
        return Ok(Recovered::default());
    }
    let mut rows = open_rows(&journal)?;
    let complete = complete_length(&journal)?;
    let seals = read_seal(results.path())?;
    let mut out = Recovered {
        joints: rows.joints(),
        ..Recovered::default()
    };
    let mut seen = HashMap::new();
    let mut line = 2;
    loop {
        let at = rows.position();
        if at.byte() >= complete {
            break;
        }
        let Some(row) = rows.next() else {
            break;
        };
        let row = row.map_err(|e| TableError {
            path: Some(journal.clone()),
            ..e
        })?;
        let rows_error = |error| JournalError::Rows {
            path: journal.clone(),
            error,
        };
        check_run_names(&row, line).map_err(rows_error)?;
        let key = row.key();
        if let Some(first) = seen.insert(key.clone(), line) {
            return Err(rows_error(RowsError::Twice {
                line,
                key: key.to_string(),
                first,
            }));
        }
        line += 1;
        if row.git_rev != git_rev {
            out.other_revision.push((key, row.git_rev));
            continue;
        }
        let rel = ResultsDir::trace_rel(&key);
        let sealed = match seals.get(&trace_name(&rel)) {
            _ if !traced(&key) => true,
            Some(sha256) => results.tracked().adopt_sealed(&rel, sha256)?,
            None => false,
        };
        if sealed {
            out.current.push(Entry { key, at });
        } else {
            out.unsealed.push(key);
        }
    }
    out.current.sort_unstable_by(|a, b| a.key.cmp(&b.key));
    Ok(out)
}

/// The length of the journal at `journal` up to its last newline (a kill can cut the last
/// line short), found by reading its end backwards.
fn complete_length(journal: &Path) -> Result<u64, JournalError> {
    use std::io::{Read, Seek, SeekFrom};
    let io = |e| IoError::at(journal, IoAction::Read)(e);
    let mut file = crate::owned_dir::open_file(journal).map_err(&io)?;
    let mut end = file.seek(SeekFrom::End(0)).map_err(&io)?;
    let mut block = vec![0u8; 4096];
    while end > 0 {
        let start = end.saturating_sub(block.len() as u64);
        let len = (end - start) as usize;
        file.seek(SeekFrom::Start(start)).map_err(&io)?;
        file.read_exact(&mut block[..len]).map_err(&io)?;
        if let Some(i) = block[..len].iter().rposition(|&b| b == b'\n') {
            return Ok(start + i as u64 + 1);
        }
        end = start;
    }
    Ok(0)
}

/// `text` up to its last newline: a kill can cut the last line short.
fn complete_lines(text: &str) -> &str {
    match text.rfind('\n') {
        Some(end) => &text[..=end],
        None => "",
    }
}

/// The seal of `dir`'s journal: trace path -> SHA-256 (none without a seal; a later line for
/// the same trace wins, as the later write did).
fn read_seal(dir: &Path) -> Result<HashMap<String, String>, JournalError> {
    let path = seal_path(dir);
    let text = match crate::owned_dir::read_text(&path) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(HashMap::new()),
        Err(e) => return Err(IoError::at(&path, IoAction::Read)(e).into()),
    };
    let mut seals = HashMap::new();
    for (i, line) in complete_lines(&text).lines().enumerate() {
        let parsed = line.split_once("  ").filter(|(sha, name)| {
            sha.len() == 64
                && sha
                    .bytes()
                    .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
                && !name.is_empty()
        });
        let Some((sha, name)) = parsed else {
            return Err(JournalError::Seal { path, line: i + 1 });
        };
        seals.insert(name.to_string(), sha.to_string());
    }
    Ok(seals)
}

/// Removes the journal of `dir` and its seal (after its rows are in runs.csv).
pub fn remove(dir: &Path) -> Result<(), IoError> {
    for file in [path(dir), seal_path(dir)] {
        match std::fs::remove_file(&file) {
            Ok(()) => crate::kill_point::passed(),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(IoError::at(file, IoAction::Remove)(e)),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrity::Fingerprint;
    use crate::tracked_dir::Edits;

    fn point(t: f64) -> TracePoint {
        TracePoint {
            t,
            theta: vec![0.1, 0.2],
            thetadot: vec![0.0, t],
            thetaddot: None,
            torque: None,
            desired: [0.0, 0.0, t],
            actual: [0.0, 0.0, t],
            score_dx: None,
            network_error: None,
        }
    }

    /// A run that keeps no trace by choice is checkpointed as its row alone (no trace, no
    /// seal line) and folded without one; the same row where a trace is asked for is not.
    #[test]
    fn a_run_without_a_trace_by_choice_is_folded_without_one() {
        let dir = inputs::Scratch::unmade("untraced");
        let key = spec::RunKey::from_ids("exp", "a", "exact").unwrap();
        let row = RunRow {
            git_rev: "r1".into(),
            ..RunRow::blank(&key, spec::SolverKind::Exact)
        };
        {
            let (results, _) = ResultsDir::open(&dir, "r1", Edits::Refuse).unwrap();
            Journal::open(&results, 2)
                .unwrap()
                .record(&row, None)
                .unwrap();
        }
        assert!(!dir.join(ResultsDir::trace_rel(&key)).exists());
        assert_eq!(std::fs::read_to_string(seal_path(&dir)).unwrap(), "");
        let (results, _) = ResultsDir::open(&dir, "r1", Edits::Refuse).unwrap();
        let asked = recover(&results, "r1", |_| true).unwrap();
        assert!(asked.current.is_empty() && asked.unsealed == [key.clone()]);
        let chosen = recover(&results, "r1", |_| false).unwrap();
        assert!(chosen.unsealed.is_empty());
        assert_eq!(chosen.current.len(), 1);
        assert_eq!(chosen.current[0].key, key);
        assert!(results.tracked().listed("traces/").unwrap().is_empty());
    }

    /// A run killed after checkpointing four runs saved no manifest; the seal names each trace
    /// with its hash (as `sha256sum` writes), and only the rows whose trace still matches
    /// their seal are folded, their traces then recorded in the manifest.
    #[test]
    fn only_runs_whose_trace_matches_its_seal_are_folded() {
        let dir = inputs::Scratch::unmade("seal");
        let rows: Vec<RunRow> = ["a", "b", "c", "d", "e"]
            .iter()
            .map(|v| RunRow {
                git_rev: if *v == "e" { "r0" } else { "r1" }.into(),
                ..RunRow::blank(
                    &spec::RunKey::from_ids("exp", v, "exact").unwrap(),
                    spec::SolverKind::Exact,
                )
            })
            .collect();
        {
            let (results, _) = ResultsDir::open(&dir, "r1", Edits::Refuse).unwrap();
            let journal = Journal::open(&results, 2).unwrap();
            for r in &rows {
                journal.record(r, Some(&[point(0.0), point(1.0)])).unwrap();
            }
        } // killed: nothing saved
        assert!(!dir.join(crate::integrity::FILE).exists());
        let seal = std::fs::read_to_string(seal_path(&dir)).unwrap();
        let trace = |v: &str| format!("traces/exp/{v}__exact.csv");
        for (line, r) in seal.lines().zip(&rows) {
            let bytes = std::fs::read(dir.join(trace(&r.variant))).unwrap();
            let want = format!("{}  {}", Fingerprint::of(&bytes).sha256, trace(&r.variant));
            assert_eq!(line, want);
        }
        // b's trace edited, c's removed, d's seal line the last one, cut short by the kill.
        std::fs::write(dir.join(trace("b")), "t\n").unwrap();
        std::fs::remove_file(dir.join(trace("c"))).unwrap();
        let lines: Vec<&str> = seal.lines().collect();
        let e_line = lines[4];
        let reordered = format!(
            "{}\n{}\n{}\n{e_line}\n{}",
            lines[0],
            lines[1],
            lines[2],
            &lines[3][..20]
        );
        std::fs::write(seal_path(&dir), reordered).unwrap();

        let (results, _) = ResultsDir::open(&dir, "r1", Edits::Refuse).unwrap();
        let got = recover(&results, "r1", |_| true).unwrap();
        let variants = |keys: Vec<&RunKey>| {
            keys.iter()
                .map(|k| k.variant.to_string())
                .collect::<Vec<_>>()
        };
        assert_eq!(
            variants(got.current.iter().map(|e| &e.key).collect()),
            ["a"]
        );
        assert_eq!(variants(got.unsealed.iter().collect()), ["b", "c", "d"]);
        assert_eq!(
            variants(got.other_revision.iter().map(|(k, _)| k).collect()),
            ["e"]
        );
        assert_eq!(got.other_revision[0].1, "r0");
        // The folded rows read back from the journal, whole.
        let back: Vec<RunRow> = got.rows(&dir).unwrap().collect::<Result<_, _>>().unwrap();
        assert_eq!(back.len(), 1);
        assert_eq!(back[0].key(), rows[0].key());
        assert_eq!(back[0].git_rev, "r1");
        results.save().unwrap();
        let listed = results.tracked().listed("traces/").unwrap();
        assert_eq!(listed, [trace("a")]);

        // A whole line that is not `<sha256>  <path>` is not a seal this program wrote.
        std::fs::write(seal_path(&dir), format!("{e_line}\nnot a seal\n")).unwrap();
        let e = recover(&results, "r1", |_| true).unwrap_err();
        assert!(matches!(e, JournalError::Seal { line: 2, .. }), "{e}");
        assert!(e.to_string().contains(SEAL), "{e}");
        remove(&dir).unwrap();
        assert!(!path(&dir).exists() && !seal_path(&dir).exists());
    }

    /// The fold's rows come back from the journal in key order, whatever order the runs
    /// finished in, and one at a time from the file (nothing of a row is held but its key and
    /// place): a journal cut after the first row is read makes the next read fail.
    #[test]
    fn folded_rows_are_read_back_in_key_order_one_at_a_time() {
        let dir = inputs::Scratch::unmade("fold");
        let (results, _) = ResultsDir::open(&dir, "r1", Edits::Refuse).unwrap();
        let journal = Journal::open(&results, 2).unwrap();
        for v in ["m", "c", "x", "a"] {
            let row = RunRow {
                git_rev: "r1".into(),
                drift: vec![0.5, -0.25],
                ..RunRow::blank(
                    &spec::RunKey::from_ids("exp", v, "exact").unwrap(),
                    spec::SolverKind::Exact,
                )
            };
            journal.record(&row, Some(&[point(0.0)])).unwrap();
        }
        drop(journal);
        let got = recover(&results, "r1", |_| true).unwrap();
        assert_eq!(got.joints, 2);
        let mut rows = got.rows(&dir).unwrap();
        let first = rows.next().unwrap().unwrap();
        assert_eq!(
            (first.variant.as_str(), first.drift.as_slice()),
            ("a", &[0.5, -0.25][..])
        );
        let all: Vec<String> = got
            .rows(&dir)
            .unwrap()
            .map(|r| r.unwrap().variant)
            .collect();
        assert_eq!(all, ["a", "c", "m", "x"]);
        let text = std::fs::read_to_string(path(&dir)).unwrap();
        let header = text.lines().next().unwrap();
        std::fs::write(path(&dir), format!("{header}\n")).unwrap();
        assert!(
            rows.next().unwrap().is_err(),
            "the next row is read from the file"
        );
    }
}
