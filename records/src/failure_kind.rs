//! The `failure_kind` column of `results/runs.csv`: what stopped a run, as a category a table
//! can be grouped by (kebab-case in the file: `setup`, `exact-qp`, `diverged`, `non-finite`,
//! `integrator`, `step-limit`, `wall-time`, `eval-budget`, `numerical-method`, `network`; empty for a
//! completed run). The engine (`simulation::RunError::kind`) says which category each of its
//! errors is; `network` is the Python package's (`python/`), for a network whose own code failed.

use serde::{Deserialize, Serialize};

/// What stopped a run.
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
    /// The right-hand-side evaluation budget (`max_rhs_evals`), a numerical run's iteration
    /// budget, or the exact path's Clarabel budget ran out.
    EvalBudget,
    /// A numerical run solver did not meet its stopping rule at an instant (iteration limit,
    /// a singular matrix its rule inverts, or a non-finite iterate).
    NumericalMethod,
    /// A network written in Python raised an exception in one of its methods, or returned a
    /// result that is not a finite real array of its state's size (the Python package's
    /// leaderboard records such an entry's run as failed and goes on).
    Network,
}

impl FailureKind {
    /// The column's text, as `runs.csv` stores it (`diverged`, `wall-time`, ...).
    pub fn id(self) -> &'static str {
        match self {
            FailureKind::Setup => "setup",
            FailureKind::ExactQp => "exact-qp",
            FailureKind::Diverged => "diverged",
            FailureKind::NonFinite => "non-finite",
            FailureKind::Integrator => "integrator",
            FailureKind::StepLimit => "step-limit",
            FailureKind::WallTime => "wall-time",
            FailureKind::EvalBudget => "eval-budget",
            FailureKind::NumericalMethod => "numerical-method",
            FailureKind::Network => "network",
        }
    }
}

impl std::fmt::Display for FailureKind {
    /// [`FailureKind::id`]: messages name a kind as the file stores it.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The text a message shows is the column's own (serde's kebab-case), for every kind.
    #[test]
    fn the_shown_kind_is_the_stored_one() {
        for k in [
            FailureKind::Setup,
            FailureKind::ExactQp,
            FailureKind::Diverged,
            FailureKind::NonFinite,
            FailureKind::Integrator,
            FailureKind::StepLimit,
            FailureKind::WallTime,
            FailureKind::EvalBudget,
            FailureKind::NumericalMethod,
            FailureKind::Network,
        ] {
            let stored = toml::Value::try_from(k).unwrap();
            assert_eq!(stored.as_str(), Some(k.id()));
            assert_eq!(k.to_string(), k.id());
        }
    }
}
