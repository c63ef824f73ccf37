//! jia2019: the VLTCO scheme (velocity-level tri-criteria optimisation) and its special cases
//! MVN and MVN-INVM, as one QP family (Jia et al. 2019, eq. 2.17–2.20).
//!
//! Decision variable x = [thetadot; p] in R^(n+1), p = |thetadot|_inf (INVM auxiliary):
//!
//! ```text
//! min   x'Dx/2 + g'x                                          (2.17)
//! s.t.  [J 0] x = rdot*                                        (2.18)
//!       [I -1; -I -1] x <= 0          (2n rows: |thetadot_i| <= p)   (2.19, 2.13)
//!       x- <= x <= x+                                          (2.20)
//! D = diag((phi + tau) I_n, 1 - phi - tau)
//! g = [tau Lambda (theta - theta0); 0]
//! x- = [zeta-; 0],  x+ = [zeta+; varpi]
//! zeta-_i = max{kappa (theta-_i - theta_i), thetadot-_i}      (2.15)
//! zeta+_i = min{kappa (theta+_i - theta_i), thetadot+_i}      (2.16)
//! ```
//!
//! (phi, tau) = (1, 0) is MVN, (0.2, 0) MVN-INVM and (0.2, 0.4) VLTCO. MVN's D has a zero last
//! entry (p is then free up to the inequality rows): D is PSD, which is all the QP needs.
//!
//! Choices (documented deviations):
//! - b = rdot* exactly as printed: no position feedback, so tracking error integrates.
//! - The RMP term's linear coefficient is by default the QP data as printed,
//!   g = tau Lambda (theta - theta0) with Lambda = 20; the expansion of jia2019 (2.11) with
//!   Lambda = 2 mu gives tau Lambda / 2, and the text's mu = 5 gives tau mu. All three are
//!   available ([`RmpReading`], [`Jia2019::with_rmp`]; see [`crate::rmp`]).
//! - varpi, "a large constant standing for +inf", is `f64::INFINITY` by default (the QP type
//!   supports absent bounds); [`Jia2019::with_varpi`] sets a finite constant for solvers that
//!   need a finite box.
//! - theta0 is the run's initial joint vector, fixed at construction.

use std::sync::Arc;

use crate::qp::{Qp, QpDims};
use nalgebra::SVector;
use robots::Robot;

use crate::joint_limits::{merged_bounds, merged_bounds_dot};
use crate::paths::Path;
use crate::qp_dot::QpDotScratch;
use crate::rmp::RmpReading;
use crate::scheme::{Level, Scheme};

/// jia2019's tri-criteria scheme (MVN / MVN-INVM / VLTCO), eq. 2.17–2.20.
pub struct Jia2019<const N: usize> {
    robot: Arc<dyn Robot<N>>,
    path: Arc<dyn Path>,
    theta0: SVector<f64, N>,
    /// MVN weight phi.
    pub phi: f64,
    /// RMP weight tau.
    pub tau: f64,
    /// Joint-limit conversion gain kappa of (2.14).
    pub kappa: f64,
    /// RMP gain Lambda.
    pub lambda: f64,
    /// Which reading of the RMP coefficient g uses (default: as printed, tau Lambda).
    pub rmp: RmpReading,
    /// The text's RMP gain mu of C = mu (theta - theta0) (used by [`RmpReading::TextGain`]).
    pub mu: f64,
    /// Upper bound of p (the paper's "large constant"); +inf by default.
    pub varpi: f64,
}

impl<const N: usize> Jia2019<N> {
    /// Scheme with weights (phi, tau), joint-limit gain kappa and RMP gain Lambda; theta0 is the
    /// run's initial joint vector.
    pub fn new(
        robot: Arc<dyn Robot<N>>,
        path: Arc<dyn Path>,
        theta0: SVector<f64, N>,
        phi: f64,
        tau: f64,
        kappa: f64,
        lambda: f64,
    ) -> Self {
        Self {
            robot,
            path,
            theta0,
            phi,
            tau,
            kappa,
            lambda,
            rmp: RmpReading::Printed,
            mu: 5.0,
            varpi: f64::INFINITY,
        }
    }

    /// Use `reading` for the RMP coefficient, with the text's gain `mu` (used only by
    /// [`RmpReading::TextGain`]).
    pub fn with_rmp(mut self, reading: RmpReading, mu: f64) -> Self {
        self.rmp = reading;
        self.mu = mu;
        self
    }

    /// The factor c of g = [c (theta - theta0); 0]: tau times the reading's coefficient
    /// (tau Lambda as printed).
    pub fn rmp_coefficient(&self) -> f64 {
        self.tau * self.rmp.coefficient(self.lambda, self.mu)
    }

    /// Replace varpi = +inf by a finite constant.
    pub fn with_varpi(mut self, varpi: f64) -> Self {
        self.varpi = varpi;
        self
    }

    pub fn theta0(&self) -> &SVector<f64, N> {
        &self.theta0
    }

    /// The paper's name for the weights: MVN (phi = 1, tau = 0), MVN-INVM (tau = 0),
    /// otherwise VLTCO.
    pub fn scheme_name(phi: f64, tau: f64) -> &'static str {
        if tau == 0.0 && phi == 1.0 {
            "MVN"
        } else if tau == 0.0 {
            "MVN-INVM"
        } else {
            "VLTCO"
        }
    }
}

