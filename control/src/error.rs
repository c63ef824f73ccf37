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
