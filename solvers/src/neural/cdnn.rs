//! FP-CDNN and VP-CDNN (zhang2018 eq. 2.15 and 2.11) and their perturbed forms (eq. 3.2, 3.1).
//!
//! Both are the zeroing network of [`super::zeroing`] on the Lagrange system of the
//! equality-only QP (zhang2018 eq. 2.8: Q = [W J'; J 0], y = [x; lambda], u = [-eta; b]):
//!
//! ```text
//!   VP-CDNN (2.11):  Q ydot = -Qdot y - gamma exp(t) Phi(Q y - u) + udot
//!   FP-CDNN (2.15):  Q ydot = -Qdot y - gamma        Phi(Q y - u) + udot
//!   perturbed (3.1 / 3.2):
//!                    Q ydot = -(Qdot + DeltaD(t)) y - g(t) Phi(Q y - u) + udot + Delta s(t)
//! ```
//!
//! i.e. DeltaD(t) is added to Qdot where it multiplies y (the "differential errors of matrix
//! Q") and Delta s(t) is added to udot (the "differential errors of vector u as well as external
//! disturbance"); Q itself, u and the activated error term are unperturbed. Activation linear
//! unless stated (the robustness theorem of zhang2018 is for the linear activation).
//!
//! # The reference perturbation
//!
//! The paper only says "sine or cosine functions". We use the one of docs/experiments.md (from the
//! group's own VP-CDNN code), with w = pi t / T, T the task duration, for n + m = 9:
//!
//! ```text
//!   Delta s(t) = A_s [2 sin w, 4 cos 2w, -5 sin 3w, cos 3w, -sin 3w, 3 cos w, -sin w, -sin 2w, cos w]'
//!   DeltaD(t)  = A_D D0(t)     (D0: the 9 x 9 table in [`D0_TABLE`])
//! ```
//!
//! with reference amplitudes A_s = 1.5 and A_D = 1.0; both amplitudes and T are parameters
//! (the robustness claim is about how the networks degrade as they grow).

use super::activation::Activation;
use super::error::NetworkError;
use super::zeroing::{Gain, ZeroingNetwork};
use nalgebra::DMatrix;
use schemes::qp::QpDims;
use serde::Deserialize;
use std::f64::consts::PI;

/// Size of the reference perturbation: n + m = 6 + 3 (Jaco2, position task).
pub const PERTURBATION_DIM: usize = 9;
/// Reference amplitude A_D of DeltaD.
pub const REFERENCE_A_D: f64 = 1.0;
/// Reference amplitude A_s of Delta s.
pub const REFERENCE_A_S: f64 = 1.5;

/// One entry of D0: sign * (sin | cos)(k w).
#[derive(Clone, Copy, Debug)]
pub struct Trig {
    pub sign: f64,
    pub sine: bool,
    pub k: f64,
}

const fn s(k: f64) -> Trig {
    Trig {
        sign: 1.0,
        sine: true,
        k,
    }
}
const fn ns(k: f64) -> Trig {
    Trig {
        sign: -1.0,
        sine: true,
        k,
    }
}
const fn c(k: f64) -> Trig {
    Trig {
        sign: 1.0,
        sine: false,
        k,
    }
}
const fn nc(k: f64) -> Trig {
    Trig {
        sign: -1.0,
        sine: false,
        k,
    }
}

impl Trig {
    #[inline]
    fn eval(&self, w: f64) -> f64 {
        let a = self.k * w;
        self.sign * if self.sine { a.sin() } else { a.cos() }
    }
}

/// D0(t) of the reference perturbation (docs/experiments.md), row by row, as functions of w = pi t / T.
pub const D0_TABLE: [[Trig; 9]; 9] = [
    [
        s(1.),
        c(1.),
        ns(2.),
        c(1.),
        ns(1.),
        c(3.),
        ns(1.),
        c(1.),
        ns(1.),
    ],
    [
        c(2.),
        c(2.),
        nc(4.),
        s(1.),
        ns(2.),
        nc(3.),
        ns(2.),
        c(1.),
        ns(1.),
    ],
    [
        s(3.),
        ns(4.),
        c(5.),
        nc(3.),
        c(4.),
        ns(5.),
        c(2.),
        ns(1.),
        c(1.),
    ],
    [
        s(1.),
        c(1.),
        ns(1.),
        c(1.),
        ns(1.),
        c(1.),
        ns(1.),
        c(1.),
        ns(1.),
    ],
    [
        s(1.),
        c(2.),
        ns(1.),
        c(1.),
        ns(2.),
        c(1.),
        ns(2.),
        c(1.),
        ns(1.),
    ],
    [
        ns(2.),
        c(1.),
        ns(2.),
        c(1.),
        ns(1.),
        c(1.),
        c(2.),
        ns(1.),
        c(1.),
    ],
    [
        s(1.),
        c(1.),
        ns(1.),
        c(2.),
        ns(2.),
        c(1.),
        ns(2.),
        c(1.),
        ns(1.),
    ],
    [
        s(1.),
        c(1.),
        ns(1.),
        c(1.),
        ns(1.),
        c(1.),
        c(1.),
        ns(1.),
        c(1.),
    ],
    [
        ns(2.),
        c(2.),
        ns(1.),
        c(1.),
        ns(1.),
        c(2.),
        ns(2.),
        c(1.),
        ns(1.),
    ],
];

