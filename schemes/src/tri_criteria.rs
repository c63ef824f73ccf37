//! The vocabulary's tri-criteria scheme: minimum velocity norm, infinity norm through an
//! auxiliary variable and the repetitive term, with the joint limits converted into velocity
//! bounds. jia2019's VLTCO (with MVN and MVN-INVM) and zhong2021's CMCO are its two presets
//! ([`TriCriteria::vltco`], [`TriCriteria::cmco`]); they differ only in the names of the letters
//! and in where the bounds are written ([`BoundPlacement`]).
//!
//! Decision variable x = [thetadot; p] in R^(n+1), p = |thetadot|_inf (the auxiliary variable
//! of the infinity norm):
//!
//! ```text
//! min   x'Dx/2 + g'x                                   jia2019 (2.17), zhong2021 (2.16)
//! s.t.  [J 0] x = rdot*                                jia2019 (2.18), zhong2021 (2.17)
//!       [I -1; -I -1] x <= 0    (|thetadot_i| <= p)   jia2019 (2.19), zhong2021 (2.18)
//!       x- <= x <= x+                                  jia2019 (2.20), zhong2021 (2.18)
//! D = diag((w_v + w_r) I_n, 1 - w_v - w_r)
//! g = [w_r k (theta - theta0); 0]
//! x- = [zeta-; 0],  x+ = [zeta+; varpi]
//! zeta-_i = max{gain (theta-_i - theta_i), thetadot-_i}    jia2019 (2.15), zhong2021 (2.14)
//! zeta+_i = min{gain (theta+_i - theta_i), thetadot+_i}    jia2019 (2.16), zhong2021 (2.15)
//! ```
//!
//! The weights are (w_v, w_r) = (phi, tau) in jia2019 and (eta, delta) in zhong2021; the bound
//! gain is jia2019's kappa or zhong2021's upsilon. (w_v, w_r) = (1, 0) is MVN, (0.2, 0)
//! MVN-INVM and (0.2, 0.4) VLTCO. MVN's D has a zero last entry (p is then free up to the
//! inequality rows): D is PSD, which is all the QP needs.
//!
//! The coefficient k of the repetitive term has three readings ([`RmpReading`], see
//! [`crate::rmp`]); by default k = Lambda, the QP data as printed.
//!
//! Where the bounds go ([`BoundPlacement`]):
//! - jia2019 keeps x- <= x <= x+ as variable bounds (G holds the 2n infinity-norm rows);
//! - zhong2021 writes every inequality as rows of B x <= h, B = [s; E; -E] in
//!   R^((4n+2) x (n+1)), s = [I -1; -I -1], E = I_(n+1), h = [0; x+; -x-], so that VP-RNN-PF's
//!   exponential penalty zhong2021 (2.19) sees every one of them (the QP's own bounds are then
//!   +-inf). The paper prints h = [d; x+; x-]; the rows -E x <= h encode x >= x- only with h's
//!   last block equal to -x-, which is used. zhong2021 writes the conversion piecewise
//!   ((2.14)-(2.15), [`crate::joint_limits::piecewise_bounds`]); it is the same law as the
//!   max/min form (tested), which both presets use.
//!
//! Choices (documented deviations): b = rdot* exactly as printed (no position feedback, so the
//! tracking error integrates); varpi, "a large constant standing for +inf", is `f64::INFINITY`
//! by default ([`TriCriteria::with_varpi`] sets a finite constant for solvers that need a finite
//! box); theta0 is the run's initial joint vector, fixed at construction.

use std::sync::Arc;

use robots::Robot;

use crate::joint_limits::{merged_bounds, merged_bounds_dot};
use crate::paths::Path;
use crate::rmp::RmpReading;
use crate::scheme::{Level, Scheme};
use qp::dot::QpDotScratch;
use qp::{Qp, QpDims};

/// Where the converted bounds x- <= x <= x+ are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoundPlacement {
    /// As the QP's variable bounds (jia2019 (2.20)); G holds only the 2n infinity-norm rows.
    VariableBounds,
    /// As rows of G x <= h (zhong2021 (2.18)): B = [s; E; -E], 4n + 2 rows in all.
    InequalityRows,
}

/// The preset a [`TriCriteria`] was made as, which fixes its display name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// jia2019's family: MVN, MVN-INVM or VLTCO by the weights.
    Vltco,
    /// zhong2021's CMCO.
    Cmco,
}

