//! zhong2021: the CMCO (constrained multi-criteria optimisation, also called PNMCO in the
//! paper) scheme, eq. 2.16–2.18 (Zhong et al. 2021).
//!
//! Decision variable x = [thetadot; k] in R^(n+1), k = |thetadot|_inf:
//!
//! ```text
//! min   x'Qx/2 + g'x                                          (2.16)
//! s.t.  A x = b,  A = [J 0],  b = rdot*                        (2.17)
//!       B x <= h                                               (2.18)
//! Q = diag((eta + delta) I_n, 1 - eta - delta)
//! g = [delta Lambda (theta - theta0); 0]
//! B = [s; E; -E] in R^((4n+2) x (n+1)),  s = [I -1; -I -1],  E = I_(n+1)
//! h = [d; x+; -x-],  d = 0 in R^(2n),  x- = [zeta-; 0],  x+ = [zeta+; varpi]
//! zeta-_i = upsilon (theta-_i - theta_i) if theta_i <= xi1, else thetadot-_i     (2.14)
//! zeta+_i = thetadot+_i if theta_i <= xi2, else upsilon (theta+_i - theta_i)     (2.15)
//! xi1 = theta-_i - thetadot-_i / upsilon,  xi2 = theta+_i - thetadot+_i / upsilon
//! ```
//!
//! All inequalities, including the variable bounds, are rows of G = B and h as the paper writes
//! them, so VP-RNN-PF's exponential penalty (2.19) sees every one of them; `lower`/`upper` of
//! the QP are +-inf.
//!
//! Choices (documented deviations):
//! - The paper prints h = [d; x+; x-]; the rows -E x <= h encode x >= x- only with h's last
//!   block equal to -x-, which we use.
//! - varpi ("an infinite constant") is `f64::INFINITY` by default, so the row k <= varpi has
//!   h = +inf (its penalty term exp(-sigma (h - Bx)) is exactly 0); [`Zhong2021::with_varpi`]
//!   sets a finite constant.
//! - Lambda (= 2 tau in the text, zhong2021 (2.10)) is a parameter; the experiments use
//!   Lambda = 20. The RMP term's linear coefficient is by default the QP data as printed,
//!   g = delta Lambda (theta - theta0); the expansion of delta ||thetadot + c||^2 / 2 with
//!   c = tau (theta - theta0) and Lambda = 2 tau gives delta Lambda / 2, and a given gain tau
//!   gives delta tau ([`RmpReading`], [`Zhong2021::with_rmp`]; see [`crate::rmp`]).
//! - theta0 is the run's initial joint vector; b = rdot* has no position feedback, as printed.

use std::sync::Arc;

use crate::qp::{Qp, QpDims};
use nalgebra::SVector;
use robots::Robot;

use crate::jia2019::{write_invm_rows, write_tri_criteria, write_tri_criteria_dot};
use crate::joint_limits::{merged_bounds_dot, piecewise_bounds};
use crate::paths::Path;
use crate::qp_dot::QpDotScratch;
use crate::rmp::RmpReading;
use crate::scheme::{Level, Scheme};

/// zhong2021's CMCO scheme, eq. 2.16–2.18.
pub struct Zhong2021<const N: usize> {
    robot: Arc<dyn Robot<N>>,
    path: Arc<dyn Path>,
    theta0: SVector<f64, N>,
    /// MVN weight eta.
    pub eta: f64,
    /// RMP weight delta.
    pub delta: f64,
    /// Joint-limit conversion gain upsilon of (2.13).
    pub upsilon: f64,
    /// RMP gain Lambda.
    pub lambda: f64,
    /// Which reading of the RMP coefficient g uses (default: as printed, delta Lambda).
    pub rmp: RmpReading,
    /// The text's RMP gain tau of c = tau (theta - theta0) (used by [`RmpReading::TextGain`]).
    pub tau: f64,
    /// Upper bound of k; +inf by default.
    pub varpi: f64,
}

