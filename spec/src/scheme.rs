//! Schemes as data: the serde form experiment files use, its checks and the term lists it
//! expands to (the engine builds the scheme: `schemes::build_scheme`).
//!
//! ```toml
//! [scheme]
//! kind = "vltco"              # or cmco, hl-jdf, finite-time-rmp, znn-rmp (presets), or
//!                             # velocity-rmp (the vocabulary's composed scheme)
//! phi = 0.2
//! tau = 0.4
//! kappa = 20.0
//! lambda = 20.0
//! ```
//!
//! Field names follow the papers: jia2019 (phi, tau, kappa, lambda = Lambda), zhong2021 (eta,
//! delta, upsilon, lambda = Lambda, default 20 as in every zhong2021 run), zhang2018 (zeta,
//! alpha, beta, rho_v, rho_p), kong2019 finite time (beta_theta, k_p, alpha), kong2019 ZNN (mu,
//! k_p). Unknown fields are rejected.
//!
//! Every kind is a preset: it expands to a list of terms ([`SchemeSpec::expand`],
//! [`crate::TermSpec`]) and every scheme is the one composed scheme (`schemes::composed`);
//! `kind = "composed"` lists the terms itself ([`ComposedSpec`], [`crate::TermSpec`]).
//!
//! `velocity-rmp` is the velocity-level template (docs/schemes.md): `weight` (w of the velocity norm, default 1),
//! `repetitive = "linear"` (default; g = lambda (theta - theta_ref)) or `"sign-power"` (g =
//! lambda |e|^alpha sgn(e), with `alpha`), `lambda` (>= 0; 0 drops the term), `k_p` (tracking
//! feedback, default 0) and `upsilon` (the bound conversion of the joint limits, robio2018 (10);
//! absent: no bounds). Kinds are named for what they
//! are; the papers' names are accepted as aliases: `jia2019` (= `vltco`), `zhong2021`
//! (`cmco`), `zhang2018` (`hl-jdf`), `kong2019-finite-time` (`finite-time-rmp`),
//! `kong2019-znn` (`znn-rmp`).
//!
//! The RMP term's linear coefficient has three readings ([`RmpReading`], see [`crate::rmp`]):
//! jia2019 takes `rmp = "printed"` (default, g = tau Lambda (theta - theta0)), `"expansion"`
//! (tau Lambda / 2, jia2019 (2.11) with Lambda = 2 mu) or `"text-mu"` (tau mu) with `mu`
//! (default 5, the text's value); zhong2021 takes the same readings (`"text-tau"` is accepted for
//! `"text-mu"`) with its gain `tau` of c = tau (theta - theta0) (default 10 = Lambda / 2 at the
//! papers' Lambda = 20, from zhong2021 (2.10)'s Lambda = 2 tau; the paper gives no value).
//! Both fields are optional and left out when serialised at their defaults.

use std::fmt;

use serde::{Deserialize, Serialize};

use crate::rmp::RmpReading;
use crate::terms::{BoundPlacement, ComposedSpec, Penalty, TermSpec};

/// Whether the scheme resolves redundancy at the velocity or the acceleration level (in a
/// file: `velocity`, `acceleration`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Level {
    /// x[..n] = thetadot; the arm state is theta.
    Velocity,
    /// x[..n] = thetaddot; the arm state is (theta, thetadot).
    Acceleration,
}

fn default_zhong_lambda() -> f64 {
    20.0
}

/// jia2019's mu = 5 (text after jia2019 (2.9)).
fn default_jia_mu() -> f64 {
    5.0
}

fn is_default_jia_mu(mu: &f64) -> bool {
    *mu == default_jia_mu()
}

/// zhong2021's tau of c = tau (theta - theta0): Lambda / 2 = 10 at Lambda = 20 (zhong2021 (2.10)).
fn default_zhong_tau() -> f64 {
    10.0
}

fn is_default_zhong_tau(tau: &f64) -> bool {
    *tau == default_zhong_tau()
}

