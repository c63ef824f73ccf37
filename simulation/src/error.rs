//! The simulation layer's errors: why a run failed, typed. The error of each layer a run passes
//! through (building its parts: the catalog's `SetupError`; the exact QP; the integrator) is
//! wrapped by [`RunError`], and its [`FailureKind`] is the `failure_kind` column of
//! `results/runs.csv`. The message (the `failure` column) is the error's `Display`.

use catalog::error::SetupError;
use serde::{Deserialize, Serialize};
use solvers::ode::OdeError;
use solvers::ExactError;

/// What stopped a run, as a category a table can be grouped by.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FailureKind {
    /// The run could not be built (robot, path, scheme or network).
    Setup,
    /// The exact QP had no solution (infeasible, or the solver failed).
    ExactQp,
    /// A joint velocity or the state left the stated divergence bounds.
    Diverged,
    /// The state became NaN or infinite.
    NonFinite,
    /// The integrator gave up (step size underflow, Newton failure).
    Integrator,
    /// More than `max_steps` accepted steps.
    StepLimit,
    /// The wall-time budget (`max_wall_s`) ran out.
    WallTime,
    /// The right-hand-side evaluation budget (`max_rhs_evals`) ran out.
    EvalBudget,
}

/// Why a run stopped before its path's end.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RunError {
    /// A part of the job could not be built.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The exact QP at instant t had no solution.
    #[error("exact QP at t = {t:.6}: {error}")]
    ExactQp { t: f64, error: ExactError },
    /// The observer stopped a diverging run (see `simulate::DIVERGENCE_FACTOR`).
    #[error("stopped at t = {t:.6}: {reason}")]
    Diverged { t: f64, reason: String },
    /// The integrator stopped.
    #[error(transparent)]
    Integration(#[from] OdeError),
}

impl RunError {
    /// The category of this failure.
    pub fn kind(&self) -> FailureKind {
        match self {
            RunError::Setup(_) => FailureKind::Setup,
            RunError::ExactQp { .. } => FailureKind::ExactQp,
            RunError::Diverged { .. } => FailureKind::Diverged,
            RunError::Integration(e) => match e {
                OdeError::Solver { .. } | OdeError::Stopped { .. } => FailureKind::Integrator,
                OdeError::NonFinite { .. } => FailureKind::NonFinite,
                OdeError::TooManySteps { .. } => FailureKind::StepLimit,
                OdeError::WallBudget { .. } => FailureKind::WallTime,
                OdeError::EvalBudget { .. } => FailureKind::EvalBudget,
            },
        }
    }
}
