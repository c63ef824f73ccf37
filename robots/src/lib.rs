//! Robot models for driftbench: forward kinematics of the task point, the 3 x n position
//! Jacobian and its time derivative, joint limits, and (for the Jaco2) rigid-body dynamics.
//!
//! The joint count n is a run-time value ([`Robot::dof`]): joint vectors are slices, task-space
//! points `Vector3<f64>`, and Jacobians are written into the caller's buffers (allocated once
//! per run), so no call in the simulation's hot path allocates.
//!
//! Models (see `docs/robots.md`):
//! - [`Jaco2::pen`] — the papers' Jaco2 (`jaco2-pen`): D6 = 0.1425, pen tip (0, -0.075, 0) in
//!   frame 6, base tilt Rx(-0.02) Ry(-0.05).
//! - [`Jaco2::pen_exp2`] — the group's EXP2 variant (`jaco2-pen-exp2`): D4 = D5 = 0.07433,
//!   D6 = 0.13, wrist half-angle 11 pi / 72, same pen tip and tilt.
//! - [`Jaco2::kinova`] — Kinova's own model (`jaco2`): D6 = 0.16, hand centre, no tilt.
//! - [`Katana6m180`] — kong2019's eq. (2), 5 joints.
//! - [`Panda::model`] — Franka Emika Panda (`panda`), 7 joints, Franka's modified-DH table, flange
//!   centre.
//! - [`NLink`] — the synthetic n-link family (`nlink-<n>`, any n from 2 to [`NLINK_MAX`]): a yaw joint and a planar
//!   pitch chain, for cost scaling.
//! - [`DataRobot`] — any serial arm declared by a robot file ([`RobotSpec`], TOML): the
//!   built-in files `robots/data/*.toml` (e.g. `puma560`, and data twins of the DH models above)
//!   are embedded in the library ([`builtin_models`]).
//! - [`ChainRobot`] — a [`Chain`] as a model: the URDF form of a paper's robot file
//!   (a URDF read at run time by [`read_urdf`]), with [`Dynamics`]
//!   where every moving joint carries an inertial.
//! - [`Mounted`] — any of these with a tool offset and a base transform of an
//!   experiment's own (needs [`Orientation`] for a tool offset).
//!
//! Capabilities beyond the position task: [`Dynamics`] (H, c, g) and [`Orientation`] (the tool
//! frame's rotation and angular Jacobian), asked of a model by [`Robot::orientation`] and the
//! registry's [`Model::dynamics`].
//!
//! The modules are private; what other crates use is re-exported here: the models above, the
//! registry ([`robot_by_name`], [`register_file`], [`Model`]: the one map from the robot names
//! of experiment files to models), the robot file format ([`RobotSpec`], [`RobotFileError`]),
//! serial chains and URDFs ([`Chain`], [`read_urdf`], [`parse_urdf`]), the Jaco2's inertial
//! table ([`jaco2_bodies`]), recursive Newton–Euler's bodies ([`RigidBody`]), DH frames
//! ([`Frame`]), and a robot with an experiment's limits or mount ([`Limited`], [`Mounted`]).

#![deny(missing_docs)]

use nalgebra::{DMatrix, DVector, Matrix3, Matrix3xX, Vector3};

mod chain;
mod chain_robot;
mod data_robot;
mod dh;
mod file_rules;
mod geometric_jacobian;
mod jaco2;
mod jaco2_dynamics;
mod katana;
mod limited;
mod mounted;
mod nlink;
mod panda;
mod registry;
mod rigid_body;
mod robot_file;
mod urdf;