/// A scheme and its parameters, as an experiment file names them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum SchemeSpec {
    /// jia2019 (2.17)-(2.20): MVN (phi = 1, tau = 0), MVN-INVM (0.2, 0), VLTCO (0.2, 0.4).
    /// Expands to velocity-norm (phi), repetitive (squared, weight tau), tracking,
    /// infinity-norm (1 - phi - tau) and bound-conversion (kappa). Alias `jia2019`.
    #[serde(alias = "jia2019")]
    Vltco {
        /// Weight phi of the velocity norm (the tri-criteria w_v), jia2019 (2.17); >= 0, with
        /// phi + tau <= 1.
        phi: f64,
        /// Weight tau of the repetitive term (the tri-criteria w_r), jia2019 (2.17); >= 0, with
        /// phi + tau <= 1.
        tau: f64,
        /// Gain kappa (> 0) of the conversion of the joint-angle limits into velocity bounds,
        /// jia2019 (2.15)-(2.16).
        kappa: f64,
        /// Repetitive gain Lambda (> 0) of g = tau Lambda (theta - theta0) as printed,
        /// jia2019 (2.17).
        lambda: f64,
        /// Reading of the RMP coefficient (default `printed`: tau Lambda).
        #[serde(default, skip_serializing_if = "RmpReading::is_printed")]
        rmp: RmpReading,
        /// The text's gain mu of C = mu (theta - theta0), used by `rmp = "text-mu"`.
        #[serde(default = "default_jia_mu", skip_serializing_if = "is_default_jia_mu")]
        mu: f64,
    },
    /// zhong2021 (2.16)-(2.18): jia2019's terms with eta, delta, upsilon, and every bound as
    /// rows of G (`bounds = "rows"`). Alias `zhong2021`.
    #[serde(alias = "zhong2021")]
    Cmco {
        /// Weight eta of the velocity norm (the tri-criteria w_v), zhong2021 (2.16); >= 0, with
        /// eta + delta <= 1.
        eta: f64,
        /// Weight delta of the repetitive term (the tri-criteria w_r), zhong2021 (2.16); >= 0, with
        /// eta + delta <= 1.
        delta: f64,
        /// Gain upsilon (> 0) of the conversion of the joint-angle limits into velocity bounds,
        /// zhong2021 (2.14)-(2.15).
        upsilon: f64,
        /// Repetitive gain Lambda (> 0) of c = delta Lambda (theta - theta0) as printed,
        /// zhong2021 (2.16); default 20, as in every zhong2021 run.
        #[serde(default = "default_zhong_lambda")]
        lambda: f64,
        /// Reading of the RMP coefficient (default `printed`: delta Lambda).
        #[serde(default, skip_serializing_if = "RmpReading::is_printed")]
        rmp: RmpReading,
        /// The text's gain tau of c = tau (theta - theta0), used by `rmp = "text-mu"`
        /// (or `"text-tau"`).
        #[serde(
            default = "default_zhong_tau",
            skip_serializing_if = "is_default_zhong_tau"
        )]
        tau: f64,
    },
    /// zhang2018 (2.5)-(2.6), HL-JDF (MTN when zeta = 0): acceleration level, expands to
    /// acceleration-norm (zeta), drift-damping (zeta, alpha, beta), torque-norm (1 - zeta) and
    /// tracking (rho_v, rho_p). Alias `zhang2018`.
    #[serde(alias = "zhang2018")]
    HlJdf {
        /// Weight zeta in [0, 1] of the velocity criterion against the torque criterion,
        /// W = zeta I + (1 - zeta) H^2, zhang2018 (2.5): 0 is MTN, 1 MVN.
        zeta: f64,
        /// Drift gain alpha (> 0) of sigma = (alpha + beta) thetadot + alpha beta (theta - theta0),
        /// zhang2018 (2.5).
        alpha: f64,
        /// Drift gain beta (> 0) of sigma, zhang2018 (2.5) (see `alpha`).
        beta: f64,
        /// Velocity feedback gain rho_v (> 0) of b's rho_v (rdot* - J thetadot), zhang2018 (2.6).
        rho_v: f64,
        /// Position feedback gain rho_p (> 0) of b's rho_p (r* - f(theta)), zhang2018 (2.6).
        rho_p: f64,
    },
    /// kong2019 (14), the finite-time repeatable scheme: velocity-norm, sign-power repetitive
    /// term, tracking with k_p. Alias `kong2019-finite-time`.
    #[serde(alias = "kong2019-finite-time")]
    FiniteTimeRmp {
        /// Gain beta_theta (> 0) of the sign-power repetitive term
        /// beta_theta |e|^alpha sgn(e), e = theta - theta_ref, kong2019 (14).
        beta_theta: f64,
        /// Position feedback gain k_p of b = rdot* + k_p (r* - f(theta)) (>= 0; 0: none).
        k_p: f64,
        /// Exponent alpha of the sign-power term (> 0; the paper takes 0 < alpha < 1).
        alpha: f64,
    },
    /// kong2019 (22), the ZNN repetitive baseline: velocity-norm, linear repetitive term
    /// (lambda = mu), tracking with k_p. Alias `kong2019-znn`.
    #[serde(alias = "kong2019-znn")]
    ZnnRmp {
        /// Gain mu of the linear repetitive term mu (theta - theta_ref), kong2019 (22) (>= 0;
        /// 0: no repetitive term).
        mu: f64,
        /// Position feedback gain k_p of b = rdot* + k_p (r* - f(theta)) (>= 0; 0: none).
        k_p: f64,
    },
    /// The velocity-level template: velocity-norm (weight), repetitive (lambda), tracking
    /// (k_p) and bound-conversion (upsilon) when given; robio2018's RMP (11)-(13).
    VelocityRmp {
        /// Weight w of the velocity norm (P = w I).
        #[serde(default = "one", skip_serializing_if = "is_one")]
        weight: f64,
        /// Form of the repetitive term.
        #[serde(default, skip_serializing_if = "RepetitiveForm::is_linear")]
        repetitive: RepetitiveForm,
        /// Gain lambda of the repetitive term (0: none).
        lambda: f64,
        /// Exponent alpha of the sign-power form (ignored by the linear form).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        alpha: Option<f64>,
        /// Position feedback gain k_p (default 0: b = rdot*).
        #[serde(default, skip_serializing_if = "is_zero")]
        k_p: f64,
        /// Gain upsilon of the bound conversion robio2018 (10) (absent: no bounds).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        upsilon: Option<f64>,
    },
    /// A scheme of its own terms ([`ComposedSpec`]).
    Composed(ComposedSpec),
}

