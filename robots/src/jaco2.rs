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

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

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

/// Kinova's actuator effort limits (N m), joints 1-6.
pub const EFFORT_LIMITS: [f64; 6] = [40.0, 80.0, 40.0, 20.0, 20.0, 20.0];

/// The Jaco2 DH table for a given D6 (D4 = D5 = 0.0741, aa = pi/6).
pub fn jaco2_dh(d6: f64) -> [DhParam; 6] {
    jaco2_dh_wrist(Wrist { d6, ..PEN_WRIST })
}

/// The Jaco2 DH table (`docs/robots.md`) for a given wrist, with k = sin(aa)/sin(2aa).
pub fn jaco2_dh_wrist(w: Wrist) -> [DhParam; 6] {
    let aa = w.half_angle;
    let k = aa.sin() / (2.0 * aa).sin();
    [
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
fn papers_limits() -> JointLimits<6> {
    let deg = PI / 180.0;
    let upper = [1e4, 223.0, 71.0, 1e4, 1e4, 1e4];
    let lower = [-1e4, -137.0, -289.0, -1e4, -1e4, -1e4];
    JointLimits {
        theta_min: SVector::from(lower) * deg,
        theta_max: SVector::from(upper) * deg,
        thetadot_min: SVector::repeat(-1.5),
        thetadot_max: SVector::repeat(1.5),
    }
}

/// A Jaco2 model: kinematic chain to the task point, joint limits, and the physical arm's
/// rigid-body model (see [`crate::jaco2_dynamics`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jaco2 {
    name: &'static str,
    chain: DhChain<6>,
    tip: Vector3<f64>,
    limits: JointLimits<6>,
    dynamics: RigidChain<6>,
}

impl Jaco2 {
    /// The papers' model `jaco2-pen`: D6 = 0.1425, pen tip (0, -0.075, 0) in frame 6, base tilt
    /// `Rx(-0.02) Ry(-0.05)`. Limits from the group's code: theta2 in [-137, 223] deg,
    /// theta3 in [-289, 71] deg, joints 1, 4, 5, 6 in [-1e4, 1e4] deg; |thetadot| <= 1.5 rad/s.
    pub fn pen() -> Self {
        Self::pen_with_wrist(JACO2_PEN, PEN_WRIST)
    }

    /// The group's EXP2 model `jaco2-pen-exp2` (`docs/group-code.md`): `jaco2-pen` with the wrist
    /// D4 = D5 = 0.07433, D6 = 0.13, aa = 11 pi / 72 ([`EXP2_WRIST`]); same pen tip, tilt and
    /// limits, and the same rigid-body model (the group's code does no dynamics).
    pub fn pen_exp2() -> Self {
        Self::pen_with_wrist(JACO2_PEN_EXP2, EXP2_WRIST)
    }

    /// A pen model named `name`: the chain with wrist `w`, pen tip (0, -0.075, 0) in frame 6,
    /// base tilt `Rx(-0.02) Ry(-0.05)`, the papers' limits, the physical arm's dynamics.
    pub fn pen_with_wrist(name: &'static str, w: Wrist) -> Self {
        Jaco2 {
            name,
            chain: DhChain::new(jaco2_dh_wrist(w))
                .with_base(Frame::rotation(rot_x(TILT_X) * rot_y(TILT_Y))),
            tip: Vector3::from(PEN_TIP),
            limits: papers_limits(),
            dynamics: jaco2_rigid_chain(),
        }
    }

    /// `jaco2-hand`: Kinova's kinematics (D6 = 0.16, hand centre, no tilt) with the papers'
    /// joint limits, so that a run differs from `jaco2-pen` by the task point alone (the
    /// model check of jia2019: joint 6 cannot move the hand centre).
    pub fn hand() -> Self {
        Jaco2 {
            name: JACO2_HAND,
            limits: papers_limits(),
            ..Self::kinova()
        }
    }

    /// Kinova's model `jaco2`: D6 = 0.16, task point = origin of frame 6 (hand centre), no tilt.
    /// Kinova's physical limits: theta2 in [-0.7505, 3.8921], theta3 in [-4.3808, 1.2392], joints
    /// 1, 4, 5, 6 unlimited; |thetadot| <= 0.6283 (joints 1-3) and 0.8378 rad/s (joints 4-6).
    pub fn kinova() -> Self {
        let inf = f64::INFINITY;
        let vmax = SVector::from([0.6283, 0.6283, 0.6283, 0.8378, 0.8378, 0.8378]);
        Jaco2 {
            name: JACO2,
            chain: DhChain::new(jaco2_dh(D6_KINOVA)),
            tip: Vector3::zeros(),
            limits: JointLimits {
                theta_min: SVector::from([-inf, -0.7505, -4.3808, -inf, -inf, -inf]),
                theta_max: SVector::from([inf, 3.8921, 1.2392, inf, inf, inf]),
                thetadot_min: -vmax,
                thetadot_max: vmax,
            },
            dynamics: jaco2_rigid_chain(),
        }
    }

    /// The kinematic chain to the task point (including the base tilt of the pen model).
    pub fn chain(&self) -> &DhChain<6> {
        &self.chain
    }

    /// Task point in DH frame 6 (m).
    pub fn tip(&self) -> Vector3<f64> {
        self.tip
    }

    /// Rigid-body model of the physical arm (D6 = 0.16 chain, untilted DH frame 0, gravity
    /// (0, 0, -9.81)), shared by both variants.
    pub fn rigid_chain(&self) -> &RigidChain<6> {
        &self.dynamics
    }
}

impl Robot<6> for Jaco2 {
    fn name(&self) -> &'static str {
        self.name
    }

    fn position(&self, theta: &SVector<f64, 6>) -> Vector3<f64> {
        self.chain.frames(theta).frame(6).transform_point(&self.tip)
    }

    fn jacobian(&self, theta: &SVector<f64, 6>) -> SMatrix<f64, 3, 6> {
        let frames = self.chain.frames(theta);
        let p = frames.frame(6).transform_point(&self.tip);
        frames.point_jacobian(6, &p)
    }

    fn jacobian_dot(
        &self,
        theta: &SVector<f64, 6>,
        thetadot: &SVector<f64, 6>,
    ) -> SMatrix<f64, 3, 6> {
        let frames = self.chain.frames(theta);
        let p = frames.frame(6).transform_point(&self.tip);
        frames.point_jacobian_dot(6, &p, thetadot)
    }

    fn limits(&self) -> JointLimits<6> {
        self.limits
    }

    /// The origins of DH frames 0..=6 (frame 0 is the base, the world origin), then the task
    /// point.
    fn skeleton(&self, theta: &SVector<f64, 6>) -> Vec<Vector3<f64>> {
        let frames = self.chain.frames(theta);
        (0..=6)
            .map(|k| frames.origin(k))
            .chain(std::iter::once(frames.frame(6).transform_point(&self.tip)))
            .collect()
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

impl Dynamics<6> for Jaco2 {
    fn inertia(&self, theta: &SVector<f64, 6>) -> SMatrix<f64, 6, 6> {
        self.rigid_chain().inertia(theta)
    }

    fn coriolis(&self, theta: &SVector<f64, 6>, thetadot: &SVector<f64, 6>) -> SVector<f64, 6> {
        self.rigid_chain().coriolis(theta, thetadot)
    }

    fn coriolis_matrix(
        &self,
        theta: &SVector<f64, 6>,
        thetadot: &SVector<f64, 6>,
    ) -> SMatrix<f64, 6, 6> {
        self.rigid_chain().coriolis_matrix(theta, thetadot)
    }

    fn gravity(&self, theta: &SVector<f64, 6>) -> SVector<f64, 6> {
        self.rigid_chain().gravity_torques(theta)
    }
}