pub use chain::{Chain, ChainJoint, ChainWorkspace, JointKind, JointRange};
pub use chain_robot::ChainRobot;
pub use data_robot::DataRobot;
pub use data_robot::{builtin_files, builtin_model, builtin_models, parse_builtin};
pub use dh::Frame;
pub use jaco2::{Jaco2, JACO2, JACO2_HAND, JACO2_PEN, JACO2_PEN_EXP2};
pub use jaco2::{
    EXP2_WRIST as JACO2_EXP2_WRIST, PAPERS_THETA0 as JACO2_PAPERS_THETA0,
    PEN_WRIST as JACO2_PEN_WRIST,
};
pub use jaco2_dynamics::jaco2_bodies;
pub use katana::{Katana6m180, KATANA6M180};
pub use limited::Limited;
pub use mounted::{Mount, Mounted, MAX_OFFSET};
pub use nlink::NLink;
pub use nlink::{H0 as NLINK_H0, NLINK_MAX, NLINK_MIN, REACH as NLINK_REACH};
pub use panda::QDOT_MAX as PANDA_QDOT_MAX;
pub use panda::{Panda, PANDA};
pub use registry::{
    nlink_name, register_file, robot_by_name, robot_names, robots_with_dynamics, Kinematics, Model,
    RegistryError,
};
pub use rigid_body::RigidBody;
pub use robot_file::{
    RobotFileError, RobotForm, RobotSpec, RuleError, UrdfRobotSpec,
    MAX_FILE_BYTES as ROBOT_FILE_MAX_BYTES, MAX_LENGTH,
};
pub use urdf::{
    parse as parse_urdf, read as read_urdf, ChainEnds, UrdfChainError, MAX_DEPTH as URDF_MAX_DEPTH,
    MAX_JOINTS as URDF_MAX_JOINTS, MAX_LISTED_LINKS as URDF_MAX_LISTED_LINKS,
};

/// Number of task-space coordinates (end-effector position only) in every paper.
pub const M: usize = 3;

/// Joint-angle and joint-velocity limits, elementwise (one entry per joint); `f64::INFINITY`
/// where unlimited.
#[derive(Clone, Debug, PartialEq)]
pub struct JointLimits {
    /// Lower joint-angle limits (rad).
    pub theta_min: DVector<f64>,
    /// Upper joint-angle limits (rad).
    pub theta_max: DVector<f64>,
    /// Lower joint-velocity limits (rad/s).
    pub thetadot_min: DVector<f64>,
    /// Upper joint-velocity limits (rad/s).
    pub thetadot_max: DVector<f64>,
}

impl JointLimits {
    /// The limits of `n` joints, each `[-theta_max, theta_max]` and `[-thetadot_max,
    /// thetadot_max]`.
    pub fn symmetric(theta_max: &[f64], thetadot_max: &[f64]) -> Self {
        let theta_max = DVector::from_column_slice(theta_max);
        let thetadot_max = DVector::from_column_slice(thetadot_max);
        JointLimits {
            theta_min: -&theta_max,
            theta_max,
            thetadot_min: -&thetadot_max,
            thetadot_max,
        }
    }

    /// The number of joints.
    pub fn dof(&self) -> usize {
        self.theta_min.len()
    }
}

/// A serial arm whose task point is tracked in position (m = 3), with its joint count `n` a
/// run-time value ([`Robot::dof`]).
///
/// Joint vectors are slices of length `n`; Jacobians are written, column-major 3 x n, into the
/// caller's buffer of length `3 n` (e.g. a QP's `A`, allocated once per run), so no call in the
/// simulation's hot path allocates.
pub trait Robot: Send + Sync {
    /// Model name as used in experiment files (`jaco2-pen`, `jaco2`, `katana6m180`, `panda`,
    /// `nlink-7`, `puma560`); a data robot's name is read from its file.
    fn name(&self) -> &str;
    /// The number of joints n.
    fn dof(&self) -> usize;
    /// Task-point position f(theta) in the world frame.
    fn position(&self, theta: &[f64]) -> Vector3<f64>;
    /// Writes the position Jacobian J(theta) = df/dtheta (3 x n, column-major) into `jac`.
    fn jacobian(&self, theta: &[f64], jac: &mut [f64]);
    /// Writes the time derivative dJ/dt along thetadot (3 x n, column-major) into `jdot`.
    fn jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]);
    /// f(theta), with J(theta) written into `jac`: the same numbers, bit for bit, as
    /// [`Robot::position`] and [`Robot::jacobian`] (the default calls both). A model overrides
    /// it to share the work the two have in common (the Katana's sines and cosines): the
    /// schemes' tracking term asks for both at every evaluation.
    fn position_jacobian(&self, theta: &[f64], jac: &mut [f64]) -> Vector3<f64> {
        self.jacobian(theta, jac);
        self.position(theta)
    }
    /// Joint limits the papers' schemes use.
    fn limits(&self) -> &JointLimits;
    /// Points of the arm from the base to the task point, for drawing (allocates; not for the
    /// hot path). The default is the world origin and the task point; a model overrides it
    /// with its joint origins in between.
    fn skeleton(&self, theta: &[f64]) -> Vec<Vector3<f64>> {
        vec![Vector3::zeros(), self.position(theta)]
    }
    /// The model's [`Orientation`] capability, where it has one (default: none). A model whose
    /// task point hangs on a frame of the arm (the DH robots, [`ChainRobot`]) gives itself.
    fn orientation(&self) -> Option<&dyn Orientation> {
        None
    }
    /// J(theta) as a new matrix (allocates: for set-up, checks and tests).
    fn jacobian_matrix(&self, theta: &[f64]) -> Matrix3xX<f64> {
        let mut jac = Matrix3xX::zeros(self.dof());
        self.jacobian(theta, jac.as_mut_slice());
        jac
    }
    /// dJ/dt as a new matrix (allocates: for set-up, checks and tests).
    fn jacobian_dot_matrix(&self, theta: &[f64], thetadot: &[f64]) -> Matrix3xX<f64> {
        let mut jdot = Matrix3xX::zeros(self.dof());
        self.jacobian_dot(theta, thetadot, jdot.as_mut_slice());
        jdot
    }
}