/// The form of the repetitive term ([`crate::TermSpec::Repetitive`]; the engine's term
/// is `schemes::terms::repetitive`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RepetitiveForm {
    /// g = lambda (theta - theta_ref).
    #[default]
    Linear,
    /// g = lambda |e|^alpha sgn(e), e = theta - theta_ref.
    SignPower,
}

impl RepetitiveForm {
    pub(crate) fn is_linear(&self) -> bool {
        *self == RepetitiveForm::Linear
    }
}

fn one() -> f64 {
    1.0
}

fn is_one(v: &f64) -> bool {
    *v == 1.0
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// Why a [`SchemeSpec`] could not be turned into a scheme.
#[derive(Clone, Debug, PartialEq)]
pub enum SchemeError {
    /// The scheme needs rigid-body dynamics and none was given.
    MissingDynamics {
        /// The scheme's `kind` tag.
        scheme: &'static str,
    },
    /// The dynamics model is not the kinematic robot.
    RobotMismatch {
        /// The scheme's `kind` tag.
        scheme: &'static str,
        /// The kinematic robot's model name.
        robot: String,
        /// The dynamics model's name.
        dynamics: String,
    },
    /// A parameter is out of its range.
    InvalidParameter {
        /// The scheme's `kind` tag.
        scheme: &'static str,
        /// The parameter, by its field name in the experiment file.
        field: &'static str,
        /// The value given (NaN when a required parameter is absent).
        value: f64,
        /// The range it must be in, as text.
        requirement: &'static str,
    },
    /// A term's parameter is out of its range (`kind = "composed"`; boxed to keep the error
    /// small).
    InvalidTerm(Box<TermFault>),
    /// A term of the other level.
    TermLevel {
        /// The term's place in `terms`.
        index: usize,
        /// The term's `kind` tag.
        term: &'static str,
        /// The scheme's level.
        level: &'static str,
    },
    /// A tracking term's `axes` are invalid.
    InvalidAxes {
        /// The term's place in `terms`.
        index: usize,
        /// What they must be.
        requirement: &'static str,
    },
    /// A tracking term's `orientation` without `task = "pose"`.
    OrientationWithoutPose {
        /// The term's place in `terms`.
        index: usize,
    },
    /// A pose task on a robot without the orientation capability.
    NoOrientation {
        /// The term's place in `terms`.
        index: usize,
        /// The robot's model name.
        robot: String,
    },
    /// A composed scheme without terms.
    NoTerms,
    /// A composed scheme's display name is empty, too long or has other characters.
    InvalidName {
        /// The longest name.
        max: usize,
    },
    /// The joint reference has not one entry per joint.
    ReferenceLength {
        /// The robot's joint count.
        joints: usize,
        /// The reference's length.
        given: usize,
    },
}

/// Which parameter of which term is out of range ([`SchemeError::InvalidTerm`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TermFault {
    /// The term's place in `terms` (from 0).
    pub index: usize,
    /// The term's `kind` tag.
    pub term: &'static str,
    /// The parameter, by its field name.
    pub field: &'static str,
    /// The value given (NaN when a required parameter is absent).
    pub value: f64,
    /// The range it must be in, as text.
    pub requirement: &'static str,
}

