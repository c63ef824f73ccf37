//! Why a case could not be prepared for timing.

use schemes::paths::PathError;
use settings::error::NetworkError;
use simulation::error::RunError;

#[derive(Debug, thiserror::Error)]
pub enum CostError {
    /// The fixed-size path was asked for an N the registry has no `NLink<N>` for.
    #[error("nlink-{0} is not in the registry (NLINK_SIZES); the dynamic path measures it")]
    NotRegistered(usize),
    /// The dynamic path was asked for a scheme it does not build (jia2019).
    #[error("{0}: the dynamic-size path builds the QP of kong2019 (22) only")]
    NoDynamicScheme(&'static str),
    #[error("an n-link arm has at least 3 joints, not {0}")]
    TooFewJoints(usize),
    #[error("{label}: {error}")]
    Path { label: String, error: PathError },
    #[error("{label}: {error}")]
    Network { label: String, error: NetworkError },
    #[error("{label}: the exact run does not start: {error}")]
    Run { label: String, error: RunError },
    #[error("{0}: the exact run left no trace")]
    NoTrace(String),
    /// The network needs dQP/dt at the states and none was given.
    #[error("{0}: the network needs dQP/dt at the states, and none was given")]
    NeedsQpDot(String),
}
