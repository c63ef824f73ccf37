//! Terms as data: the serde form of a composed scheme in an experiment file and its checks
//! (the engine builds the terms: `schemes::build_composed`).
//!
//! ```toml
//! [scheme]
//! kind = "composed"
//! level = "velocity"            # or "acceleration"
//! bounds = "variables"          # default; "rows": every bound as rows of G (zhong2021)
//! name = "my scheme"            # optional display name
//! [[scheme.terms]]
//! kind = "velocity-norm"
//! weight = 1.0
//! [[scheme.terms]]
//! kind = "tracking"
//! k_p = 5.0
//! task = "planar"               # or "position" (default), "pose"; or axes = ["x", "z"]
//! ```
//!
//! Term kinds and fields (defaults after `=`; docs/schemes.md gives each equation):
//! `velocity-norm` (weight = 1), `acceleration-norm` (weight = 1), `repetitive` (lambda, form =
//! "linear" or "sign-power" with alpha in (0, 1], weight = 1, squared = false),
//! `drift-damping` (alpha, beta, weight = 1), `torque-norm` (weight = 1; needs a robot with
//! dynamics), `infinity-norm` (weight = 1, penalty = "squared" or "linear", varpi = +inf), `tracking` (velocity level: k_p = 0;
//! acceleration level: rho_v, rho_p; task = "position", "planar" or "pose" (position and
//! orientation; orientation = a rotation vector, default the start pose's), or axes),
//! `bound-conversion` (gain), `velocity-limits`, `acceleration-limits` (a_max, velocity_gain =
//! none). Unknown kinds and fields are rejected.

use serde::{Deserialize, Serialize};

use crate::scheme::{Level, RepetitiveForm, SchemeError, TermFault};

/// Where a scheme's bounds are written: as the QP's variable bounds or as rows of its
/// inequality matrix G.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BoundPlacement {
    /// As the QP's variable bounds l <= x <= u (jia2019 (2.20), robio2018 (13)).
    #[default]
    Variables,
    /// As rows [I; -I] x <= [u; -l] of G, after the terms' rows (zhong2021 (2.18)).
    Rows,
}

fn one() -> f64 {
    1.0
}

fn is_one(v: &f64) -> bool {
    *v == 1.0
}

fn infinity() -> f64 {
    f64::INFINITY
}

fn is_infinite(v: &f64) -> bool {
    *v == f64::INFINITY
}

fn is_false(v: &bool) -> bool {
    !*v
}

/// A task of the tracking equality.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Task {
    /// The 3-D tool position: x, y and z.
    #[default]
    Position,
    /// The tool position in the x-y plane (a planar arm): x and y.
    Planar,
    /// The tool position (x, y, z) and the tool frame's orientation (three more rows), on a
    /// robot with the orientation capability.
    Pose,
}

/// One axis of the tool position.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// x.
    X,
    /// y.
    Y,
    /// z.
    Z,
}

/// The infinity norm's penalty on its variable s.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Penalty {
    /// w s^2 / 2 (jia2019 (2.17), zhong2021 (2.16)).
    #[default]
    Squared,
    /// w s.
    Linear,
}

impl Penalty {
    fn is_squared(&self) -> bool {
        *self == Penalty::Squared
    }
}

