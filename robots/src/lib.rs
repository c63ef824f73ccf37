//! Robot models for driftbench: forward kinematics of the task point, the 3 x n position
//! Jacobian and its time derivative, joint limits, and (for the Jaco2) rigid-body dynamics.
//!
//! Every quantity uses fixed-size nalgebra types: `SVector<f64, N>` for joint vectors,
//! `Vector3<f64>` for task-space points and `SMatrix<f64, 3, N>` for Jacobians, so no call in
//! the simulation's hot path allocates.
//!
//! Models (see `docs/robots.md`):
//! - [`Jaco2::pen`] — the papers' Jaco2 (`jaco2-pen`): D6 = 0.1425, pen tip (0, -0.075, 0) in
//!   frame 6, base tilt Rx(-0.02) Ry(-0.05).
//! - [`Jaco2::pen_exp2`] — the group's EXP2 variant (`jaco2-pen-exp2`): D4 = D5 = 0.07433,
//!   D6 = 0.13, wrist half-angle 11 pi / 72, same pen tip and tilt.
//! - [`Jaco2::kinova`] — Kinova's own model (`jaco2`): D6 = 0.16, hand centre, no tilt.
//! - [`Katana6m180`] — kong2019's eq. (2), 5 joints.
//! - [`Panda`] — Franka Emika Panda (`panda`), 7 joints, Franka's modified-DH table, flange
//!   centre.
//! - [`NLink`] — the synthetic n-link family (`nlink-3` .. `nlink-30`): a yaw joint and a planar
//!   pitch chain, for cost scaling.
//! - [`DataRobot`] — any serial arm declared by a robot file ([`robot_file`], TOML): the
//!   built-in files `robots/data/*.toml` (e.g. `puma560`, and data twins of the DH models above)
//!   are embedded in the library ([`data_robot::builtin_models`]).
//!
//! Modules: [`dh`] (classical DH forward kinematics), [`geometric_jacobian`] (point and body
//! Jacobians and their time derivatives), [`rigid_body`] (recursive Newton–Euler, inertia and
//! Coriolis matrices), [`jaco2`] (Jaco2 kinematics and its [`Dynamics`] implementation),
//! [`jaco2_dynamics`] (the Jaco2's inertial table), [`katana`] (Katana 6M180), [`panda`] (Franka
//! Emika Panda), [`nlink`] (the n-link family), [`robot_file`] (the robot file format and its
//! validation), [`data_robot`] (the model of a robot file, the built-in files), [`joint_counts`]
//! (the joint counts a robot file may have), [`registry`] (the one map from the robot names of
//! experiment files to models).

#![deny(missing_docs)]

use nalgebra::{SMatrix, SVector, Vector3};

pub mod chain;
pub mod data_robot;
pub mod dh;
pub mod geometric_jacobian;
pub mod jaco2;
pub mod jaco2_dynamics;
pub mod joint_counts;
pub mod katana;
pub mod limited;
pub mod nlink;
pub mod nlink_dyn;
pub mod panda;
pub mod registry;
pub mod rigid_body;
pub mod robot_file;
pub mod urdf;

pub use data_robot::{DataModel, DataRobot};
pub use jaco2::{Jaco2, JACO2, JACO2_HAND, JACO2_PEN, JACO2_PEN_EXP2};
pub use katana::{Katana6m180, KATANA6M180};
pub use nlink::NLink;
pub use nlink_dyn::NLinkDyn;
pub use panda::{Panda, PANDA};

/// Number of task-space coordinates (end-effector position only) in every paper.
pub const M: usize = 3;

/// Joint-angle and joint-velocity limits, elementwise; `f64::INFINITY` where unlimited.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimits<const N: usize> {
    /// Lower joint-angle limits (rad).
    pub theta_min: SVector<f64, N>,
    /// Upper joint-angle limits (rad).
    pub theta_max: SVector<f64, N>,
    /// Lower joint-velocity limits (rad/s).
    pub thetadot_min: SVector<f64, N>,
    /// Upper joint-velocity limits (rad/s).
    pub thetadot_max: SVector<f64, N>,
}

/// A serial arm whose task point is tracked in position (m = 3).
pub trait Robot<const N: usize>: Send + Sync {
    /// Model name as used in experiment files (`jaco2-pen`, `jaco2`, `katana6m180`, `panda`,
    /// `nlink-7`, `puma560`); a data robot's name is read from its file.
    fn name(&self) -> &str;
    /// Task-point position f(theta) in the world frame.
    fn position(&self, theta: &SVector<f64, N>) -> Vector3<f64>;
    /// Position Jacobian J(theta) = df/dtheta.
    fn jacobian(&self, theta: &SVector<f64, N>) -> SMatrix<f64, 3, N>;
    /// Time derivative dJ/dt along thetadot.
    fn jacobian_dot(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, 3, N>;
    /// Joint limits the papers' schemes use.
    fn limits(&self) -> JointLimits<N>;
    /// Points of the arm from the base to the task point, for drawing (allocates; not for the
    /// hot path). The default is the world origin and the task point; a model overrides it
    /// with its joint origins in between.
    fn skeleton(&self, theta: &SVector<f64, N>) -> Vec<Vector3<f64>> {
        vec![Vector3::zeros(), self.position(theta)]
    }
}

/// Rigid-body dynamics H(theta) thetaddot + c(theta, thetadot) + g(theta) = tau.
pub trait Dynamics<const N: usize>: Robot<N> {
    /// Joint-space inertia matrix H(theta) (symmetric positive definite).
    fn inertia(&self, theta: &SVector<f64, N>) -> SMatrix<f64, N, N>;
    /// Coriolis and centrifugal vector c(theta, thetadot).
    fn coriolis(&self, theta: &SVector<f64, N>, thetadot: &SVector<f64, N>) -> SVector<f64, N>;
    /// A Coriolis matrix C(theta, thetadot) with c = C thetadot and Hdot - 2C skew-symmetric
    /// (Christoffel symbols of the first kind).
    fn coriolis_matrix(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, N, N>;
    /// Gravity vector g(theta) = dU/dtheta.
    fn gravity(&self, theta: &SVector<f64, N>) -> SVector<f64, N>;
}