/// Writes the constant INVM rows [I -1; -I -1] x <= 0 into g (2n x (n+1)) and h.
pub(crate) fn write_invm_rows<const N: usize>(qp: &mut Qp, row0: usize) {
    for i in 0..N {
        for j in 0..=N {
            qp.g[(row0 + i, j)] = 0.0;
            qp.g[(row0 + N + i, j)] = 0.0;
        }
        qp.g[(row0 + i, i)] = 1.0;
        qp.g[(row0 + i, N)] = -1.0;
        qp.g[(row0 + N + i, i)] = -1.0;
        qp.g[(row0 + N + i, N)] = -1.0;
        qp.h[row0 + i] = 0.0;
        qp.h[row0 + N + i] = 0.0;
    }
}

/// Writes D = diag((w1 + w2) I, 1 - w1 - w2), g = [c (theta - theta0); 0], A = [J 0],
/// b = rdot*: the part of the QP that jia2019 and zhong2021 share ((w1, w2) = (phi, tau) or
/// (eta, delta), c = tau Lambda or delta Lambda).
#[allow(clippy::too_many_arguments)]
pub(crate) fn write_tri_criteria<const N: usize>(
    qp: &mut Qp,
    robot: &dyn Robot<N>,
    path: &dyn Path,
    t: f64,
    theta: &SVector<f64, N>,
    theta0: &SVector<f64, N>,
    w1: f64,
    w2: f64,
    c: f64,
) {
    qp.p.as_mut_slice().fill(0.0);
    for i in 0..N {
        qp.p[(i, i)] = w1 + w2;
        qp.q[i] = c * (theta[i] - theta0[i]);
    }
    qp.p[(N, N)] = 1.0 - w1 - w2;
    qp.q[N] = 0.0;
    let j = robot.jacobian(theta);
    qp.a.view_mut((0, 0), (3, N)).copy_from(&j);
    for r in 0..3 {
        qp.a[(r, N)] = 0.0;
    }
    qp.b.copy_from(&path.at(t).rdot);
}

/// Time derivative of [`write_tri_criteria`]'s data: Ddot = 0, gdot = [c thetadot; 0],
/// Adot = [Jdot 0], bdot = rddot*.
pub(crate) fn write_tri_criteria_dot<const N: usize>(
    qp_dot: &mut Qp,
    robot: &dyn Robot<N>,
    path: &dyn Path,
    t: f64,
    theta: &SVector<f64, N>,
    thetadot: &SVector<f64, N>,
    c: f64,
) {
    qp_dot.p.as_mut_slice().fill(0.0);
    for i in 0..N {
        qp_dot.q[i] = c * thetadot[i];
    }
    qp_dot.q[N] = 0.0;
    let jd = robot.jacobian_dot(theta, thetadot);
    qp_dot.a.view_mut((0, 0), (3, N)).copy_from(&jd);
    for r in 0..3 {
        qp_dot.a[(r, N)] = 0.0;
    }
    qp_dot.b.copy_from(&path.at(t).rddot);
}

impl<const N: usize> Scheme<N> for Jia2019<N> {
    fn name(&self) -> String {
        Self::scheme_name(self.phi, self.tau).to_string()
    }

    fn level(&self) -> Level {
        Level::Velocity
    }

    fn dims(&self) -> QpDims {
        QpDims {
            nx: N + 1,
            n_eq: 3,
            n_in: 2 * N,
        }
    }

    fn build(&self, t: f64, theta: &SVector<f64, N>, _thetadot: &SVector<f64, N>, qp: &mut Qp) {
        debug_assert_eq!(qp.dims(), self.dims());
        write_tri_criteria(
            qp,
            &*self.robot,
            &*self.path,
            t,
            theta,
            &self.theta0,
            self.phi,
            self.tau,
            self.rmp_coefficient(),
        );
        write_invm_rows::<N>(qp, 0);
        let (lo, hi) = merged_bounds(&self.robot.limits(), theta, self.kappa);
        qp.lower.rows_mut(0, N).copy_from(&lo);
        qp.upper.rows_mut(0, N).copy_from(&hi);
        qp.lower[N] = 0.0;
        qp.upper[N] = self.varpi;
    }

    /// Analytic: Ddot = 0, gdot = [c thetadot; 0] (c = [`Jia2019::rmp_coefficient`]),
    /// Adot = [Jdot 0], bdot = rddot*,
    /// Gdot = 0, hdot = 0, bounds by [`merged_bounds_dot`] (right-hand derivative at the kink).
    fn build_dot(
        &self,
        t: f64,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
        _thetaddot: &SVector<f64, N>,
        qp_dot: &mut Qp,
        _scratch: &mut QpDotScratch,
    ) {
        debug_assert_eq!(qp_dot.dims(), self.dims());
        write_tri_criteria_dot(
            qp_dot,
            &*self.robot,
            &*self.path,
            t,
            theta,
            thetadot,
            self.rmp_coefficient(),
        );
        qp_dot.g.as_mut_slice().fill(0.0);
        qp_dot.h.as_mut_slice().fill(0.0);
        let (lo, hi) = merged_bounds_dot(&self.robot.limits(), theta, thetadot, self.kappa);
        qp_dot.lower.rows_mut(0, N).copy_from(&lo);
        qp_dot.upper.rows_mut(0, N).copy_from(&hi);
        qp_dot.lower[N] = 0.0;
        qp_dot.upper[N] = 0.0;
    }
}
