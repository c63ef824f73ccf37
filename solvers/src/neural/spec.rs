//! Serde-readable solver specifications for experiment files, and the factory that builds the
//! network for a QP of given sizes.
//!
//! ```toml
//! solver = { kind = "lvi-pdnn", gamma = 1e7 }
//! solver = { kind = "s-lvi-pdnn", beta = 1e7 }
//! solver = { kind = "vp-rnn-pf", p = 1e-4, sigma = 400, gamma = 2, activation = "power-sigmoid", alpha = 4, chi = 3 }
//! solver = { kind = "fp-cdnn", gamma = 200, perturbation = { a_d = 1.0, a_s = 1.5, task_duration = 8 } }
//! solver = { kind = "vp-cdnn", gamma = 200 }
//! solver = { kind = "finite-time", beta = 1, alpha = 0.1, smoothing = 1e-8 }   # smoothing optional
//! solver = { kind = "znn", gamma = 1 }
//! ```
//!
//! `activation` is `linear` (default), `sinh` or `power-sigmoid`; `alpha`/`chi` (defaults 4 and
//! 3) are the power-sigmoid's parameters (zhong2021 eq. 2.29) and are ignored otherwise. The
//! CDNNs accept an activation too (the paper's runs are linear), with the power-sigmoid at its
//! defaults.

use super::activation::{Activation, ActivationKind, POWER_SIGMOID_ALPHA, POWER_SIGMOID_CHI};
use super::cdnn::{fp_cdnn, vp_cdnn, ReferencePerturbation};
use super::projection::{LviPdnn, SLviPdnn};
use super::vp_rnn_pf::VpRnnPf;
use super::znn::{finite_time, znn, FINITE_TIME_SMOOTHING};
use super::NeuralSolver;
use crate::qp::QpDims;
use serde::{Deserialize, Serialize};

fn default_alpha() -> f64 {
    POWER_SIGMOID_ALPHA
}
fn default_chi() -> f64 {
    POWER_SIGMOID_CHI
}
fn default_smoothing() -> f64 {
    FINITE_TIME_SMOOTHING
}

/// A network and its parameters, by the papers' names.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum SolverSpec {
    /// jia2019 eq. 2.23 (gamma = 1e7 in the paper).
    LviPdnn { gamma: f64 },
    /// zhong2021 eq. 2.35 (beta = 1e7 in the paper).
    SLviPdnn { beta: f64 },
    /// zhong2021 eq. 2.30.
    VpRnnPf {
        p: f64,
        sigma: f64,
        gamma: f64,
        #[serde(default)]
        activation: ActivationKind,
        /// Power-sigmoid alpha (eq. 2.29).
        #[serde(default = "default_alpha")]
        alpha: f64,
        /// Power-sigmoid chi (eq. 2.29).
        #[serde(default = "default_chi")]
        chi: f64,
    },
    /// zhang2018 eq. 2.15 (eq. 3.2 when perturbed).
    FpCdnn {
        gamma: f64,
        #[serde(default)]
        activation: ActivationKind,
        #[serde(default)]
        perturbation: Option<ReferencePerturbation>,
    },
    /// zhang2018 eq. 2.11 (eq. 3.1 when perturbed).
    VpCdnn {
        gamma: f64,
        #[serde(default)]
        activation: ActivationKind,
        #[serde(default)]
        perturbation: Option<ReferencePerturbation>,
    },
    /// kong2019 eq. 20 (derived form): gain beta, sign-power exponent alpha (paper: 1 and 0.1),
    /// linear zone |e| < smoothing of the sign-power (ours, see [`super::znn`]).
    FiniteTime {
        beta: f64,
        alpha: f64,
        #[serde(default = "default_smoothing")]
        smoothing: f64,
    },
    /// Linear ZNN (kong2019's comparison solver).
    Znn { gamma: f64 },
}

fn activation_of(kind: ActivationKind, alpha: f64, chi: f64) -> Activation {
    match kind {
        ActivationKind::Linear => Activation::Linear,
        ActivationKind::Sinh => Activation::Sinh,
        ActivationKind::PowerSigmoid => Activation::PowerSigmoid { alpha, chi },
    }
}

fn check_gain(name: &str, symbol: &str, v: f64) -> Result<(), String> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(format!(
            "{name}: {symbol} must be positive and finite, got {v}"
        ))
    }
}