impl fmt::Display for SchemeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SchemeError::MissingDynamics { scheme } => write!(
                f,
                "scheme {scheme} needs a robot with dynamics (H, c, g), but none was given"
            ),
            SchemeError::RobotMismatch {
                scheme,
                robot,
                dynamics,
            } => write!(
                f,
                "scheme {scheme}: the dynamics model '{dynamics}' is not the robot '{robot}'"
            ),
            SchemeError::InvalidParameter {
                scheme,
                field,
                value,
                requirement,
            } => write!(
                f,
                "scheme {scheme}: parameter '{field}' = {value} is invalid (must be {requirement})"
            ),
            SchemeError::InvalidTerm(fault) => {
                let TermFault {
                    index,
                    term,
                    field,
                    value,
                    requirement,
                } = &**fault;
                write!(
                f,
                "scheme composed: terms[{index}] ({term}): parameter '{field}' = {value} is invalid \
                 (must be {requirement})"
                )
            }
            SchemeError::TermLevel { index, term, level } => write!(
                f,
                "scheme composed: terms[{index}] ({term}) is not a term of the {level} level \
                 (velocity: velocity-norm, repetitive, infinity-norm, tracking, bound-conversion, \
                 velocity-limits; acceleration: acceleration-norm, drift-damping, torque-norm, \
                 tracking, acceleration-limits)"
            ),
            SchemeError::InvalidAxes { index, requirement } => write!(
                f,
                "scheme composed: terms[{index}] (tracking): field 'axes' is invalid (must be \
                 {requirement})"
            ),
            SchemeError::OrientationWithoutPose { index } => write!(
                f,
                "scheme composed: terms[{index}] (tracking): field 'orientation' is given without \
                 task = \"pose\" (give task = \"pose\" or drop it)"
            ),
            SchemeError::NoOrientation { index, robot } => write!(
                f,
                "scheme composed: terms[{index}] (tracking): field 'task' = \"pose\" needs a robot \
                 with a tool frame (the orientation capability: DH robots, robot files, URDF \
                 chains, e.g. panda, jaco2), but robot '{robot}' has none (choose task = \
                 \"position\", \"planar\" or axes)"
            ),
            SchemeError::NoTerms => write!(
                f,
                "scheme composed: field 'terms' is empty (list at least one [[scheme.terms]])"
            ),
            SchemeError::InvalidName { max } => write!(
                f,
                "scheme composed: field 'name' is invalid (must be 1 to {max} characters of \
                 letters, digits, space and -_.()=+)"
            ),
            SchemeError::ReferenceLength { joints, given } => write!(
                f,
                "scheme: the joint reference has {given} entries, the robot {joints} joints"
            ),
        }
    }
}

impl std::error::Error for SchemeError {}

fn check(
    scheme: &'static str,
    field: &'static str,
    value: f64,
    ok: bool,
    requirement: &'static str,
) -> Result<(), SchemeError> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(SchemeError::InvalidParameter {
            scheme,
            field,
            value,
            requirement,
        })
    }
}

