//! kong2019's ZNN scheme (kong2019 (22)) on the n-link arm of any joint count
//! ([`robots::NLinkDyn`]), as a [`SliceScheme`]: the scheme that runs whole at N = 50 ... 200,
//! where no const-generic `NLink<N>` is compiled.
//!
//! The QP is that of [`crate::velocity_rmp`] with w = 1, the linear repetitive term
//! lambda = mu, tracking gain k_p and no bounds:
//!
//! ```text
//! P = I,  q = mu (theta - theta_ref),  A = J(theta),  b = rdot* + k_p (r* - f(theta))
//! Pdot = 0,  qdot = mu thetadot,  Adot = Jdot(theta, thetadot),
//! bdot = rddot* + k_p (rdot* - J thetadot)
//! ```
//!
//! with the arm's f, J and Jdot written straight into the QP's storage (no allocation per
//! build), P, b and the absent bounds by [`fill_tracking`], as the const-generic scheme. The
//! entries are computed in the order [`crate::velocity_rmp::VelocityRmp`] computes
//! them on `NLink<N>`, so the two agree to the last bit on the QP (tested in
//! `schemes/tests/velocity_rmp_dyn.rs`).

use crate::paths::Path;
use crate::qp::{Qp, QpDims};
use crate::qp_dot::QpDotScratch;
use crate::scheme::Level;
use crate::slice_scheme::SliceScheme;
use crate::velocity_rmp::fill_tracking;
use robots::NLinkDyn;
use std::sync::Arc;

/// kong2019 (22) on [`NLinkDyn`] (module docs).
pub struct NLinkZnn {
    arm: NLinkDyn,
    path: Arc<dyn Path>,
    theta_ref: Vec<f64>,
    mu: f64,
    k_p: f64,
}

impl NLinkZnn {
    /// The scheme on `arm` following `path` with joint reference `theta_ref` (one entry per
    /// joint), gains mu and k_p. `None` when `theta_ref` does not have one entry per joint.
    pub fn new(
        arm: NLinkDyn,
        path: Arc<dyn Path>,
        theta_ref: &[f64],
        mu: f64,
        k_p: f64,
    ) -> Option<Self> {
        (theta_ref.len() == arm.joints()).then(|| NLinkZnn {
            arm,
            path,
            theta_ref: theta_ref.to_vec(),
            mu,
            k_p,
        })
    }
}

impl SliceScheme for NLinkZnn {
    fn name(&self) -> String {
        "ZNN".to_string()
    }

    fn level(&self) -> Level {
        Level::Velocity
    }

    fn dims(&self) -> QpDims {
        QpDims {
            nx: self.arm.joints(),
            n_eq: 3,
            n_in: 0,
        }
    }

    fn joints(&self) -> usize {
        self.arm.joints()
    }

    fn build(&self, t: f64, theta: &[f64], _thetadot: &[f64], qp: &mut Qp) {
        debug_assert_eq!(qp.dims(), self.dims());
        for ((q, th), r) in qp.q.iter_mut().zip(theta).zip(&self.theta_ref) {
            *q = (th - r) * self.mu;
        }
        self.arm.jacobian_to(theta, qp.a.as_mut_slice());
        fill_tracking(qp, &self.arm.tip(theta), &self.path.at(t), self.k_p);
    }

    fn build_dot(
        &self,
        t: f64,
        theta: &[f64],
        thetadot: &[f64],
        _thetaddot: &[f64],
        qp_dot: &mut Qp,
        scratch: &mut QpDotScratch,
    ) {
        debug_assert_eq!(qp_dot.dims(), self.dims());
        qp_dot.p.fill(0.0);
        for (q, v) in qp_dot.q.iter_mut().zip(thetadot) {
            *q = self.mu * v;
        }
        self.arm
            .jacobian_dot_to(theta, thetadot, qp_dot.a.as_mut_slice());
        // J thetadot, with J written into the scratch QP's A (same 3 x n shape).
        let jac = &mut scratch.plus.a;
        self.arm.jacobian_to(theta, jac.as_mut_slice());
        let pp = self.path.at(t);
        let mut jthd = nalgebra::Vector3::zeros();
        for (j, v) in thetadot.iter().enumerate() {
            for i in 0..3 {
                jthd[i] += jac[(i, j)] * v;
            }
        }
        qp_dot
            .b
            .copy_from(&(pp.rddot + (pp.rdot - jthd) * self.k_p));
        qp_dot.lower.fill(0.0);
        qp_dot.upper.fill(0.0);
    }
}
