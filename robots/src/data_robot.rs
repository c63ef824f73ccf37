//! [`DataRobot`]: the model a robot file declares ([`crate::robot_file`]), and the built-in
//! files `robots/data/*.toml` embedded in the library.
//!
//! # Mathematics
//!
//! A file's table becomes one classical DH chain [`DhChain<N>`] with base `B` and task point
//! `p` in frame `N`:
//!
//! - standard: `B` is the file's base and `p` its `tool`;
//! - modified: [`DhChain::from_modified`] turns rows `1..=N` and the flange row into classical
//!   links, base `S_1 = Rx(alpha_1) Tx(a_1)` and flange origin `(0, 0, d_f)` in classical frame
//!   `N`; the chain's base is then `B S_1`, and `p = tool + (0, 0, d_f)` (the flange frame is
//!   classical frame `N` translated by `d_f` along its z axis, so a point's coordinates shift by
//!   that translation only).
//!
//! At joint angles `theta` the chain is evaluated at the DH angles `q = theta + offset`, giving
//! world frames `T_k = B A_1(q_1) ... A_k(q_k)` with origins `o_k` and z axes `z_k`. Then
//!
//! ```text
//! f(theta)  = T_N p,
//! J_j       = z_{j-1} x (f - o_{j-1}),
//! Jdot_j    = (omega_{j-1} x z_{j-1}) x (f - o_{j-1}) + z_{j-1} x (fdot - v_{j-1}),
//! ```
//!
//! with `omega_k`, `v_k` the angular velocity of frame `k` and the velocity of `o_k` along
//! `thetadot` ([`crate::geometric_jacobian`]; `qdot = thetadot`, the offsets being constant). All
//! three are the shared [`DhChain`] / [`crate::dh::ChainFrames`] code of the Rust models, on the
//! stack: nothing allocates.
//!
//! # Joint counts
//!
//! Any: the chain is evaluated at run time into a buffer of n frames ([`crate::dh`]). The
//! Rust models that are DH chains (the Jaco2 variants, the Panda) are data robots built in
//! code ([`DataRobot::from_chain`]).

use std::sync::{Arc, OnceLock};

use nalgebra::{DVector, Vector3};

use crate::dh::{DhChain, DhParam, ModifiedDhParam};
use crate::robot_file::{JointSpec, RobotFileError, RobotSpec};
use crate::{JointLimits, Orientation, Robot};

/// A serial arm of classical DH links with a task point (kinematics only): a robot file's
/// model, or a Rust model's kinematics.
#[derive(Clone, Debug, PartialEq)]
pub struct DataRobot {
    name: String,
    chain: DhChain,
    offset: Vec<f64>,
    tool: Vector3<f64>,
    limits: JointLimits,
    acceleration_max: DVector<f64>,
    stated_pose: Vec<f64>,
}

impl DataRobot {
    /// The model of `spec` (mathematics in the module documentation).
    pub fn new(spec: &RobotSpec) -> Self {
        let joints = spec.joints();
        let column = |f: fn(&JointSpec) -> f64| joints.iter().map(f).collect::<Vec<f64>>();
        let (chain, tool) = match spec.flange() {
            None => (
                DhChain::new(
                    joints
                        .iter()
                        .map(|j| DhParam::new(j.row.a, j.row.alpha, j.row.d))
                        .collect(),
                ),
                spec.tool(),
            ),
            Some(f) => {
                let rows: Vec<ModifiedDhParam> = joints
                    .iter()
                    .map(|j| ModifiedDhParam::new(j.row.a, j.row.alpha, j.row.d))
                    .collect();
                let (chain, flange) =
                    DhChain::from_modified(&rows, ModifiedDhParam::new(f.a, f.alpha, f.d));
                (chain, spec.tool() + flange)
            }
        };
        let base = spec.base().compose(&chain.base);
        let chain = chain.with_base(base);
        let vector = |f: fn(&JointSpec) -> f64| DVector::from_vec(column(f));
        DataRobot {
            name: spec.name().to_string(),
            chain,
            offset: column(|j| j.offset),
            tool,
            limits: JointLimits {
                theta_min: vector(|j| j.theta_min),
                theta_max: vector(|j| j.theta_max),
                thetadot_min: vector(|j| j.velocity_min),
                thetadot_max: vector(|j| j.velocity_max),
            },
            acceleration_max: vector(|j| j.acceleration_max),
            stated_pose: spec
                .stated_pose()
                .map_or_else(|| vec![0.0; joints.len()], <[f64]>::to_vec),
        }
    }

    /// A model built in code: `chain` with the task point `tool` in its last frame, `limits`,
    /// no angle offsets, no acceleration limits, check values stated at `stated_pose`.
    pub fn from_chain(
        name: &str,
        chain: DhChain,
        tool: Vector3<f64>,
        limits: JointLimits,
        stated_pose: Vec<f64>,
    ) -> Self {
        let n = chain.dof();
        assert!(
            limits.dof() == n && stated_pose.len() == n,
            "data robot: one limit and one pose entry per joint"
        );
        DataRobot {
            name: name.to_string(),
            chain,
            offset: vec![0.0; n],
            tool,
            limits,
            acceleration_max: DVector::from_element(n, f64::INFINITY),
            stated_pose,
        }
    }

    /// The classical chain the task point hangs on (base included).
    pub fn chain(&self) -> &DhChain {
        &self.chain
    }

    /// The joint-angle offsets: the DH angles are `theta + offset`.
    pub fn offset(&self) -> &[f64] {
        &self.offset
    }

