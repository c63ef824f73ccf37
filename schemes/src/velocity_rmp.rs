//! The velocity-level repetitive-motion scheme composed from the vocabulary's terms
//! (docs/schemes.md), x = thetadot in R^n:
//!
//! ```text
//! min   w thetadot'thetadot/2 + g(theta)'thetadot          velocity norm + repetitive term
//! s.t.  J thetadot = rdot* + k_p (r* - f(theta))           tracking equality
//!       zeta-(theta) <= thetadot <= zeta+(theta)           bound conversion (optional)
//! ```
//!
//! so P = w I, q = g(theta), A = J, b = rdot* + k_p (r* - f(theta)), no inequality rows. Terms:
//!
//! - **velocity norm** `w > 0` (the papers all take w = 1; `w (thetadot + C)'(thetadot + C)/2`
//!   of robio2018 (4)-(5) expands to this with w = 1 and a constant dropped);
//! - **repetitive term** g (theta_ref is the scheme's joint reference, theta0 or kong2019's
//!   theta*0), in one of two forms:
//!   - `linear`: g = lambda (theta - theta_ref), lambda >= 0 (robio2018 (4) C = lambda
//!     (theta - theta(0)); kong2019 (22) with lambda = mu). lambda = 0 drops the term: robio2018's
//!     baseline of Fig. 2(a) "λ = 0 denotes no consideration of drift-free";
//!   - `sign-power`: g_i = beta |e_i|^alpha sgn(e_i), e = theta - theta_ref (kong2019 (14),
//!     beta = beta_theta, 0 < alpha < 1), smoothed over |e| ~ delta as below;
//! - **tracking** gain k_p >= 0 (0: b = rdot* as robio2018 (12) prints);
//! - **bound conversion** with gain upsilon > 0 of the joint-angle limits into velocity bounds,
//!   intersected with the velocity limits (robio2018 (9)-(10), jia2019 (2.15)-(2.16)):
//!   zeta-_i = max{thetadot-_i, upsilon (theta-_i - theta_i)}, zeta+_i = min{thetadot+_i,
//!   upsilon (theta+_i - theta_i)} ([`crate::joint_limits::merged_bounds`]).
//!
//! kong2019's two schemes are presets: the finite-time scheme (14) is w = 1, sign-power with
//! beta_theta and alpha, tracking k_p, no bounds; the ZNN scheme (22) is w = 1, linear with
//! lambda = mu, tracking k_p, no bounds. robio2018's RMP (11)-(13) is w = 1, linear with lambda,
//! k_p = 0 and the bound conversion with upsilon.
//!
//! kong2019 (22) as printed uses theta(0), the actual initial state, and the text adds that the
//! ZNN scheme "assumes the joints start at the desired position", i.e. theta(0) = theta*0 in
//! its own setting; the reference comes from the constructor for every term, so an experiment
//! chooses theta*0 (the fair comparison, and what kong2019's Table 3 drifts suggest) or theta(0).
//!
//! Time derivatives (analytic, `build_dot`): Pdot = 0, Adot = Jdot,
//! bdot = rddot* + k_p (rdot* - J thetadot); linear: qdot = lambda thetadot; sign-power:
//! qdot_i = beta c'(e_i) thetadot_i; bounds: [`crate::joint_limits::merged_bounds_dot`].
//!
//! Regularisation (a deviation, documented in the report): c is Hölder, not Lipschitz, at
//! e = 0 for alpha < 1, so after the finite-time convergence the closed loop
//! thetadot_i = -beta_theta |e_i|^alpha sgn(e_i) (joint 5 exactly) chatters around e_i = 0 and
//! no integrator can step there (explicit steps shrink to ~1e-8 s, Newton iterations of
//! implicit ones diverge). We use the smoothed sign-power of the finite-time network,
//! c(e) = e (e^2 + delta^2)^((alpha - 1)/2) (`settings::sign_power::sign_power`, delta =
//! `smoothing`, default 1e-6 rad): odd, increasing, smooth, equal to |e|^alpha sgn(e) to 0.5 %
//! for |e| >= 10 delta, and with slope delta^(alpha - 1) at 0 (so e decays exponentially with
//! time constant delta^(1 - alpha) / beta_theta ~ 4e-6 s once inside the band).