/// The `kind` tag of jia2019's tri-criteria preset ([`SchemeSpec::Vltco`]).
pub const VLTCO_KIND: &str = "vltco";
/// The `kind` tag of kong2019's ZNN preset ([`SchemeSpec::ZnnRmp`]).
pub const ZNN_RMP_KIND: &str = "znn-rmp";
/// The `kind` tag of the velocity-level template ([`SchemeSpec::VelocityRmp`]).
pub const VELOCITY_RMP_KIND: &str = "velocity-rmp";

impl SchemeSpec {
    /// Whether the scheme reads kinematics and limits from a dynamics model (a torque-norm
    /// term: zhang2018's HL-JDF).
    pub fn needs_dynamics(&self) -> bool {
        self.expand().needs_dynamics()
    }

    /// The spec's `kind` tag.
    pub fn kind(&self) -> &'static str {
        match self {
            SchemeSpec::Vltco { .. } => VLTCO_KIND,
            SchemeSpec::Cmco { .. } => "cmco",
            SchemeSpec::HlJdf { .. } => "hl-jdf",
            SchemeSpec::FiniteTimeRmp { .. } => "finite-time-rmp",
            SchemeSpec::ZnnRmp { .. } => ZNN_RMP_KIND,
            SchemeSpec::VelocityRmp { .. } => VELOCITY_RMP_KIND,
            SchemeSpec::Composed(_) => "composed",
        }
    }

    /// The scheme's name as the paper writes it, with the parameters that distinguish runs,
    /// e.g. `VLTCO (phi=0.2, tau=0.4)`, `CMCO (eta=0.1, delta=0.8)`, `MTN (zeta=0)`. A
    /// non-default RMP reading is appended: `VLTCO (phi=0.2, tau=0.4, rmp=expansion)`,
    /// `VLTCO (phi=0.2, tau=0.4, rmp=text-mu, mu=5)`, `CMCO (eta=0.1, delta=0.8, rmp=text-tau,
    /// tau=10)`.
    pub fn display_name(&self) -> String {
        match *self {
            SchemeSpec::Vltco {
                phi, tau, rmp, mu, ..
            } => {
                let reading = match rmp {
                    RmpReading::Printed => String::new(),
                    RmpReading::Expansion => ", rmp=expansion".to_string(),
                    RmpReading::TextGain => format!(", rmp=text-mu, mu={mu}"),
                };
                format!("{} (phi={phi}, tau={tau}{reading})", vltco_name(phi, tau))
            }
            SchemeSpec::Cmco {
                eta,
                delta,
                rmp,
                tau,
                ..
            } => {
                let reading = match rmp {
                    RmpReading::Printed => String::new(),
                    RmpReading::Expansion => ", rmp=expansion".to_string(),
                    RmpReading::TextGain => format!(", rmp=text-tau, tau={tau}"),
                };
                format!("CMCO (eta={eta}, delta={delta}{reading})")
            }
            SchemeSpec::HlJdf { zeta, .. } => {
                format!("{} (zeta={zeta})", hl_jdf_name(zeta))
            }
            SchemeSpec::FiniteTimeRmp {
                beta_theta, alpha, ..
            } => {
                format!("finite-time (beta_theta={beta_theta}, alpha={alpha})")
            }
            SchemeSpec::ZnnRmp { mu, .. } => format!("ZNN (mu={mu})"),
            SchemeSpec::VelocityRmp {
                weight,
                repetitive,
                lambda,
                alpha,
                k_p,
                upsilon,
            } => {
                let mut parts = vec![format!("lambda={lambda}")];
                if repetitive == RepetitiveForm::SignPower {
                    parts.push(format!("alpha={}", alpha.unwrap_or(f64::NAN)));
                }
                if weight != 1.0 {
                    parts.push(format!("w={weight}"));
                }
                if k_p != 0.0 {
                    parts.push(format!("k_p={k_p}"));
                }
                if let Some(u) = upsilon {
                    parts.push(format!("upsilon={u}"));
                }
                format!("RMP ({})", parts.join(", "))
            }
            SchemeSpec::Composed(ref c) => c.display_name(),
        }
    }

    /// Checks every parameter's range (finite, and as the papers require: the feedback and
    /// drift gains are positive design parameters, so 0 is rejected as well as inf and NaN).
    pub fn validate(&self) -> Result<(), SchemeError> {
        let s = self.kind();
        match *self {
            SchemeSpec::Vltco {
                phi,
                tau,
                kappa,
                lambda,
                mu,
                ..
            } => check_vltco(s, mu, phi, tau, kappa, lambda),
            SchemeSpec::Cmco {
                eta,
                delta,
                upsilon,
                lambda,
                tau,
                ..
            } => check_cmco(s, tau, eta, delta, upsilon, lambda),
            SchemeSpec::HlJdf {
                zeta,
                alpha,
                beta,
                rho_v,
                rho_p,
            } => check_hl_jdf(s, zeta, alpha, beta, rho_v, rho_p),
            SchemeSpec::FiniteTimeRmp {
                beta_theta,
                k_p,
                alpha,
            } => {
                check(
                    s,
                    "beta_theta",
                    beta_theta,
                    beta_theta > 0.0,
                    "finite and > 0",
                )?;
                check_position_gain(s, k_p)?;
                check(
                    s,
                    "alpha",
                    alpha,
                    alpha > 0.0,
                    "finite and > 0 (the paper: 0 < alpha < 1)",
                )
            }
            SchemeSpec::ZnnRmp { mu, k_p } => {
                check(
                    s,
                    "mu",
                    mu,
                    mu >= 0.0,
                    "finite and >= 0 (0: no repetitive term)",
                )?;
                check_position_gain(s, k_p)
            }
            SchemeSpec::VelocityRmp {
                weight,
                repetitive,
                lambda,
                alpha,
                k_p,
                upsilon,
            } => check_velocity_rmp(s, weight, repetitive, lambda, alpha, k_p, upsilon),
            SchemeSpec::Composed(ref c) => c.validate(),
        }
    }
}

