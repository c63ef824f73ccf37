//! Why a case could not be prepared for timing.

use settings::NetworkError;
use simulation::RunError;
use spec::PathError;
use spec::SchemeError;

#[derive(Debug, thiserror::Error)]
pub enum CostError {
    /// There is no n-link arm of this many joints (`robots::nlink`: 2 to 1000).
    #[error("there is no n-link arm of {0} joints (robots::nlink: 2 to 1000)")]
    NotRegistered(usize),
    #[error("{label}: {error}")]
    Path { label: String, error: PathError },
    #[error("{label}: {error}")]
    Scheme { label: String, error: SchemeError },
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
