//! The checkpoint journal: `results/journal.csv`, one `runs.csv` row appended (and flushed) as
//! each run finishes, its trace written beside it at once. A run that is interrupted (SIGINT,
//! SIGKILL, a pre-empted job) loses only the runs that were in flight: the next start folds the
//! journal into `runs.csv` (atomically) and skips the runs it holds. Only rows of the current
//! code revision are folded: a row of another revision (an old journal, or one copied in) is
//! not, and the start says so run by run; those runs are run again. A normal end merges
//! everything into `runs.csv` and removes the journal. A line cut short by a kill (the last
//! one) is dropped; any other bad line, a name that cannot name a file, or a run listed twice
//! is an error naming the file and the line (a journal this program wrote has each run once).

use crate::error::{IoAction, IoError, JournalError};
use crate::results_dir::ResultsDir;
use crate::runs::{check_rows, RunRow};
use crate::table;
use crate::trace::TracePoint;
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The journal's file name in a results directory.
pub const FILE: &str = "journal.csv";

/// The journal of the results directory `dir`.
pub fn path(dir: &Path) -> PathBuf {
    dir.join(FILE)
}

/// An open journal, shared by the worker threads.
pub struct Journal<'a> {
    results: &'a ResultsDir,
    /// Per-joint columns of its header (the most joints among the runs it will hold).
    joints: usize,
    file: Mutex<File>,
}

impl<'a> Journal<'a> {
    /// Opens (creating, with the header) the journal of `results` for appending rows of arms
    /// with at most `joints` joints. An existing journal keeps its header: a run resumed with
    /// arms of more joints than it was started with starts a new journal.
    pub fn open(results: &'a ResultsDir, joints: usize) -> Result<Self, JournalError> {
        let path = results.tracked().resolve(Path::new(FILE))?;
        let mut file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .map_err(IoError::at(&path, IoAction::Open))?;
        let empty = file.metadata().map(|m| m.len() == 0).unwrap_or(true);
        let header = table::header::<RunRow>(joints);
        if empty {
            writeln!(file, "{}", header.join(",")).map_err(IoError::at(&path, IoAction::Write))?;
        } else {
            let text =
                std::fs::read_to_string(&path).map_err(IoError::at(&path, IoAction::Read))?;
            if text.lines().next() != Some(header.join(",").as_str()) {
                return Err(JournalError::Header { path });
            }
        }
        Ok(Self {
            results,
            joints,
            file: Mutex::new(file),
        })
    }

    /// Checkpoints one finished run: its trace, then its row (one write, flushed).
    pub fn record(&self, row: &RunRow, trace: &[TracePoint]) -> Result<(), JournalError> {
        self.results.write_trace(&row.key(), trace)?;
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
        let mut file = self.file.lock().map_err(|_| JournalError::Poisoned)?;
        file.write_all(&line)
            .and_then(|()| file.flush())
            .map_err(IoError::at(journal, IoAction::Write))?;
        Ok(())
    }
}

/// What an interrupted run's journal holds.
#[derive(Debug, Default)]
pub struct Recovered {
    /// Rows of the current code revision: folded into `runs.csv`, not run again.
    pub current: Vec<RunRow>,
    /// Rows of another revision: not folded (run again).
    pub other_revision: Vec<RunRow>,
}

/// The rows of an interrupted run's journal in `dir` (none without one), split by code
/// revision (`git_rev`: the current one). A last line cut short by a kill is dropped.
pub fn recover(dir: &Path, git_rev: &str) -> Result<Recovered, JournalError> {
    let journal = path(dir);
    if !journal.exists() {
        return Ok(Recovered::default());
    }
    let text = std::fs::read_to_string(&journal).map_err(IoError::at(&journal, IoAction::Read))?;
    // Keep only complete lines: a kill can cut the last one short.
    let complete = match text.rfind('\n') {
        Some(end) => &text[..=end],
        None => "",
    };
    let rows: Vec<RunRow> =
        table::from_reader(complete.as_bytes()).map_err(|e| table::TableError {
            path: Some(journal.clone()),
            ..e
        })?;
    check_rows(&rows).map_err(|error| JournalError::Rows {
        path: journal,
        error,
    })?;
    let (current, other_revision) = rows.into_iter().partition(|r| r.git_rev == git_rev);
    Ok(Recovered {
        current,
        other_revision,
    })
}

/// Removes the journal of `dir` (after its rows are in runs.csv).
pub fn remove(dir: &Path) -> Result<(), IoError> {
    let journal = path(dir);
    match std::fs::remove_file(&journal) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(IoError::at(journal, IoAction::Remove)(e)),
    }
}