/// The tri-criteria scheme (module docs).
pub struct TriCriteria {
    robot: Arc<dyn Robot>,
    path: Arc<dyn Path>,
    theta0: Vec<f64>,
    preset: Preset,
    /// Weight w_v of the velocity norm (jia2019 phi, zhong2021 eta).
    pub w_velocity: f64,
    /// Weight w_r of the repetitive term (jia2019 tau, zhong2021 delta).
    pub w_repetitive: f64,
    /// Gain of the bound conversion (jia2019 kappa, zhong2021 upsilon).
    pub bound_gain: f64,
    /// The repetitive gain Lambda.
    pub lambda: f64,
    /// Which reading of the repetitive coefficient g uses (default: as printed, Lambda).
    pub rmp: RmpReading,
    /// The text's gain of C = gain (theta - theta0) (jia2019 mu, zhong2021 tau), used by
    /// [`RmpReading::TextGain`].
    pub text_gain: f64,
    /// Upper bound of p (the papers' "large constant"); +inf by default.
    pub varpi: f64,
    /// Where the bounds go.
    pub placement: BoundPlacement,
}

impl TriCriteria {
    /// jia2019's VLTCO family (MVN, MVN-INVM, VLTCO) with weights (phi, tau), bound gain kappa
    /// and Lambda; the text's mu = 5 for the `text-mu` reading.
    pub fn vltco(
        robot: Arc<dyn Robot>,
        path: Arc<dyn Path>,
        theta0: &[f64],
        phi: f64,
        tau: f64,
        kappa: f64,
        lambda: f64,
    ) -> Self {
        Self {
            robot,
            path,
            theta0: theta0.to_vec(),
            preset: Preset::Vltco,
            w_velocity: phi,
            w_repetitive: tau,
            bound_gain: kappa,
            lambda,
            rmp: RmpReading::Printed,
            text_gain: 5.0,
            varpi: f64::INFINITY,
            placement: BoundPlacement::VariableBounds,
        }
    }

    /// zhong2021's CMCO with weights (eta, delta), bound gain upsilon and Lambda; every
    /// inequality as rows of G; the text's tau defaults to Lambda / 2 = 10 at Lambda = 20.
    pub fn cmco(
        robot: Arc<dyn Robot>,
        path: Arc<dyn Path>,
        theta0: &[f64],
        eta: f64,
        delta: f64,
        upsilon: f64,
        lambda: f64,
    ) -> Self {
        Self {
            preset: Preset::Cmco,
            text_gain: 10.0,
            placement: BoundPlacement::InequalityRows,
            ..Self::vltco(robot, path, theta0, eta, delta, upsilon, lambda)
        }
    }

    /// Use `reading` for the repetitive coefficient, with the text's gain (used only by
    /// [`RmpReading::TextGain`]).
    pub fn with_rmp(mut self, reading: RmpReading, text_gain: f64) -> Self {
        self.rmp = reading;
        self.text_gain = text_gain;
        self
    }

    /// Replace varpi = +inf by a finite constant.
    pub fn with_varpi(mut self, varpi: f64) -> Self {
        self.varpi = varpi;
        self
    }

    /// The factor c of g = [c (theta - theta0); 0]: w_r times the reading's coefficient
    /// (w_r Lambda as printed).
    pub fn rmp_coefficient(&self) -> f64 {
        self.w_repetitive * self.rmp.coefficient(self.lambda, self.text_gain)
    }

    /// The joint reference theta0 of the repetitive term g = [c (theta - theta0); 0], as given at
    /// construction.
    pub fn theta0(&self) -> &[f64] {
        &self.theta0
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
}

/// Writes the constant infinity-norm rows [I -1; -I -1] x <= 0 into G's first 2n rows and h.
fn write_infinity_norm_rows(n: usize, qp: &mut Qp) {
    for i in 0..n {
        for j in 0..=n {
            qp.g[(i, j)] = 0.0;
            qp.g[(n + i, j)] = 0.0;
        }
        qp.g[(i, i)] = 1.0;
        qp.g[(i, n)] = -1.0;
        qp.g[(n + i, i)] = -1.0;
        qp.g[(n + i, n)] = -1.0;
        qp.h[i] = 0.0;
        qp.h[n + i] = 0.0;
    }
}

impl Scheme for TriCriteria {
    fn name(&self) -> String {
        match self.preset {
            Preset::Vltco => Self::vltco_name(self.w_velocity, self.w_repetitive).to_string(),
            Preset::Cmco => "CMCO".to_string(),
        }
    }

    fn level(&self) -> Level {
        Level::Velocity
    }

    fn joints(&self) -> usize {
        self.theta0.len()
    }

    fn dims(&self) -> QpDims {
        let n = self.joints();
        QpDims {
            nx: n + 1,
            n_eq: 3,
            n_in: match self.placement {
                BoundPlacement::VariableBounds => 2 * n,
                BoundPlacement::InequalityRows => 4 * n + 2,
            },
        }
    }

