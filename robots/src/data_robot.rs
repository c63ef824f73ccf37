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
//! `N` must be one the simulation is instantiated for ([`JOINT_COUNTS`]: those of the Katana,
//! the Jaco2, the Panda and the n-link sizes of the registry); [`DataModel`] holds a data robot
//! of any of them, and a file with another count is refused when parsed.

use std::sync::{Arc, OnceLock};

use nalgebra::{SMatrix, SVector, Vector3};

use crate::dh::{DhChain, DhParam, ModifiedDhParam};
use crate::joint_counts::JOINT_COUNTS;
use crate::robot_file::{JointSpec, RobotFileError, RobotSpec};
use crate::{JointLimits, Robot};

/// A serial arm declared by a robot file (kinematics only).
#[derive(Clone, Debug, PartialEq)]
pub struct DataRobot<const N: usize> {
    name: String,
    chain: DhChain<N>,
    offset: SVector<f64, N>,
    tool: Vector3<f64>,
    limits: JointLimits<N>,
    acceleration_max: SVector<f64, N>,
    stated_pose: SVector<f64, N>,
}

impl<const N: usize> DataRobot<N> {
    /// The model of `spec` (mathematics in the module documentation); an error if the file does
    /// not have `N` joints.
    pub fn new(spec: &RobotSpec) -> Result<Self, RobotFileError> {
        let joints = spec.joints();
        if joints.len() != N {
            return Err(RobotFileError::JointCount {
                file: spec.file().to_string(),
                joints: joints.len(),
                supported: &[N],
            });
        }
        let column = |f: fn(&JointSpec) -> f64| SVector::<f64, N>::from_fn(|i, _| f(&joints[i]));
        let (chain, tool) = match spec.flange() {
            None => (
                DhChain::new(core::array::from_fn(|i| {
                    let r = joints[i].row;
                    DhParam::new(r.a, r.alpha, r.d)
                })),
                spec.tool(),
            ),
            Some(f) => {
                let (chain, flange) = DhChain::from_modified(
                    core::array::from_fn(|i| {
                        let r = joints[i].row;
                        ModifiedDhParam::new(r.a, r.alpha, r.d)
                    }),
                    ModifiedDhParam::new(f.a, f.alpha, f.d),
                );
                (chain, spec.tool() + flange)
            }
        };
        let chain = DhChain {
            base: spec.base().compose(&chain.base),
            ..chain
        };
        Ok(DataRobot {
            name: spec.name().to_string(),
            chain,
            offset: column(|j| j.offset),
            tool,
            limits: JointLimits {
                theta_min: column(|j| j.theta_min),
                theta_max: column(|j| j.theta_max),
                thetadot_min: column(|j| j.velocity_min),
                thetadot_max: column(|j| j.velocity_max),
            },
            acceleration_max: column(|j| j.acceleration_max),
            stated_pose: spec
                .stated_pose()
                .map_or_else(SVector::zeros, SVector::from_column_slice),
        })
    }

    /// The classical chain the task point hangs on (base included).
    pub fn chain(&self) -> &DhChain<N> {
        &self.chain
    }

    /// The joint-angle offsets: the DH angles are `theta + offset`.
    pub fn offset(&self) -> &SVector<f64, N> {
        &self.offset
    }

    /// The task point in classical frame `N` (m).
    pub fn tool(&self) -> Vector3<f64> {
        self.tool
    }

    /// The symmetric joint-acceleration limits (rad/s^2; infinite where the file gives none).
    pub fn acceleration_max(&self) -> &SVector<f64, N> {
        &self.acceleration_max
    }

    /// The pose the file states its check values at (zero if it states none).
    pub fn stated_pose(&self) -> &SVector<f64, N> {
        &self.stated_pose
    }
}

impl<const N: usize> Robot<N> for DataRobot<N> {
    fn name(&self) -> &str {
        &self.name
    }

    fn position(&self, theta: &SVector<f64, N>) -> Vector3<f64> {
        self.chain
            .frames(&(theta + self.offset))
            .frame(N)
            .transform_point(&self.tool)
    }

