//! A per-instant QP solver as a run's solver, as experiment files name it:
//!
//! ```toml
//! numerical = [{ method = "94lvi" }, { method = "m5", tolerance = 1e-3, step = 1e-3 }]
//! numerical = [{ method = "active-set" }, { method = "clarabel" }]
//! ```
//!
//! `method` is any registered QP solver's id (crate `settings`' `qp_solver`: robio2018's six
//! PLPE methods, `active-set`, `clarabel`, `osqp`, or an outside solver registered through
//! `solvers::registry::register`), `tolerance` and `max_iterations` its typed settings, checked
//! at load against the ranges the solver declares (a setting it does not take is an error);
//! `step` is the run's sampling gap h.
//!
//! A numerical run follows robio2018's Algorithm 1 at every sampling instant t_k = k h of a
//! fixed-step loop: the scheme's QP at (t_k, theta_k) is solved by the solver, started from
//! what it left at the previous instant (a PLPE method iterates U <- U - rho(U) Q e(U),
//! robio2018 (21), from the previous U until |e(U)|_2 <= `tolerance`, default 1e-3 as in
//! robio2018 Algorithm 1, step 3), and the arm moves on with the first n entries of the answer
//! held over the step: theta_{k+1} = theta_k + h thetadot_k. The run's drift therefore includes
//! the solver's own error. The solvers themselves are crate `solvers`'; this file only names
//! them and their settings.

use serde::{Deserialize, Serialize};
use settings::qp_solver::{QpSolverError, QpSolverKey, QpSolverSettings};

/// Sampling gap h of the fixed-step loop (s); the paper does not print one (report/deviations.md).
pub const DEFAULT_STEP: f64 = 1e-3;

fn default_step() -> f64 {
    DEFAULT_STEP
}

/// One numerical run solver of a variant (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NumericalSpec {
    /// The solver, by its registered id (`method = "94lvi"`).
    pub method: QpSolverKey,
    /// The solver's stopping tolerance (the PLPE methods': |e(U)|_2 <= tolerance).
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// Fail the instant (and the run) after this many iterations.
    #[serde(default)]
    pub max_iterations: Option<u32>,
    /// Sampling gap h of the fixed-step loop (s).
    #[serde(default = "default_step")]
    pub step: f64,
}

/// A [`NumericalSpec`] field out of its range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NumericalSpecError {
    /// A setting the solver does not take, or out of the range it declares.
    #[error(transparent)]
    Settings(#[from] QpSolverError),
    /// `step` is not a positive finite number no longer than the path.
    #[error("numerical {method}: step = {value} must be finite, > 0 and at most the path's duration {duration}")]
    Step {
        /// The solver's id.
        method: &'static str,
        /// The step given (s).
        value: f64,
        /// The path's duration (s).
        duration: f64,
    },
    /// The run would take more than `MAX_STEPS` sampling instants.
    #[error("numerical {method}: {steps} steps of {step} s exceed the cap of {cap} per run")]
    TooManySteps {
        /// The solver's id.
        method: &'static str,
        /// The step (s).
        step: f64,
        /// The instants it needs: ceil(duration / step).
        steps: f64,
        /// The cap, `MAX_STEPS`.
        cap: f64,
    },
}

/// Most sampling instants one numerical run may take (a bound on its work).
pub const MAX_STEPS: f64 = 1e7;

impl NumericalSpec {
    /// The solver's settings as given.
    pub fn settings(&self) -> QpSolverSettings {
        QpSolverSettings {
            tolerance: self.tolerance,
            max_iterations: self.max_iterations,
        }
    }

    /// The settings completed with the solver's defaults ([`QpSolverInfo::resolve`]), or why
    /// they do not fit it.
    ///
    /// [`QpSolverInfo::resolve`]: settings::qp_solver::QpSolverInfo::resolve
    pub fn resolved(&self) -> Result<QpSolverSettings, QpSolverError> {
        self.method.info().resolve(&self.settings())
    }

    /// The spec with the settings in effect written out (the solver's defaults filled in, as
    /// [`NumericalSpec::resolved`] gives them), or why they do not fit the solver.
    pub fn with_defaults(&self) -> Result<NumericalSpec, QpSolverError> {
        let settings = self.resolved()?;
        Ok(NumericalSpec {
            tolerance: settings.tolerance,
            max_iterations: settings.max_iterations,
            ..*self
        })
    }