/// The orientation of a robot's tool frame: the capability a pose task needs beyond the
/// position task of [`Robot`], asked of a model by [`Robot::orientation`].
///
/// The tool frame is the frame the task point is fixed in (its origin need not be the task
/// point): the last DH frame of a DH robot (classical frame n; its flange frame, which has the
/// same axes, for a modified table), the tool frame of a [`chain::Chain`] (the tip link's axes).
/// With R(theta) its rotation (world from tool frame: its columns are the tool axes in world
/// coordinates), the angular velocity omega of the tool frame (`Rdot = omega x R`, column by
/// column) is linear in the joint velocities:
///
/// ```text
/// omega = J_w(theta) thetadot,   J_w = [k_1 z_1 ... k_n z_n]   (3 x n),
/// dJ_w/dt: column j = omega_{j-1} x z_j,   omega_{j-1} = sum_{i<j} k_i thetadot_i z_i,
/// ```
///
/// with z_j the world axis of joint j and k_j = 1 for a revolute joint, 0 for a prismatic one
/// (a sliding joint does not turn the tool). Matrices are written, 3 x n column-major, into the
/// caller's buffers of length 3 n, as [`Robot::jacobian`] does: no call allocates.
pub trait Orientation: Send + Sync {
    /// R(theta): the rotation of the tool frame, world from tool.
    fn tool_rotation(&self, theta: &[f64]) -> Matrix3<f64>;
    /// Writes the angular Jacobian J_w(theta) (3 x n, column-major) into `jac`.
    fn angular_jacobian(&self, theta: &[f64], jac: &mut [f64]);
    /// Writes dJ_w/dt along `thetadot` (3 x n, column-major) into `jdot`.
    fn angular_jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]);
}

/// Rigid-body dynamics H(theta) thetaddot + c(theta, thetadot) + g(theta) = tau, each written
/// into the caller's buffer (n x n matrices column-major).
pub trait Dynamics: Robot {
    /// Writes the joint-space inertia matrix H(theta) (symmetric positive definite) into `h`.
    fn inertia(&self, theta: &[f64], h: &mut [f64]);
    /// Writes the Coriolis and centrifugal vector c(theta, thetadot) into `c`.
    fn coriolis(&self, theta: &[f64], thetadot: &[f64], c: &mut [f64]);
    /// Writes a Coriolis matrix C(theta, thetadot) with c = C thetadot and Hdot - 2C
    /// skew-symmetric (Christoffel symbols of the first kind) into `cm`.
    fn coriolis_matrix(&self, theta: &[f64], thetadot: &[f64], cm: &mut [f64]);
    /// Writes the gravity vector g(theta) = dU/dtheta into `g`.
    fn gravity(&self, theta: &[f64], g: &mut [f64]);
    /// H(theta) as a new matrix (allocates: for set-up, checks and tests).
    fn inertia_matrix(&self, theta: &[f64]) -> DMatrix<f64> {
        let n = self.dof();
        let mut h = DMatrix::zeros(n, n);
        self.inertia(theta, h.as_mut_slice());
        h
    }
}
