//! Kinova Jaco2 (j2n6s300), 6 revolute joints, in classical DH convention (`docs/robots.md`).
//!
//! DH table (`a_i`, `alpha_i`, `d_i`), with wrist half-angle `aa = pi/6` and
//! `k = sin(aa)/sin(2aa) = 1/sqrt(3)`:
//!
//! | i | a  | alpha | d                 |
//! |---|----|-------|-------------------|
//! | 1 | 0  | pi/2  | D1                |
//! | 2 | D2 | pi    | 0                 |
//! | 3 | 0  | pi/2  | -e2               |
//! | 4 | 0  | 2aa   | -(D3 + k D4)      |
//! | 5 | 0  | 2aa   | -k (D4 + D5)      |
//! | 6 | 0  | pi    | -(k D5 + D6)      |
//!
//! Variants:
//! - `jaco2-pen` ([`Jaco2::pen`], the papers' model): D6 = 0.1425, task point = pen tip
//!   (0, -0.075, 0) in frame 6, world = `Rx(-0.02) Ry(-0.05)` times DH frame 0.
//! - `jaco2-pen-exp2` ([`Jaco2::pen_exp2`], the group's EXP2 code, `docs/group-code.md`):
//!   the same chain, pen tip and tilt with D4 = D5 = 0.07433, D6 = 0.13 and aa = 11 pi / 72
//!   (so k = sin(aa)/sin(2aa) = 1/(2 cos(11 pi/72)) = 0.5637 instead of 1/sqrt(3)).
//! - `jaco2-hand` ([`Jaco2::hand`]): Kinova's kinematics with the papers' limits.
//! - `jaco2` ([`Jaco2::kinova`], Kinova's model): D6 = 0.16, task point = origin of frame 6,
//!   no tilt.
//!
//! Dynamics: every variant carries the physical arm's rigid chain ([`jaco2_rigid_chain`], the
//! inertial table of [`crate::jaco2_dynamics`] on the D6 = 0.16 chain) and implements
//! [`Dynamics`] on it.
//!
//! Task point `f(theta) = B T_6(theta) p_tip`; its Jacobian is the geometric
//! `J_j = z_{j-1} x (f - o_{j-1})` and `Jdot` its analytic time derivative
//! (see [`crate::geometric_jacobian`]). The fixed tilt `B` is part of the chain's base frame,
//! so all axes and origins are already in world coordinates.

use std::f64::consts::PI;

use nalgebra::{DVector, Matrix3, SMatrix, SVector, Vector3};

use crate::data_robot::DataRobot;
use crate::dh::{DhChain, DhParam, Frame};
use crate::jaco2_dynamics::{jaco2_bodies, G0};
use crate::rigid_body::RigidChain;
use crate::{Dynamics, JointLimits, Robot};

/// Model name of the papers' Jaco2 with pen tip and base tilt.
pub const JACO2_PEN: &str = "jaco2-pen";
/// Model name of Kinova's own Jaco2 model (hand centre, no tilt).
pub const JACO2: &str = "jaco2";
/// Name of [`Jaco2::hand`].
pub const JACO2_HAND: &str = "jaco2-hand";
/// Model name of the group's EXP2 pen model ([`Jaco2::pen_exp2`]).
pub const JACO2_PEN_EXP2: &str = "jaco2-pen-exp2";

/// Base to shoulder height D1 (m).
pub const D1: f64 = 0.2755;
/// Upper-arm length D2 (m).
pub const D2: f64 = 0.4100;
/// Forearm length D3 (m).
pub const D3: f64 = 0.2073;
/// First wrist length D4 (m).
pub const D4: f64 = 0.0741;
/// Second wrist length D5 (m).
pub const D5: f64 = 0.0741;
/// Elbow offset e2 (m).
pub const E2: f64 = 0.0098;
/// Wrist-to-end length D6 of the papers' pen model (m).
pub const D6_PEN: f64 = 0.1425;
/// Wrist-to-hand-centre length D6 of Kinova's model (m).
pub const D6_KINOVA: f64 = 0.16;
/// Wrist half-angle aa (rad).
pub const WRIST_HALF_ANGLE: f64 = PI / 6.0;
/// Pen tip in DH frame 6 of the pen model (m).
pub const PEN_TIP: [f64; 3] = [0.0, -0.075, 0.0];
/// Base tilt of the pen model: world = Rx(TILT_X) Ry(TILT_Y) * DH frame 0 (rad).
pub const TILT_X: f64 = -0.02;
/// See [`TILT_X`].
pub const TILT_Y: f64 = -0.05;
/// The wrist of a Jaco2 chain: the lengths D4, D5, D6 (m) and the wrist half-angle aa (rad);
/// the other DH lengths (D1, D2, D3, e2) are common to every variant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wrist {
    /// First wrist length D4 (m).
    pub d4: f64,
    /// Second wrist length D5 (m).
    pub d5: f64,
    /// Wrist-to-end length D6 (m): to the pen's frame 6 or Kinova's hand centre.
    pub d6: f64,
    /// Wrist half-angle aa (rad); the DH table's k = sin(aa)/sin(2aa).
    pub half_angle: f64,
}