/// One term of a composed scheme, as a file names it (module docs).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum TermSpec {
    /// w |thetadot|^2 / 2 (velocity level).
    VelocityNorm {
        /// Weight w > 0.
        #[serde(default = "one", skip_serializing_if = "is_one")]
        weight: f64,
    },
    /// w |thetaddot|^2 / 2 (acceleration level).
    AccelerationNorm {
        /// Weight w >= 0.
        #[serde(default = "one", skip_serializing_if = "is_one")]
        weight: f64,
    },
    /// q += w g(theta) (and P += w I when squared), velocity level.
    Repetitive {
        /// The form of g.
        #[serde(default, skip_serializing_if = "RepetitiveForm::is_linear")]
        form: RepetitiveForm,
        /// Gain lambda >= 0.
        lambda: f64,
        /// Exponent of the sign-power form, in (0, 1].
        #[serde(default, skip_serializing_if = "Option::is_none")]
        alpha: Option<f64>,
        /// Weight w >= 0.
        #[serde(default = "one", skip_serializing_if = "is_one")]
        weight: f64,
        /// w ||thetadot + g||^2 / 2 (true) or w g'thetadot (false).
        #[serde(default, skip_serializing_if = "is_false")]
        squared: bool,
    },
    /// q += w sigma, zhang2018's drift damping (acceleration level).
    DriftDamping {
        /// Gain alpha > 0.
        alpha: f64,
        /// Gain beta > 0.
        beta: f64,
        /// Weight w >= 0.
        #[serde(default = "one", skip_serializing_if = "is_one")]
        weight: f64,
    },
    /// w |tau|^2 / 2 through the dynamics (acceleration level).
    TorqueNorm {
        /// Weight w >= 0.
        #[serde(default = "one", skip_serializing_if = "is_one")]
        weight: f64,
    },
    /// w s^2 / 2 (or w s) with |thetadot_i| <= s <= varpi (velocity level).
    InfinityNorm {
        /// Weight w >= 0.
        #[serde(default = "one", skip_serializing_if = "is_one")]
        weight: f64,
        /// The penalty: `squared` w s^2 / 2 (default, the papers') or `linear` w s.
        #[serde(default, skip_serializing_if = "Penalty::is_squared")]
        penalty: Penalty,
        /// Upper bound of s (> 0; default +inf).
        #[serde(default = "infinity", skip_serializing_if = "is_infinite")]
        varpi: f64,
    },
    /// The tracking equality, one row per task axis.
    Tracking {
        /// The task (default: the 3-D position); not with `axes`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        task: Option<Task>,
        /// The task axes, explicitly (distinct, at least one); not with `task`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        axes: Option<Vec<Axis>>,
        /// Position gain k_p >= 0 (velocity level; default 0).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        k_p: Option<f64>,
        /// Velocity gain rho_v > 0 (acceleration level).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        rho_v: Option<f64>,
        /// Position gain rho_p > 0 (acceleration level).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        rho_p: Option<f64>,
        /// The pose task's desired orientation as a rotation vector phi_d (rad, world frame;
        /// R_d = exp(skew(phi_d))); absent: the start pose's, R(theta_ref). Only with `task =
        /// "pose"`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        orientation: Option<[f64; 3]>,
    },
    /// The joint-angle limits as velocity bounds (velocity level).
    BoundConversion {
        /// Gain (kappa, upsilon) > 0.
        gain: f64,
    },
    /// The joint-velocity limits as bounds (velocity level).
    VelocityLimits,
    /// The joint-acceleration limits (and the velocity limits converted) as bounds
    /// (acceleration level).
    AccelerationLimits {
        /// The largest joint acceleration a > 0 (rad/s^2).
        a_max: f64,
        /// The conversion gain mu > 0 of the velocity limits (absent: not converted).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        velocity_gain: Option<f64>,
    },
}

/// A scheme of terms, as a file writes it (module docs).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ComposedSpec {
    /// Whether x[..n] is thetadot or thetaddot.
    pub level: Level,
    /// Where the bounds go (default: as variable bounds).
    #[serde(default, skip_serializing_if = "is_variables")]
    pub bounds: BoundPlacement,
    /// Display name (default `composed`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The terms, in order.
    pub terms: Vec<TermSpec>,
}

fn is_variables(b: &BoundPlacement) -> bool {
    *b == BoundPlacement::Variables
}

/// The longest display name.
const NAME_MAX: usize = 60;