/// VLTCO's ranges (scheme kind `s`): mu, kappa and lambda positive; the weights phi and tau of
/// jia2019's criterion non-negative with phi + tau <= 1.
fn check_vltco(
    s: &'static str,
    mu: f64,
    phi: f64,
    tau: f64,
    kappa: f64,
    lambda: f64,
) -> Result<(), SchemeError> {
    check(s, "mu", mu, mu > 0.0, "finite and > 0")?;
    check(s, "phi", phi, phi >= 0.0, "finite and >= 0")?;
    check(
        s,
        "tau",
        tau,
        tau >= 0.0 && phi + tau <= 1.0,
        "finite, >= 0, phi + tau <= 1",
    )?;
    check(s, "kappa", kappa, kappa > 0.0, "finite and > 0")?;
    check(s, "lambda", lambda, lambda > 0.0, "finite and > 0")
}

/// CMCO's ranges (scheme kind `s`): tau, upsilon and lambda positive; the weights eta and delta
/// of zhong2021's criterion non-negative with eta + delta <= 1.
fn check_cmco(
    s: &'static str,
    tau: f64,
    eta: f64,
    delta: f64,
    upsilon: f64,
    lambda: f64,
) -> Result<(), SchemeError> {
    check(s, "tau", tau, tau > 0.0, "finite and > 0")?;
    check(s, "eta", eta, eta >= 0.0, "finite and >= 0")?;
    check(
        s,
        "delta",
        delta,
        delta >= 0.0 && eta + delta <= 1.0,
        "finite, >= 0, eta + delta <= 1",
    )?;
    check(s, "upsilon", upsilon, upsilon > 0.0, "finite and > 0")?;
    check(s, "lambda", lambda, lambda > 0.0, "finite and > 0")
}

/// HL-JDF's ranges (scheme kind `s`): the blend zeta in [0, 1], the gains alpha and beta and the
/// limit margins rho_v and rho_p positive.
fn check_hl_jdf(
    s: &'static str,
    zeta: f64,
    alpha: f64,
    beta: f64,
    rho_v: f64,
    rho_p: f64,
) -> Result<(), SchemeError> {
    check(s, "zeta", zeta, (0.0..=1.0).contains(&zeta), "in [0, 1]")?;
    check(s, "alpha", alpha, alpha > 0.0, "finite and > 0")?;
    check(s, "beta", beta, beta > 0.0, "finite and > 0")?;
    check(s, "rho_v", rho_v, rho_v > 0.0, "finite and > 0")?;
    check(s, "rho_p", rho_p, rho_p > 0.0, "finite and > 0")
}

