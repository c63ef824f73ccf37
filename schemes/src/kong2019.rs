//! kong2019: the finite-time repeatable-motion scheme (eq. 14) and the ZNN repetitive scheme it
//! is compared with (eq. 22) (Kong et al. 2019), both velocity level, x = thetadot in R^n:
//!
//! ```text
//! finite time (14):  min thetadot'thetadot/2 + beta_theta c'thetadot
//!                    c_i = |theta_i - theta*0_i|^alpha sgn(theta_i - theta*0_i),  0 < alpha < 1
//! ZNN (22):          min thetadot'thetadot/2 + mu (theta - theta*0)'thetadot
//! both s.t.          J thetadot = rdot* + k_p (r* - f(theta))
//! ```
//!
//! so P = I, q = beta_theta c (or mu (theta - theta*0)), A = J, b = rdot* + k_p (r* - f(theta));
//! no inequalities, no bounds (the paper enforces no joint limits).
//!
//! theta*0 is the desired initial joint vector, given to the constructor. Eq. (22) as printed
//! uses theta(0), the actual initial state, and the text adds that the ZNN scheme "assumes the
//! joints start at the desired position", i.e. theta(0) = theta*0 in its own setting; we take
//! the reference from the constructor for both schemes, so an experiment chooses theta*0 (the
//! fair comparison, and what Table 3's drifts suggest) or theta(0) (the print, literally).
//!
//! Time derivatives (analytic, `build_dot`): Pdot = 0, Adot = Jdot,
//! bdot = rddot* + k_p (rdot* - J thetadot); ZNN: qdot = mu thetadot; finite time:
//! qdot_i = beta_theta c'(e_i) thetadot_i with e = theta - theta*0.
//!
//! Regularisation (a deviation, documented in the report): c is Hölder, not Lipschitz, at
//! e = 0 for alpha < 1, so after the finite-time convergence the closed loop
//! thetadot_i = -beta_theta |e_i|^alpha sgn(e_i) (joint 5 exactly) chatters around e_i = 0 and
//! no integrator can step there (explicit steps shrink to ~1e-8 s, Newton iterations of
//! implicit ones diverge). We use the smoothed sign-power of the finite-time network,
//! c(e) = e (e^2 + delta^2)^((alpha - 1)/2) (`crate::sign_power::sign_power`, delta =
//! `smoothing`, default 1e-6 rad): odd, increasing, smooth, equal to |e|^alpha sgn(e) to 0.5 %
//! for |e| >= 10 delta, and with slope delta^(alpha - 1) at 0 (so e decays exponentially with
//! time constant delta^(1 - alpha) / beta_theta ~ 4e-6 s once inside the band).

use std::sync::Arc;

use crate::qp::{Qp, QpDims};
use crate::sign_power::{sign_power, sign_power_slope};
use nalgebra::{SVector, Vector3};
use robots::Robot;

use crate::paths::{Path, PathPoint};
use crate::qp_dot::QpDotScratch;
use crate::scheme::{Level, Scheme};

/// The repetitive term of the linear part of the objective.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Repetitive {
    /// q = beta_theta |e|^alpha sgn(e) (eq. 14).
    FiniteTime {
        beta_theta: f64,
        alpha: f64,
        smoothing: f64,
    },
    /// q = mu e (eq. 22).
    Znn { mu: f64 },
}

/// kong2019's velocity-level repetitive schemes: finite time (eq. 14) or ZNN (eq. 22).
pub struct Kong2019<const N: usize> {
    robot: Arc<dyn Robot<N>>,
    path: Arc<dyn Path>,
    theta_star0: SVector<f64, N>,
    /// Position feedback gain k_p.
    pub k_p: f64,
    term: Repetitive,
}

/// Default smoothing width delta of c (see the module docs).
pub const SMOOTHING: f64 = 1e-6;

/// c = |e|^alpha sgn(e) elementwise, e = theta - theta*0 (kong2019's eq. (3)/(14)), smoothed
/// over |e| ~ delta = `smoothing` (exact for delta = 0).
pub fn finite_time_c<const N: usize>(
    theta: &SVector<f64, N>,
    theta_star0: &SVector<f64, N>,
    alpha: f64,
    smoothing: f64,
) -> SVector<f64, N> {
    (theta - theta_star0).map(|e| sign_power(e, alpha, smoothing))
}

