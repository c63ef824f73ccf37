//! Katana 6M180, 5 joints, exactly as kong2019's eq. (2) (`docs/robots.md`).
//!
//! With `C1 = cos theta1`, `C23 = cos(theta2 + theta3)`, `S234 = sin(theta2 + theta3 + theta4)`
//! etc. and `L = l4 + l5`:
//!
//! ```text
//! h    = l2 C2 + l3 C23 + L S234
//! f(θ) = [ C1 h,  S1 h,  l1 - L C234 + l2 S2 + l3 S23 ]
//! ```
//!
//! Joint 5 (wrist roll) does not appear: its Jacobian column is zero. With the partial
//! derivatives of `h` and of the height `z`,
//!
//! ```text
//! h2 = -l2 S2 - l3 S23 + L C234,   h3 = -l3 S23 + L C234,   h4 = L C234,
//! z2 =  l2 C2 + l3 C23 + L S234 = h,   z3 = l3 C23 + L S234,   z4 = L S234,
//! J  = [ -S1 h   C1 h2   C1 h3   C1 h4   0 ]
//!      [  C1 h   S1 h2   S1 h3   S1 h4   0 ]
//!      [  0      z2      z3      z4      0 ]
//! ```
//!
//! and `Jdot` is its exact time derivative, using the angle rates `w2 = thetadot2`,
//! `w23 = thetadot2 + thetadot3`, `w234 = w23 + thetadot4`:
//! `hdot2 = -l2 C2 w2 - l3 C23 w23 - L S234 w234`, `hdot3 = -l3 C23 w23 - L S234 w234`,
//! `hdot4 = -L S234 w234`, `zdot2 = hdot = h2 thetadot2 + h3 thetadot3 + h4 thetadot4`,
//! `zdot3 = -l3 S23 w23 + L C234 w234`, `zdot4 = L C234 w234`.
//!
//! Joint limits: kong2019's scheme enforces none, so all limits are infinite.

use nalgebra::{DVector, MatrixViewMut, Vector3, U3, U5};

use crate::{JointLimits, Robot};

/// Model name of the Katana 6M180.
pub const KATANA6M180: &str = "katana6m180";

/// The Katana 6M180 position model of kong2019, eq. (2).
#[derive(Clone, Debug, PartialEq)]
pub struct Katana6m180 {
    /// Base height l1 (m).
    pub l1: f64,
    /// Upper-arm length l2 (m).
    pub l2: f64,
    /// Forearm length l3 (m).
    pub l3: f64,
    /// Wrist length l4 (m).
    pub l4: f64,
    /// Gripper length l5 (m); only l4 + l5 matters.
    pub l5: f64,
    /// No joint limits: kong2019 states none.
    limits: JointLimits,
}

/// Sines and cosines shared by the position, Jacobian and Jdot.
#[derive(Clone, Copy)]
struct Trig {
    s1: f64,
    c1: f64,
    s2: f64,
    c2: f64,
    s23: f64,
    c23: f64,
    s234: f64,
    c234: f64,
}

thread_local! {
    /// The last angles this thread asked for and their `Trig`: a network's right-hand side
    /// asks for f and J, then for Jdot, at the same angles, and the observer again at an
    /// accepted step's (a Runge-Kutta method's last stage), so the eight sines and cosines are
    /// evaluated once there. The values only depend on the angles, compared bit for bit.
    static LAST: std::cell::Cell<Option<([u64; 5], Trig)>> = const { std::cell::Cell::new(None) };
}

impl Trig {
    /// The sines and cosines at `theta`, from this thread's last evaluation when the angles
    /// are the same bit for bit (`LAST`).
    fn new(theta: &[f64]) -> Self {
        assert_eq!(theta.len(), 5, "katana6m180: 5 joint angles");
        let key = [0, 1, 2, 3, 4].map(|i| theta[i].to_bits());
        LAST.with(|last| match last.get() {
            Some((k, t)) if k.iter().zip(&key).all(|(a, b)| a == b) => t,
            _ => {
                let t = Self::compute(theta);
                last.set(Some((key, t)));
                t
            }
        })
    }

    fn compute(theta: &[f64]) -> Self {
        let (s1, c1) = theta[0].sin_cos();
        let (s2, c2) = theta[1].sin_cos();
        let (s23, c23) = (theta[1] + theta[2]).sin_cos();
        let (s234, c234) = (theta[1] + theta[2] + theta[3]).sin_cos();
        Trig {
            s1,
            c1,
            s2,
            c2,
            s23,
            c23,
            s234,
            c234,
        }
    }
}

impl Katana6m180 {
    /// The Katana manual's lengths: l1 = 0.2015, l2 = 0.19, l3 = 0.139, l4 = 0.1523, l5 = 0.1505.
    pub fn new() -> Self {
        Katana6m180 {
            l1: 0.2015,
            l2: 0.19,
            l3: 0.139,
            l4: 0.1523,
            l5: 0.1505,
            limits: JointLimits {
                theta_min: DVector::repeat(5, f64::NEG_INFINITY),
                theta_max: DVector::repeat(5, f64::INFINITY),
                thetadot_min: DVector::repeat(5, f64::NEG_INFINITY),
                thetadot_max: DVector::repeat(5, f64::INFINITY),
            },
        }
    }

