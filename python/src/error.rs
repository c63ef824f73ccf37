//! The binding's own error (the library's errors are raised as they are, as
//! `driftbench.DriftbenchError` with the library's message: `lib_err` in the crate root).

/// A solver id that is not among a task's runs.
#[derive(Debug, thiserror::Error)]
#[error("task \"{task}\" has no solver \"{label}\"; its solvers: {}", solvers.join(", "))]
pub struct NoSolver {
    pub task: String,
    pub label: String,
    pub solvers: Vec<String>,
}