    fn jacobian(&self, theta: &SVector<f64, N>) -> SMatrix<f64, 3, N> {
        let frames = self.chain.frames(&(theta + self.offset));
        let p = frames.frame(N).transform_point(&self.tool);
        frames.point_jacobian(N, &p)
    }

    fn jacobian_dot(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, 3, N> {
        let frames = self.chain.frames(&(theta + self.offset));
        let p = frames.frame(N).transform_point(&self.tool);
        frames.point_jacobian_dot(N, &p, thetadot)
    }

    fn limits(&self) -> JointLimits<N> {
        self.limits
    }

    /// The origins of classical frames 0..=N (frame 0 is the base), then the task point.
    fn skeleton(&self, theta: &SVector<f64, N>) -> Vec<Vector3<f64>> {
        let frames = self.chain.frames(&(theta + self.offset));
        (0..=N)
            .map(|k| frames.origin(k))
            .chain(std::iter::once(frames.frame(N).transform_point(&self.tool)))
            .collect()
    }
}

/// Code generic in the joint count, run on a [`DataModel`] ([`DataModel::visit`]).
pub trait DataVisitor {
    /// What [`DataVisitor::visit`] returns, whatever the joint count.
    type Output;
    /// Called with the model at its joint count.
    fn visit<const N: usize>(self, robot: Arc<DataRobot<N>>) -> Self::Output;
}

/// Declares [`DataModel`] with one variant per joint count of
/// `crate::joint_counts::with_joint_counts!`.
macro_rules! data_models {
    ($($variant:ident = $n:literal),* $(,)?) => {
        /// A data robot of any joint count in [`JOINT_COUNTS`].
        #[derive(Clone, Debug, PartialEq)]
        pub enum DataModel {
            $(
                #[doc = concat!("A robot file with ", stringify!($n), " joints.")]
                $variant(Arc<DataRobot<$n>>),
            )*
        }

        impl DataModel {
            /// The model of `spec`, at its joint count.
            pub fn new(spec: &RobotSpec) -> Result<Self, RobotFileError> {
                match spec.joints().len() {
                    $($n => Ok(DataModel::$variant(Arc::new(DataRobot::new(spec)?))),)*
                    joints => Err(RobotFileError::JointCount {
                        file: spec.file().to_string(),
                        joints,
                        supported: JOINT_COUNTS,
                    }),
                }
            }

            /// Runs `visitor` on the model with its joint count.
            pub fn visit<V: DataVisitor>(&self, visitor: V) -> V::Output {
                match self {
                    $(DataModel::$variant(r) => visitor.visit::<$n>(r.clone()),)*
                }
            }

            /// The model name.
            pub fn name(&self) -> &str {
                match self {
                    $(DataModel::$variant(r) => r.name(),)*
                }
            }

            /// The number of joints.
            pub fn dof(&self) -> usize {
                match self {
                    $(DataModel::$variant(_) => $n,)*
                }
            }

            /// The pose the file states its check values at (zero if it states none).
            pub fn stated_pose(&self) -> &[f64] {
                match self {
                    $(DataModel::$variant(r) => r.stated_pose().as_slice(),)*
                }
            }
        }
    };
}

crate::joint_counts::with_joint_counts!(data_models);

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

/// The models of the built-in robot files, in [`builtin_files`] order, parsed once per process.
///
/// # Panics
///
/// If a built-in file is invalid. The files are compiled into the library, not user input, and
/// robots' tests (`tests/data_robots.rs`) load every one of them, so a bad file fails the test
/// run, not a user's run.
pub fn builtin_models() -> &'static [DataModel] {
    static MODELS: OnceLock<Vec<DataModel>> = OnceLock::new();
    MODELS.get_or_init(|| {
        builtin_files()
            .iter()
            .map(|(file, text)| {
                parse_builtin(file, text)
                    .and_then(|spec| DataModel::new(&spec))
                    .unwrap_or_else(|e| panic!("invalid built-in robot file: {e}"))
            })
            .collect()
    })
}

/// The built-in data model called `name`, if there is one.
pub fn builtin_model(name: &str) -> Option<&'static DataModel> {
    builtin_models().iter().find(|m| m.name() == name)
}