impl<const N: usize> Zhong2021<N> {
    /// Scheme with weights (eta, delta), joint-limit gain upsilon and RMP gain Lambda; theta0
    /// is the run's initial joint vector.
    pub fn new(
        robot: Arc<dyn Robot<N>>,
        path: Arc<dyn Path>,
        theta0: SVector<f64, N>,
        eta: f64,
        delta: f64,
        upsilon: f64,
        lambda: f64,
    ) -> Self {
        Self {
            robot,
            path,
            theta0,
            eta,
            delta,
            upsilon,
            lambda,
            rmp: RmpReading::Printed,
            tau: 10.0,
            varpi: f64::INFINITY,
        }
    }

    /// Use `reading` for the RMP coefficient, with the text's gain `tau` (used only by
    /// [`RmpReading::TextGain`]).
    pub fn with_rmp(mut self, reading: RmpReading, tau: f64) -> Self {
        self.rmp = reading;
        self.tau = tau;
        self
    }

    /// The factor c of g = [c (theta - theta0); 0]: delta times the reading's coefficient
    /// (delta Lambda as printed).
    pub fn rmp_coefficient(&self) -> f64 {
        self.delta * self.rmp.coefficient(self.lambda, self.tau)
    }

    /// Replace varpi = +inf by a finite constant.
    pub fn with_varpi(mut self, varpi: f64) -> Self {
        self.varpi = varpi;
        self
    }

    pub fn theta0(&self) -> &SVector<f64, N> {
        &self.theta0
    }
}

impl<const N: usize> Scheme<N> for Zhong2021<N> {
    fn name(&self) -> String {
        "CMCO".to_string()
    }

    fn level(&self) -> Level {
        Level::Velocity
    }

    fn dims(&self) -> QpDims {
        QpDims {
            nx: N + 1,
            n_eq: 3,
            n_in: 4 * N + 2,
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
            self.eta,
            self.delta,
            self.rmp_coefficient(),
        );
        // s rows (INVM), h = d = 0.
        write_invm_rows::<N>(qp, 0);
        // E rows (x <= x+) and -E rows (-x <= -x-).
        let (lo, hi) = piecewise_bounds(&self.robot.limits(), theta, self.upsilon);
        let (e0, m0) = (2 * N, 3 * N + 1);
        // Column by column: nalgebra's fill of a strided row view goes element by element.
        let rows = qp.g.nrows();
        for column in qp.g.as_mut_slice().chunks_exact_mut(rows) {
            column[e0..e0 + 2 * N + 2].fill(0.0);
        }
        for i in 0..=N {
            qp.g[(e0 + i, i)] = 1.0;
            qp.g[(m0 + i, i)] = -1.0;
        }
        for i in 0..N {
            qp.h[e0 + i] = hi[i];
            qp.h[m0 + i] = -lo[i];
        }
        qp.h[e0 + N] = self.varpi;
        qp.h[m0 + N] = 0.0;
        qp.lower.as_mut_slice().fill(f64::NEG_INFINITY);
        qp.upper.as_mut_slice().fill(f64::INFINITY);
    }

    /// Analytic: Qdot = 0, gdot = [c thetadot; 0] (c = [`Zhong2021::rmp_coefficient`]),
    /// Adot = [Jdot 0], bdot = rddot*,
    /// Bdot = 0, hdot = [0; zeta+dot; 0; -zeta-dot; 0] (right-hand derivative at the switch
    /// points xi1, xi2).
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
        let (lo, hi) = merged_bounds_dot(&self.robot.limits(), theta, thetadot, self.upsilon);
        let (e0, m0) = (2 * N, 3 * N + 1);
        for i in 0..N {
            qp_dot.h[e0 + i] = hi[i];
            qp_dot.h[m0 + i] = -lo[i];
        }
        qp_dot.lower.as_mut_slice().fill(0.0);
        qp_dot.upper.as_mut_slice().fill(0.0);
    }
}
