//! The binary's errors: each lower crate's error wrapped as it is (its message names the file,
//! line or field), and the few the command line itself finds: a thread count, paper,
//! experiment or table no file knows, a gate baseline that cannot be read, a results directory
//! the report cannot go beside.

use records::error::{IoError, RunsError};
use records::journal::JournalError;
use records::owned_dir::PathError;
use records::results_dir::ResultsError;
use records::shard::ShardError;
use records::tracked_dir::TrackedError;
use std::path::PathBuf;

/// Why `reproduce` stopped (printed as `error: ...`, exit code 2).
#[derive(Debug, thiserror::Error)]
pub enum ReproduceError {
    /// `--threads` beyond `per_core` (`project::MAX_THREADS_PER_CORE`) per core.
    #[error("--threads {threads}: at most {max} ({per_core} per core; this machine has {cores})")]
    TooManyThreads {
        threads: u64,
        max: usize,
        per_core: usize,
        cores: usize,
    },
    /// `--paper` names no experiment file's paper.
    #[error("unknown paper \"{paper}\" (known: {})", known.join(", "))]
    UnknownPaper { paper: String, known: Vec<String> },
    /// `--experiment` names no experiment.
    #[error("unknown experiment \"{experiment}\" (known: {})", known.join(", "))]
    UnknownExperiment {
        experiment: String,
        known: Vec<String>,
    },
    /// `--infer` selects no published table.
    #[error("--infer {which}: no such table (known: all, a paper, or one of {})", known.join(", "))]
    UnknownTable { which: String, known: Vec<String> },
    /// The report is written beside a results directory named `results` only.
    #[error(
        "the report needs a results directory named `results` (got {}); use --dry-run for a scratch run",
        .0.display()
    )]
    ResultsNotNamedResults(PathBuf),
    /// `--baseline` names a directory.
    #[error(
        "--baseline {}: is a directory; give a runs.csv file (e.g. {})",
        .0.display(),
        .0.join(records::results_dir::RUNS).display()
    )]
    BaselineIsDirectory(PathBuf),
    /// The file given as `--baseline` cannot be read as runs.
    #[error("--baseline: {0}")]
    GivenBaseline(#[source] BaselineError),
    /// The gate's default baseline cannot be read as runs.
    #[error(transparent)]
    Baseline(#[from] BaselineError),
    #[error(transparent)]
    Root(#[from] catalog::root::RootNotFound),
    #[error(transparent)]
    Experiments(#[from] catalog::error::ExperimentFileError),
    #[error(transparent)]
    Shard(#[from] ShardError),
    #[error(transparent)]
    Results(#[from] ResultsError),
    #[error(transparent)]
    Journal(#[from] JournalError),
    #[error(transparent)]
    Runs(#[from] RunsError),
    #[error(transparent)]
    Io(#[from] IoError),
    #[error(transparent)]
    Tracked(#[from] TrackedError),
    #[error(transparent)]
    Path(#[from] PathError),
    #[error(transparent)]
    Papers(#[from] analysis::papers::PapersError),
    #[error(transparent)]
    Explain(#[from] explain::error::ExplainError),
    #[error(transparent)]
    Inference(#[from] explain::error::InferenceError),
    #[error(transparent)]
    Report(#[from] presentation::error::ReportError),
    #[error(transparent)]
    TaskCard(#[from] crate::task_card::TaskCardError),
    #[error(transparent)]
    Score(#[from] ScoreError),
    #[error(transparent)]
    Control(#[from] control::ControlError),
    #[error(transparent)]
    Timing(#[from] crate::timing::TimingError),
    #[error(transparent)]
    ThreadPool(#[from] rayon::ThreadPoolBuildError),
    #[error(transparent)]
    DofCost(#[from] records::error::DofCostError),
}

/// Why a trajectory could not be scored on a task, or its files written.
#[derive(Debug, thiserror::Error)]
pub enum ScoreError {
    #[error(transparent)]
    Experiments(#[from] catalog::error::ExperimentFileError),
    #[error(
        "no task \"{0}\" (a task is \"<experiment> / <variant>\", ids; `reproduce --list` lists them)"
    )]
    NoTask(String),
    #[error(transparent)]
    Trajectory(#[from] records::trajectory_file::ReadError),
    /// (The scoring error boxed: it is large.)
    #[error("{}: {error} (task \"{task}\")", file.display())]
    Score {
        file: std::path::PathBuf,
        task: String,
        error: Box<simulation::score_trajectory::TrajectoryError>,
    },
    #[error(transparent)]
    Table(#[from] records::table::TableError),
    #[error("{}: {source}", path.display())]
    Csv {
        path: std::path::PathBuf,
        source: csv::Error,
    },
    #[error(transparent)]
    Io(#[from] records::error::IoError),
    #[error(transparent)]
    Figure(#[from] presentation::error::FigureError),
    #[error(transparent)]
    Path(#[from] records::owned_dir::PathError),
    #[error("--name {name:?}: a scored trajectory's name is its solver id, a slug (lower-case letters, digits, `.` and `-`, at most {max} bytes), e.g. {suggestion:?}")]
    Name {
        name: String,
        suggestion: String,
        max: usize,
    },
    #[error("--name {name:?}: the exact column's solver id is reserved (a scored trajectory would pass for the exact optimum); use another name, e.g. \"trajectory\"")]
    ReservedName { name: String },
    /// The task's row under this name holds another file's score.
    #[error("{}: the row of task \"{task}\" named {name:?} holds the score of another file ({holder}); give this one its own --name, or another --out", scores.display())]
    Taken {
        scores: std::path::PathBuf,
        task: String,
        name: String,
        holder: String,
    },
    #[error("{}: the scores go into a directory of their own, not into {} (sealed by this program's manifest.toml: results/, report/ or a shard)", out.display(), sealed.display())]
    Sealed {
        out: std::path::PathBuf,
        sealed: std::path::PathBuf,
    },
}

/// Why a gate baseline's rows cannot be used; each names the file (or `git HEAD:...`).
#[derive(Debug, thiserror::Error)]
pub enum BaselineError {
    /// Refused or unreadable by the input reader (it names the file).
    #[error(transparent)]
    Read(#[from] inputs::InputError),
    #[error("{name}: {source}")]
    Migrate {
        name: String,
        source: records::migrate::MigrateError,
    },
    #[error("{name}: {source}")]
    Table {
        name: String,
        source: records::table::TableError,
    },
    #[error("{name}: {source}")]
    Rows {
        name: String,
        source: records::error::RowsError,
    },
}