/// The velocity-level RMP's ranges (scheme kind `s`): a positive weight, a non-negative
/// repetitive gain lambda with the exponent its form needs ([`check_repetitive_exponent`]), a
/// non-negative position gain, and positive bounds upsilon where given.
fn check_velocity_rmp(
    s: &'static str,
    weight: f64,
    repetitive: RepetitiveForm,
    lambda: f64,
    alpha: Option<f64>,
    k_p: f64,
    upsilon: Option<f64>,
) -> Result<(), SchemeError> {
    check(s, "weight", weight, weight > 0.0, "finite and > 0")?;
    check(
        s,
        "lambda",
        lambda,
        lambda >= 0.0,
        "finite and >= 0 (0: no repetitive term)",
    )?;
    check_repetitive_exponent(s, repetitive, alpha)?;
    check_position_gain(s, k_p)?;
    if let Some(u) = upsilon {
        check(
            s,
            "upsilon",
            u,
            u > 0.0,
            "finite and > 0 (absent: no bounds)",
        )?;
    }
    Ok(())
}

/// The exponent alpha of a repetitive term of form `repetitive` (scheme kind `s`): given, in
/// (0, 1], for the sign-power form; absent for the linear form, which has none.
fn check_repetitive_exponent(
    s: &'static str,
    repetitive: RepetitiveForm,
    alpha: Option<f64>,
) -> Result<(), SchemeError> {
    match (repetitive, alpha) {
        (RepetitiveForm::SignPower, Some(a)) => {
            check(s, "alpha", a, a > 0.0 && a <= 1.0, "in (0, 1]")
        }
        (RepetitiveForm::SignPower, None) => Err(SchemeError::InvalidParameter {
            scheme: s,
            field: "alpha",
            value: f64::NAN,
            requirement: "given, in (0, 1], for repetitive = \"sign-power\"",
        }),
        (RepetitiveForm::Linear, Some(a)) => Err(SchemeError::InvalidParameter {
            scheme: s,
            field: "alpha",
            value: a,
            requirement: "absent for repetitive = \"linear\" (it has no exponent)",
        }),
        (RepetitiveForm::Linear, None) => Ok(()),
    }
}

/// The position-feedback gain k_p of an RMP scheme (kind `s`): finite and >= 0 (0: none).
fn check_position_gain(s: &'static str, k_p: f64) -> Result<(), SchemeError> {
    check(
        s,
        "k_p",
        k_p,
        k_p >= 0.0,
        "finite and >= 0 (0: no position feedback)",
    )
}

/// jia2019's name for the weights: MVN (phi = 1, tau = 0), MVN-INVM (tau = 0), otherwise
/// VLTCO.
pub fn vltco_name(phi: f64, tau: f64) -> &'static str {
    if tau == 0.0 && phi == 1.0 {
        "MVN"
    } else if tau == 0.0 {
        "MVN-INVM"
    } else {
        "VLTCO"
    }
}

/// zhang2018's name: MTN for zeta = 0, HL-JDF otherwise.
pub fn hl_jdf_name(zeta: f64) -> &'static str {
    if zeta == 0.0 {
        "MTN"
    } else {
        "HL-JDF"
    }
}

/// The tri-criteria terms of jia2019 (2.17)-(2.20) and zhong2021 (2.16)-(2.18): velocity norm
/// (w_v), squared repetitive term (w_r, coefficient k), tracking without feedback, infinity
/// norm (1 - w_v - w_r) and the bound conversion (gain).
fn tri_criteria(w_v: f64, w_r: f64, k: f64, gain: f64, bounds: BoundPlacement) -> ComposedSpec {
    ComposedSpec {
        level: Level::Velocity,
        bounds,
        name: None,
        terms: vec![
            TermSpec::VelocityNorm { weight: w_v },
            TermSpec::Repetitive {
                form: RepetitiveForm::Linear,
                lambda: k,
                alpha: None,
                weight: w_r,
                squared: true,
            },
            tracking(0.0),
            TermSpec::InfinityNorm {
                weight: 1.0 - w_v - w_r,
                penalty: Penalty::Squared,
                varpi: f64::INFINITY,
            },
            TermSpec::BoundConversion { gain },
        ],
    }
}

