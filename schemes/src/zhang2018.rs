//! zhang2018: the HL-JDF scheme (hybrid-level joint-drift-free, mixing minimum torque norm and
//! minimum velocity norm), eq. 2.5–2.6 (Zhang et al. 2018).
//!
//! Acceleration level, x = thetaddot in R^n:
//!
//! ```text
//! min   x'Wx/2 + eta'x                                          (2.5)
//! s.t.  J x = b                                                 (2.6)
//! W     = zeta I + (1 - zeta) H^2
//! eta   = zeta sigma + (1 - zeta) H'(c + g)
//! sigma = (alpha + beta) thetadot + alpha beta (theta - theta0)
//! b     = rddot* - Jdot thetadot + rho_v (rdot* - J thetadot) + rho_p (r* - f(theta))
//! ```
//!
//! from min (zeta |thetadot + s|^2 + (1 - zeta) |tau|^2)/2 with tau = H thetaddot + c + g (2.2)–(2.4).
//! zeta = 0 is MTN (minimum torque norm), zeta = 1 MVN; W is symmetric positive definite for
//! zeta in (0, 1] and also for zeta = 0 (H is SPD). No inequalities, no bounds.
//!
//! Choices (documented deviations): mu and "K = I" of the paper's parameter list do not appear
//! in the QP as printed (sigma uses alpha and beta) and are not parameters here; theta0 is the
//! run's initial joint vector. `build_dot` is the default central difference (an analytic
//! derivative would need dc/dt, dg/dt, J-double-dot and the path's jerk, none of which the robot
//! and path interfaces provide).

use std::sync::Arc;

use crate::qp::{Qp, QpDims};
use nalgebra::{SMatrix, SVector};
use robots::Dynamics;

use crate::paths::Path;
use crate::scheme::{Level, Scheme};

/// zhang2018's HL-JDF scheme (MTN when zeta = 0), eq. 2.5–2.6.
pub struct Zhang2018<const N: usize> {
    robot: Arc<dyn Dynamics<N>>,
    path: Arc<dyn Path>,
    theta0: SVector<f64, N>,
    /// MVN/MTN mixing weight zeta in [0, 1].
    pub zeta: f64,
    /// Drift-criterion gain alpha of sigma = (alpha + beta) thetadot + alpha beta
    /// (theta - theta0).
    pub alpha: f64,
    /// Drift-criterion gain beta of sigma (see `alpha`).
    pub beta: f64,
    /// Velocity feedback gain rho_v of b's rho_v (rdot* - J thetadot).
    pub rho_v: f64,
    /// Position feedback gain rho_p of b's rho_p (r* - f(theta)).
    pub rho_p: f64,
}

impl<const N: usize> Zhang2018<N> {
    /// Scheme on a robot with dynamics (kinematics are taken from the same model).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        robot: Arc<dyn Dynamics<N>>,
        path: Arc<dyn Path>,
        theta0: SVector<f64, N>,
        zeta: f64,
        alpha: f64,
        beta: f64,
        rho_v: f64,
        rho_p: f64,
    ) -> Self {
        Self {
            robot,
            path,
            theta0,
            zeta,
            alpha,
            beta,
            rho_v,
            rho_p,
        }
    }

    /// The joint reference theta0 of sigma, as given at construction.
    pub fn theta0(&self) -> &SVector<f64, N> {
        &self.theta0
    }

    /// The paper's name: MTN for zeta = 0, HL-JDF otherwise.
    pub fn scheme_name(zeta: f64) -> &'static str {
        if zeta == 0.0 {
            "MTN"
        } else {
            "HL-JDF"
        }
    }

    /// W = zeta I + (1 - zeta) H(theta)^2.
    pub fn weight_matrix(&self, theta: &SVector<f64, N>) -> SMatrix<f64, N, N> {
        let h = self.robot.inertia(theta);
        SMatrix::<f64, N, N>::identity() * self.zeta + (h * h) * (1.0 - self.zeta)
    }
}

impl<const N: usize> Scheme<N> for Zhang2018<N> {
    fn name(&self) -> String {
        Self::scheme_name(self.zeta).to_string()
    }

    fn level(&self) -> Level {
        Level::Acceleration
    }

    fn dims(&self) -> QpDims {
        QpDims {
            nx: N,
            n_eq: 3,
            n_in: 0,
        }
    }

    fn build(&self, t: f64, theta: &SVector<f64, N>, thetadot: &SVector<f64, N>, qp: &mut Qp) {
        debug_assert_eq!(qp.dims(), self.dims());
        let z = self.zeta;
        let h = self.robot.inertia(theta);
        let w = SMatrix::<f64, N, N>::identity() * z + (h * h) * (1.0 - z);
        // Symmetrise against rounding so P is exactly symmetric.
        let w = (w + w.transpose()) * 0.5;
        qp.p.copy_from(&w);
        let cg = self.robot.coriolis(theta, thetadot) + self.robot.gravity(theta);
        let sigma =
            thetadot * (self.alpha + self.beta) + (theta - self.theta0) * (self.alpha * self.beta);
        let eta = sigma * z + h.tr_mul(&cg) * (1.0 - z);
        qp.q.copy_from(&eta);
        let j = self.robot.jacobian(theta);
        qp.a.copy_from(&j);
        let pp = self.path.at(t);
        let jd = self.robot.jacobian_dot(theta, thetadot);
        let jthd = j * thetadot;
        let b = pp.rddot - jd * thetadot
            + (pp.rdot - jthd) * self.rho_v
            + (pp.r - self.robot.position(theta)) * self.rho_p;
        qp.b.copy_from(&b);
        // No inequalities (n_in = 0) and no bounds.
        qp.lower.as_mut_slice().fill(f64::NEG_INFINITY);
        qp.upper.as_mut_slice().fill(f64::INFINITY);
    }

    fn torque(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
        thetaddot: &SVector<f64, N>,
    ) -> Option<SVector<f64, N>> {
        Some(
            self.robot.inertia(theta) * thetaddot
                + self.robot.coriolis(theta, thetadot)
                + self.robot.gravity(theta),
        )
    }
}
