//! The binary's errors: each lower crate's error wrapped as it is (its message names the file,
//! line or field), and the few the command line itself finds: a thread count, paper,
//! experiment or table no file knows, a gate baseline that cannot be read, a results directory
//! the report cannot go beside. Each error is of one kind ([`ReproduceError::exit`]), and each
//! kind has its exit code ([`Exit`], docs/reference/exit-codes.md).

use settings::shown;
use std::path::PathBuf;
use std::process::ExitCode;
use store::integrity::IntegrityError;
use store::journal::JournalError;
use store::results_dir::ResultsError;
use store::shard::ShardError;
use store::PathError;
use store::TrackedError;
use store::{IoAction, IoError, RunsError};

/// How `reproduce` ended: one exit code per outcome (docs/reference/exit-codes.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// 0: everything ran as the experiment files say; the gate found no difference.
    Success,
    /// 1: a run failed that no experiment file expects.
    UnexpectedFailure,
    /// 2: an input or usage error (a file, an option or an argument refused).
    Input,
    /// 3: the regression gate (`check`) found a difference.
    GateDifference,
    /// 4: the system refused to write, remove or lock a file the program owns (a full disk,
    /// a read-only file system).
    Io,
    /// 70 (`EX_SOFTWARE` of sysexits.h): a fault of the program itself (a worker pool that
    /// cannot start, a lock poisoned by a panicking thread).
    Internal,
}

impl Exit {
    /// The process's exit status.
    pub const fn code(self) -> u8 {
        match self {
            Exit::Success => 0,
            Exit::UnexpectedFailure => 1,
            Exit::Input => 2,
            Exit::GateDifference => 3,
            Exit::Io => 4,
            Exit::Internal => 70,
        }
    }
}

impl From<Exit> for ExitCode {
    fn from(exit: Exit) -> Self {
        ExitCode::from(exit.code())
    }
}