    /// Wrist-plus-gripper length L = l4 + l5.
    fn wrist(&self) -> f64 {
        self.l4 + self.l5
    }

    /// Horizontal reach `h` and its partials `(h2, h3, h4)`.
    fn reach(&self, t: &Trig) -> (f64, [f64; 3]) {
        let l = self.wrist();
        let h = self.l2 * t.c2 + self.l3 * t.c23 + l * t.s234;
        let h4 = l * t.c234;
        let h3 = -self.l3 * t.s23 + h4;
        let h2 = -self.l2 * t.s2 + h3;
        (h, [h2, h3, h4])
    }

    /// f(theta) of eq. (2) from its sines and cosines.
    fn position_at(&self, t: &Trig) -> Vector3<f64> {
        let (h, _) = self.reach(t);
        let z = self.l1 - self.wrist() * t.c234 + self.l2 * t.s2 + self.l3 * t.s23;
        Vector3::new(t.c1 * h, t.s1 * h, z)
    }

    /// J(theta) (module docs) from the sines and cosines, into the 3 x 5 column-major `jac`.
    fn jacobian_at(&self, t: &Trig, jac: &mut [f64]) {
        let (h, dh) = self.reach(t);
        let z4 = self.wrist() * t.s234;
        let z3 = self.l3 * t.c23 + z4;
        let dz = [h, z3, z4];
        let mut jac = MatrixViewMut::<f64, U3, U5>::from_slice(jac);
        jac.fill(0.0);
        jac[(0, 0)] = -t.s1 * h;
        jac[(1, 0)] = t.c1 * h;
        for k in 0..3 {
            jac[(0, k + 1)] = t.c1 * dh[k];
            jac[(1, k + 1)] = t.s1 * dh[k];
            jac[(2, k + 1)] = dz[k];
        }
    }
}

impl Default for Katana6m180 {
    fn default() -> Self {
        Self::new()
    }
}

impl Robot for Katana6m180 {
    fn name(&self) -> &'static str {
        KATANA6M180
    }

    fn dof(&self) -> usize {
        5
    }

    fn position(&self, theta: &[f64]) -> Vector3<f64> {
        self.position_at(&Trig::new(theta))
    }

    fn jacobian(&self, theta: &[f64], jac: &mut [f64]) {
        self.jacobian_at(&Trig::new(theta), jac);
    }

    /// One set of sines and cosines for both.
    fn position_jacobian(&self, theta: &[f64], jac: &mut [f64]) -> Vector3<f64> {
        let t = Trig::new(theta);
        self.jacobian_at(&t, jac);
        self.position_at(&t)
    }
    fn jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        let t = Trig::new(theta);
        let l = self.wrist();
        let (h, dh) = self.reach(&t);
        let w1 = thetadot[0];
        let w2 = thetadot[1];
        let w23 = w2 + thetadot[2];
        let w234 = w23 + thetadot[3];
        let h_dot = dh[0] * thetadot[1] + dh[1] * thetadot[2] + dh[2] * thetadot[3];
        let dh4_dot = -l * t.s234 * w234;
        let dh3_dot = -self.l3 * t.c23 * w23 + dh4_dot;
        let dh2_dot = -self.l2 * t.c2 * w2 + dh3_dot;
        let dh_dot = [dh2_dot, dh3_dot, dh4_dot];
        let dz4_dot = l * t.c234 * w234;
        let dz3_dot = -self.l3 * t.s23 * w23 + dz4_dot;
        let dz_dot = [h_dot, dz3_dot, dz4_dot];
        let mut jdot = MatrixViewMut::<f64, U3, U5>::from_slice(jdot);
        jdot.fill(0.0);
        jdot[(0, 0)] = -t.c1 * w1 * h - t.s1 * h_dot;
        jdot[(1, 0)] = -t.s1 * w1 * h + t.c1 * h_dot;
        for k in 0..3 {
            jdot[(0, k + 1)] = -t.s1 * w1 * dh[k] + t.c1 * dh_dot[k];
            jdot[(1, k + 1)] = t.c1 * w1 * dh[k] + t.s1 * dh_dot[k];
            jdot[(2, k + 1)] = dz_dot[k];
        }
    }

    fn limits(&self) -> &JointLimits {
        &self.limits
    }

    /// Base, shoulder, elbow, wrist and task point, from the pieces of eq. (2):
    /// shoulder `(0, 0, l1)`, elbow `shoulder + l2 [C1 C2, S1 C2, S2]`, wrist
    /// `elbow + l3 [C1 C23, S1 C23, S23]`, task point `wrist + L [C1 S234, S1 S234, -C234]`.
    fn skeleton(&self, theta: &[f64]) -> Vec<Vector3<f64>> {
        let t = Trig::new(theta);
        let base = Vector3::zeros();
        let shoulder = Vector3::new(0.0, 0.0, self.l1);
        let elbow = shoulder + self.l2 * Vector3::new(t.c1 * t.c2, t.s1 * t.c2, t.s2);
        let wrist = elbow + self.l3 * Vector3::new(t.c1 * t.c23, t.s1 * t.c23, t.s23);
        vec![base, shoulder, elbow, wrist, self.position(theta)]
    }
}