use std::sync::Arc;

use crate::joint_limits::{merged_bounds, merged_bounds_dot};
use nalgebra::Vector3;
use qp::{Qp, QpDims};
use robots::Robot;
use settings::sign_power::{sign_power, sign_power_slope};

use crate::paths::{Path, PathPoint};
use crate::scheme::{Level, Scheme};
use qp::dot::QpDotScratch;

/// The repetitive term g(theta) of the linear part of the objective.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Repetitive {
    /// g = lambda (theta - theta_ref) (robio2018 (4), kong2019 (22)); lambda = 0: no term.
    Linear {
        /// Gain lambda (>= 0; 0: no term).
        lambda: f64,
    },
    /// g = beta |e|^alpha sgn(e), smoothed (kong2019 (14)).
    SignPower {
        /// Gain beta (> 0; kong2019's beta_theta).
        beta: f64,
        /// Exponent alpha (> 0; kong2019 takes 0 < alpha < 1).
        alpha: f64,
        /// Smoothing width delta (rad) of c(e) = e (e^2 + delta^2)^((alpha - 1)/2) (module docs;
        /// default [`SMOOTHING`]).
        smoothing: f64,
    },
}

/// The velocity-level repetitive-motion scheme of the vocabulary (module docs).
pub struct VelocityRmp {
    robot: Arc<dyn Robot>,
    path: Arc<dyn Path>,
    theta_ref: Vec<f64>,
    /// Weight w of the velocity norm (P = w I).
    pub weight: f64,
    /// Position feedback gain k_p.
    pub k_p: f64,
    term: Repetitive,
    /// Gain upsilon of the bound conversion, or none (no bounds).
    bounds: Option<f64>,
    /// The scheme's name as its paper writes it (display only).
    name: &'static str,
}

/// Default smoothing width delta of c (see the module docs).
pub const SMOOTHING: f64 = 1e-6;

/// Writes the parts of the scheme's QP with w = 1 that do not depend on how the arm's
/// vectors are stored: P = I, b = rdot* + k_p (r* - f(theta)), no bounds. q and A (= J) are
/// the caller's.
fn fill_tracking(qp: &mut Qp, f: &Vector3<f64>, desired: &PathPoint, k_p: f64) {
    qp.p.fill_with_identity();
    qp.b.copy_from(&(desired.rdot + (desired.r - f) * k_p));
    qp.lower.as_mut_slice().fill(f64::NEG_INFINITY);
    qp.upper.as_mut_slice().fill(f64::INFINITY);
}

impl VelocityRmp {
    /// The scheme of every term given: weight `w`, repetitive `term`, tracking gain `k_p`,
    /// and the bound conversion with gain `bounds` (none: no bounds). `name` is display only.
    /// `theta_ref` has one entry per joint of `robot`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        robot: Arc<dyn Robot>,
        path: Arc<dyn Path>,
        theta_ref: &[f64],
        weight: f64,
        term: Repetitive,
        k_p: f64,
        bounds: Option<f64>,
        name: &'static str,
    ) -> Self {
        assert_eq!(
            theta_ref.len(),
            robot.dof(),
            "theta_ref: one entry per joint"
        );
        Self {
            robot,
            path,
            theta_ref: theta_ref.to_vec(),
            weight,
            k_p,
            term,
            bounds,
            name,
        }
    }

    /// kong2019's finite-time scheme (14) with gain beta_theta, exponent alpha and feedback
    /// k_p (a preset).
    pub fn finite_time(
        robot: Arc<dyn Robot>,
        path: Arc<dyn Path>,
        theta_star0: &[f64],
        beta_theta: f64,
        alpha: f64,
        k_p: f64,
    ) -> Self {
        let term = Repetitive::SignPower {
            beta: beta_theta,
            alpha,
            smoothing: SMOOTHING,
        };
        Self::new(
            robot,
            path,
            theta_star0,
            1.0,
            term,
            k_p,
            None,
            "finite-time",
        )
    }

    /// kong2019's ZNN repetitive scheme (22) with gain mu and feedback k_p (a preset).
    pub fn znn(
        robot: Arc<dyn Robot>,
        path: Arc<dyn Path>,
        theta_star0: &[f64],
        mu: f64,
        k_p: f64,
    ) -> Self {
        let term = Repetitive::Linear { lambda: mu };
        Self::new(robot, path, theta_star0, 1.0, term, k_p, None, "ZNN")
    }

    /// The scheme's joint reference (theta0, or kong2019's theta*0).
    pub fn theta_ref(&self) -> &[f64] {
        &self.theta_ref
    }

    /// Writes the linear objective term g(theta) (module docs) into `q`.
    pub fn linear_term(&self, theta: &[f64], q: &mut [f64]) {
        let pairs = q.iter_mut().zip(theta.iter().zip(&self.theta_ref));
        match self.term {
            Repetitive::SignPower {
                beta,
                alpha,
                smoothing,
            } => {
                for (q, (th, r)) in pairs {
                    *q = sign_power(th - r, alpha, smoothing) * beta;
                }
            }
            Repetitive::Linear { lambda } => {
                for (q, (th, r)) in pairs {
                    *q = (th - r) * lambda;
                }
            }
        }
    }
}

