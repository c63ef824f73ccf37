//! `results/` (or a shard directory) as one type: every path under it, the one-writer lock,
//! the integrity manifest, the journal's place, the traces and pruning.
//!
//! Layout:
//!
//! ```text
//! results/
//!   .lock                     advisory lock: one writer at a time
//!   manifest.toml             what the program wrote (crate::integrity), saved last
//!   runs.csv                  one row per run (records::runs)
//!   runs.part-<n>.csv         a shard's rows appended since runs.csv was last written
//!                             (ResultsDir::append_part), merged into it at its end
//!   journal.csv               the checkpoint of an interrupted run (crate::journal)
//!   journal-traces.sha256     the seal of the journal's traces (crate::journal)
//!   traces/<experiment>/<variant>__<solver>.csv
//!                             one run's trace (records::trace)
//!   *.csv                     the explanation layer's and other tables
//! ```
//!
//! Opening ([`ResultsDir::open`]) takes the lock, refuses tables that differ from the
//! manifest (a truncated or hand-edited `runs.csv`), and removes only the temporary files of
//! the program's own interrupted writes. Every id read from a row is checked as it is read
//! (its type, [`spec::ids`], holds only slugs) and every path it leads to is resolved
//! inside the directory ([`OwnedDir::resolve`]), and a
//! file is deleted only if the manifest proves the program wrote it
//! ([`TrackedDir::remove`]).

use crate::integrity::Fingerprint;
use crate::owned_dir::{OwnedDir, PathError};
use crate::runs::read_runs;
use crate::tracked_dir::{Edits, Removal, TrackedDir, TrackedError};
use records::{runs_csv, RunRow};
use records::{trace_csv, TracePoint};
use spec::RunKey;
use std::path::{Path, PathBuf};

/// The results directory's name under the project root.
pub const DIR: &str = "results";
/// `runs.csv`.
pub const RUNS: &str = "runs.csv";
/// `traces/`.
pub const TRACES: &str = "traces";
/// The start of the name of a part of `runs.csv` ([`ResultsDir::append_part`]).
const PART_PREFIX: &str = "runs.part-";

/// The name of the `n`-th part of `runs.csv` (from 1): `runs.part-<n>.csv`.
fn part_name(n: usize) -> String {
    format!("{PART_PREFIX}{n}.csv")
}

/// The number of a part's name ([`part_name`]), `None` for any other name.
fn part_number(name: &str) -> Option<usize> {
    let n = name.strip_prefix(PART_PREFIX)?.strip_suffix(".csv")?;
    (!n.starts_with('0') && n.bytes().all(|b| b.is_ascii_digit()))
        .then(|| n.parse().ok())
        .flatten()
}

/// The checkpoint journal of an interrupted run ([`crate::journal`]).
pub const JOURNAL: &str = "journal.csv";
/// The explanation layer's tolerance ladder.
pub const LADDER: &str = "ladder.csv";
/// The explanation layer's drift attribution.
pub const ATTRIBUTION: &str = "attribution.csv";
/// The setup inference's best fits.
pub const INFERENCE: &str = "inference.csv";
/// The setup inference's per-entry table.
pub const INFERENCE_ENTRIES: &str = "inference-entries.csv";
/// The control experiments' runs ([`records::control::ControlRow`]).
pub const CONTROL: &str = "control.csv";
/// The noise floor of the control experiments' runs ([`records::control::NoiseRow`]).
pub const CONTROL_NOISE: &str = "control-noise.csv";
/// The networks' Euler stability limits ([`records::control::StabilityRow`]).
pub const CONTROL_STABILITY: &str = "control-stability.csv";
/// zhong2021's efficiency claim per task ([`records::control::ClaimRow`]).
pub const CONTROL_CLAIM: &str = "control-claim.csv";
/// The drift after every cycle of the many-cycles runs ([`records::control::CycleRow`]).
pub const CYCLES: &str = "cycles.csv";
/// The many-cycles runs' trends ([`records::control::TrendRow`]).
pub const CYCLES_TREND: &str = "cycles-trend.csv";
/// The leaderboard.
pub const LEADERBOARD: &str = "leaderboard.csv";
/// The leaderboard with the Python package's entry (written by `python/examples/leaderboard.py`).
pub const LEADERBOARD_PYTHON: &str = "leaderboard-python.csv";
/// The cost of a Python call (written by `python/bench/call_cost.py`).
pub const PYTHON_CALL_COST: &str = "python-call-cost.csv";
/// The advisory lock's file name.
pub const LOCK: &str = ".lock";

