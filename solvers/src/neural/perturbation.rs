//! zhang2018's reference perturbation of the zeroing networks (eq. 3.1-3.2): the matrix term
//! DeltaD(t) added to Qdot and the vector term Delta s(t) added to udot (`docs/networks.md` says
//! where they enter; [`super::zeroing`] adds them).
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

use nalgebra::DMatrix;
use settings::ReferencePerturbation;
use std::f64::consts::PI;

/// One entry of D0: sign * (sin | cos)(k w).
#[derive(Clone, Copy, Debug)]
pub struct Trig {
    /// The entry's sign, +1 or -1.
    pub sign: f64,
    /// Whether the entry is a sine (else a cosine).
    pub sine: bool,
    /// The multiple k of w = pi t / T in the argument.
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

/// The terms of zhang2018's reference perturbation ([`ReferencePerturbation`], the experiment
/// files' data) at time t.
pub trait PerturbationTerms {
    /// DeltaD(t) = A_D D0(t) into `out` (9 x 9).
    fn delta_d(&self, t: f64, out: &mut DMatrix<f64>);
    /// Delta s(t) into `out` (9 entries).
    fn delta_s(&self, t: f64, out: &mut [f64]);
}

/// w = pi t / T.
#[inline]
fn w(p: &ReferencePerturbation, t: f64) -> f64 {
    PI * t / p.task_duration
}

impl PerturbationTerms for ReferencePerturbation {
    fn delta_d(&self, t: f64, out: &mut DMatrix<f64>) {
        let w = w(self, t);
        for (i, row) in D0_TABLE.iter().enumerate() {
            for (j, e) in row.iter().enumerate() {
                out[(i, j)] = self.a_d * e.eval(w);
            }
        }
    }

    fn delta_s(&self, t: f64, out: &mut [f64]) {
        let w = w(self, t);
        for (o, (scale, e)) in out.iter_mut().zip(DELTA_S_TABLE.iter()) {
            *o = self.a_s * scale * e.eval(w);
        }
    }
}