impl SolverSpec {
    /// The network's name as the papers write it, with the variant where it matters,
    /// e.g. `VP-RNN-PF (sinh)`, `FP-CDNN (perturbed)`.
    pub fn display_name(&self) -> String {
        match self {
            SolverSpec::LviPdnn { .. } => "LVI-PDNN".into(),
            SolverSpec::SLviPdnn { .. } => "S-LVI-PDNN".into(),
            SolverSpec::VpRnnPf { activation, .. } => {
                format!("VP-RNN-PF ({})", kind_label(*activation))
            }
            SolverSpec::FpCdnn {
                activation,
                perturbation,
                ..
            } => cdnn_name("FP-CDNN", *activation, perturbation),
            SolverSpec::VpCdnn {
                activation,
                perturbation,
                ..
            } => cdnn_name("VP-CDNN", *activation, perturbation),
            SolverSpec::FiniteTime { .. } => "FTNN".into(),
            SolverSpec::Znn { .. } => "ZNN".into(),
        }
    }

    /// Whether the network needs dQP/dt (zeroing networks).
    pub fn needs_qp_dot(&self) -> bool {
        !matches!(
            self,
            SolverSpec::LviPdnn { .. } | SolverSpec::SLviPdnn { .. }
        )
    }

    /// Whether the network handles inequality rows and bounds (only the equality part otherwise).
    pub fn handles_inequalities(&self) -> bool {
        matches!(
            self,
            SolverSpec::LviPdnn { .. } | SolverSpec::SLviPdnn { .. } | SolverSpec::VpRnnPf { .. }
        )
    }
}

fn kind_label(k: ActivationKind) -> &'static str {
    match k {
        ActivationKind::Linear => "linear",
        ActivationKind::Sinh => "sinh",
        ActivationKind::PowerSigmoid => "power-sigmoid",
    }
}

fn cdnn_name(base: &str, act: ActivationKind, pert: &Option<ReferencePerturbation>) -> String {
    let mut s = base.to_string();
    let mut extra = Vec::new();
    if act != ActivationKind::Linear {
        extra.push(kind_label(act).to_string());
    }
    if let Some(p) = pert {
        extra.push(format!("perturbed A_D={}, A_s={}", p.a_d, p.a_s));
    }
    if !extra.is_empty() {
        s.push_str(&format!(" ({})", extra.join(", ")));
    }
    s
}

/// Build the network of `spec` for QPs of sizes `dims` (scratch preallocated for them).
pub fn build_solver(spec: &SolverSpec, dims: QpDims) -> Result<Box<dyn NeuralSolver>, String> {
    Ok(match *spec {
        SolverSpec::LviPdnn { gamma } => {
            check_gain("LVI-PDNN", "gamma", gamma)?;
            Box::new(LviPdnn::new(gamma, dims))
        }
        SolverSpec::SLviPdnn { beta } => {
            check_gain("S-LVI-PDNN", "beta", beta)?;
            Box::new(SLviPdnn::new(beta, dims))
        }
        SolverSpec::VpRnnPf {
            p,
            sigma,
            gamma,
            activation,
            alpha,
            chi,
        } => {
            check_gain("VP-RNN-PF", "gamma", gamma)?;
            Box::new(VpRnnPf::new(
                p,
                sigma,
                gamma,
                activation_of(activation, alpha, chi),
                dims,
            )?)
        }
        SolverSpec::FpCdnn {
            gamma,
            activation,
            perturbation,
        } => {
            check_gain("FP-CDNN", "gamma", gamma)?;
            let act = activation_of(activation, POWER_SIGMOID_ALPHA, POWER_SIGMOID_CHI);
            Box::new(fp_cdnn(gamma, act, perturbation, dims)?)
        }
        SolverSpec::VpCdnn {
            gamma,
            activation,
            perturbation,
        } => {
            check_gain("VP-CDNN", "gamma", gamma)?;
            let act = activation_of(activation, POWER_SIGMOID_ALPHA, POWER_SIGMOID_CHI);
            Box::new(vp_cdnn(gamma, act, perturbation, dims)?)
        }
        SolverSpec::FiniteTime {
            beta,
            alpha,
            smoothing,
        } => {
            check_gain("FTNN", "beta", beta)?;
            Box::new(finite_time(beta, alpha, smoothing, dims)?)
        }
        SolverSpec::Znn { gamma } => {
            check_gain("ZNN", "gamma", gamma)?;
            Box::new(znn(gamma, dims)?)
        }
    })
}