/// Writes the QP of (14)/(22) from its parts, as slices so that fixed- and dynamic-size
/// storage both fit (the const-generic [`Kong2019`] and the cost harness's arms of hundreds of
/// joints): P = I, q = `q`, A = J (`jac`: 3 x n, column-major), b = rdot* + k_p (r* - f(theta)),
/// no bounds.
pub fn fill_qp(
    qp: &mut Qp,
    q: &[f64],
    jac: &[f64],
    f: &Vector3<f64>,
    desired: &PathPoint,
    k_p: f64,
) {
    qp.p.fill_with_identity();
    qp.q.as_mut_slice().copy_from_slice(q);
    qp.a.as_mut_slice().copy_from_slice(jac);
    qp.b.copy_from(&(desired.rdot + (desired.r - f) * k_p));
    qp.lower.as_mut_slice().fill(f64::NEG_INFINITY);
    qp.upper.as_mut_slice().fill(f64::INFINITY);
}

impl<const N: usize> Kong2019<N> {
    /// The finite-time scheme (14) with gain beta_theta, exponent alpha and feedback k_p.
    pub fn finite_time(
        robot: Arc<dyn Robot<N>>,
        path: Arc<dyn Path>,
        theta_star0: SVector<f64, N>,
        beta_theta: f64,
        alpha: f64,
        k_p: f64,
    ) -> Self {
        Self {
            robot,
            path,
            theta_star0,
            k_p,
            term: Repetitive::FiniteTime {
                beta_theta,
                alpha,
                smoothing: SMOOTHING,
            },
        }
    }

    /// The ZNN repetitive scheme (22) with gain mu and feedback k_p.
    pub fn znn(
        robot: Arc<dyn Robot<N>>,
        path: Arc<dyn Path>,
        theta_star0: SVector<f64, N>,
        mu: f64,
        k_p: f64,
    ) -> Self {
        Self {
            robot,
            path,
            theta_star0,
            k_p,
            term: Repetitive::Znn { mu },
        }
    }

    pub fn theta_star0(&self) -> &SVector<f64, N> {
        &self.theta_star0
    }

    /// The linear objective term q(theta) (beta_theta c, or mu (theta - theta*0)).
    pub fn linear_term(&self, theta: &SVector<f64, N>) -> SVector<f64, N> {
        match self.term {
            Repetitive::FiniteTime {
                beta_theta,
                alpha,
                smoothing,
            } => finite_time_c(theta, &self.theta_star0, alpha, smoothing) * beta_theta,
            Repetitive::Znn { mu } => (theta - self.theta_star0) * mu,
        }
    }
}

impl<const N: usize> Scheme<N> for Kong2019<N> {
    fn name(&self) -> String {
        match self.term {
            Repetitive::FiniteTime { .. } => "finite-time".to_string(),
            Repetitive::Znn { .. } => "ZNN".to_string(),
        }
    }

    fn level(&self) -> Level {
        Level::Velocity
    }

    fn dims(&self) -> QpDims {
        QpDims {
            nx: N,
            n_eq: 3,
            n_in: 0,
        }
    }

    fn build(&self, t: f64, theta: &SVector<f64, N>, _thetadot: &SVector<f64, N>, qp: &mut Qp) {
        debug_assert_eq!(qp.dims(), self.dims());
        fill_qp(
            qp,
            self.linear_term(theta).as_slice(),
            self.robot.jacobian(theta).as_slice(),
            &self.robot.position(theta),
            &self.path.at(t),
            self.k_p,
        );
    }

    /// Analytic (see the module docs for the finite-time regularisation at e = 0).
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
        qp_dot.p.as_mut_slice().fill(0.0);
        match self.term {
            Repetitive::FiniteTime {
                beta_theta,
                alpha,
                smoothing,
            } => {
                for i in 0..N {
                    let e = theta[i] - self.theta_star0[i];
                    qp_dot.q[i] = beta_theta * sign_power_slope(e, alpha, smoothing) * thetadot[i];
                }
            }
            Repetitive::Znn { mu } => {
                for i in 0..N {
                    qp_dot.q[i] = mu * thetadot[i];
                }
            }
        }
        qp_dot
            .a
            .copy_from(&self.robot.jacobian_dot(theta, thetadot));
        let pp = self.path.at(t);
        let jthd = self.robot.jacobian(theta) * thetadot;
        qp_dot
            .b
            .copy_from(&(pp.rddot + (pp.rdot - jthd) * self.k_p));
        qp_dot.lower.as_mut_slice().fill(0.0);
        qp_dot.upper.as_mut_slice().fill(0.0);
    }
}
