//! The simulation layer's errors: why a run failed, typed. The error of each layer a run passes
//! through (building its parts: `spec::SetupError`; the exact QP; the integrator) is
//! wrapped by [`RunError`], and its [`FailureKind`] (records' type) is the `failure_kind`
//! column of `results/runs.csv`. The message (the `failure` column) is the error's `Display`.

use records::FailureKind;
use solvers::ode::OdeError;
use solvers::ExactError;
use spec::SetupError;

/// Why a run stopped before its path's end.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RunError {
    /// A part of the job could not be built.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The exact QP at instant t had no solution.
    #[error("exact QP at t = {t:.6}: {error}")]
    ExactQp {
        /// The instant (s).
        t: f64,
        /// The exact solver's error.
        error: ExactError,
    },
    /// The observer stopped a diverging run (see `observer::DIVERGENCE_FACTOR`).
    #[error("stopped at t = {t:.6}: {reason}")]
    Diverged {
        /// The time of the step it stopped at (s).
        t: f64,
        /// Which bound was exceeded, and by what.
        reason: String,
    },
    /// The integrator stopped.
    #[error(transparent)]
    Integration(#[from] OdeError),
    /// A numerical run used up its iteration budget
    /// (`numerical::ITERATIONS_PER_SECOND` per second of the path's duration) by the
    /// instant t.
    #[error("numerical method at t = {t:.6}: iteration budget of {budget} iterations ({} per second of the path's duration) used up", crate::numerical::ITERATIONS_PER_SECOND)]
    IterationBudget {
        /// The instant (s).
        t: f64,
        /// The run's budget (iterations).
        budget: u64,
    },
    /// A numerical run's QP solver failed at the instant t.
    #[error("numerical method at t = {t:.6}: {message}")]
    Numerical {
        /// The instant (s).
        t: f64,
        /// How the solve ended ([`qp::QpStatus`]).
        status: qp::QpStatus,
        /// The solver's own error, as text (it is open: any type an outside solver has).
        message: String,
    },
}

impl RunError {
    /// The category of this failure.
    pub fn kind(&self) -> FailureKind {
        match self {
            RunError::Setup(_) => FailureKind::Setup,
            RunError::ExactQp { .. } => FailureKind::ExactQp,
            RunError::Diverged { .. } => FailureKind::Diverged,
            RunError::Numerical { .. } => FailureKind::NumericalMethod,
            RunError::IterationBudget { .. } => FailureKind::EvalBudget,
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