    /// The task point in classical frame `n` (m).
    pub fn tool(&self) -> Vector3<f64> {
        self.tool
    }

    /// The symmetric joint-acceleration limits (rad/s^2; infinite where the file gives none).
    pub fn acceleration_max(&self) -> &DVector<f64> {
        &self.acceleration_max
    }

    /// The pose the file states its check values at (zero if it states none).
    pub fn stated_pose(&self) -> &[f64] {
        &self.stated_pose
    }

    /// Runs `f` on the frames at joint angles `theta` (DH angles `theta + offset`).
    fn with_frames<R>(&self, theta: &[f64], f: impl FnOnce(&crate::dh::ChainFrames<'_>) -> R) -> R {
        assert_eq!(
            theta.len(),
            self.dof(),
            "{}: one angle per joint",
            self.name
        );
        self.chain.with_frames(|i| theta[i] + self.offset[i], f)
    }
}

impl Robot for DataRobot {
    fn name(&self) -> &str {
        &self.name
    }

    fn dof(&self) -> usize {
        self.chain.dof()
    }

    fn position(&self, theta: &[f64]) -> Vector3<f64> {
        let n = self.dof();
        self.with_frames(theta, |frames| frames.frame(n).transform_point(&self.tool))
    }

    fn jacobian(&self, theta: &[f64], jac: &mut [f64]) {
        let n = self.dof();
        self.with_frames(theta, |frames| {
            let p = frames.frame(n).transform_point(&self.tool);
            frames.point_jacobian(n, &p, jac)
        })
    }

    fn jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        let n = self.dof();
        self.with_frames(theta, |frames| {
            let p = frames.frame(n).transform_point(&self.tool);
            frames.point_jacobian_dot(n, &p, thetadot, jdot)
        })
    }

    /// p and J from one evaluation of the chain's frames.
    fn position_jacobian(&self, theta: &[f64], jac: &mut [f64]) -> Vector3<f64> {
        let n = self.dof();
        self.with_frames(theta, |frames| {
            let p = frames.frame(n).transform_point(&self.tool);
            frames.point_jacobian(n, &p, jac);
            p
        })
    }

    fn limits(&self) -> &JointLimits {
        &self.limits
    }

    fn orientation(&self) -> Option<&dyn Orientation> {
        Some(self)
    }

    /// The origins of classical frames 0..=n (frame 0 is the base), then the task point.
    fn skeleton(&self, theta: &[f64]) -> Vec<Vector3<f64>> {
        let n = self.dof();
        self.with_frames(theta, |frames| {
            (0..=n)
                .map(|k| frames.origin(k))
                .chain(std::iter::once(frames.frame(n).transform_point(&self.tool)))
                .collect()
        })
    }
}

/// The tool frame is classical frame n (the task point is fixed in it; a modified table's
/// flange frame has its axes): R = T_n's rotation, J_w's columns z_{j-1}
/// (`geometric_jacobian`).
impl Orientation for DataRobot {
    fn tool_rotation(&self, theta: &[f64]) -> nalgebra::Matrix3<f64> {
        let n = self.dof();
        self.with_frames(theta, |frames| frames.frame(n).rot)
    }

    fn angular_jacobian(&self, theta: &[f64], jac: &mut [f64]) {
        let n = self.dof();
        self.with_frames(theta, |frames| frames.angular_jacobian(n, jac))
    }

    fn angular_jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        let n = self.dof();
        self.with_frames(theta, |frames| {
            frames.angular_jacobian_dot(n, thetadot, jdot)
        })
    }
}

/// The built-in robot files, `(file name, text)`, sorted by file name: every `robots/data/*.toml`
/// at build time (`build.rs`).
pub fn builtin_files() -> &'static [(&'static str, &'static str)] {
    const FILES: &[(&str, &str)] = include!(concat!(env!("OUT_DIR"), "/builtin_robots.rs"));
    FILES
}

/// The built-in robot file `file_name` (e.g. `puma560.toml`) parsed and validated; its name must
/// be the file's stem.
pub fn parse_builtin(file_name: &str, text: &str) -> Result<RobotSpec, RobotFileError> {
    let stem = file_name.strip_suffix(".toml").unwrap_or(file_name);
    RobotSpec::parse_named(&format!("robots/data/{file_name}"), stem, text)
}

/// A built-in robot file's stem, with its model or why it was refused.
pub type BuiltinModel = (&'static str, Result<DataRobot, Arc<RobotFileError>>);

/// The built-in robot files, each with its model or why it was refused, in [`builtin_files`]
/// order, parsed once per process. A refused file fails only the lookups of its own name
/// ([`crate::robot_by_name`]).
pub fn builtin_models() -> &'static [BuiltinModel] {
    static MODELS: OnceLock<Vec<BuiltinModel>> = OnceLock::new();
    MODELS.get_or_init(|| {
        builtin_files()
            .iter()
            .map(|(file, text)| {
                let stem = file.strip_suffix(".toml").unwrap_or(file);
                (
                    stem,
                    parse_builtin(file, text)
                        .map(|spec| DataRobot::new(&spec))
                        .map_err(Arc::new),
                )
            })
            .collect()
    })
}

/// The built-in data model called `name`, if there is a valid one.
pub fn builtin_model(name: &str) -> Option<&'static DataRobot> {
    builtin_models()
        .iter()
        .find(|(stem, _)| *stem == name)
        .and_then(|(_, m)| m.as_ref().ok())
}