impl TermSpec {
    /// The term's `kind` tag.
    pub fn kind(&self) -> &'static str {
        match self {
            TermSpec::VelocityNorm { .. } => "velocity-norm",
            TermSpec::AccelerationNorm { .. } => "acceleration-norm",
            TermSpec::Repetitive { .. } => "repetitive",
            TermSpec::DriftDamping { .. } => "drift-damping",
            TermSpec::TorqueNorm { .. } => "torque-norm",
            TermSpec::InfinityNorm { .. } => "infinity-norm",
            TermSpec::Tracking { .. } => "tracking",
            TermSpec::BoundConversion { .. } => "bound-conversion",
            TermSpec::VelocityLimits => "velocity-limits",
            TermSpec::AccelerationLimits { .. } => "acceleration-limits",
        }
    }

    /// The level the term belongs to (None: both).
    fn level(&self) -> Option<Level> {
        match self {
            TermSpec::VelocityNorm { .. }
            | TermSpec::Repetitive { .. }
            | TermSpec::InfinityNorm { .. }
            | TermSpec::BoundConversion { .. }
            | TermSpec::VelocityLimits => Some(Level::Velocity),
            TermSpec::AccelerationNorm { .. }
            | TermSpec::DriftDamping { .. }
            | TermSpec::TorqueNorm { .. }
            | TermSpec::AccelerationLimits { .. } => Some(Level::Acceleration),
            TermSpec::Tracking { .. } => None,
        }
    }

    /// Checks the term's fields at `level`; `index` is its place in the list.
    fn validate(&self, index: usize, level: Level) -> Result<(), SchemeError> {
        let kind = self.kind();
        if let Some(own) = self.level() {
            if own != level {
                return Err(SchemeError::TermLevel {
                    index,
                    term: kind,
                    level: level_name(level),
                });
            }
        }
        let check = |field: &'static str, value: f64, ok: bool, requirement: &'static str| {
            if value.is_finite() && ok {
                Ok(())
            } else {
                Err(SchemeError::InvalidTerm(Box::new(TermFault {
                    index,
                    term: kind,
                    field,
                    value,
                    requirement,
                })))
            }
        };
        let weight = |w: f64| check("weight", w, w >= 0.0, "finite and >= 0");
        match *self {
            TermSpec::VelocityNorm { weight } => {
                check("weight", weight, weight > 0.0, "finite and > 0")
            }
            TermSpec::AccelerationNorm { weight: w } | TermSpec::TorqueNorm { weight: w } => {
                weight(w)
            }
            TermSpec::Repetitive {
                form,
                lambda,
                alpha,
                weight: w,
                ..
            } => {
                weight(w)?;
                check(
                    "lambda",
                    lambda,
                    lambda >= 0.0,
                    "finite and >= 0 (0: no term)",
                )?;
                match (form, alpha) {
                    (RepetitiveForm::SignPower, Some(a)) => {
                        check("alpha", a, a > 0.0 && a <= 1.0, "in (0, 1]")
                    }
                    (RepetitiveForm::SignPower, None) => check(
                        "alpha",
                        f64::NAN,
                        false,
                        "given, in (0, 1], for form = \"sign-power\"",
                    ),
                    (RepetitiveForm::Linear, Some(a)) => check(
                        "alpha",
                        a,
                        false,
                        "absent for form = \"linear\" (it has no exponent)",
                    ),
                    (RepetitiveForm::Linear, None) => Ok(()),
                }
            }
            TermSpec::DriftDamping {
                alpha,
                beta,
                weight: w,
            } => {
                weight(w)?;
                check("alpha", alpha, alpha > 0.0, "finite and > 0")?;
                check("beta", beta, beta > 0.0, "finite and > 0")
            }
            TermSpec::InfinityNorm {
                weight: w, varpi, ..
            } => {
                weight(w)?;
                let v = if varpi == f64::INFINITY { 1.0 } else { varpi };
                check("varpi", v, v > 0.0, "> 0 (default +inf: no bound)")
            }
            TermSpec::Tracking {
                task,
                ref axes,
                k_p,
                rho_v,
                rho_p,
                orientation,
            } => {
                if let Some(phi) = orientation {
                    if task != Some(Task::Pose) {
                        return Err(SchemeError::OrientationWithoutPose { index });
                    }
                    for v in phi {
                        check(
                            "orientation",
                            v,
                            true,
                            "a rotation vector of three finite entries (rad)",
                        )?;
                    }
                }
                if let Some(axes) = axes {
                    let requirement = if task.is_some() {
                        Some("not both: give task or axes")
                    } else if axes.is_empty() {
                        Some("at least one of \"x\", \"y\", \"z\"")
                    } else if (1..axes.len()).any(|i| axes[..i].contains(&axes[i])) {
                        Some("distinct axes")
                    } else {
                        None
                    };
                    if let Some(requirement) = requirement {
                        return Err(SchemeError::InvalidAxes { index, requirement });
                    }
                }
                match level {
                    Level::Velocity => {
                        if let Some((field, v)) =
                            rho_v.map(|v| ("rho_v", v)).or(rho_p.map(|v| ("rho_p", v)))
                        {
                            return check(
                                field,
                                v,
                                false,
                                "absent at the velocity level (use k_p)",
                            );
                        }
                        let k_p = k_p.unwrap_or(0.0);
                        check("k_p", k_p, k_p >= 0.0, "finite and >= 0 (0: no feedback)")
                    }
                    Level::Acceleration => {
                        if let Some(k) = k_p {
                            return check(
                                "k_p",
                                k,
                                false,
                                "absent at the acceleration level (use rho_v, rho_p)",
                            );
                        }
                        let rho_v = rho_v.unwrap_or(f64::NAN);
                        check("rho_v", rho_v, rho_v > 0.0, "given, finite and > 0")?;
                        let rho_p = rho_p.unwrap_or(f64::NAN);
                        check("rho_p", rho_p, rho_p > 0.0, "given, finite and > 0")
                    }
                }
            }
            TermSpec::BoundConversion { gain } => check("gain", gain, gain > 0.0, "finite and > 0"),
            TermSpec::VelocityLimits => Ok(()),
            TermSpec::AccelerationLimits {
                a_max,
                velocity_gain,
            } => {
                check("a_max", a_max, a_max > 0.0, "finite and > 0 (rad/s^2)")?;
                match velocity_gain {
                    Some(mu) => check(
                        "velocity_gain",
                        mu,
                        mu > 0.0,
                        "finite and > 0 (absent: no conversion)",
                    ),
                    None => Ok(()),
                }
            }
        }
    }
}

