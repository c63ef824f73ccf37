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
    Read,
    List,
    Open,
    Write,
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
    pub path: PathBuf,
    pub action: IoAction,
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
    Name { line: usize, error: NameError },
    #[error("line {line}: the run {key} is listed twice (first on line {first})")]
    Twice {
        line: usize,
        key: String,
        first: usize,
    },
}

/// Why `results/runs.csv` (or a journal) cannot be read; the message says how to recover.
#[derive(Debug, thiserror::Error)]
pub enum RunsError {
    #[error("{error}; {}", recovery_hint(path))]
    Table { path: PathBuf, error: TableError },
    #[error("{}: {error}; {}", path.display(), recovery_hint(path))]
    Rows { path: PathBuf, error: RowsError },
    #[error("{}: not writable: {source}", dir.display())]
    NotWritable {
        dir: PathBuf,
        source: std::io::Error,
    },
    /// The table or a file could not be written.
    #[error("{}: {source}", path.display())]
    Write { path: PathBuf, source: csv::Error },
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
    pub experiment: String,
    pub variant: String,
    pub solver: String,
}

/// Why the journal of an interrupted run cannot be opened, written or read back.
#[derive(Debug, thiserror::Error)]
pub enum JournalError {
    #[error(transparent)]
    Io(#[from] IoError),
    #[error(transparent)]
    Path(#[from] PathError),
    #[error(transparent)]
    Results(#[from] crate::results_dir::ResultsError),
    #[error("{}: its header is not that of this run (more joints, or another version); fold it in by running the same selection again, or remove it", path.display())]
    Header { path: PathBuf },
    #[error("{}: {source}", path.display())]
    Csv { path: PathBuf, source: csv::Error },
    #[error("journal lock poisoned")]
    Poisoned,
    #[error(transparent)]
    Table(#[from] TableError),
    #[error("{}: {error}; this is not a journal this program wrote: remove it (its runs are run again)", path.display())]
    Rows { path: PathBuf, error: RowsError },
    #[error(transparent)]
    Tracked(#[from] TrackedError),
    #[error("{}: line {line}: not `<sha256>  <trace path>`, so not a seal this program wrote: remove it and the journal beside it (their runs are run again)", path.display())]
    Seal { path: PathBuf, line: usize },
}

/// Why a trajectory CSV cannot be read (module docs of [`crate::trajectory`]).
#[derive(Debug, thiserror::Error)]
#[error("{}: {}{problem}", path.display(), line.map(|l| format!("line {l}: ")).unwrap_or_default())]
pub struct TrajectoryFileError {
    pub path: PathBuf,
    /// The 1-based line (the header is line 1), where the problem is in one.
    pub line: Option<usize>,
    pub problem: TrajectoryProblem,
}

/// What is wrong in a trajectory CSV.
#[derive(Debug, thiserror::Error)]
pub enum TrajectoryProblem {
    #[error(transparent)]
    Csv(#[from] csv::Error),
    #[error("unknown column \"{0}\" (the columns are t, theta_1 .. theta_n and optionally thetadot_1 .. thetadot_n)")]
    UnknownColumn(String),
    #[error("no column \"{0}\"")]
    NoColumn(&'static str),
    /// A column named twice (which would silently win otherwise).
    #[error("column \"{0}\" is given twice (each column once)")]
    ColumnTwice(String),
    #[error("the {stem}_i columns must be numbered 1 .. n without gaps, got {numbers:?}")]
    Gaps {
        stem: &'static str,
        numbers: Vec<usize>,
    },
    #[error("{theta} theta_i columns but {thetadot} thetadot_i columns")]
    ColumnCounts { theta: usize, thetadot: usize },
    #[error("column \"{column}\" is \"{value}\", not a number")]
    NotANumber { column: String, value: String },
}

/// Why a shard cannot be chosen, written, read or merged.
#[derive(Debug, thiserror::Error)]
pub enum ShardError {
    #[error("the number of shards N must be at least 1")]
    NoShards,
    #[error("shard {k} of {n}: K must be in 1..={n} (K is 1-based)")]
    OutOfRange { k: usize, n: usize },
    #[error("--shard {0}: expected K/N, e.g. 2/8")]
    Syntax(String),
    #[error("--shard {0}: expected K/N with whole numbers, e.g. 2/8")]
    NotWhole(String),
    #[error("environment variable {name}={value} is not a whole number")]
    Environment { name: String, value: String },
    #[error("JOB_COMPLETION_INDEX={index} (a Kubernetes Indexed Job) gives K but not the number of shards N: give --shards N or set DRIFTBENCH_SHARDS=N (the Job's completions)")]
    IndexWithoutCount { index: usize },
    #[error("the Slurm array ({said}) does not tell the number of shards N: only an array of exactly 1-N with N >= 2 does, not one task (a resubmitted one), a part of an array, or a stepped, sparse or 0-based array; give --shards N or set DRIFTBENCH_SHARDS=N")]
    ArrayWithoutCount { said: String },
    #[error("SLURM_ARRAY_TASK_ID={id}: task ids are shard numbers 1..={n} (submit --array=1-{n}; resubmit one task as --array=K)")]
    TaskId { id: usize, n: usize },
    #[error("--shard without K/N reads the scheduler's environment, but neither SLURM_ARRAY_TASK_ID nor JOB_COMPLETION_INDEX is set; give --shard K/N")]
    NoScheduler,
    #[error(transparent)]
    Io(#[from] IoError),
    #[error("{}: {source}", path.display())]
    WriteManifest {
        path: PathBuf,
        source: toml::ser::Error,
    },
    #[error("{}: {source}", path.display())]
    ReadManifest {
        path: PathBuf,
        source: inputs::TomlError,
    },
    /// `shard.toml` refused or unreadable by the input reader (a link outside the shard
    /// directory, a FIFO, over its cap).
    #[error(transparent)]
    Input(#[from] inputs::InputError),
    #[error("{}: `shard = {shard}`, `shards = {shards}`: {source}", path.display())]
    ManifestShard {
        path: PathBuf,
        shard: usize,
        shards: usize,
        source: Box<ShardError>,
    },
    #[error("{}: `runs`, entry {index} \"{entry}\": {problem}", path.display())]
    ManifestRun {
        path: PathBuf,
        index: usize,
        entry: String,
        problem: RunEntryProblem,
    },
    #[error("{}: {source}", path.display())]
    ReadBinding {
        path: PathBuf,
        source: inputs::TomlError,
    },
    #[error("{}: bound to another shard, so nothing was run: {}; one directory serves one shard of one selection: give this shard its own --results-dir, or remove {} if its runs are not wanted", dir.display(), differences.join("; "), dir.display())]
    BoundElsewhere {
        dir: PathBuf,
        differences: Vec<String>,
    },
    #[error("{}: holds {file} but no {}, so which selection it ran cannot be told (a directory of an older version, or not a shard's); nothing was run: give this shard its own --results-dir, or remove the directory", dir.display(), crate::shard::BINDING)]
    Unbound { dir: PathBuf, file: &'static str },
    #[error("{}: no {}: the shard has not finished (run it again; it resumes where it stopped)", dir.display(), crate::shard::MANIFEST)]
    Unfinished { dir: PathBuf },
    #[error("{}: no such directory (give the directories that `reproduce --shard K/N` wrote)", dir.display())]
    NoDirectory { dir: PathBuf },
    #[error(transparent)]
    Integrity(#[from] IntegrityError),
    #[error("{}: no {}: not a shard this version wrote, so its files cannot be checked; run the shard again", dir.display(), crate::integrity::FILE)]
    NoIntegrity { dir: PathBuf },
    #[error("{}: {} file(s) differ from what the shard wrote:\n{}\nrun the shard again, or merge with --accept-edited if the edit is deliberate", dir.display(), mismatches.len(), mismatches.iter().map(|m| format!("  {m}")).collect::<Vec<_>>().join("\n"))]
    Edited {
        dir: PathBuf,
        mismatches: Vec<Mismatch>,
    },
    #[error(transparent)]
    Runs(#[from] RunsError),
    #[error(transparent)]
    Path(#[from] PathError),
    #[error(transparent)]
    Tracked(#[from] TrackedError),
    #[error(transparent)]
    Results(#[from] crate::results_dir::ResultsError),
    #[error("--merge needs at least one shard directory")]
    NoShardDirectories,
    /// The shards do not fit together; every problem, one a line.
    #[error("cannot merge; nothing was written:\n{}", problems.join("\n"))]
    CannotMerge { problems: Vec<String> },
}

/// What is wrong with an entry of a shard manifest's `runs`.
#[derive(Debug, thiserror::Error)]
pub enum RunEntryProblem {
    /// Not a run key, or a part that is no valid id.
    #[error("not a run key: {0}")]
    NotAKey(catalog::run_key::KeyError),
    #[error("belongs to shard {owner}/{n}, not to this shard")]
    OtherShard { owner: usize, n: usize },
    #[error("listed twice")]
    Twice,
}

/// Why `results/dof-cost.csv` could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum DofCostError {
    #[error("{}: {source}", path.display())]
    Csv { path: PathBuf, source: csv::Error },
    #[error(transparent)]
    Io(#[from] IoError),
    #[error(transparent)]
    Table(#[from] TableError),
}

/// Why a result file of the control experiments (`results/control*.csv`, `results/cycles*.csv`,
/// [`crate::control`]) could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum ControlFileError {
    #[error("{}: {source}", path.display())]
    Csv { path: PathBuf, source: csv::Error },
    #[error(transparent)]
    Io(#[from] IoError),
}
