//! Numerical QP methods as run solvers, as experiment files name them:
//!
//! ```toml
//! numerical = [{ method = "94lvi" }, { method = "m5", tolerance = 1e-3, step = 1e-3 }]
//! ```
//!
//! A numerical run follows robio2018's Algorithm 1 at every sampling instant t_k = k h of a
//! fixed-step loop: the scheme's QP at (t_k, theta_k) is written as its piecewise-linear
//! projection equation e(U) = 0 (robio2018 (20)), the method iterates U <- U - rho(U) Q e(U)
//! (robio2018 (21)) from the previous instant's U (a warm start; U = 0 at t = 0) until
//! |e(U)|_2 <= `tolerance` (robio2018 Algorithm 1, step 3: 1e-3), and the arm moves on with the
//! first n entries of U held over the step: theta_{k+1} = theta_k + h thetadot_k. The run's
//! drift therefore includes the method's own error. The methods themselves are crate
//! `solvers`' (`solvers::lvi_numerical`); this file only names them and their settings.

use serde::{Deserialize, Serialize};

/// robio2018's stopping rule |e(U)|_2 <= 1e-3 (Algorithm 1, step 3).
pub const DEFAULT_TOLERANCE: f64 = 1e-3;
/// Iterations after which one instant's solve fails (the run then fails with that reason).
pub const DEFAULT_MAX_ITERATIONS: u32 = 100_000;
/// Sampling gap h of the fixed-step loop (s); the paper does not print one (report/deviations.md).
pub const DEFAULT_STEP: f64 = 1e-3;
/// The range of `tolerance`: [`MIN_TOLERANCE`, `MAX_TOLERANCE`]. Below 1e-12 the residual
/// |e(U)|_2 of a QP of the papers' sizes (entries of order 1, at most a few hundred) is within
/// a few hundred rounding errors of its own computation and may never be reached; above 1 the
/// "solution" is not one.
pub const MIN_TOLERANCE: f64 = 1e-12;
/// The largest `tolerance` ([`MIN_TOLERANCE`]).
pub const MAX_TOLERANCE: f64 = 1.0;
/// The largest `max_iterations` of one instant: 10x the default. The run as a whole is bounded
/// besides by its iteration budget (`simulation::numerical`), scaled from its duration.
pub const MAX_MAX_ITERATIONS: u32 = 1_000_000;

/// The six methods of robio2018 (22)-(27), by the ids experiment files use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum NumericalMethod {
    /// robio2018 (22).
    #[serde(rename = "94lvi")]
    Lvi94,
    /// robio2018 (23).
    #[serde(rename = "e47")]
    E47,
    /// robio2018 (24).
    #[serde(rename = "m3")]
    M3,
    /// robio2018 (25).
    #[serde(rename = "m4")]
    M4,
    /// robio2018 (26).
    #[serde(rename = "m5")]
    M5,
    /// robio2018 (27).
    #[serde(rename = "m6")]
    M6,
}

impl NumericalMethod {
    /// Every method, in the paper's order.
    pub const ALL: [NumericalMethod; 6] = [
        NumericalMethod::Lvi94,
        NumericalMethod::E47,
        NumericalMethod::M3,
        NumericalMethod::M4,
        NumericalMethod::M5,
        NumericalMethod::M6,
    ];

    /// The id in experiment files, run keys and results (`94lvi`, `e47`, `m3`, ...).
    pub fn id(self) -> &'static str {
        match self {
            NumericalMethod::Lvi94 => "94lvi",
            NumericalMethod::E47 => "e47",
            NumericalMethod::M3 => "m3",
            NumericalMethod::M4 => "m4",
            NumericalMethod::M5 => "m5",
            NumericalMethod::M6 => "m6",
        }
    }

    /// The name the paper prints (`94LVI`, `E47`, `M3`, ...): display only.
    pub fn name(self) -> &'static str {
        match self {
            NumericalMethod::Lvi94 => "94LVI",
            NumericalMethod::E47 => "E47",
            NumericalMethod::M3 => "M3",
            NumericalMethod::M4 => "M4",
            NumericalMethod::M5 => "M5",
            NumericalMethod::M6 => "M6",
        }
    }
}

fn default_tolerance() -> f64 {
    DEFAULT_TOLERANCE
}
fn default_max_iterations() -> u32 {
    DEFAULT_MAX_ITERATIONS
}
fn default_step() -> f64 {
    DEFAULT_STEP
}

/// One numerical run solver of a variant (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NumericalSpec {
    /// The method, by its id (`method = "94lvi"`).
    pub method: NumericalMethod,
    /// Stop one instant's iteration at |e(U)|_2 <= tolerance.
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Fail the instant (and the run) after this many iterations.
    #[serde(default = "default_max_iterations")]
    pub max_iterations: u32,
    /// Sampling gap h of the fixed-step loop (s).
    #[serde(default = "default_step")]
    pub step: f64,
}