    fn build(&self, t: f64, theta: &[f64], _thetadot: &[f64], qp: &mut Qp) {
        debug_assert_eq!(qp.dims(), self.dims());
        let n = self.joints();
        let c = self.rmp_coefficient();
        qp.p.as_mut_slice().fill(0.0);
        for (i, (th, t0)) in theta.iter().zip(&self.theta0).enumerate() {
            qp.p[(i, i)] = self.w_velocity + self.w_repetitive;
            qp.q[i] = c * (th - t0);
        }
        qp.p[(n, n)] = 1.0 - self.w_velocity - self.w_repetitive;
        qp.q[n] = 0.0;
        self.robot
            .jacobian(theta, &mut qp.a.as_mut_slice()[..3 * n]);
        for r in 0..3 {
            qp.a[(r, n)] = 0.0;
        }
        qp.b.copy_from(&self.path.at(t).rdot);
        write_infinity_norm_rows(n, qp);
        merged_bounds(
            self.robot.limits(),
            theta,
            self.bound_gain,
            &mut qp.lower.as_mut_slice()[..n],
            &mut qp.upper.as_mut_slice()[..n],
        );
        match self.placement {
            BoundPlacement::VariableBounds => {
                qp.lower[n] = 0.0;
                qp.upper[n] = self.varpi;
            }
            BoundPlacement::InequalityRows => {
                let (e0, m0) = (2 * n, 3 * n + 1);
                // Column by column: nalgebra's fill of a strided row view goes element by
                // element.
                let rows = qp.g.nrows();
                for column in qp.g.as_mut_slice().chunks_exact_mut(rows) {
                    column[e0..e0 + 2 * n + 2].fill(0.0);
                }
                for i in 0..=n {
                    qp.g[(e0 + i, i)] = 1.0;
                    qp.g[(m0 + i, i)] = -1.0;
                }
                // zeta+ and zeta- were written into upper and lower above.
                for i in 0..n {
                    qp.h[e0 + i] = qp.upper[i];
                    qp.h[m0 + i] = -qp.lower[i];
                }
                qp.h[e0 + n] = self.varpi;
                qp.h[m0 + n] = 0.0;
                qp.lower.as_mut_slice().fill(f64::NEG_INFINITY);
                qp.upper.as_mut_slice().fill(f64::INFINITY);
            }
        }
    }

    /// Analytic: Ddot = 0, gdot = [c thetadot; 0] (c = [`TriCriteria::rmp_coefficient`]),
    /// Adot = [Jdot 0], bdot = rddot*, Gdot = 0; the bounds' derivative by
    /// [`merged_bounds_dot`] (right-hand derivative at the kink), in the bounds or in hdot by
    /// the placement.
    fn build_dot(
        &self,
        t: f64,
        theta: &[f64],
        thetadot: &[f64],
        _thetaddot: &[f64],
        qp_dot: &mut Qp,
        _scratch: &mut QpDotScratch,
    ) {
        debug_assert_eq!(qp_dot.dims(), self.dims());
        let n = self.joints();
        let c = self.rmp_coefficient();
        qp_dot.p.as_mut_slice().fill(0.0);
        for (q, v) in qp_dot.q.iter_mut().zip(thetadot) {
            *q = c * v;
        }
        qp_dot.q[n] = 0.0;
        self.robot
            .jacobian_dot(theta, thetadot, &mut qp_dot.a.as_mut_slice()[..3 * n]);
        for r in 0..3 {
            qp_dot.a[(r, n)] = 0.0;
        }
        qp_dot.b.copy_from(&self.path.at(t).rddot);
        qp_dot.g.as_mut_slice().fill(0.0);
        qp_dot.h.as_mut_slice().fill(0.0);
        merged_bounds_dot(
            self.robot.limits(),
            theta,
            thetadot,
            self.bound_gain,
            &mut qp_dot.lower.as_mut_slice()[..n],
            &mut qp_dot.upper.as_mut_slice()[..n],
        );
        match self.placement {
            BoundPlacement::VariableBounds => {
                qp_dot.lower[n] = 0.0;
                qp_dot.upper[n] = 0.0;
            }
            BoundPlacement::InequalityRows => {
                // The bounds' derivatives were written into upper and lower above.
                for i in 0..n {
                    qp_dot.h[2 * n + i] = qp_dot.upper[i];
                    qp_dot.h[3 * n + 1 + i] = -qp_dot.lower[i];
                }
                qp_dot.lower.as_mut_slice().fill(0.0);
                qp_dot.upper.as_mut_slice().fill(0.0);
            }
        }
    }
}
