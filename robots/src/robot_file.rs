//! The robot file: one TOML file declares one serial arm of revolute joints by its
//! Denavit–Hartenberg table, so that an arm is data, not Rust (`docs/robots.md`). A file may
//! instead point at a URDF ([`UrdfRobotSpec`], the URDF form); [`RobotForm::parse_named`] reads
//! either.
//!
//! ```toml
//! name = "puma560"                    # a slug: the model name experiment files use
//! source = "Corke, mdl_puma560; ..."  # where the numbers come from (free text)
//! convention = "standard"             # or "modified" (stated, required)
//! tool = [0.0, 0.0, 0.05625]          # task point in the last frame (m)
//! stated_pose = [0.0, -0.785, 0.0, 1.571, -0.785, 0.0]   # optional (rad)
//! # flange = { a = 0.0, alpha = 0.0, d = 0.107 }        # modified DH only, required there
//!
//! [base]                              # optional: world from DH frame 0 (default identity)
//! translation = [0.0, 0.0, 0.0]       # optional (m)
//! rotation = [{ axis = "x", angle = -0.02 }, { axis = "y", angle = -0.05 }]
//! # or: matrix = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]   (rows; not both)
//!
//! [[joint]]                           # one table per joint, base to tip
//! a = 0.0                             # m
//! alpha = 1.5707963267948966          # rad
//! d = 0.0                             # m
//! offset = 0.0                        # optional joint-angle offset (rad), default 0
//! theta_min = -2.7751                 # optional (rad); omitted = unlimited
//! theta_max = 2.7751                  # optional (rad); omitted = unlimited
//! velocity_max = 1.5                  # optional (rad/s); omitted = unlimited
//! # velocity_min = -1.0               # optional (rad/s); default -velocity_max
//! # acceleration_max = 10.0           # optional (rad/s^2), symmetric; omitted = unlimited
//! # link = { mass = 17.4, center_of_mass = [0.068, 0.006, -0.016],
//! #          inertia = [0.13, 0.524, 0.539, 0.0, 0.0, 0.0] }   # optional, validated only
//! ```
//!
//! # Mathematics
//!
//! With `q_i = theta_i + offset_i`:
//!
//! - `convention = "standard"` (classical DH): link `i` is `A_i = Rz(q_i) Tz(d_i) Tx(a_i)
//!   Rx(alpha_i)`, and the world frame of link `k` is `T_k = B A_1 ... A_k` with `B` the base
//!   transform; the task point is `f = T_N tool`.
//! - `convention = "modified"` (Craig): row `i` is `Rx(alpha_i) Tx(a_i) Rz(q_i) Tz(d_i)` and the
//!   flange row `F = Rx(alpha_f) Tx(a_f) Tz(d_f)` follows joint `N`; the task point is
//!   `f = B M_1 ... M_N F tool` (`tool` in the flange frame). It is evaluated as the equivalent
//!   classical chain ([`crate::dh::DhChain::from_modified`], derivation in [`crate::dh`]).
//! - The base is `B = Trans(translation) R` with `R` the product of the elementary rotations in
//!   the order listed (`R = R_1 R_2 ...`, e.g. the Jaco2 pen model's `Rx(-0.02) Ry(-0.05)`), or
//!   the given matrix (rows), which must be a rotation (orthonormal to 1e-9, determinant +1).
//!
//! The Jacobian and its derivative are those of [`crate::geometric_jacobian`]
//! (`J_j = z_{j-1} x (f - o_{j-1})`); the model is [`crate::DataRobot`].
//!
//! # Validation
//!
//! The checks that need no linear algebra are the rules of `robots/src/file_rules.rs`, which
//! the build script also runs on every built-in file (a bad built-in file fails the build);
//! the two that need `nalgebra` (a base matrix that is a rotation, a positive semi-definite
//! inertia) run here only. [`RobotSpec::parse`] refuses, with a [`RobotFileError`] naming the file and the field:
//! unknown fields and unknown choices (`convention`, `axis`: the message lists the valid ones),
//! missing required fields, non-finite numbers (TOML's `nan` and `inf`; an unlimited bound is
//! written by omitting it), lengths (`tool`, `base.translation`, `a`, `d`, the flange's `a` and
//! `d`, a link's `center_of_mass`) beyond [`MAX_LENGTH`] of zero, `theta_min >= theta_max`, `velocity_max <= 0`, `velocity_min >= 0`,
//! `acceleration_max <= 0`, fewer than [`MIN_JOINTS`] or more than [`MAX_JOINTS`] joints, a name that is not a slug, a flange row missing from a
//! modified table or given with a standard one, a `stated_pose` of the wrong length, a base with
//! both `rotation` and `matrix` or a matrix that is not a rotation, and link inertias with a
//! non-positive mass or a tensor that is not symmetric positive semi-definite. Files above
//! [`MAX_FILE_BYTES`] are refused before parsing. Joints are numbered from 1, base to tip.
//!
//! Link inertias (`link`) are parsed and validated but not used: a data robot has kinematics
//! only (no [`crate::Dynamics`]).