/// The task axes of a tracking term (indices into x, y, z): `axes` when given, else those of
/// `task` (x, y for `planar`; x, y, z for `position`, the default).
pub fn tracking_axes(task: Option<Task>, axes: &Option<Vec<Axis>>) -> Vec<usize> {
    match (task, axes) {
        (_, Some(axes)) => axes.iter().map(|a| *a as usize).collect(),
        (Some(Task::Planar), None) => vec![0, 1],
        (Some(Task::Position | Task::Pose) | None, None) => vec![0, 1, 2],
    }
}

/// The level's name in a file.
fn level_name(level: Level) -> &'static str {
    match level {
        Level::Velocity => "velocity",
        Level::Acceleration => "acceleration",
    }
}

impl ComposedSpec {
    /// Checks the name and every term (at least one; each of the scheme's level, its fields in
    /// range).
    pub fn validate(&self) -> Result<(), SchemeError> {
        if let Some(name) = &self.name {
            let ok = !name.trim().is_empty()
                && name.len() <= NAME_MAX
                && name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || " -_.()=+".contains(c));
            if !ok {
                return Err(SchemeError::InvalidName { max: NAME_MAX });
            }
        }
        if self.terms.is_empty() {
            return Err(SchemeError::NoTerms);
        }
        for (index, term) in self.terms.iter().enumerate() {
            term.validate(index, self.level)?;
        }
        Ok(())
    }

    /// Whether a term reads a dynamics model (torque-norm).
    pub fn needs_dynamics(&self) -> bool {
        self.terms
            .iter()
            .any(|t| matches!(t, TermSpec::TorqueNorm { .. }))
    }

    /// The display name: `name`, or `composed`.
    pub fn display_name(&self) -> String {
        self.name.clone().unwrap_or_else(|| "composed".to_string())
    }
}
