//! The torque norm at the acceleration level through a dynamics model: with
//! tau = H(theta) thetaddot + c(theta, thetadot) + g(theta) (zhang2018 (2.2)-(2.4)),
//! w |tau|^2 / 2 = w (thetaddot' H^2 thetaddot / 2 + (H'(c + g))' thetaddot) + const, so
//!
//! ```text
//! P[..n, ..n] += w H^2  (symmetrised: (H^2 + (H^2)') / 2)
//! q[..n]      += w H'(c + g)
//! ```
//!
//! zhang2018 (2.5)'s (1 - zeta) part of W = zeta I + (1 - zeta) H^2 and of
//! eta = zeta sigma + (1 - zeta) H'(c + g); H is SPD, so the term is convex. The term also gives
//! the scheme its torque ([`Term::torque`]). No exact derivative (it would need dc/dt, dg/dt):
//! a scheme with it takes the central difference.

use std::sync::{Arc, Mutex};

use nalgebra::{DMatrix, DVector};
use qp::Qp;
use robots::Dynamics;

use super::{Slot, State, Term};

/// The torque norm (module docs).
pub struct TorqueNorm {
    dynamics: Arc<dyn Dynamics>,
    /// Weight w.
    weight: f64,
    /// H, H^2, c + g, g and H'(c + g), allocated with the term.
    scratch: Mutex<Scratch>,
}

struct Scratch {
    h: DMatrix<f64>,
    hh: DMatrix<f64>,
    cg: DVector<f64>,
    g: DVector<f64>,
    htcg: DVector<f64>,
}

/// (a b)_{ij} = sum_k a_{ik} b_{kj}, summed in k order from k = 0, written into `out`.
fn product_to(a: &DMatrix<f64>, b: &DMatrix<f64>, out: &mut DMatrix<f64>) {
    let n = a.nrows();
    for j in 0..n {
        for i in 0..n {
            let mut s = a[(i, 0)] * b[(0, j)];
            for k in 1..n {
                s += a[(i, k)] * b[(k, j)];
            }
            out[(i, j)] = s;
        }
    }
}

impl TorqueNorm {
    /// The term with weight `weight` on `dynamics`.
    pub fn new(dynamics: Arc<dyn Dynamics>, weight: f64) -> Self {
        let n = dynamics.dof();
        Self {
            dynamics,
            weight,
            scratch: Mutex::new(Scratch {
                h: DMatrix::zeros(n, n),
                hh: DMatrix::zeros(n, n),
                cg: DVector::zeros(n),
                g: DVector::zeros(n),
                htcg: DVector::zeros(n),
            }),
        }
    }
}

impl Term for TorqueNorm {
    fn describe(&self) -> String {
        format!(
            "torque-norm (w={}): P[..n, ..n] += w H^2, q[..n] += w H'(c + g)",
            self.weight
        )
    }

    fn write(&self, state: &State<'_>, _slot: Slot, qp: &mut Qp) {
        let (theta, thetadot, w) = (state.theta, state.thetadot, self.weight);
        let n = theta.len();
        let mut scratch = self
            .scratch
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let Scratch { h, hh, cg, g, htcg } = &mut *scratch;
        self.dynamics.inertia(theta, h.as_mut_slice());
        product_to(h, h, hh);
        for j in 0..n {
            qp.p[(j, j)] += hh[(j, j)] * w;
            for i in 0..j {
                let s = (hh[(i, j)] * w + hh[(j, i)] * w) * 0.5;
                qp.p[(i, j)] += s;
                qp.p[(j, i)] += s;
            }
        }
        self.dynamics.coriolis(theta, thetadot, cg.as_mut_slice());
        self.dynamics.gravity(theta, g.as_mut_slice());
        *cg += &*g;
        h.tr_mul_to(cg, htcg);
        for i in 0..n {
            qp.q[i] += htcg[i] * w;
        }
    }

    fn torque(&self, theta: &[f64], thetadot: &[f64], thetaddot: &[f64], tau: &mut [f64]) -> bool {
        let n = theta.len();
        let mut scratch = self
            .scratch
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let Scratch { h, cg, g, .. } = &mut *scratch;
        self.dynamics.inertia(theta, h.as_mut_slice());
        self.dynamics.coriolis(theta, thetadot, cg.as_mut_slice());
        self.dynamics.gravity(theta, g.as_mut_slice());
        // tau = (H thetaddot + c) + g, H thetaddot summed column by column in joint order.
        for (i, t) in tau.iter_mut().enumerate().take(n) {
            let mut s = h[(i, 0)] * thetaddot[0];
            for k in 1..n {
                s += h[(i, k)] * thetaddot[k];
            }
            *t = s + cg[i] + g[i];
        }
        true
    }
}
