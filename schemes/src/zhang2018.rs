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

use std::sync::{Arc, Mutex};

use nalgebra::{DMatrix, DVector, Vector3};
use qp::{Qp, QpDims};
use robots::Dynamics;

use crate::paths::Path;
use crate::scheme::{Level, Scheme};

/// zhang2018's HL-JDF scheme (MTN when zeta = 0), eq. 2.5–2.6.
pub struct Zhang2018 {
    robot: Arc<dyn Dynamics>,
    path: Arc<dyn Path>,
    theta0: Vec<f64>,
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
    /// H, c, g and Jdot of one build, allocated with the scheme (no allocation per build).
    scratch: Mutex<Scratch>,
}

/// The buffers of one build.
struct Scratch {
    /// H(theta), n x n.
    h: DMatrix<f64>,
    /// c(theta, thetadot), then c + g.
    cg: DVector<f64>,
    /// g(theta).
    g: DVector<f64>,
    /// H' (c + g).
    htcg: DVector<f64>,
    /// Jdot(theta, thetadot), 3 x n column-major.
    jdot: Vec<f64>,
}

impl Scratch {
    fn new(n: usize) -> Self {
        Scratch {
            h: DMatrix::zeros(n, n),
            cg: DVector::zeros(n),
            g: DVector::zeros(n),
            htcg: DVector::zeros(n),
            jdot: vec![0.0; 3 * n],
        }
    }
}

/// (a b)_{ij} = sum_k a_{ik} b_{kj}, summed in k order from k = 0 (the order of nalgebra's
/// small-matrix product, which the fixed-size scheme used), written into `out`.
fn product_to(a: &DMatrix<f64>, b: &DMatrix<f64>, out: &mut [f64]) {
    let n = a.nrows();
    for j in 0..n {
        for i in 0..n {
            let mut s = a[(i, 0)] * b[(0, j)];
            for k in 1..n {
                s += a[(i, k)] * b[(k, j)];
            }
            out[i + j * n] = s;
        }
    }
}

/// y = a x for a 3 x n column-major `a`, summed column by column in joint order.
fn times(a: &[f64], x: &[f64]) -> Vector3<f64> {
    let mut y = Vector3::zeros();
    for (j, v) in x.iter().enumerate() {
        for i in 0..3 {
            y[i] += a[3 * j + i] * v;
        }
    }
    y
}

impl Zhang2018 {
    /// Scheme on a robot with dynamics (kinematics are taken from the same model); `theta0` has
    /// one entry per joint.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        robot: Arc<dyn Dynamics>,
        path: Arc<dyn Path>,
        theta0: &[f64],
        zeta: f64,
        alpha: f64,
        beta: f64,
        rho_v: f64,
        rho_p: f64,
    ) -> Self {
        let n = robot.dof();
        assert_eq!(theta0.len(), n, "theta0: one entry per joint");
        Self {
            robot,
            path,
            theta0: theta0.to_vec(),
            zeta,
            alpha,
            beta,
            rho_v,
            rho_p,
            scratch: Mutex::new(Scratch::new(n)),
        }
    }

    /// The joint reference theta0 of sigma, as given at construction.
    pub fn theta0(&self) -> &[f64] {
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

    /// W = zeta I + (1 - zeta) H(theta)^2 (allocates: for checks and tests).
    pub fn weight_matrix(&self, theta: &[f64]) -> DMatrix<f64> {
        let n = self.joints();
        let h = self.robot.inertia_matrix(theta);
        let mut hh = DMatrix::zeros(n, n);
        product_to(&h, &h, hh.as_mut_slice());
        DMatrix::from_fn(n, n, |i, j| {
            let identity = if i == j { 1.0 } else { 0.0 };
            identity * self.zeta + hh[(i, j)] * (1.0 - self.zeta)
        })
    }
}

impl Scheme for Zhang2018 {
    fn name(&self) -> String {
        Self::scheme_name(self.zeta).to_string()
    }

    fn level(&self) -> Level {
        Level::Acceleration
    }

    fn joints(&self) -> usize {
        self.theta0.len()
    }

    fn dims(&self) -> QpDims {
        QpDims {
            nx: self.joints(),
            n_eq: 3,
            n_in: 0,
        }
    }

    fn build(&self, t: f64, theta: &[f64], thetadot: &[f64], qp: &mut Qp) {
        debug_assert_eq!(qp.dims(), self.dims());
        let n = self.joints();
        let z = self.zeta;
        let mut scratch = self
            .scratch
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let Scratch {
            h,
            cg,
            g,
            htcg,
            jdot,
        } = &mut *scratch;
        self.robot.inertia(theta, h.as_mut_slice());
        // P = W = zeta I + (1 - zeta) H^2, symmetrised: (W + W') / 2.
        product_to(h, h, qp.p.as_mut_slice());
        for j in 0..n {
            for i in 0..n {
                let identity = if i == j { 1.0 } else { 0.0 };
                qp.p[(i, j)] = identity * z + qp.p[(i, j)] * (1.0 - z);
            }
        }
        for j in 0..n {
            for i in 0..j {
                let w = (qp.p[(i, j)] + qp.p[(j, i)]) * 0.5;
                qp.p[(i, j)] = w;
                qp.p[(j, i)] = w;
            }
        }
        // eta = zeta sigma + (1 - zeta) H'(c + g).
        self.robot.coriolis(theta, thetadot, cg.as_mut_slice());
        self.robot.gravity(theta, g.as_mut_slice());
        *cg += &*g;
        h.tr_mul_to(cg, htcg);
        for i in 0..n {
            let sigma = thetadot[i] * (self.alpha + self.beta)
                + (theta[i] - self.theta0[i]) * (self.alpha * self.beta);
            qp.q[i] = sigma * z + htcg[i] * (1.0 - z);
        }
        // A = J; b = rddot* - Jdot thetadot + rho_v (rdot* - J thetadot) + rho_p (r* - f).
        self.robot.jacobian(theta, qp.a.as_mut_slice());
        let pp = self.path.at(t);
        self.robot.jacobian_dot(theta, thetadot, jdot);
        let jthd = times(qp.a.as_slice(), thetadot);
        let b = pp.rddot - times(jdot, thetadot)
            + (pp.rdot - jthd) * self.rho_v
            + (pp.r - self.robot.position(theta)) * self.rho_p;
        qp.b.copy_from(&b);
        qp.lower.as_mut_slice().fill(f64::NEG_INFINITY);
        qp.upper.as_mut_slice().fill(f64::INFINITY);
    }

    fn torque(&self, theta: &[f64], thetadot: &[f64], thetaddot: &[f64], tau: &mut [f64]) -> bool {
        let n = self.joints();
        let mut scratch = self
            .scratch
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let Scratch { h, cg, g, .. } = &mut *scratch;
        self.robot.inertia(theta, h.as_mut_slice());
        self.robot.coriolis(theta, thetadot, cg.as_mut_slice());
        self.robot.gravity(theta, g.as_mut_slice());
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
