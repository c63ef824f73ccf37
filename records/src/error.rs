//! The records layer's errors: reading and writing the results files (`runs.csv`, the journal,
//! shards, trajectories, the leaderboard, the control experiments' files). They wrap the layer
//! below them: the catalog's
//! naming errors ([`catalog::naming::NameError`]), the tables' [`TableError`] and the
//! results directory's own errors ([`PathError`], [`TrackedError`], [`IntegrityError`]).
//! Each names the file and, where it applies, the line.

use crate::integrity::{IntegrityError, Mismatch};
use crate::owned_dir::PathError;
use crate::table::TableError;
use crate::tracked_dir::TrackedError;
use catalog::naming::NameError;
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

/// Why the rows of a results file (`runs.csv`, a journal) are not usable.
#[derive(Debug, thiserror::Error)]
pub enum RowsError {
    /// A row names a run with a name that cannot name a file.
    #[error("line {line}: {error}")]
    Name {
        /// The row's line (the header is line 1).
        line: usize,
        /// Why the name cannot name a file.
        error: NameError,
    },
    /// Two rows have the same run key.
    #[error("line {line}: the run {key} is listed twice (first on line {first})")]
    Twice {
        /// The second row's line (the header is line 1).
        line: usize,
        /// The run key, `experiment / variant / solver`.
        key: String,
        /// The first row's line.
        first: usize,
    },
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

/// A run an [`crate::index::Runs`] does not hold.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("no run of {solver} on {experiment} / {variant}")]
pub struct MissingRun {
    /// The experiment asked for.
    pub experiment: String,
    /// The variant asked for.
    pub variant: String,
    /// The solver asked for.
    pub solver: String,
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

/// Why a trajectory CSV cannot be read (module docs of [`crate::trajectory`]).
#[derive(Debug, thiserror::Error)]
#[error("{}: {}{problem}", path.display(), line.map(|l| format!("line {l}: ")).unwrap_or_default())]
pub struct TrajectoryFileError {
    /// The file.
    pub path: PathBuf,
    /// The 1-based line (the header is line 1), where the problem is in one.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: TrajectoryProblem,
}

/// What is wrong in a trajectory CSV.
#[derive(Debug, thiserror::Error)]
pub enum TrajectoryProblem {
    /// The file is not CSV (or a row has another width).
    #[error(transparent)]
    Csv(#[from] csv::Error),
    /// A header names a column that is none of the trajectory's (its name).
    #[error("unknown column \"{0}\" (the columns are t, theta_1 .. theta_n and optionally thetadot_1 .. thetadot_n)")]
    UnknownColumn(String),
    /// A required column is absent: `t` or `theta_1`.
    #[error("no column \"{0}\"")]
    NoColumn(&'static str),
    /// A column named twice (which would silently win otherwise).
    #[error("column \"{0}\" is given twice (each column once)")]
    ColumnTwice(String),
    /// The theta_i or thetadot_i columns are not numbered 1 .. n.
    #[error("the {stem}_i columns must be numbered 1 .. n without gaps, got {numbers:?}")]
    Gaps {
        /// The columns' stem: `theta` or `thetadot`.
        stem: &'static str,
        /// The numbers given, ascending.
        numbers: Vec<usize>,
    },
    /// The thetadot columns are not one per theta column.
    #[error("{theta} theta_i columns but {thetadot} thetadot_i columns")]
    ColumnCounts {
        /// The theta_i columns.
        theta: usize,
        /// The thetadot_i columns.
        thetadot: usize,
    },
    /// A cell does not parse as a number.
    #[error("column \"{column}\" is \"{value}\", not a number")]
    NotANumber {
        /// The cell's column.
        column: String,
        /// The cell's text.
        value: String,
    },
}

/// Why a shard cannot be chosen, written, read or merged.
#[derive(Debug, thiserror::Error)]
pub enum ShardError {
    /// N is 0.
    #[error("the number of shards N must be at least 1")]
    NoShards,
    /// K is not in 1..=N.
    #[error("shard {k} of {n}: K must be in 1..={n} (K is 1-based)")]
    OutOfRange {
        /// The shard number K given.
        k: usize,
        /// The number of shards N.
        n: usize,
    },
    /// `--shard` has no `/` (the text given).
    #[error("--shard {0}: expected K/N, e.g. 2/8")]
    Syntax(String),
    /// K or N of `--shard` is not a whole number (the text given).
    #[error("--shard {0}: expected K/N with whole numbers, e.g. 2/8")]
    NotWhole(String),
    /// A scheduler's or driftbench's environment variable is not a whole number.
    #[error("environment variable {name}={value} is not a whole number")]
    Environment {
        /// The variable.
        name: String,
        /// Its value.
        value: String,
    },
    /// A Kubernetes Indexed Job's index without the number of shards N.
    #[error("JOB_COMPLETION_INDEX={index} (a Kubernetes Indexed Job) gives K but not the number of shards N: give --shards N or set DRIFTBENCH_SHARDS=N (the Job's completions)")]
    IndexWithoutCount {
        /// `JOB_COMPLETION_INDEX` (from 0).
        index: usize,
    },
    /// A Slurm array task, N not given, whose array is not exactly 1-N with N >= 2.
    #[error("the Slurm array ({said}) does not tell the number of shards N: only an array of exactly 1-N with N >= 2 does, not one task (a resubmitted one), a part of an array, or a stepped, sparse or 0-based array; give --shards N or set DRIFTBENCH_SHARDS=N")]
    ArrayWithoutCount {
        /// The Slurm array variables as set (or unset).
        said: String,
    },
    /// The Slurm task id is not a shard number 1..=N.
    #[error("SLURM_ARRAY_TASK_ID={id}: task ids are shard numbers 1..={n} (submit --array=1-{n}; resubmit one task as --array=K)")]
    TaskId {
        /// `SLURM_ARRAY_TASK_ID`.
        id: usize,
        /// The number of shards N.
        n: usize,
    },
    /// `--shard` without K/N, and no scheduler's variable is set.
    #[error("--shard without K/N reads the scheduler's environment, but neither SLURM_ARRAY_TASK_ID nor JOB_COMPLETION_INDEX is set; give --shard K/N")]
    NoScheduler,
    /// A file operation failed.
    #[error(transparent)]
    Io(#[from] IoError),
    /// `shard.toml` or `shard-binding.toml` could not be serialised.
    #[error("{}: {source}", path.display())]
    WriteManifest {
        /// The file.
        path: PathBuf,
        /// The TOML error.
        source: toml::ser::Error,
    },
    /// `shard.toml` does not read as a shard manifest.
    #[error("{}: {source}", path.display())]
    ReadManifest {
        /// The file.
        path: PathBuf,
        /// The TOML error, with its line.
        source: inputs::TomlError,
    },
    /// `shard.toml` refused or unreadable by the input reader (a link outside the shard
    /// directory, a FIFO, over its cap).
    #[error(transparent)]
    Input(#[from] inputs::InputError),
    /// `shard.toml` names no valid shard.
    #[error("{}: `shard = {shard}`, `shards = {shards}`: {source}", path.display())]
    ManifestShard {
        /// The file.
        path: PathBuf,
        /// Its `shard`.
        shard: usize,
        /// Its `shards`.
        shards: usize,
        /// Why they make no shard.
        source: Box<ShardError>,
    },
    /// An entry of `shard.toml`'s `runs` is not a run of the shard.
    #[error("{}: `runs`, entry {index} \"{entry}\": {problem}", path.display())]
    ManifestRun {
        /// The file.
        path: PathBuf,
        /// The entry's position, from 1.
        index: usize,
        /// The entry as written.
        entry: String,
        /// What is wrong with it.
        problem: RunEntryProblem,
    },
    /// `shard-binding.toml` does not read as a binding.
    #[error("{}: {source}", path.display())]
    ReadBinding {
        /// The file.
        path: PathBuf,
        /// The TOML error, with its line.
        source: inputs::TomlError,
    },
    /// The directory is bound to another shard, selection or set of experiment files.
    #[error("{}: bound to another shard, so nothing was run: {}; one directory serves one shard of one selection: give this shard its own --results-dir, or remove {} if its runs are not wanted", dir.display(), differences.join("; "), dir.display())]
    BoundElsewhere {
        /// The shard directory.
        dir: PathBuf,
        /// What differs, one item each.
        differences: Vec<String>,
    },
    /// The directory holds results but no binding.
    #[error("{}: holds {file} but no {}, so which selection it ran cannot be told (a directory of an older version, or not a shard's); nothing was run: give this shard its own --results-dir, or remove the directory", dir.display(), crate::shard::BINDING)]
    Unbound {
        /// The shard directory.
        dir: PathBuf,
        /// The result file it holds (`runs.csv`, the journal, `shard.toml`).
        file: &'static str,
    },
    /// The shard directory has no `shard.toml`: the shard has not finished.
    #[error("{}: no {}: the shard has not finished (run it again; it resumes where it stopped)", dir.display(), crate::shard::MANIFEST)]
    Unfinished {
        /// The shard directory.
        dir: PathBuf,
    },
    /// A directory given to merge does not exist.
    #[error("{}: no such directory (give the directories that `reproduce --shard K/N` wrote)", dir.display())]
    NoDirectory {
        /// The path given.
        dir: PathBuf,
    },
    /// The shard's integrity manifest could not be read.
    #[error(transparent)]
    Integrity(#[from] IntegrityError),
    /// The shard directory has no integrity manifest.
    #[error("{}: no {}: not a shard this version wrote, so its files cannot be checked; run the shard again", dir.display(), crate::integrity::FILE)]
    NoIntegrity {
        /// The shard directory.
        dir: PathBuf,
    },
    /// Files of the shard differ from its integrity manifest.
    #[error("{}: {} file(s) differ from what the shard wrote:\n{}\nrun the shard again, or merge with --accept-edited if the edit is deliberate", dir.display(), mismatches.len(), mismatches.iter().map(|m| format!("  {m}")).collect::<Vec<_>>().join("\n"))]
    Edited {
        /// The shard directory.
        dir: PathBuf,
        /// Every file that differs, and how.
        mismatches: Vec<Mismatch>,
    },
    /// A shard's `runs.csv` could not be read.
    #[error(transparent)]
    Runs(#[from] RunsError),
    /// A path under a directory was refused.
    #[error(transparent)]
    Path(#[from] PathError),
    /// A tracked write failed.
    #[error(transparent)]
    Tracked(#[from] TrackedError),
    /// The results directory merged into failed.
    #[error(transparent)]
    Results(#[from] crate::results_dir::ResultsError),
    /// `--merge` was given no shard directory.
    #[error("--merge needs at least one shard directory")]
    NoShardDirectories,
    /// The shards do not fit together; every problem, one a line.
    #[error("cannot merge; nothing was written:\n{}", problems.join("\n"))]
    CannotMerge {
        /// The problems, one each.
        problems: Vec<String>,
    },
}

/// What is wrong with an entry of a shard manifest's `runs`.
#[derive(Debug, thiserror::Error)]
pub enum RunEntryProblem {
    /// Not a run key, or a part that is no valid id.
    #[error("not a run key: {0}")]
    NotAKey(catalog::run_key::KeyError),
    /// The run belongs to another shard.
    #[error("belongs to shard {owner}/{n}, not to this shard")]
    OtherShard {
        /// The shard it belongs to.
        owner: usize,
        /// The number of shards N.
        n: usize,
    },
    /// The run is listed twice.
    #[error("listed twice")]
    Twice,
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