/// The velocity-level tracking term on the 3-D position with gain k_p.
fn tracking(k_p: f64) -> TermSpec {
    TermSpec::Tracking {
        task: None,
        axes: None,
        k_p: Some(k_p),
        rho_v: None,
        rho_p: None,
        orientation: None,
    }
}

/// The velocity-level template: velocity norm, repetitive term, tracking, bound conversion.
fn velocity_template(
    weight: f64,
    form: RepetitiveForm,
    lambda: f64,
    alpha: Option<f64>,
    k_p: f64,
    upsilon: Option<f64>,
) -> ComposedSpec {
    let mut terms = vec![
        TermSpec::VelocityNorm { weight },
        TermSpec::Repetitive {
            form,
            lambda,
            alpha,
            weight: 1.0,
            squared: false,
        },
        tracking(k_p),
    ];
    if let Some(gain) = upsilon {
        terms.push(TermSpec::BoundConversion { gain });
    }
    ComposedSpec {
        level: Level::Velocity,
        bounds: BoundPlacement::Variables,
        name: None,
        terms,
    }
}

impl SchemeSpec {
    /// The term list a spec stands for (presets expand; `composed` is its own list).
    pub fn expand(&self) -> ComposedSpec {
        match *self {
            SchemeSpec::Vltco {
                phi,
                tau,
                kappa,
                lambda,
                rmp,
                mu,
            } => tri_criteria(
                phi,
                tau,
                rmp.coefficient(lambda, mu),
                kappa,
                BoundPlacement::Variables,
            ),
            SchemeSpec::Cmco {
                eta,
                delta,
                upsilon,
                lambda,
                rmp,
                tau,
            } => tri_criteria(
                eta,
                delta,
                rmp.coefficient(lambda, tau),
                upsilon,
                BoundPlacement::Rows,
            ),
            SchemeSpec::HlJdf {
                zeta,
                alpha,
                beta,
                rho_v,
                rho_p,
            } => ComposedSpec {
                level: Level::Acceleration,
                bounds: BoundPlacement::Variables,
                name: None,
                terms: vec![
                    TermSpec::AccelerationNorm { weight: zeta },
                    TermSpec::DriftDamping {
                        alpha,
                        beta,
                        weight: zeta,
                    },
                    TermSpec::TorqueNorm { weight: 1.0 - zeta },
                    TermSpec::Tracking {
                        task: None,
                        axes: None,
                        k_p: None,
                        rho_v: Some(rho_v),
                        rho_p: Some(rho_p),
                        orientation: None,
                    },
                ],
            },
            SchemeSpec::FiniteTimeRmp {
                beta_theta,
                k_p,
                alpha,
            } => velocity_template(
                1.0,
                RepetitiveForm::SignPower,
                beta_theta,
                Some(alpha),
                k_p,
                None,
            ),
            SchemeSpec::ZnnRmp { mu, k_p } => {
                velocity_template(1.0, RepetitiveForm::Linear, mu, None, k_p, None)
            }
            SchemeSpec::VelocityRmp {
                weight,
                repetitive,
                lambda,
                alpha,
                k_p,
                upsilon,
            } => velocity_template(weight, repetitive, lambda, alpha, k_p, upsilon),
            SchemeSpec::Composed(ref c) => c.clone(),
        }
    }

    /// The scheme's short name as its paper writes it (`VLTCO`, `CMCO`, `MTN`, `HL-JDF`,
    /// `finite-time`, `ZNN`, `RMP`; a composed scheme's own name).
    pub fn scheme_name(&self) -> String {
        match *self {
            SchemeSpec::Vltco { phi, tau, .. } => vltco_name(phi, tau).to_string(),
            SchemeSpec::Cmco { .. } => "CMCO".to_string(),
            SchemeSpec::HlJdf { zeta, .. } => hl_jdf_name(zeta).to_string(),
            SchemeSpec::FiniteTimeRmp { .. } => "finite-time".to_string(),
            SchemeSpec::ZnnRmp { .. } => "ZNN".to_string(),
            SchemeSpec::VelocityRmp { .. } => "RMP".to_string(),
            SchemeSpec::Composed(ref c) => c.display_name(),
        }
    }
}