use nalgebra::{Matrix3, Vector3};
use serde::Deserialize;

use crate::chain_robot::ChainRobot;
use crate::dh::Frame;
use crate::file_rules::{self, all_finite, all_lengths, RawBase, RawFile};
pub use crate::file_rules::{
    Axis, Convention, DhRow, ElementaryRotation, JointSpec, LinkInertia, RuleError, MAX_FILE_BYTES,
    MAX_LENGTH,
};
use crate::urdf::ChainEnds;

impl ElementaryRotation {
    /// The rotation matrix.
    pub fn matrix(&self) -> Matrix3<f64> {
        let (s, c) = self.angle.sin_cos();
        match self.axis {
            Axis::X => Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
            Axis::Y => Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
            Axis::Z => Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
        }
    }
}

/// A validated robot file (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct RobotSpec {
    file: String,
    name: String,
    source: String,
    convention: Convention,
    flange: Option<DhRow>,
    base: Frame,
    tool: Vector3<f64>,
    stated_pose: Option<Vec<f64>>,
    joints: Vec<JointSpec>,
}

/// Why a robot file was refused. Every variant names the file; joints are numbered from 1.
#[derive(Debug, thiserror::Error)]
pub enum RobotFileError {
    /// The file could not be read (a symbolic link out of its directory, a special file, too
    /// large: the reader's reason, which never quotes the file).
    #[error("{file}: cannot read the robot file: {reason}")]
    Unreadable {
        /// The robot file.
        file: String,
        /// Why (the reader's message).
        reason: String,
    },
    /// A robot file read at run time declares a name the suite already has.
    #[error(
        "{file}: declares robot {}, a name the suite already has (a built-in model, \
         another spelling of an n-link arm's name, or another robot file); rename the file and \
         its `name`",
        settings::shown(name)
    )]
    Shadows {
        /// The robot file.
        file: String,
        /// The name (the file's stem).
        name: String,
    },
    /// file's lines, which the TOML parser's own message quotes).
    #[error("{file}: {source}")]
    Syntax {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The TOML parser's message and position.
        #[source]
        source: inputs::TomlError,
    },
    /// The model name is not a slug or is longer than `MAX_NAME_LEN`.
    /// A rule of the shared checks (`file_rules`: a number, a range, a limit, the joint
    /// count, the name, the flange, ...), naming the field.
    #[error("{file}: {source}")]
    Rule {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The rule broken.
        #[source]
        source: RuleError,
    },
    /// The base matrix is not a rotation (orthonormal to 1e-9, determinant +1).
    #[error("{file}: base.matrix is not a rotation (|R^T R - I| = {deviation:e}, det R = {det}); its rows must be orthonormal with det +1")]
    NotARotation {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The Frobenius norm |R^T R - I|.
        deviation: f64,
        /// The determinant of R.
        det: f64,
    },
    /// A joint vector of a URDF robot file (`stated_pose`, `velocity_max`) has not one entry per
    /// joint of the chain.
    #[error("{file}: {field} has {given} entries, the chain from the URDF has {joints} joints")]
    JointVector {
        /// The robot file.
        file: String,
        /// `stated_pose` or `velocity_max`.
        field: &'static str,
        /// The number of entries given.
        given: usize,
        /// The chain's joint count.
        joints: usize,
    },
    /// A `velocity_max` entry of a URDF robot file is not positive.
    #[error("{file}: velocity_max[{index}] = {value}, must be > 0")]
    VelocityMax {
        /// The robot file.
        file: String,
        /// The entry, from 0.
        index: usize,
        /// Its value (rad/s or m/s).
        value: f64,
    },
    /// The URDF a robot file points at gives no chain (the URDF's own error, naming it).
    #[error("{file}: field `urdf` (with `base` and `tip`): {source}")]
    Urdf {
        /// The robot file.
        file: String,
        /// The URDF's error.
        #[source]
        source: Box<crate::urdf::UrdfChainError>,
    },
}

/// Names the file of a broken rule.
fn rule(file: &str) -> impl FnOnce(RuleError) -> RobotFileError + '_ {
    move |source| RobotFileError::Rule {
        file: file.to_string(),
        source,
    }
}

