//! The errors of the control experiments: [`ControlError`] wraps the simulation layer's
//! (a task that cannot be built), the solvers' (networks, LVI, OSQP, the exact QP) and the records
//! layer's (the result files).

use settings::NetworkError;
use solvers::{ExactError, QpSolverError};
use store::ControlFileError;

/// Why a control run, or the whole reproduction, could not go on.
#[derive(Debug, thiserror::Error)]
pub enum ControlError {
    #[error("task {0} is not in the experiment files")]
    UnknownTask(String),
    /// A network whose parameters make no valid solver id.
    #[error(transparent)]
    Id(#[from] spec::ids::IdError),
    /// The standard task set file is refused by the input reader (a link out of the
    /// experiments directory, not a regular file, over its cap, not UTF-8; the error names the
    /// path).
    #[error(transparent)]
    TaskSetFile(#[from] inputs::InputError),
    /// The standard task set file is not valid TOML or not a task set (`path` names it; the
    /// error gives line and column, never the file's text).
    #[error("{path}: {source}")]
    TaskSet {
        path: String,
        source: inputs::TomlError,
    },
    /// The project declares no standard task set (a project of its own papers may have none).
    #[error("{0} does not exist: the project declares no control task set")]
    NoTaskSet(String),
    #[error("{0}: the task set lists no [[task]]")]
    EmptyTaskSet(String),
    /// A field of the task set's `[budget]` is out of its range (`valid` says what it may be;
    /// the value is not quoted).
    #[error("{path}: [budget] {field} must be {valid}")]
    Budget {
        path: String,
        field: &'static str,
        valid: &'static str,
    },
    #[error("task {task}: {message}")]
    Setup { task: String, message: String },
    /// The task's network could not be built (`task` names the network).
    #[error("task {task}: {error}")]
    Network { task: String, error: NetworkError },
    /// A numerical QP method's solve at a tick.
    #[error(transparent)]
    Solver(#[from] QpSolverError),
    /// A numerical method's solver cannot be built (the registry's error).
    #[error(transparent)]
    Registry(#[from] solvers::registry::RegistryError),
    #[error("exact solver: {0}")]
    Exact(#[from] ExactError),
    /// A result file could not be written.
    #[error(transparent)]
    Results(#[from] ControlFileError),
}