impl Scheme for VelocityRmp {
    fn name(&self) -> String {
        self.name.to_string()
    }

    fn level(&self) -> Level {
        Level::Velocity
    }

    fn dims(&self) -> QpDims {
        QpDims {
            nx: self.joints(),
            n_eq: 3,
            n_in: 0,
        }
    }

    fn joints(&self) -> usize {
        self.theta_ref.len()
    }

    fn build(&self, t: f64, theta: &[f64], _thetadot: &[f64], qp: &mut Qp) {
        debug_assert_eq!(qp.dims(), self.dims());
        self.linear_term(theta, qp.q.as_mut_slice());
        self.robot.jacobian(theta, qp.a.as_mut_slice());
        fill_tracking(qp, &self.robot.position(theta), &self.path.at(t), self.k_p);
        if self.weight != 1.0 {
            qp.p.fill_diagonal(self.weight);
        }
        if let Some(gain) = self.bounds {
            merged_bounds(
                self.robot.limits(),
                theta,
                gain,
                qp.lower.as_mut_slice(),
                qp.upper.as_mut_slice(),
            );
        }
    }

    /// Analytic (see the module docs for the finite-time regularisation at e = 0).
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
        qp_dot.p.as_mut_slice().fill(0.0);
        match self.term {
            Repetitive::SignPower {
                beta,
                alpha,
                smoothing,
            } => {
                for i in 0..self.joints() {
                    let e = theta[i] - self.theta_ref[i];
                    qp_dot.q[i] = beta * sign_power_slope(e, alpha, smoothing) * thetadot[i];
                }
            }
            Repetitive::Linear { lambda } => {
                for (q, v) in qp_dot.q.iter_mut().zip(thetadot) {
                    *q = lambda * v;
                }
            }
        }
        self.robot
            .jacobian_dot(theta, thetadot, qp_dot.a.as_mut_slice());
        let pp = self.path.at(t);
        // J thetadot, with J written into the scratch QP's A (same 3 x n shape), summed column
        // by column in joint order.
        let jac = &mut scratch.plus.a;
        self.robot.jacobian(theta, jac.as_mut_slice());
        let mut jthd = Vector3::zeros();
        for (j, v) in thetadot.iter().enumerate() {
            for i in 0..3 {
                jthd[i] += jac[(i, j)] * v;
            }
        }
        qp_dot
            .b
            .copy_from(&(pp.rddot + (pp.rdot - jthd) * self.k_p));
        match self.bounds {
            Some(gain) => {
                merged_bounds_dot(
                    self.robot.limits(),
                    theta,
                    thetadot,
                    gain,
                    qp_dot.lower.as_mut_slice(),
                    qp_dot.upper.as_mut_slice(),
                );
            }
            None => {
                qp_dot.lower.as_mut_slice().fill(0.0);
                qp_dot.upper.as_mut_slice().fill(0.0);
            }
        }
    }
}
