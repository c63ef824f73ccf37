//! The errors of the control experiments.

use solvers::lvi_numerical::LviError;
use solvers::osqp_qp::OsqpError;
use solvers::ExactError;

/// Why a control run, or the whole reproduction, could not go on.
#[derive(Debug, thiserror::Error)]
pub enum ControlError {
    #[error("experiment files: {0}")]
    Experiments(String),
    #[error("task {0} is not in the experiment files")]
    UnknownTask(String),
    #[error("task {task}: {message}")]
    Setup { task: String, message: String },
    #[error(transparent)]
    Lvi(#[from] LviError),
    #[error(transparent)]
    Osqp(#[from] OsqpError),
    #[error("exact solver: {0}")]
    Exact(#[from] ExactError),
    #[error("{path}: {source}")]
    Csv { path: String, source: csv::Error },
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
}
