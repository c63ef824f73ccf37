//! The store's errors shared across its modules: reading and writing the results files
//! (`runs.csv`, `dof-cost.csv`, `leaderboard-timing.csv`, the control experiments' files) and
//! the I/O error every file operation reports ([`IoError`]). Where the store reads rows they
//! wrap the schemas' errors (crate `records`: [`records::table::TableError`],
//! [`records::RowsError`]). Each names the file and, where it applies, the line. A
//! module whose errors wrap the results directory's own keeps them beside its code: the
//! journal's ([`crate::journal::JournalError`]), the shards' ([`crate::shard::ShardError`]),
//! the results directory's ([`crate::results_dir::ResultsError`]).

use records::table::TableError;
use records::RowsError;
use std::path::PathBuf;

/// What was being done to a file when the system refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IoAction {
    /// Reading a file.
    Read,
    /// Listing a directory.
    List,
    /// Opening (or creating) a file.
    Open,
    /// Writing a file.
    Write,
    /// Removing a file.
    Remove,
}

impl std::fmt::Display for IoAction {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            IoAction::Read => "cannot read: ",
            IoAction::List => "cannot list: ",
            IoAction::Open => "cannot open: ",
            IoAction::Write | IoAction::Remove => "",
        })
    }
}

/// A file or directory the system would not read, list, open, write or remove.
#[derive(Debug, thiserror::Error)]
#[error("{}: {action}{source}", path.display())]
pub struct IoError {
    /// The file or directory.
    pub path: PathBuf,
    /// What was being done to it.
    pub action: IoAction,
    /// The system's error.
    pub source: std::io::Error,
}

impl IoError {
    /// The error of `action` on `path` (for `map_err`).
    pub fn at(path: impl Into<PathBuf>, action: IoAction) -> impl FnOnce(std::io::Error) -> Self {
        let path = path.into();
        move |source| IoError {
            path,
            action,
            source,
        }
    }
}

/// Why `results/runs.csv` (or a journal) cannot be read; the message says how to recover.
#[derive(Debug, thiserror::Error)]
pub enum RunsError {
    /// The file is not a table of this version's schema (unreadable, another header, a row
    /// that does not parse).
    #[error("{error}; {}", recovery_hint(path))]
    Table {
        /// The file.
        path: PathBuf,
        /// Where and what.
        error: TableError,
    },
    /// The rows parse but are not usable (a name that cannot name a file, a run listed twice).
    #[error("{}: {error}; {}", path.display(), recovery_hint(path))]
    Rows {
        /// The file.
        path: PathBuf,
        /// Which row and why.
        error: RowsError,
    },
    /// Files cannot be created in the directory.
    #[error("{}: not writable: {source}", dir.display())]
    NotWritable {
        /// The directory.
        dir: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The table or a file could not be written.
    #[error("{}: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The CSV error.
        source: csv::Error,
    },
    /// Another file operation failed.
    #[error(transparent)]
    Io(#[from] IoError),
}

/// How to recover from a `runs.csv` this version cannot read.
fn recovery_hint(path: &std::path::Path) -> String {
    format!(
        "nothing was run or written; restore the committed file with `git checkout {0}` or move \
         it away (e.g. `mv {0} {0}.old`) and run again",
        path.display()
    )
}

/// Why `results/dof-cost.csv` could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum DofCostError {
    /// The rows could not be serialised or written.
    #[error("{}: {source}", path.display())]
    Csv {
        /// The file.
        path: PathBuf,
        /// The CSV error.
        source: csv::Error,
    },
    /// A file operation failed.
    #[error(transparent)]
    Io(#[from] IoError),
    /// The file does not read as the table's schema.
    #[error(transparent)]
    Table(#[from] TableError),
}

/// Why a result file of the control experiments (`results/control*.csv`, `results/cycles*.csv`,
/// [`crate::control`]) could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum ControlFileError {
    /// The file could not be written, read or parsed as the row type.
    #[error("{}: {source}", path.display())]
    Csv {
        /// The file.
        path: PathBuf,
        /// The CSV error.
        source: csv::Error,
    },
    /// A file operation failed.
    #[error(transparent)]
    Io(#[from] IoError),
}