/// Refuses an inertia tensor (of a link whose numbers the shared rules passed) that is not
/// positive semi-definite: its least eigenvalue below `-1e-12 |I|_F`.
fn check_inertia(file: &str, joint: usize, link: &LinkInertia) -> Result<(), RobotFileError> {
    let [ixx, iyy, izz, ixy, iyz, ixz] = link.inertia;
    let tensor = Matrix3::new(ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz);
    let scale = tensor.norm().max(f64::MIN_POSITIVE);
    if tensor.symmetric_eigenvalues().min() < -1e-12 * scale {
        return Err(rule(file)(RuleError::Link {
            joint,
            field: "inertia",
            problem: "not positive semi-definite",
        }));
    }
    Ok(())
}

impl RobotSpec {
    /// Parses and validates the robot file `text`; `file` names it in errors.
    pub fn parse(file: &str, text: &str) -> Result<Self, RobotFileError> {
        Self::parse_with(file, None, text)
    }

    /// [`RobotSpec::parse`], and the name must be `stem`.
    pub fn parse_named(file: &str, stem: &str, text: &str) -> Result<Self, RobotFileError> {
        Self::parse_with(file, Some(stem), text)
    }

    fn parse_with(file: &str, stem: Option<&str>, text: &str) -> Result<Self, RobotFileError> {
        file_rules::check_size(text).map_err(rule(file))?;
        let raw: RawFile = inputs::parse_toml(text).map_err(|source| RobotFileError::Syntax {
            file: file.to_string(),
            source,
        })?;
        let joints = file_rules::check(&raw, stem).map_err(rule(file))?;
        for (i, joint) in joints.iter().enumerate() {
            if let Some(link) = &joint.link {
                check_inertia(file, i + 1, link)?;
            }
        }
        let base = match &raw.base {
            Some(b) => Self::parse_base(file, b)?,
            None => Frame::identity(),
        };
        Ok(RobotSpec {
            file: file.to_string(),
            name: raw.name,
            source: raw.source,
            convention: raw.convention,
            flange: raw.flange,
            base,
            tool: Vector3::from(raw.tool),
            stated_pose: raw.stated_pose,
            joints,
        })
    }

    /// The base frame of a `[base]` table the shared rules passed (finite, not two rotations);
    /// a matrix must be a rotation.
    fn parse_base(file: &str, raw: &RawBase) -> Result<Frame, RobotFileError> {
        let rot = match (&raw.rotation, &raw.matrix) {
            (Some(list), _) => list
                .iter()
                .fold(Matrix3::identity(), |rot, r| rot * r.matrix()),
            (None, Some(rows)) => {
                let m = Matrix3::from_fn(|r, c| rows[r][c]);
                let deviation = (m.transpose() * m - Matrix3::identity()).norm();
                let det = m.determinant();
                if deviation > 1e-9 || det <= 0.0 {
                    return Err(RobotFileError::NotARotation {
                        file: file.to_string(),
                        deviation,
                        det,
                    });
                }
                m
            }
            (None, None) => Matrix3::identity(),
        };
        Ok(Frame {
            rot,
            origin: Vector3::from(raw.translation.unwrap_or([0.0; 3])),
        })
    }

    /// The file's name as given to [`RobotSpec::parse`] or its path.
    pub fn file(&self) -> &str {
        &self.file
    }

    /// The model name (a slug).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Where the numbers come from.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The DH convention of the table.
    pub fn convention(&self) -> Convention {
        self.convention
    }

    /// The flange row of a modified table (`None` for a standard one).
    pub fn flange(&self) -> Option<DhRow> {
        self.flange
    }

    /// World from DH frame 0 (the file's `base`).
    pub fn base(&self) -> Frame {
        self.base
    }

    /// The task point in the last frame (frame N, or the flange frame of a modified table).
    pub fn tool(&self) -> Vector3<f64> {
        self.tool
    }

    /// The pose the check values are stated at, if the file states one.
    pub fn stated_pose(&self) -> Option<&[f64]> {
        self.stated_pose.as_deref()
    }

    /// The joints, base to tip.
    pub fn joints(&self) -> &[JointSpec] {
        &self.joints
    }
}

