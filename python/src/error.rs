//! The binding's own errors (the library's errors are raised as they are, as
//! `driftbench.DriftbenchError` with the library's message: `lib_err` in the crate root).

use std::path::PathBuf;

/// A solver id that is not among a task's runs.
#[derive(Debug, thiserror::Error)]
#[error("task \"{task}\" has no solver \"{label}\"; its solvers: {}", solvers.join(", "))]
pub struct NoSolver {
    pub task: String,
    pub label: String,
    pub solvers: Vec<String>,
}

/// The tasks of a project root could not be read.
#[derive(Debug, thiserror::Error)]
pub enum TaskError {
    /// An experiment file is missing, unreadable or refused.
    #[error(transparent)]
    File(#[from] catalog::ExperimentFileError),
    /// A task's scheme could not be built to read its QP's sizes.
    #[error("task \"{task}\": {source}")]
    Shape {
        task: String,
        source: spec::SetupError,
    },
}

/// A `root=` that is not a project root.
#[derive(Debug, thiserror::Error)]
pub enum RootError {
    #[error(
        "root={}: no experiments/ folder there; root= names a driftbench checkout (or a \
         directory with experiments/*.toml), or leave it out to use the data the package carries",
        root.display()
    )]
    NoExperiments { root: PathBuf },
    #[error(
        "root={}: experiments/ holds no experiment file (*.toml); root= names a driftbench \
         checkout (or a directory with experiments/*.toml), or leave it out to use the data the \
         package carries",
        root.display()
    )]
    NoFiles { root: PathBuf },
}

/// An id of `tasks=` (or of `task`) that names no task of the set.
#[derive(Debug, thiserror::Error)]
#[error("no {set}task \"{id}\" (ids are \"<experiment> / <variant>\"); valid ids: {}", valid.join(", "))]
pub struct UnknownTask {
    pub id: String,
    /// "" for every task, "standard " for the standard task set.
    pub set: &'static str,
    pub valid: Vec<String>,
}

/// An `out_dir=` that is, or lies inside, a directory driftbench seals with a manifest.
#[derive(Debug, thiserror::Error)]
#[error(
    "out_dir={}: the files go into a directory of their own, not into {} (sealed by driftbench's \
     manifest.toml: results/, report/ or a shard; a script puts a table into results/ with \
     driftbench.into_results)",
    out.display(),
    sealed.display()
)]
pub struct SealedOutDir {
    pub out: PathBuf,
    pub sealed: PathBuf,
}

/// A panic inside the library: a bug (no input should reach one), raised as
/// `DriftbenchError` rather than pyo3's `PanicException`, which `except Exception` misses.
#[derive(Debug, thiserror::Error)]
#[error("an internal error of driftbench (a bug, please report it): {message}")]
pub struct Panicked {
    pub message: String,
}

impl Panicked {
    /// The panic's message, from the payload `catch_unwind` returned.
    pub fn from_payload(payload: &(dyn std::any::Any + Send)) -> Self {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic without a message".to_string());
        Panicked { message }
    }
}

/// A table `into_results` could not seal into `results/`.
#[derive(Debug, thiserror::Error)]
pub enum IntoResultsError {
    #[error(
        "{}: into_results takes the tables the package's scripts write, by file name: {}",
        file.display(),
        valid.join(", ")
    )]
    Name {
        file: PathBuf,
        valid: Vec<&'static str>,
    },
    #[error(transparent)]
    Read(#[from] inputs::InputError),
    #[error("{}: not a table of its schema: {source}", file.display())]
    Table {
        file: PathBuf,
        source: records::table::TableError,
    },
    /// A text of the table holds markup or a line break (its content is not quoted).
    #[error("{}: line {line}, column `{column}`: holds HTML, a Markdown link or a line break; names reach the report as they are", file.display())]
    Markup {
        file: PathBuf,
        line: usize,
        column: &'static str,
    },
    #[error(transparent)]
    Results(#[from] store::results_dir::ResultsError),
    #[error(transparent)]
    Tracked(#[from] store::TrackedError),
}