/// Pruning removes at most this percentage of the stored runs unless asked to (`--prune`): an
/// empty or mistaken experiments directory must not wipe the results.
pub const PRUNE_LIMIT_PERCENT: usize = 25;

/// A problem with the results directory.
#[derive(Debug, thiserror::Error)]
pub enum ResultsError {
    /// The directory's manifest or a tracked write or removal failed.
    #[error(transparent)]
    Tracked(#[from] TrackedError),
    /// A path under the directory was refused.
    #[error(transparent)]
    Path(#[from] PathError),
    /// Another process holds the directory's lock.
    #[error("another reproduce is writing to {dir} (lock {lock}): wait for it to finish, or give this run another --results-dir")]
    Locked {
        /// The results directory.
        dir: PathBuf,
        /// The lock file.
        lock: PathBuf,
    },
    /// The lock file could not be opened or locked.
    #[error("{path}: cannot lock: {source}")]
    Lock {
        /// The lock file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// `runs.csv` could not be read.
    #[error(transparent)]
    Read(#[from] crate::error::RunsError),
    /// `runs.csv` or a trace could not be serialised.
    #[error("{path}: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The CSV error.
        source: csv::Error,
    },
    /// Another file operation failed.
    #[error(transparent)]
    Io(#[from] crate::error::IoError),
    /// A table written before run ids could not be brought up to date.
    #[error("{}: {source}", path.display())]
    Migrate {
        /// The table.
        path: PathBuf,
        /// Why.
        source: crate::migrate::MigrateError,
    },
    /// Pruning would remove more than [`PRUNE_LIMIT_PERCENT`] of the stored runs without
    /// `--prune`.
    #[error("{count} of the {stored} stored runs in {runs} are described by no experiment file of {experiments} ({percent} %, more than the {PRUNE_LIMIT_PERCENT} % pruned without asking); nothing was run or written. If the experiment files are right and those runs should go, run again with --prune; otherwise point --experiments-dir at the right directory. The first of them: {first}")]
    TooMuchPruning {
        /// Stored runs no experiment file describes.
        count: usize,
        /// Stored runs in all.
        stored: usize,
        /// `count` over `stored`, in per cent, rounded up.
        percent: usize,
        /// The `runs.csv` read.
        runs: PathBuf,
        /// The experiments directory.
        experiments: PathBuf,
        /// The key of the first run that would go.
        first: String,
    },
}

/// The results directory, locked for this process.
#[derive(Debug)]
pub struct ResultsDir {
    tracked: TrackedDir,
    /// Held until the process ends (or the value is dropped).
    _lock: std::fs::File,
}

impl ResultsDir {
    /// Opens (creating) `dir` for writing: takes the lock, checks the tables against the
    /// manifest (see the module doc) and removes the program's own stale temporary files
    /// (returned, for a message).
    pub fn open(
        dir: &Path,
        git_rev: &str,
        edits: Edits,
    ) -> Result<(Self, Vec<PathBuf>), ResultsError> {
        let owned = OwnedDir::open(dir)?;
        let lock = lock(&owned)?;
        let removed = remove_own_tmp(&owned);
        // Tables are checked at every start; traces only when a shard is merged (a killed run
        // may have rewritten some before it could save the manifest).
        // A listed part of runs.csv that is missing was being removed when a kill came, after
        // its rows were committed into runs.csv (ResultsDir::remove_parts): not an edit; it is
        // dropped from the manifest below.
        let missing_part = |f: &str| part_number(f).is_some() && !dir.join(f).exists();
        let tracked = TrackedDir::open(dir, git_rev, edits, Some(RUNS), |f| {
            !f.contains('/') && !missing_part(f)
        })?;
        for name in tracked.listed(PART_PREFIX)? {
            if missing_part(&name) {
                tracked.adopt(Path::new(&name))?;
            }
        }
        // The staged copy of a part the manifest does not list: its commit was cut before its
        // commit point (TrackedDir::commit), so its rows are still in the journal.
        for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            let staged_part = name
                .strip_prefix(&crate::tracked_dir::pending(""))
                .filter(|p| part_number(p).is_some());
            if let Some(part) = staged_part {
                if tracked.lists(Path::new(part))? {
                    continue;
                }
                std::fs::remove_file(e.path()).map_err(crate::error::IoError::at(
                    e.path(),
                    crate::error::IoAction::Remove,
                ))?;
            }
        }
        let results = Self {
            tracked,
            _lock: lock,
        };
        // Every experiment's trace directory must stay inside (checked before anything runs,
        // not when the first trace is written).
        for e in std::fs::read_dir(dir.join(TRACES))
            .into_iter()
            .flatten()
            .flatten()
        {
            results
                .tracked
                .resolve(&Path::new(TRACES).join(e.file_name()))?;
        }
        if edits == Edits::Accept {
            for f in results.layout_files() {
                results.tracked.adopt(&f)?;
            }
        }
        Ok((results, removed))
    }

    /// Every file of the layout present: top-level `*.csv` but the journal, and the traces
    /// (regular files in real directories only).
    fn layout_files(&self) -> Vec<PathBuf> {
        let entries = |dir: &Path| -> Vec<std::fs::DirEntry> {
            std::fs::read_dir(dir)
                .into_iter()
                .flatten()
                .flatten()
                .collect()
        };
        let is = |e: &std::fs::DirEntry, f: fn(&std::fs::FileType) -> bool| {
            e.file_type().is_ok_and(|k| f(&k))
        };
        let csv = |e: &std::fs::DirEntry| e.path().extension().is_some_and(|x| x == "csv");
        let mut out = self.tables();
        if let Ok(traces) = self.tracked.resolve(Path::new(TRACES)) {
            for exp in entries(&traces)
                .iter()
                .filter(|e| is(e, std::fs::FileType::is_dir))
            {
                let rel = Path::new(TRACES).join(exp.file_name());
                out.extend(
                    entries(&exp.path())
                        .iter()
                        .filter(|e| is(e, std::fs::FileType::is_file) && csv(e))
                        .map(|e| rel.join(e.file_name())),
                );
            }
        }
        out.sort();
        out
    }

    /// The top-level tables present: `*.csv` but the journal.
    fn tables(&self) -> Vec<PathBuf> {
        std::fs::read_dir(self.path())
            .into_iter()
            .flatten()
            .flatten()
            .filter(|e| e.file_type().is_ok_and(|k| k.is_file()))
            .filter(|e| e.path().extension().is_some_and(|x| x == "csv"))
            .filter(|e| e.file_name() != JOURNAL)
            .map(|e| PathBuf::from(e.file_name()))
            .collect()
    }

    /// The directory as given.
    pub fn path(&self) -> &Path {
        self.tracked.path()
    }

    /// The tracked directory (for the journal and other writers).
    pub fn tracked(&self) -> &TrackedDir {
        &self.tracked
    }

    /// `runs.csv`'s path.
    pub fn runs_path(&self) -> PathBuf {
        self.path().join(RUNS)
    }

    /// The stored rows (none without a `runs.csv`), every name checked.
    pub fn read_runs(&self) -> Result<Vec<RunRow>, ResultsError> {
        let path = self.runs_path();
        if !path.exists() {
            return Ok(Vec::new());
        }
        read_runs(&path).map_err(ResultsError::Read)
    }

    /// Brings tables written before run ids up to date (see `migrate`): `runs.csv`,
    /// `ladder.csv` and `attribution.csv` get their id columns, and each run's trace moves to
    /// its id-named file, by the index `index()` makes of the experiment files' runs (made
    /// only for a table that lacks ids). Returns what was done, for a message; nothing when
    /// already current. A table whose header has the ids (every table this version writes) is
    /// read no further than its header, so a current `runs.csv` of any size costs a line.
    pub fn migrate_ids(
        &self,
        index: impl Fn() -> crate::migrate::LabelIndex,
    ) -> Result<Vec<String>, ResultsError> {
        let mut done = Vec::new();
        for table in [RUNS, LADDER, ATTRIBUTION] {
            let path = self.path().join(table);
            if crate::migrate::has_ids(&path) {
                continue;
            }
            let Ok(text) = crate::owned_dir::read_file(&path) else {
                continue;
            };
            let migrated = crate::migrate::add_ids(&text, &index)
                .map_err(|source| ResultsError::Migrate { path, source })?;
            let Some((bytes, keys)) = migrated else {
                continue;
            };
            self.tracked.write(Path::new(table), &bytes)?;
            done.push(format!("{table}: {} rows given run ids", keys.len()));
            if table != RUNS {
                continue;
            }
            let mut moved = 0;
            for ((e, v, s), key) in &keys {
                let old = Path::new(TRACES).join(crate::migrate::legacy_trace_name(e, v, s));
                let new = Self::trace_rel(key);
                let Ok(old_path) = self.tracked.resolve(&old) else {
                    continue;
                };
                if old == new || !old_path.is_file() {
                    continue;
                }
                let bytes = crate::owned_dir::read_file(&old_path).map_err(
                    crate::error::IoError::at(&old_path, crate::error::IoAction::Read),
                )?;
                self.tracked.write(&new, &bytes)?;
                self.tracked.remove(&old)?;
                moved += 1;
            }
            done.push(format!("{moved} traces renamed to their run ids"));
        }
        if !done.is_empty() {
            self.save()?;
        }
        Ok(done)
    }

    /// Writes `runs.csv` and saves the manifest, as one step a kill cannot split
    /// ([`TrackedDir::commit`]).
    pub fn write_runs(&self, rows: &[RunRow]) -> Result<(), ResultsError> {
        let bytes = runs_csv(rows).map_err(|source| ResultsError::Write {
            path: self.runs_path(),
            source,
        })?;
        self.tracked.commit(RUNS, &bytes)?;
        Ok(())
    }

    /// Writes `runs.csv` from `rows` (in key order, each with at most `joints` per-joint
    /// values) one row at a time, and saves the manifest, as one step a kill cannot split
    /// ([`TrackedDir::commit_with`]): memory independent of the number of rows. Returns how
    /// many rows were written. An error of `rows` leaves `runs.csv` and the manifest as they
    /// were.
    pub fn commit_runs<E: From<ResultsError>>(
        &self,
        joints: usize,
        rows: impl Iterator<Item = Result<RunRow, E>>,
    ) -> Result<usize, E> {
        self.commit_table(RUNS, joints, rows)
    }

    /// Appends a part to `runs.csv`: `rows` (in key order, each with at most `joints`
    /// per-joint values) written as the next part `runs.part-<n>.csv` (n one
    /// more than the last part listed) and committed with the manifest as `runs.csv` is
    /// ([`TrackedDir::commit_with`]). A shard appends each chunk's rows so, writing each row
    /// once, where rewriting `runs.csv` after every chunk wrote R^2 / (2 x chunk) rows for R
    /// runs; its parts are merged into `runs.csv` once, at its end or its next start
    /// ([`ResultsDir::parts`], [`ResultsDir::remove_parts`]). Returns how many rows were
    /// written.
    pub fn append_part<E: From<ResultsError>>(
        &self,
        joints: usize,
        rows: impl Iterator<Item = Result<RunRow, E>>,
    ) -> Result<usize, E> {
        let last = self
            .tracked
            .listed(PART_PREFIX)
            .map_err(ResultsError::from)?
            .iter()
            .filter_map(|name| part_number(name))
            .max();
        let name = part_name(last.unwrap_or(0) + 1);
        self.commit_table(&name, joints, rows)
    }

    /// The parts of `runs.csv` the manifest lists ([`ResultsDir::append_part`]), in the order
    /// they were appended. Only the program's own: a part is listed when it is committed.
    pub fn parts(&self) -> Result<Vec<PathBuf>, ResultsError> {
        let mut parts: Vec<(usize, String)> = self
            .tracked
            .listed(PART_PREFIX)?
            .into_iter()
            .filter_map(|name| part_number(&name).map(|n| (n, name)))
            .collect();
        parts.sort_unstable();
        Ok(parts
            .into_iter()
            .map(|(_, name)| self.path().join(name))
            .collect())
    }

    /// Removes the parts of `runs.csv` (once their rows are committed into it): each file,
    /// then the manifest saved without them. A kill between the two leaves listed parts
    /// missing, which [`ResultsDir::open`] drops from the manifest (a part is removed only
    /// after its rows are in `runs.csv`; one lost otherwise costs its runs, run again).
    pub fn remove_parts(&self) -> Result<(), ResultsError> {
        let parts = self.tracked.listed(PART_PREFIX)?;
        for name in &parts {
            let path = self.tracked.resolve(Path::new(name))?;
            match std::fs::remove_file(&path) {
                Ok(()) => crate::kill_point::passed(),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
                Err(e) => {
                    return Err(
                        crate::error::IoError::at(&path, crate::error::IoAction::Remove)(e).into(),
                    )
                }
            }
            self.tracked.adopt(Path::new(name))?;
        }
        if !parts.is_empty() {
            self.tracked.save()?;
        }
        Ok(())
    }

    /// [`ResultsDir::commit_runs`] into the top-level table `name`.
    fn commit_table<E: From<ResultsError>>(
        &self,
        name: &str,
        joints: usize,
        rows: impl Iterator<Item = Result<RunRow, E>>,
    ) -> Result<usize, E> {
        let mut failed = None;
        let mut written = 0;
        let path = self.path().join(name);
        let csv_error = |source| ResultsError::Write {
            path: path.clone(),
            source,
        };
        let committed = self.tracked.commit_with(name, |out| {
            let mut w = csv::Writer::from_writer(out);
            w.write_record(records::table::header::<RunRow>(joints))?;
            for row in rows {
                let row = match row {
                    Ok(row) => row,
                    Err(e) => {
                        failed = Some(e);
                        return Err(std::io::Error::other("the rows stopped"));
                    }
                };
                let record = records::table::record(&row, joints).map_err(|e| {
                    failed = Some(csv_error(e).into());
                    std::io::Error::other("a row did not serialise")
                })?;
                w.write_record(record)?;
                written += 1;
            }
            w.flush()
        });
        match (failed, committed) {
            (Some(e), _) => Err(e),
            (None, Err(e)) => Err(ResultsError::from(e).into()),
            (None, Ok(())) => Ok(written),
        }
    }

    /// A run's trace, relative to the directory: `traces/<experiment>/<variant>__<solver>.csv`
    /// (the key's ids are slugs, so these are safe names: `spec::ids`).
    pub fn trace_rel(key: &RunKey) -> PathBuf {
        Path::new(TRACES)
            .join(&key.experiment)
            .join(format!("{}.csv", key.stem()))
    }

    /// Writes the trace of the run `key` ([`records::TracePoint`]); returns its fingerprint.
    pub fn write_trace(
        &self,
        key: &RunKey,
        trace: &[TracePoint],
    ) -> Result<Fingerprint, ResultsError> {
        let rel = Self::trace_rel(key);
        let bytes = trace_csv(trace).map_err(|source| ResultsError::Write {
            path: self.path().join(&rel),
            source,
        })?;
        Ok(self.tracked.write_fingerprinted(&rel, &bytes)?)
    }

    /// Saves the manifest: call after each step that changed the directory. The top-level
    /// tables are fingerprinted as they are now: the layers that write them (the explanation
    /// layer, the leaderboard, the cost curve) write while this process holds the lock, and
    /// they were checked against the manifest when it was taken.
    pub fn save(&self) -> Result<(), ResultsError> {
        for t in self.tables() {
            self.tracked.adopt(&t)?;
        }
        Ok(self.tracked.save()?)
    }

    /// Splits `stored` into the rows `describes` keeps and the rows to prune, refusing (before
    /// anything is changed) to prune more than [`PRUNE_LIMIT_PERCENT`] of them unless `allow`.
    pub fn plan_pruning(
        &self,
        stored: Vec<RunRow>,
        describes: impl Fn(&RunRow) -> bool,
        allow: bool,
        experiments: &Path,
    ) -> Result<(Vec<RunRow>, Vec<RunRow>), ResultsError> {
        let total = stored.len();
        let (kept, pruned): (Vec<RunRow>, Vec<RunRow>) = stored.into_iter().partition(describes);
        self.check_pruning(total, &pruned, allow, experiments)?;
        Ok((kept, pruned))
    }

    /// The rows of `runs.csv` that `describes` does not keep (to prune), read row by row
    /// ([`crate::sorted::read_key_ordered`]): memory of the pruned rows only. Refused as
    /// [`ResultsDir::plan_pruning`] refuses.
    pub fn plan_pruning_streamed(
        &self,
        describes: impl Fn(&RunRow) -> bool,
        allow: bool,
        experiments: &Path,
    ) -> Result<Vec<RunRow>, ResultsError> {
        let mut total = 0;
        let mut pruned = Vec::new();
        for row in crate::sorted::read_key_ordered(&self.runs_path())? {
            let row = row?;
            total += 1;
            if !describes(&row) {
                pruned.push(row);
            }
        }
        self.check_pruning(total, &pruned, allow, experiments)?;
        Ok(pruned)
    }

    /// Refuses to prune `pruned` of `total` stored runs when that is more than
    /// [`PRUNE_LIMIT_PERCENT`] of them, unless `allow`.
    fn check_pruning(
        &self,
        total: usize,
        pruned: &[RunRow],
        allow: bool,
        experiments: &Path,
    ) -> Result<(), ResultsError> {
        let percent = if total == 0 {
            0
        } else {
            (100 * pruned.len()).div_ceil(total)
        };
        if !allow && percent > PRUNE_LIMIT_PERCENT {
            return Err(ResultsError::TooMuchPruning {
                count: pruned.len(),
                stored: total,
                percent,
                runs: self.runs_path(),
                experiments: experiments.to_path_buf(),
                first: pruned[0].key().to_string(),
            });
        }
        Ok(())
    }

    /// Removes the traces of pruned rows (only those the program wrote and nobody edited since)
    /// and returns one line per run for the user.
    pub fn prune(&self, pruned: &[RunRow]) -> Result<Vec<String>, ResultsError> {
        let mut said = Vec::with_capacity(pruned.len());
        for r in pruned {
            let key = r.key().to_string();
            let rel = Self::trace_rel(&r.key());
            said.push(match self.tracked.remove(&rel)? {
                Removal::Removed => {
                    format!("pruned {key} and its trace (no experiment file describes it)")
                }
                Removal::Absent => {
                    format!("pruned {key} (no experiment file describes it; it had no trace)")
                }
                Removal::Kept(why) => {
                    format!("pruned {key} (no experiment file describes it); its trace {why}")
                }
            });
        }
        Ok(said)
    }
}

/// The advisory lock on `dir` (`<dir>/.lock`, the operating system's file lock through
/// `std::fs::File::try_lock`): a second writer refuses at once, naming the directory, instead
/// of overwriting the first one's results with its own. The lock ends with the process.
fn lock(dir: &OwnedDir) -> Result<std::fs::File, ResultsError> {
    let path = dir.resolve(Path::new(LOCK))?;
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(|source| ResultsError::Lock {
            path: path.clone(),
            source,
        })?;
    match file.try_lock() {
        Ok(()) => Ok(file),
        Err(std::fs::TryLockError::WouldBlock) => Err(ResultsError::Locked {
            dir: dir.path().to_path_buf(),
            lock: path,
        }),
        Err(std::fs::TryLockError::Error(source)) => Err(ResultsError::Lock { path, source }),
    }
}

/// Whether `name` is a temporary file of the program's own (module docs of
/// `atomic::TMP_PREFIX`): `.driftbench-tmp.<pid>.<counter>.<name>` of an atomic write, or
/// `.driftbench-tmp.<pid>.probe` of a writability probe, pid and counter decimal.
pub fn is_own_tmp(name: &str) -> bool {
    let Some(rest) = name.strip_prefix(crate::atomic::TMP_PREFIX) else {
        return false;
    };
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    let mut parts = rest.splitn(3, '.');
    match (parts.next(), parts.next(), parts.next()) {
        (Some(pid), Some("probe"), None) => digits(pid),
        (Some(pid), Some(counter), Some(base)) => {
            digits(pid) && digits(counter) && !base.is_empty()
        }
        _ => false,
    }
}

/// Removes the program's own temporary files ([`is_own_tmp`]) that a killed run left in `dir`
/// and its sub-directories down to two levels (`traces/<experiment>/`, `figures/`): regular
/// files only, never through a symbolic link, never anything else. Returns what it removed.
pub fn remove_own_tmp(dir: &OwnedDir) -> Vec<PathBuf> {
    fn walk(dir: &Path, depth: usize, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            let path = entry.path();
            if kind.is_dir() && depth < 2 {
                walk(&path, depth + 1, out);
            } else if kind.is_file()
                && is_own_tmp(&entry.file_name().to_string_lossy())
                && std::fs::remove_file(&path).is_ok()
            {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(dir.path(), 0, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(variant: &str) -> RunRow {
        RunRow::blank(
            &RunKey::from_ids("exp", variant, "exact").unwrap(),
            spec::SolverKind::Exact,
        )
    }

    fn rows(names: &[&str]) -> impl Iterator<Item = Result<RunRow, ResultsError>> {
        names
            .iter()
            .map(|v| Ok(row(v)))
            .collect::<Vec<_>>()
            .into_iter()
    }

    fn variants(path: &Path) -> Vec<String> {
        crate::sorted::read_key_ordered(path)
            .unwrap()
            .map(|r| r.unwrap().variant_id.to_string())
            .collect()
    }

    #[test]
    fn part_names_are_numbered_from_one() {
        assert_eq!(part_name(12), "runs.part-12.csv");
        assert_eq!(part_number("runs.part-12.csv"), Some(12));
        for other in [
            "runs.csv",
            "runs.part-.csv",
            "runs.part-01.csv",
            "runs.part-1.csv.bak",
            "runs.part-x.csv",
            "runs.part--1.csv",
        ] {
            assert_eq!(part_number(other), None, "{other}");
        }
    }

    /// Parts are appended in order, each committed with the manifest, and each row written
    /// once; removing them leaves `runs.csv` alone; a kill inside the removal (a listed part
    /// gone, the manifest not saved yet) or inside a part's first commit (its staged copy,
    /// unlisted) leaves a directory the next open takes as it is, without the part.
    #[test]
    fn parts_are_appended_once_each_and_a_cut_removal_or_commit_is_cleared_on_open() {
        let base = inputs::Scratch::unmade("parts");
        let open = || ResultsDir::open(&base, "r", Edits::Refuse).map(|(r, _)| r);
        let results = open().unwrap();
        results.commit_runs(0, rows(&["a", "d"])).unwrap();
        assert!(results.parts().unwrap().is_empty());
        assert_eq!(results.append_part(0, rows(&["b", "e"])).unwrap(), 2);
        assert_eq!(results.append_part(0, rows(&["c"])).unwrap(), 1);
        let parts = results.parts().unwrap();
        assert_eq!(
            parts,
            [base.join("runs.part-1.csv"), base.join("runs.part-2.csv")]
        );
        assert_eq!(variants(&parts[0]), ["b", "e"]);
        assert_eq!(variants(&parts[1]), ["c"]);
        assert_eq!(variants(&results.runs_path()), ["a", "d"]);
        drop(results);
        // Committed: a new open finds the parts listed and as written.
        let results = open().unwrap();
        assert_eq!(results.parts().unwrap().len(), 2);
        // A kill after the first part's removal, before the manifest is saved.
        std::fs::remove_file(base.join("runs.part-1.csv")).unwrap();
        drop(results);
        let results = open().unwrap();
        assert_eq!(results.parts().unwrap(), [base.join("runs.part-2.csv")]);
        results.remove_parts().unwrap();
        assert!(results.parts().unwrap().is_empty() && !base.join("runs.part-2.csv").exists());
        assert_eq!(variants(&results.runs_path()), ["a", "d"]);
        // A part's staged copy left by a kill before its commit point, unlisted: removed;
        // another program's file of that shape is not the manifest's either, and is kept.
        let staged = base.join(crate::tracked_dir::pending("runs.part-1.csv"));
        std::fs::write(&staged, b"cut").unwrap();
        std::fs::write(base.join("notes.part-1.csv"), b"mine").unwrap();
        drop(results);
        let results = open().unwrap();
        assert!(!staged.exists());
        assert!(base.join("notes.part-1.csv").exists());
        // An edited part is refused as any edited table is.
        results.append_part(0, rows(&["f"])).unwrap();
        drop(results);
        std::fs::write(base.join("runs.part-1.csv"), b"edited").unwrap();
        let e = open().unwrap_err().to_string();
        assert!(e.contains("runs.part-1.csv") && e.contains("edited"), "{e}");
    }

    #[test]
    fn only_the_programs_own_temporary_files_are_recognised() {
        assert!(is_own_tmp(".driftbench-tmp.1234.0.runs.csv"));
        assert!(is_own_tmp(".driftbench-tmp.99.17.v__s.csv"));
        assert!(is_own_tmp(".driftbench-tmp.42.probe"));
        for user in [
            "notes.2024.12.tmp",
            "backup.2025.1.tmp",
            "runs.csv.1234.0.tmp",
            ".driftbench-tmp.12.notes",
            ".driftbench-tmp.x.1.a",
            ".driftbench-tmp.1.2.",
            ".write-probe.42.tmp",
            "notes.tmp",
            "draft.tmp",
            "work.tmp",
            "a.b.tmp",
            "x.12.tmp",
            "runs.csv.1a.0.tmp",
            ".12.3.tmp",
        ] {
            assert!(!is_own_tmp(user), "{user}");
        }
    }

    #[test]
    fn stale_temporary_files_are_removed_only_near_the_top_and_only_ours() {
        let base = inputs::Scratch::unmade("tmp");
        for f in [
            ".driftbench-tmp.1.0.runs.csv",
            "traces/e/.driftbench-tmp.1.2.v__s.csv",
            "notes.tmp",
            "notes.2024.12.tmp",
            "traces/e/backup.2025.1.tmp",
            "a/b/c/work.tmp",
            "a/b/c/.driftbench-tmp.1.0.x.csv",
        ] {
            let p = base.join(f);
            std::fs::create_dir_all(p.parent().unwrap()).unwrap();
            std::fs::write(&p, b"x").unwrap();
        }
        let dir = OwnedDir::open(&base).unwrap();
        let mut removed: Vec<String> = remove_own_tmp(&dir)
            .iter()
            .map(|p| {
                p.strip_prefix(&base)
                    .unwrap()
                    .to_string_lossy()
                    .into_owned()
            })
            .collect();
        removed.sort();
        assert_eq!(
            removed,
            [
                ".driftbench-tmp.1.0.runs.csv",
                "traces/e/.driftbench-tmp.1.2.v__s.csv"
            ]
        );
        for user in [
            "notes.tmp",
            "notes.2024.12.tmp",
            "traces/e/backup.2025.1.tmp",
            "a/b/c/work.tmp",
        ] {
            assert!(base.join(user).exists(), "{user}");
        }
        assert!(
            base.join("a/b/c/.driftbench-tmp.1.0.x.csv").exists(),
            "deeper than two levels is not ours"
        );
    }
}