/// The URDF form of a robot file: the arm is the chain of a URDF between two links
/// (`docs/robots.md`, "How a robot file is found").
///
/// ```toml
/// name = "ur5"                         # a slug, the file's stem
/// source = "..."                       # where the numbers come from (free text)
/// urdf = "ur5.urdf"                    # relative to the robot file's directory, inside it
/// base = "base_link"                   # the chain's first link (its frame is the world)
/// tip = "tool0"                        # the chain's last link
/// tool = [0.0, 0.0, 0.0]               # optional: task point in the tip frame (m)
/// stated_pose = [0.0, -1.0, ...]       # optional (one entry per moving joint)
/// velocity_max = [3.15, ...]           # optional: overrides the URDF's velocity limits
/// ```
///
/// [`RobotForm::parse_named`] refuses unknown and missing fields, non-finite numbers, a `tool`
/// entry beyond [`MAX_LENGTH`] of zero and a name that is not a slug; [`UrdfRobotSpec::build`] reads the URDF (through the `inputs` reader,
/// inside the robot file's directory) and refuses its errors ([`crate::read_urdf`]), joint vectors
/// of the wrong length and non-positive velocity limits, each naming the robot file and field.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UrdfRobotSpec {
    name: String,
    source: String,
    urdf: String,
    base: String,
    tip: String,
    tool: Option<[f64; 3]>,
    stated_pose: Option<Vec<f64>>,
    velocity_max: Option<Vec<f64>>,
}

/// A robot file of either form.
#[derive(Clone, Debug, PartialEq)]
pub enum RobotForm {
    /// A Denavit–Hartenberg table ([`RobotSpec`]).
    Dh(RobotSpec),
    /// A URDF chain ([`UrdfRobotSpec`]).
    Urdf(UrdfRobotSpec),
}

impl RobotForm {
    /// Parses the robot file `text` named `file`, whose name must be `stem`: the URDF form if
    /// it has a top-level `urdf` field, the DH form otherwise.
    pub fn parse_named(file: &str, stem: &str, text: &str) -> Result<Self, RobotFileError> {
        let is_urdf = text.len() as u64 <= MAX_FILE_BYTES
            && toml::from_str::<toml::Table>(text).is_ok_and(|t| t.contains_key("urdf"));
        if !is_urdf {
            return RobotSpec::parse_named(file, stem, text).map(RobotForm::Dh);
        }
        let spec: UrdfRobotSpec =
            inputs::parse_toml(text).map_err(|source| RobotFileError::Syntax {
                file: file.to_string(),
                source,
            })?;
        spec.validate(file, stem)?;
        Ok(RobotForm::Urdf(spec))
    }
}

impl UrdfRobotSpec {
    /// Checks the fields that need no URDF (module documentation).
    fn validate(&self, file: &str, stem: &str) -> Result<(), RobotFileError> {
        file_rules::check_name(&self.name, Some(stem)).map_err(rule(file))?;
        all_lengths("tool", &self.tool.unwrap_or_default()).map_err(rule(file))?;
        all_finite(
            "stated_pose",
            self.stated_pose.as_deref().unwrap_or_default(),
        )
        .map_err(rule(file))?;
        all_finite(
            "velocity_max",
            self.velocity_max.as_deref().unwrap_or_default(),
        )
        .map_err(rule(file))
    }

    /// The model name (a slug).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Where the numbers come from.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The URDF's path as written (relative to the robot file's directory).
    pub fn urdf(&self) -> &str {
        &self.urdf
    }

    /// The chain's base link.
    pub fn base(&self) -> &str {
        &self.base
    }

    /// The chain's tip link.
    pub fn tip(&self) -> &str {
        &self.tip
    }

    /// Reads the URDF next to the robot file `file` (through the `inputs` reader, inside
    /// `file`'s directory) and builds the robot and its stated pose (zero if the file states
    /// none).
    pub fn build(&self, file: &std::path::Path) -> Result<(ChainRobot, Vec<f64>), RobotFileError> {
        let shown = file.display().to_string();
        let dir = file.parent().unwrap_or(std::path::Path::new("."));
        let ends = ChainEnds {
            base: &self.base,
            tip: &self.tip,
            tool: Vector3::from(self.tool.unwrap_or_default()),
        };
        let chain = crate::urdf::read(&dir.join(&self.urdf), inputs::Origin::Under(dir), &ends)
            .map_err(|e| RobotFileError::Urdf {
                file: shown.clone(),
                source: Box::new(e),
            })?;
        let n = chain.dof();
        let length = |field: &'static str, v: &[f64]| {
            if v.len() == n {
                Ok(())
            } else {
                Err(RobotFileError::JointVector {
                    file: shown.clone(),
                    field,
                    given: v.len(),
                    joints: n,
                })
            }
        };
        let mut robot = ChainRobot::new(&self.name, chain);
        if let Some(v) = &self.velocity_max {
            length("velocity_max", v)?;
            if let Some((index, &value)) = v.iter().enumerate().find(|(_, &v)| v <= 0.0) {
                return Err(RobotFileError::VelocityMax {
                    file: shown,
                    index,
                    value,
                });
            }
            robot = robot.with_velocity_max(v);
        }
        let pose = match &self.stated_pose {
            Some(p) => {
                length("stated_pose", p)?;
                p.clone()
            }
            None => vec![0.0; n],
        };
        Ok((robot, pose))
    }
}
