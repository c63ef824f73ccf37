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
    File(#[from] catalog::error::ExperimentFileError),
    /// A task's scheme could not be built to read its QP's sizes.
    #[error("task \"{task}\": {source}")]
    Shape {
        task: String,
        source: catalog::error::SetupError,
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