/// A [`NumericalSpec`] field out of its range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NumericalSpecError {
    /// `tolerance` is outside [[`MIN_TOLERANCE`], [`MAX_TOLERANCE`]].
    #[error("numerical {method}: tolerance = {value:e} must be within [{MIN_TOLERANCE:e}, {MAX_TOLERANCE:e}]")]
    Tolerance {
        /// The method's name as robio2018 prints it.
        method: &'static str,
        /// The tolerance given.
        value: f64,
    },
    /// `max_iterations` is outside [1, [`MAX_MAX_ITERATIONS`]].
    #[error(
        "numerical {method}: max_iterations = {value} must be within [1, {MAX_MAX_ITERATIONS}]"
    )]
    MaxIterations {
        /// The method's name as robio2018 prints it.
        method: &'static str,
        /// The cap given.
        value: u32,
    },
    /// `step` is not a positive finite number no longer than the path.
    #[error("numerical {method}: step = {value} must be finite, > 0 and at most the path's duration {duration}")]
    Step {
        /// The method's name as robio2018 prints it.
        method: &'static str,
        /// The step given (s).
        value: f64,
        /// The path's duration (s).
        duration: f64,
    },
    /// The run would take more than [`MAX_STEPS`] sampling instants.
    #[error("numerical {method}: {steps} steps of {step} s exceed the cap of {cap} per run")]
    TooManySteps {
        /// The method's name as robio2018 prints it.
        method: &'static str,
        /// The step (s).
        step: f64,
        /// The instants it needs: ceil(duration / step).
        steps: f64,
        /// The cap, [`MAX_STEPS`].
        cap: f64,
    },
}

/// Most sampling instants one numerical run may take (a bound on its work).
pub const MAX_STEPS: f64 = 1e7;

impl NumericalSpec {
    /// The solver's id in run keys: the method's id, with each setting that differs from its
    /// default appended (`94lvi`, `94lvi-h-0.0001`, `m5-tol-1e-6-h-0.01`), so that one variant
    /// can run a method at several settings.
    pub fn id(&self) -> String {
        let mut id = self.method.id().to_string();
        if self.tolerance != DEFAULT_TOLERANCE {
            id.push_str(&format!("-tol-{:e}", self.tolerance));
        }
        if self.max_iterations != DEFAULT_MAX_ITERATIONS {
            id.push_str(&format!("-iter-{}", self.max_iterations));
        }
        if self.step != DEFAULT_STEP {
            id.push_str(&format!("-h-{}", self.step));
        }
        id
    }

    /// The solver's label in tables (display only), e.g. `94LVI (|e| <= 0.001)`.
    pub fn display_name(&self) -> String {
        let h = if self.step == DEFAULT_STEP {
            String::new()
        } else {
            format!(", h = {} s", self.step)
        };
        format!("{} (|e| <= {}{h})", self.method.name(), self.tolerance)
    }

    /// Checks the settings for a path of `duration` seconds.
    pub fn validate(&self, duration: f64) -> Result<(), NumericalSpecError> {
        let method = self.method.name();
        if !(MIN_TOLERANCE..=MAX_TOLERANCE).contains(&self.tolerance) {
            return Err(NumericalSpecError::Tolerance {
                method,
                value: self.tolerance,
            });
        }
        if !(1..=MAX_MAX_ITERATIONS).contains(&self.max_iterations) {
            return Err(NumericalSpecError::MaxIterations {
                method,
                value: self.max_iterations,
            });
        }
        if !(self.step.is_finite() && self.step > 0.0 && self.step <= duration) {
            return Err(NumericalSpecError::Step {
                method,
                value: self.step,
                duration,
            });
        }
        let steps = (duration / self.step).ceil();
        if steps > MAX_STEPS {
            return Err(NumericalSpecError::TooManySteps {
                method,
                step: self.step,
                steps,
                cap: MAX_STEPS,
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_round_trip_and_bad_settings_are_refused() {
        for m in NumericalMethod::ALL {
            let text = format!("method = \"{}\"", m.id());
            let spec: NumericalSpec = toml::from_str(&text).unwrap();
            assert_eq!(spec.method, m);
            assert_eq!(spec.tolerance, DEFAULT_TOLERANCE);
            assert!(spec.validate(15.0).is_ok());
        }
        let unknown = toml::from_str::<NumericalSpec>("method = \"m7\"").unwrap_err();
        assert!(unknown.to_string().contains("94lvi"), "{unknown}");
        let typo = toml::from_str::<NumericalSpec>("method = \"m3\"\ntolerence = 1e-3");
        assert!(typo.is_err());
        let spec = |tolerance: f64, step: f64| NumericalSpec {
            method: NumericalMethod::M4,
            tolerance,
            max_iterations: 10,
            step,
        };
        assert!(spec(f64::NAN, 1e-3).validate(15.0).is_err());
        assert!(spec(0.0, 1e-3).validate(15.0).is_err());
        // Outside the documented ranges: a tolerance below 1e-12 or above 1, an iteration
        // cap over 10^6.
        for tolerance in [1e-300, 1e-15, 2.0] {
            let e = spec(tolerance, 1e-3).validate(15.0).unwrap_err();
            assert!(e.to_string().contains("must be within [1e-12, 1e0]"), "{e}");
        }
        let absurd = NumericalSpec {
            max_iterations: 4_000_000_000,
            ..spec(1e-6, 1e-3)
        };
        let e = absurd.validate(15.0).unwrap_err();
        assert!(
            e.to_string()
                .contains("max_iterations = 4000000000 must be within [1, 1000000]"),
            "{e}"
        );
        assert!(spec(1e-3, 0.0).validate(15.0).is_err());
        assert!(spec(1e-3, 20.0).validate(15.0).is_err());
        assert!(spec(1e-3, 1e-9).validate(15.0).is_err());
        assert!(spec(1e-3, 1e-3).validate(15.0).is_ok());
        assert_eq!(spec(1e-3, 1e-4).id(), "m4-iter-10-h-0.0001");
        let plain: NumericalSpec = toml::from_str("method = \"e47\"").unwrap();
        assert_eq!(plain.id(), "e47");
    }
}