/// Delta s(t) / A_s of the reference perturbation (docs/experiments.md).
pub const DELTA_S_TABLE: [(f64, Trig); 9] = [
    (2.0, s(1.)),
    (4.0, c(2.)),
    (5.0, ns(3.)),
    (1.0, c(3.)),
    (1.0, ns(3.)),
    (3.0, c(1.)),
    (1.0, ns(1.)),
    (1.0, ns(2.)),
    (1.0, c(1.)),
];

fn default_a_d() -> f64 {
    REFERENCE_A_D
}
fn default_a_s() -> f64 {
    REFERENCE_A_S
}

/// The reference perturbation (module docs): amplitudes A_D, A_s and the task duration T.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct ReferencePerturbation {
    /// A_D: DeltaD(t) = A_D D0(t) (reference 1.0).
    #[serde(default = "default_a_d")]
    pub a_d: f64,
    /// A_s: the factor in front of Delta s's vector (reference 1.5).
    #[serde(default = "default_a_s")]
    pub a_s: f64,
    /// T in w = pi t / T (the task duration; 8 s in zhang2018).
    pub task_duration: f64,
}

impl ReferencePerturbation {
    /// The reference amplitudes (A_D = 1, A_s = 1.5) for a task of duration T.
    pub fn reference(task_duration: f64) -> Self {
        Self {
            a_d: REFERENCE_A_D,
            a_s: REFERENCE_A_S,
            task_duration,
        }
    }

    pub fn validate(&self, state_dim: usize) -> Result<(), NetworkError> {
        if state_dim != PERTURBATION_DIM {
            return Err(NetworkError::PerturbationDim {
                expected: PERTURBATION_DIM,
                state_dim,
            });
        }
        if !(self.task_duration > 0.0 && self.task_duration.is_finite()) {
            return Err(NetworkError::PerturbationDuration(self.task_duration));
        }
        if !self.a_d.is_finite() || !self.a_s.is_finite() {
            return Err(NetworkError::PerturbationAmplitudes);
        }
        Ok(())
    }

    #[inline]
    fn w(&self, t: f64) -> f64 {
        PI * t / self.task_duration
    }

    /// DeltaD(t) = A_D D0(t) into `out` (9 x 9).
    pub fn delta_d(&self, t: f64, out: &mut DMatrix<f64>) {
        let w = self.w(t);
        for (i, row) in D0_TABLE.iter().enumerate() {
            for (j, e) in row.iter().enumerate() {
                out[(i, j)] = self.a_d * e.eval(w);
            }
        }
    }

    /// Delta s(t) into `out` (9 entries).
    pub fn delta_s(&self, t: f64, out: &mut [f64]) {
        let w = self.w(t);
        for (o, (scale, e)) in out.iter_mut().zip(DELTA_S_TABLE.iter()) {
            *o = self.a_s * scale * e.eval(w);
        }
    }
}

/// FP-CDNN (zhang2018 eq. 2.15; eq. 3.2 with a perturbation): gain gamma.
pub fn fp_cdnn(
    gamma: f64,
    activation: Activation,
    perturbation: Option<ReferencePerturbation>,
    dims: QpDims,
) -> Result<ZeroingNetwork, NetworkError> {
    ZeroingNetwork::new(
        "FP-CDNN",
        Gain::Fixed(gamma),
        activation,
        perturbation,
        dims,
    )
}

/// VP-CDNN (zhang2018 eq. 2.11; eq. 3.1 with a perturbation): gain gamma exp(t).
pub fn vp_cdnn(
    gamma: f64,
    activation: Activation,
    perturbation: Option<ReferencePerturbation>,
    dims: QpDims,
) -> Result<ZeroingNetwork, NetworkError> {
    ZeroingNetwork::new(
        "VP-CDNN",
        Gain::Exponential(gamma),
        activation,
        perturbation,
        dims,
    )
}