/// Why `reproduce` stopped (printed as `error: ...`; the exit code is its kind's,
/// [`ReproduceError::exit`]).
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
    #[error("unknown paper {} (known: {})", shown(paper), known.join(", "))]
    UnknownPaper { paper: String, known: Vec<String> },
    /// `--experiment` names no experiment.
    #[error("unknown experiment {} (known: {})", shown(experiment), known.join(", "))]
    UnknownExperiment {
        experiment: String,
        known: Vec<String>,
    },
    /// `infer` selects no published table.
    #[error("infer {}: no such table (known: all, a paper, or one of {})", shown(which), known.join(", "))]
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
        .0.join(store::results_dir::RUNS).display()
    )]
    BaselineIsDirectory(PathBuf),
    /// The file given as `--baseline` cannot be read as runs.
    #[error("--baseline: {0}")]
    GivenBaseline(#[source] BaselineError),
    /// The gate's default baseline cannot be read as runs.
    #[error(transparent)]
    Baseline(#[from] BaselineError),
    #[error(transparent)]
    Root(#[from] catalog::RootNotFound),
    #[error(transparent)]
    Experiments(#[from] catalog::ExperimentFileError),
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
    Explain(#[from] explain::ExplainError),
    #[error(transparent)]
    Inference(#[from] explain::InferenceError),
    #[error(transparent)]
    Report(#[from] presentation::ReportError),
    #[error(transparent)]
    TaskCard(#[from] crate::task_card::TaskCardError),
    #[error(transparent)]
    Score(#[from] ScoreError),
    #[error(transparent)]
    Control(#[from] control::ControlError),
    /// The control experiments' standard task set cannot be read (`catalog::load_task_set`).
    #[error(transparent)]
    TaskSet(#[from] catalog::TaskSetError),
    #[error(transparent)]
    Timing(#[from] crate::timing::TimingError),
    #[error(transparent)]
    ThreadPool(#[from] rayon::ThreadPoolBuildError),
    #[error(transparent)]
    DofCost(#[from] store::DofCostError),
}

impl ReproduceError {
    /// The kind of this error as an exit code: [`Exit::Io`] where the system refused to write,
    /// remove or lock a file, [`Exit::Internal`] for a fault of the program, [`Exit::Input`]
    /// for everything else (a file, option or argument refused, named in the message).
    pub fn exit(&self) -> Exit {
        match self {
            ReproduceError::ThreadPool(_) | ReproduceError::Journal(JournalError::Poisoned) => {
                Exit::Internal
            }
            ReproduceError::Io(e) | ReproduceError::Journal(JournalError::Io(e)) => io(e),
            ReproduceError::Runs(e) => runs(e),
            ReproduceError::Results(e) | ReproduceError::Journal(JournalError::Results(e)) => {
                results(e)
            }
            ReproduceError::Tracked(e) | ReproduceError::Journal(JournalError::Tracked(e)) => {
                tracked(e)
            }
            ReproduceError::Journal(JournalError::Csv { .. }) => Exit::Io,
            ReproduceError::Path(e) | ReproduceError::Journal(JournalError::Path(e)) => path(e),
            ReproduceError::Report(e) => report(e),
            ReproduceError::Score(ScoreError::Io(e)) => io(e),
            _ => Exit::Input,
        }
    }
}

/// A file operation: writing or removing is the system's refusal ([`Exit::Io`]); reading,
/// listing or opening is an input that is not there or not readable ([`Exit::Input`]).
fn io(e: &IoError) -> Exit {
    match e.action {
        IoAction::Write | IoAction::Remove => Exit::Io,
        IoAction::Read | IoAction::List | IoAction::Open => Exit::Input,
    }
}

fn runs(e: &RunsError) -> Exit {
    match e {
        RunsError::Write { .. } | RunsError::NotWritable { .. } => Exit::Io,
        RunsError::Io(e) => io(e),
        RunsError::Table { .. } | RunsError::Rows { .. } => Exit::Input,
    }
}

fn results(e: &ResultsError) -> Exit {
    match e {
        ResultsError::Lock { .. } | ResultsError::Write { .. } => Exit::Io,
        ResultsError::Io(e) => io(e),
        ResultsError::Read(e) => runs(e),
        ResultsError::Tracked(e) => tracked(e),
        ResultsError::Path(e) => path(e),
        _ => Exit::Input,
    }
}

/// A directory the program owns that the system would not create or open is an I/O failure; a
/// path refused (not a plain name, a link leading out) is an input error.
fn path(e: &PathError) -> Exit {
    match e {
        PathError::Open { .. } => Exit::Io,
        _ => Exit::Input,
    }
}

fn tracked(e: &TrackedError) -> Exit {
    match e {
        TrackedError::Io { .. }
        | TrackedError::Integrity(IntegrityError::Write { .. } | IntegrityError::Stream { .. }) => {
            Exit::Io
        }
        TrackedError::Path(e) => path(e),
        _ => Exit::Input,
    }
}

fn report(e: &presentation::ReportError) -> Exit {
    use presentation::ReportError;
    match e {
        ReportError::Io(e) => io(e),
        ReportError::Runs(e) => runs(e),
        ReportError::Tracked(e) => tracked(e),
        _ => Exit::Input,
    }
}

/// Why a trajectory could not be scored on a task, or its files written.
#[derive(Debug, thiserror::Error)]
pub enum ScoreError {
    #[error(transparent)]
    Experiments(#[from] catalog::ExperimentFileError),
    #[error(
        "no task {} (a task is \"<experiment> / <variant>\", ids; `reproduce list` lists them)",
        shown(.0)
    )]
    NoTask(String),
    #[error(transparent)]
    Trajectory(#[from] inputs::trajectory::ReadError),
    /// (The scoring error boxed: it is large.)
    #[error("{}: {error} (task {})", file.display(), shown(task))]
    Score {
        file: std::path::PathBuf,
        task: String,
        error: Box<simulation::TrajectoryError>,
    },
    #[error(transparent)]
    Table(#[from] records::table::TableError),
    #[error("{}: {source}", path.display())]
    Csv {
        path: std::path::PathBuf,
        source: csv::Error,
    },
    #[error(transparent)]
    Io(#[from] store::IoError),
    #[error(transparent)]
    Figure(#[from] presentation::FigureError),
    #[error(transparent)]
    Path(#[from] store::PathError),
    #[error("--name {}: a scored trajectory's name is its solver id, a slug (lower-case letters, digits, `.` and `-`, at most {max} bytes), e.g. {}", shown(name), shown(suggestion))]
    Name {
        name: String,
        suggestion: String,
        max: usize,
    },
    #[error("--name {}: the exact column's solver id is reserved (a scored trajectory would pass for the exact optimum); use another name, e.g. \"trajectory\"", shown(name))]
    ReservedName { name: String },
    /// The task's row under this name holds another file's score.
    #[error("{}: the row of task {} named {} holds the score of another file ({}); give this one its own --name, or another --out", scores.display(), shown(task), shown(name), shown(holder))]
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
        source: store::MigrateError,
    },
    #[error("{name}: {source}")]
    Table {
        name: String,
        source: records::table::TableError,
    },
    #[error("{name}: {source}")]
    Rows {
        name: String,
        source: records::RowsError,
    },
}