/// The papers' pen model's wrist (`docs/robots.md`): D4 = D5 = 0.0741, D6 = 0.1425, aa = pi/6.
pub const PEN_WRIST: Wrist = Wrist {
    d4: D4,
    d5: D5,
    d6: D6_PEN,
    half_angle: WRIST_HALF_ANGLE,
};

/// The group's EXP2 wrist (`docs/group-code.md`): D4 = D5 = 0.07433, D6 = 0.13, aa = 11 pi / 72.
pub const EXP2_WRIST: Wrist = Wrist {
    d4: 0.07433,
    d5: 0.07433,
    d6: 0.13,
    half_angle: 11.0 * PI / 72.0,
};

/// The Jaco2 DH table for a given D6 (D4 = D5 = 0.0741, aa = pi/6).
pub fn jaco2_dh(d6: f64) -> Vec<DhParam> {
    jaco2_dh_wrist(Wrist { d6, ..PEN_WRIST })
}

/// The Jaco2 DH table (`docs/robots.md`) for a given wrist, with k = sin(aa)/sin(2aa).
pub fn jaco2_dh_wrist(w: Wrist) -> Vec<DhParam> {
    let aa = w.half_angle;
    let k = aa.sin() / (2.0 * aa).sin();
    vec![
        DhParam::new(0.0, PI / 2.0, D1),
        DhParam::new(D2, PI, 0.0),
        DhParam::new(0.0, PI / 2.0, -E2),
        DhParam::new(0.0, 2.0 * aa, -(D3 + k * w.d4)),
        DhParam::new(0.0, 2.0 * aa, -k * (w.d4 + w.d5)),
        DhParam::new(0.0, PI, -(k * w.d5 + w.d6)),
    ]
}

