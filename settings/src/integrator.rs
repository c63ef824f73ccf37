//! How an experiment integrates its runs: the method ([`Method`]) and its tolerances, step
//! limits and budgets ([`IntegratorSettings`]), as experiment files write them. The integrator
//! itself is crate `solvers`' (`solvers::ode`): the papers' group integrated everything with
//! MATLAB's `ode15s` (RelTol 1e-6, AbsTol 1e-8), whose method is diffsol's [`Method::Bdf`] (the
//! default here).

use crate::error::IntegratorError;

/// Integration method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Variable-order BDF/NDF (ode15s's method), stiff.
    Bdf,
    /// ESDIRK3(4), stiff, one-step.
    Esdirk34,
    /// TR-BDF2, stiff, one-step (ode23tb's method).
    TrBdf2,
    /// Dormand-Prince 5(4), explicit (ode45's method).
    Dopri5,
    /// Tsitouras 5(4), explicit.
    Tsit45,
}

impl Method {
    /// The method's name in experiment files and results (`bdf`, `tr-bdf2`, ...).
    pub fn label(self) -> &'static str {
        match self {
            Method::Bdf => "bdf",
            Method::Esdirk34 => "esdirk34",
            Method::TrBdf2 => "tr-bdf2",
            Method::Dopri5 => "dopri5",
            Method::Tsit45 => "tsit45",
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.label())
    }
}

/// Method and tolerances (mixed error test |e_i| <= rtol |y_i| + atol).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorSettings {
    /// The integration method.
    pub method: Method,
    /// Relative tolerance (ode15s's RelTol).
    pub rtol: f64,
    /// Absolute tolerance (ode15s's AbsTol).
    pub atol: f64,
    /// Accepted steps after which the run is abandoned as diverging.
    #[serde(default = "default_max_steps")]
    pub max_steps: usize,
    /// Wall-time budget of one integration in seconds: a run past it fails with that reason,
    /// so no input can keep the binary busy for good (default `DEFAULT_MAX_WALL_S`).
    #[serde(default = "default_max_wall_s")]
    pub max_wall_s: f64,
    /// Evaluation budget: right-hand-side evaluations (finite-difference Jacobian columns
    /// included) after which the run fails with that reason (default `DEFAULT_MAX_RHS_EVALS`;
    /// never more than [`RHS_EVALS_PER_SECOND`] per second of the span integrated,
    /// [`IntegratorSettings::rhs_budget`]).
    #[serde(default = "default_max_rhs_evals")]
    pub max_rhs_evals: usize,
    /// Largest step (ode15s's `MaxStep`; the group's code: 0.05 s). `None` (the default):
    /// unlimited. Must be positive and finite.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_step: Option<f64>,
}

impl IntegratorSettings {
    /// Checks what the integrator itself needs: 0 < `rtol` < 1, a positive finite `atol`,
    /// `max_steps` >= 1 and a positive, finite `max_step` where given. Each message names the
    /// field and its valid range.
    pub fn validate(&self) -> Result<(), IntegratorError> {
        let rtol = self.rtol;
        if !(rtol > 0.0 && rtol < 1.0) {
            return Err(IntegratorError::Rtol(rtol));
        }
        let atol = self.atol;
        if !(atol > 0.0 && atol.is_finite()) {
            return Err(IntegratorError::Atol(atol));
        }
        if self.max_steps == 0 {
            return Err(IntegratorError::NoSteps);
        }
        if self.max_rhs_evals == 0 {
            return Err(IntegratorError::NoRhsEvals);
        }
        if !(self.max_wall_s > 0.0 && self.max_wall_s.is_finite()) {
            return Err(IntegratorError::WallBudget(self.max_wall_s));
        }
        match self.max_step {
            Some(h) if !(h > 0.0 && h.is_finite()) => Err(IntegratorError::MaxStep(h)),
            _ => Ok(()),
        }
    }
}

impl IntegratorSettings {
    /// The evaluation budget of an integration over `span` seconds: `max_rhs_evals`, and at
    /// most [`RHS_EVALS_PER_SECOND`] per second of the span (at least one second's).
    pub fn rhs_budget(&self, span: f64) -> usize {
        let scaled = (RHS_EVALS_PER_SECOND * span.max(1.0)).ceil();
        // A NaN or infinite span leaves `max_rhs_evals` alone (`as` saturates).
        self.max_rhs_evals.min(scaled as usize)
    }
}

fn default_max_steps() -> usize {
    2_000_000
}

/// The default wall-time budget of one integration (s): generous, 30x the longest run of the
/// papers' experiments on a 2-core machine.
pub const DEFAULT_MAX_WALL_S: f64 = 600.0;

fn default_max_wall_s() -> f64 {
    DEFAULT_MAX_WALL_S
}

/// The default evaluation budget: 20x the heaviest run of the papers' experiments (the
/// finite-time network, ~5 million).
pub const DEFAULT_MAX_RHS_EVALS: usize = 100_000_000;

/// The evaluation budget per second of the span integrated, besides `max_rhs_evals`
/// ([`IntegratorSettings::rhs_budget`]): 15x the heaviest of the suite's committed integrations
/// (the explanation ladder's finite-time network at ESDIRK3(4), RelTol 1e-10: 68,000 per second
/// of its path) and twice a stiff network integrated by an explicit method (kong2019's
/// finite-time network under Dormand-Prince 5(4), RelTol 1e-6: ~480,000 per second), so that a
/// run whose integrator stalls (a degenerate scheme weight makes the optimum chatter between
/// vertices, each evaluation a Clarabel solve of ~10 us) ends as a failed run within seconds per
/// second of its path, not after `max_wall_s`.
pub const RHS_EVALS_PER_SECOND: f64 = 1_000_000.0;

fn default_max_rhs_evals() -> usize {
    DEFAULT_MAX_RHS_EVALS
}

impl Default for IntegratorSettings {
    /// ode15s with the papers' group tolerances (RelTol 1e-6, AbsTol 1e-8).
    fn default() -> Self {
        Self {
            method: Method::Bdf,
            rtol: 1e-6,
            atol: 1e-8,
            max_steps: default_max_steps(),
            max_wall_s: DEFAULT_MAX_WALL_S,
            max_rhs_evals: DEFAULT_MAX_RHS_EVALS,
            max_step: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_evaluation_budget_scales_with_the_span() {
        let s = IntegratorSettings::default();
        let per_second = RHS_EVALS_PER_SECOND as usize;
        assert_eq!(s.rhs_budget(5.0), 5 * per_second);
        assert_eq!(s.rhs_budget(0.01), per_second);
        let small = IntegratorSettings {
            max_rhs_evals: 50,
            ..s
        };
        assert_eq!(small.rhs_budget(5.0), 50);
        assert_eq!(s.rhs_budget(f64::INFINITY), DEFAULT_MAX_RHS_EVALS);
        assert_eq!(s.rhs_budget(1e6), DEFAULT_MAX_RHS_EVALS);
    }
}