    /// The stopping tolerance the run uses: the one given or the solver's default; `None` for
    /// a solver that takes none.
    pub fn tolerance_in_effect(&self) -> Option<f64> {
        self.tolerance
            .or(self.method.info().tolerance.map(|l| l.default))
    }

    /// The solver's id in run keys: the method's id, with each setting given that differs from
    /// the solver's default appended (`94lvi`, `94lvi-h-0.0001`, `m5-tol-1e-6-h-0.01`), so that
    /// one variant can run a method at several settings.
    pub fn id(&self) -> String {
        let info = self.method.info();
        let mut id = self.method.id().to_string();
        if let Some(t) = self.tolerance {
            if info.tolerance.map(|l| l.default) != Some(t) {
                id.push_str(&format!("-tol-{t:e}"));
            }
        }
        if let Some(m) = self.max_iterations {
            if info.max_iterations.map(|l| l.default) != Some(m) {
                id.push_str(&format!("-iter-{m}"));
            }
        }
        if self.step != DEFAULT_STEP {
            id.push_str(&format!("-h-{}", self.step));
        }
        id
    }

    /// The solver's label in tables (display only): its name with its tolerance and a step that
    /// is not the default, e.g. `94LVI (|e| <= 0.001)`, `Clarabel`, `Clarabel (h = 0.01 s)`.
    pub fn display_name(&self) -> String {
        let info = self.method.info();
        let mut parts = Vec::new();
        if let Some(t) = self.tolerance_in_effect() {
            parts.push(format!("|e| <= {t}"));
        }
        if self.step != DEFAULT_STEP {
            parts.push(format!("h = {} s", self.step));
        }
        if parts.is_empty() {
            info.name.to_string()
        } else {
            format!("{} ({})", info.name, parts.join(", "))
        }
    }

    /// Checks the settings (against the solver's declared ranges) for a path of `duration`
    /// seconds.
    pub fn validate(&self, duration: f64) -> Result<(), NumericalSpecError> {
        self.resolved()?;
        let method = self.method.id();
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
    use settings::qp_solver::BUILTIN;

    fn parse(text: &str) -> Result<NumericalSpec, toml::de::Error> {
        toml::from_str(text)
    }

    #[test]
    fn ids_round_trip_and_bad_settings_are_refused() {
        for info in BUILTIN {
            let spec = parse(&format!("method = \"{}\"", info.id)).unwrap();
            assert_eq!(spec.method.id(), info.id);
            assert_eq!(spec.id(), info.id);
            assert!(spec.validate(15.0).is_ok());
        }
        let unknown = parse("method = \"m7\"").unwrap_err();
        assert!(unknown.to_string().contains("94lvi"), "{unknown}");
        assert!(parse("method = \"m3\"\ntolerence = 1e-3").is_err());
        let spec = |tolerance: f64, step: f64| NumericalSpec {
            tolerance: Some(tolerance),
            max_iterations: Some(10),
            step,
            ..parse("method = \"m4\"").unwrap()
        };
        assert!(spec(f64::NAN, 1e-3).validate(15.0).is_err());
        assert!(spec(0.0, 1e-3).validate(15.0).is_err());
        for tolerance in [1e-300, 1e-15, 2.0] {
            let e = spec(tolerance, 1e-3).validate(15.0).unwrap_err();
            assert!(e.to_string().contains("must be within [1e-12, 1e0]"), "{e}");
        }
        let absurd = NumericalSpec {
            max_iterations: Some(4_000_000_000),
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
        assert_eq!(spec(1e-3, 1e-3).display_name(), "M4 (|e| <= 0.001)");
        let clarabel = parse("method = \"clarabel\"\nstep = 0.01").unwrap();
        assert_eq!(clarabel.display_name(), "Clarabel (h = 0.01 s)");
        let e = parse("method = \"clarabel\"\ntolerance = 1e-6")
            .unwrap()
            .validate(15.0)
            .unwrap_err();
        assert!(
            e.to_string().contains("takes no setting `tolerance`"),
            "{e}"
        );
    }
}