/// Rotation about x by `a` (rad).
fn rot_x(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

/// Rotation about y by `a` (rad).
fn rot_y(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}

/// The papers' joint limits (the group's code, in degrees): theta2 in [-137, 223] deg,
/// theta3 in [-289, 71] deg, joints 1, 4, 5, 6 in [-1e4, 1e4] deg; |thetadot| <= 1.5 rad/s.
fn papers_limits() -> JointLimits {
    let deg = PI / 180.0;
    let upper = [1e4, 223.0, 71.0, 1e4, 1e4, 1e4];
    let lower = [-1e4, -137.0, -289.0, -1e4, -1e4, -1e4];
    JointLimits {
        theta_min: DVector::from_column_slice(&lower) * deg,
        theta_max: DVector::from_column_slice(&upper) * deg,
        thetadot_min: DVector::repeat(6, -1.5),
        thetadot_max: DVector::repeat(6, 1.5),
    }
}

/// The papers' initial joint vector theta0 (jia2019, zhong2021, zhang2018; kong2019's Jaco2
/// runs), at which the Jaco2 models state their check values.
pub const PAPERS_THETA0: [f64; 6] = [1.675, 2.79, -3.216, 4.187, -1.71, -2.95];
/// The group's EXP2 theta0, at which `jaco2-pen-exp2` states its check values.
pub const EXP2_THETA0: [f64; 6] = [1.670, 2.845, -3.218, 4.182, -1.715, -2.655];

/// A Jaco2 model: kinematic chain to the task point, joint limits (a [`DataRobot`] built in
/// code), and the physical arm's rigid-body model (see `jaco2_dynamics`).
#[derive(Clone, Debug, PartialEq)]
pub struct Jaco2 {
    arm: DataRobot,
    dynamics: RigidChain<6>,
}

impl Jaco2 {
    /// The papers' pen model (`jaco2-pen`).
    pub fn pen() -> Self {
        Self::pen_with_wrist(JACO2_PEN, PEN_WRIST)
    }

    /// The group's EXP2 pen model (`jaco2-pen-exp2`).
    pub fn pen_exp2() -> Self {
        Self::pen_with_wrist(JACO2_PEN_EXP2, EXP2_WRIST)
    }

    /// A pen model (pen tip, base tilt, the papers' limits) with the wrist `w`, called `name`.
    pub fn pen_with_wrist(name: &'static str, w: Wrist) -> Self {
        let pose = if name == JACO2_PEN_EXP2 {
            EXP2_THETA0
        } else {
            PAPERS_THETA0
        };
        Jaco2 {
            arm: DataRobot::from_chain(
                name,
                DhChain::new(jaco2_dh_wrist(w))
                    .with_base(Frame::rotation(rot_x(TILT_X) * rot_y(TILT_Y))),
                Vector3::from(PEN_TIP),
                papers_limits(),
                pose.to_vec(),
            ),
            dynamics: jaco2_rigid_chain(),
        }
    }

    /// Kinova's model with the papers' limits (`jaco2-hand`).
    pub fn hand() -> Self {
        Self::kinova_as(JACO2_HAND, papers_limits())
    }

    /// Kinova's own model (`jaco2`): D6 = 0.16, hand centre, no tilt, Kinova's limits.
    pub fn kinova() -> Self {
        let inf = f64::INFINITY;
        let vmax = DVector::from_column_slice(&[0.6283, 0.6283, 0.6283, 0.8378, 0.8378, 0.8378]);
        Self::kinova_as(
            JACO2,
            JointLimits {
                theta_min: DVector::from_column_slice(&[-inf, -0.7505, -4.3808, -inf, -inf, -inf]),
                theta_max: DVector::from_column_slice(&[inf, 3.8921, 1.2392, inf, inf, inf]),
                thetadot_min: -&vmax,
                thetadot_max: vmax,
            },
        )
    }

    fn kinova_as(name: &'static str, limits: JointLimits) -> Self {
        Jaco2 {
            arm: DataRobot::from_chain(
                name,
                DhChain::new(jaco2_dh(D6_KINOVA)),
                Vector3::zeros(),
                limits,
                PAPERS_THETA0.to_vec(),
            ),
            dynamics: jaco2_rigid_chain(),
        }
    }

    /// The kinematic model (chain, task point, limits, stated pose).
    pub fn arm(&self) -> &DataRobot {
        &self.arm
    }

    /// The DH chain to the task point.
    pub fn chain(&self) -> &DhChain {
        self.arm.chain()
    }

    /// The task point in frame 6 (m).
    pub fn tip(&self) -> Vector3<f64> {
        self.arm.tool()
    }

    /// The rigid-body model (Kinova's chain, whatever the task point).
    pub fn rigid_chain(&self) -> &RigidChain<6> {
        &self.dynamics
    }
}

impl Robot for Jaco2 {
    fn name(&self) -> &str {
        self.arm.name()
    }

    fn dof(&self) -> usize {
        6
    }

    fn position(&self, theta: &[f64]) -> Vector3<f64> {
        self.arm.position(theta)
    }

    fn jacobian(&self, theta: &[f64], jac: &mut [f64]) {
        self.arm.jacobian(theta, jac)
    }

    fn jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        self.arm.jacobian_dot(theta, thetadot, jdot)
    }

    fn position_jacobian(&self, theta: &[f64], jac: &mut [f64]) -> Vector3<f64> {
        self.arm.position_jacobian(theta, jac)
    }

    fn limits(&self) -> &JointLimits {
        self.arm.limits()
    }

    /// The kinematic model's: the tool frame is DH frame 6.
    fn orientation(&self) -> Option<&dyn crate::Orientation> {
        Some(&self.arm)
    }

    fn skeleton(&self, theta: &[f64]) -> Vec<Vector3<f64>> {
        self.arm.skeleton(theta)
    }
}

/// The physical Jaco2 as a rigid chain: D6 = 0.16, untilted base, gravity (0, 0, -9.81).
pub fn jaco2_rigid_chain() -> RigidChain<6> {
    RigidChain {
        chain: DhChain::new(jaco2_dh(D6_KINOVA)),
        bodies: jaco2_bodies(),
        gravity: Vector3::new(0.0, 0.0, -G0),
    }
}

/// `x` as the Jaco2's joint vector.
fn joints(x: &[f64]) -> SVector<f64, 6> {
    SVector::from_column_slice(x)
}

impl Dynamics for Jaco2 {
    fn inertia(&self, theta: &[f64], h: &mut [f64]) {
        h.copy_from_slice(self.dynamics.inertia(&joints(theta)).as_slice());
    }

    fn coriolis(&self, theta: &[f64], thetadot: &[f64], c: &mut [f64]) {
        let v = self.dynamics.coriolis(&joints(theta), &joints(thetadot));
        c.copy_from_slice(v.as_slice());
    }

    fn coriolis_matrix(&self, theta: &[f64], thetadot: &[f64], cm: &mut [f64]) {
        let m: SMatrix<f64, 6, 6> = self
            .dynamics
            .coriolis_matrix(&joints(theta), &joints(thetadot));
        cm.copy_from_slice(m.as_slice());
    }

    fn gravity(&self, theta: &[f64], g: &mut [f64]) {
        g.copy_from_slice(self.dynamics.gravity_torques(&joints(theta)).as_slice());
    }
}
