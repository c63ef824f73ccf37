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
//! (`J_j = z_{j-1} x (f - o_{j-1})`); the model is [`crate::data_robot::DataRobot`].
//!
//! # Validation
//!
//! [`RobotSpec::parse`] refuses, with a [`RobotFileError`] naming the file and the field:
//! unknown fields and unknown choices (`convention`, `axis`: the message lists the valid ones),
//! missing required fields, non-finite numbers (TOML's `nan` and `inf`; an unlimited bound is
//! written by omitting it), `theta_min >= theta_max`, `velocity_max <= 0`, `velocity_min >= 0`,
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
use crate::urdf::ChainEnds;

/// Largest robot file accepted (bytes): 1 MiB.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// The fewest joints a robot file may have.
pub const MIN_JOINTS: usize = 2;
/// The most joints a robot file may have.
pub const MAX_JOINTS: usize = 1000;

/// Longest model name accepted (characters).
pub const MAX_NAME_LEN: usize = 64;

/// The DH convention a table is written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Convention {
    /// Classical DH: `Rz(theta) Tz(d) Tx(a) Rx(alpha)`.
    Standard,
    /// Modified (Craig) DH: `Rx(alpha) Tx(a) Rz(theta) Tz(d)`, then a flange row.
    Modified,
}

impl std::fmt::Display for Convention {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Convention::Standard => "standard",
            Convention::Modified => "modified",
        })
    }
}

/// A coordinate axis of an elementary rotation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// The x axis (`axis = "x"`).
    X,
    /// The y axis (`axis = "y"`).
    Y,
    /// The z axis (`axis = "z"`).
    Z,
}

/// A rotation by `angle` (rad) about a coordinate axis.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ElementaryRotation {
    /// The axis rotated about.
    pub axis: Axis,
    /// The rotation angle (rad), right-handed about `axis`.
    pub angle: f64,
}

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

/// One DH row `(a, alpha, d)` as written in the file (a modified table's flange row).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DhRow {
    /// m.
    pub a: f64,
    /// rad.
    pub alpha: f64,
    /// m.
    pub d: f64,
}

/// Mass properties of the link a joint moves (parsed and validated, not used: see the module
/// documentation).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinkInertia {
    /// kg, > 0.
    pub mass: f64,
    /// Centre of mass in the link's frame (m).
    pub center_of_mass: [f64; 3],
    /// Inertia tensor about the centre of mass, `[Ixx, Iyy, Izz, Ixy, Iyz, Ixz]` (kg m^2), as
    /// Corke's toolbox lists it; positive semi-definite.
    pub inertia: [f64; 6],
}

/// One joint of a validated file: its DH row, offset, limits (infinite where unlimited) and
/// optional link inertia.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointSpec {
    /// The joint's DH row `(a, alpha, d)` in the file's convention.
    pub row: DhRow,
    /// Joint-angle offset (rad): the DH angle is `theta + offset`.
    pub offset: f64,
    /// Lower joint-angle limit (rad).
    pub theta_min: f64,
    /// Upper joint-angle limit (rad).
    pub theta_max: f64,
    /// Lower joint-velocity limit (rad/s), < 0.
    pub velocity_min: f64,
    /// Upper joint-velocity limit (rad/s), > 0.
    pub velocity_max: f64,
    /// Symmetric joint-acceleration limit (rad/s^2), > 0.
    pub acceleration_max: f64,
    /// Mass properties of the link, if the file gives them.
    pub link: Option<LinkInertia>,
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
        "{file}: declares robot \"{name}\", a name the suite already has (a built-in model or \
         another robot file); rename the file and its `name`"
    )]
    Shadows {
        /// The robot file.
        file: String,
        /// The name (the file's stem).
        name: String,
    },
    /// The file is larger than [`MAX_FILE_BYTES`] (refused before parsing).
    #[error("{file}: {bytes} bytes; a robot file may have at most {limit} bytes")]
    TooLarge {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The file's size (bytes).
        bytes: u64,
        /// The largest size accepted (bytes), [`MAX_FILE_BYTES`].
        limit: u64,
    },
    /// TOML syntax, a missing or unknown field, a wrong type, or an unknown choice (the message
    /// names the field and lists the valid choices, with the line and column; never the
    /// file's lines, which the TOML parser's own message quotes).
    #[error("{file}: {source}")]
    Syntax {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The TOML parser's message and position.
        #[source]
        source: inputs::TomlError,
    },
    /// The model name is not a slug or is longer than [`MAX_NAME_LEN`].
    #[error(
        "{file}: name = {name:?} is not a slug (lowercase ASCII letters and digits in words \
         joined by single '-', at most {MAX_NAME_LEN} characters)"
    )]
    Name {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The name as written.
        name: String,
    },
    /// The model name differs from the file's stem ([`RobotSpec::parse_named`]).
    #[error("{file}: name = {name:?} differs from the file's stem {stem:?}")]
    NameNotStem {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The name as written.
        name: String,
        /// The file's stem (its name without `.toml`).
        stem: String,
    },
    /// A number is NaN or infinite.
    #[error(
        "{file}: {field} = {value} is not a finite number (omit a limit to leave it unlimited)"
    )]
    NotFinite {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// Where the number is, e.g. `tool[2]` or `joint 3: theta_max`.
        field: String,
        /// The number.
        value: f64,
    },
    /// A joint's `theta_min` is not below its `theta_max`.
    #[error("{file}: joint {joint}: theta_min = {min} is not below theta_max = {max}")]
    EmptyRange {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The joint, numbered from 1 (base to tip).
        joint: usize,
        /// Its `theta_min` (rad).
        min: f64,
        /// Its `theta_max` (rad).
        max: f64,
    },
    /// A joint's velocity or acceleration limit has the wrong sign.
    #[error("{file}: joint {joint}: {field} = {value}, must be {requirement}")]
    Limit {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The joint, numbered from 1 (base to tip).
        joint: usize,
        /// The limit: `velocity_min`, `velocity_max` or `acceleration_max`.
        field: &'static str,
        /// Its value (rad/s or rad/s^2), given or defaulted.
        value: f64,
        /// What it must be: `> 0` or `< 0`.
        requirement: &'static str,
    },
    /// The table has too few or too many joints.
    #[error("{file}: field `joint`: {joints} joints; a robot file may have {MIN_JOINTS} to {MAX_JOINTS}")]
    JointCount {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The number of `[[joint]]` tables.
        joints: usize,
    },
    /// A modified table without its flange row, or a standard table with one.
    #[error(
        "{file}: convention = \"modified\" needs the flange row flange = {{ a, alpha, d }}; \
         convention = \"standard\" takes none (the tool point is in frame N)"
    )]
    Flange {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The table's convention.
        convention: Convention,
    },
    /// `stated_pose` has not one angle per joint.
    #[error("{file}: stated_pose has {given} angles, the robot has {joints} joints")]
    StatedPose {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The number of angles given.
        given: usize,
        /// The robot's joint count.
        joints: usize,
    },
    /// The base gives both `rotation` and `matrix`.
    #[error("{file}: base: give the rotation as either `rotation` (elementary rotations) or `matrix`, not both")]
    TwoRotations {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
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
    /// A link's inertia is not physical: a non-positive mass or an inertia tensor that is not
    /// symmetric positive semi-definite.
    #[error("{file}: joint {joint}: link.{field} is {problem}")]
    Link {
        /// The robot file: the name given to [`RobotSpec::parse`] or the path read.
        file: String,
        /// The joint, numbered from 1 (base to tip).
        joint: usize,
        /// The field: `mass` or `inertia`.
        field: &'static str,
        /// What is wrong with it.
        problem: &'static str,
    },
}

/// The file as written, before validation.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    name: String,
    source: String,
    convention: Convention,
    tool: [f64; 3],
    stated_pose: Option<Vec<f64>>,
    flange: Option<DhRow>,
    base: Option<RawBase>,
    joint: Vec<RawJoint>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBase {
    translation: Option<[f64; 3]>,
    rotation: Option<Vec<ElementaryRotation>>,
    matrix: Option<[[f64; 3]; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawJoint {
    a: f64,
    alpha: f64,
    d: f64,
    offset: Option<f64>,
    theta_min: Option<f64>,
    theta_max: Option<f64>,
    velocity_min: Option<f64>,
    velocity_max: Option<f64>,
    acceleration_max: Option<f64>,
    link: Option<LinkInertia>,
}

/// Whether `name` is a slug: words of `[a-z0-9]` joined by single `-`.
fn is_slug(name: &str) -> bool {
    name.len() <= MAX_NAME_LEN
        && name.split('-').all(|w| {
            !w.is_empty()
                && w.bytes()
                    .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit())
        })
}

/// Collects the non-finite-number check over every number of the file.
struct Finite<'a> {
    file: &'a str,
}

impl Finite<'_> {
    fn check(&self, field: impl FnOnce() -> String, value: f64) -> Result<f64, RobotFileError> {
        if value.is_finite() {
            Ok(value)
        } else {
            Err(RobotFileError::NotFinite {
                file: self.file.to_string(),
                field: field(),
                value,
            })
        }
    }

    fn all(&self, field: &str, values: &[f64]) -> Result<(), RobotFileError> {
        for (k, &v) in values.iter().enumerate() {
            self.check(|| format!("{field}[{k}]"), v)?;
        }
        Ok(())
    }
}

impl RobotSpec {
    /// Parses and validates the robot file `text`; `file` names it in errors.
    pub fn parse(file: &str, text: &str) -> Result<Self, RobotFileError> {
        let bytes = text.len() as u64;
        if bytes > MAX_FILE_BYTES {
            return Err(RobotFileError::TooLarge {
                file: file.to_string(),
                bytes,
                limit: MAX_FILE_BYTES,
            });
        }
        let raw: RawFile =
            inputs::toml_error::from_str(text).map_err(|source| RobotFileError::Syntax {
                file: file.to_string(),
                source,
            })?;
        Self::validate(file, raw)
    }

    /// [`RobotSpec::parse`], and the name must be `stem`.
    pub fn parse_named(file: &str, stem: &str, text: &str) -> Result<Self, RobotFileError> {
        let spec = Self::parse(file, text)?;
        if spec.name != stem {
            return Err(RobotFileError::NameNotStem {
                file: file.to_string(),
                name: spec.name,
                stem: stem.to_string(),
            });
        }
        Ok(spec)
    }

    fn validate(file: &str, raw: RawFile) -> Result<Self, RobotFileError> {
        let fail_file = || file.to_string();
        if !is_slug(&raw.name) {
            return Err(RobotFileError::Name {
                file: fail_file(),
                name: raw.name,
            });
        }
        let n = raw.joint.len();
        if !(MIN_JOINTS..=MAX_JOINTS).contains(&n) {
            return Err(RobotFileError::JointCount {
                file: fail_file(),
                joints: n,
            });
        }
        let finite = Finite { file };
        finite.all("tool", &raw.tool)?;
        if let Some(pose) = &raw.stated_pose {
            if pose.len() != n {
                return Err(RobotFileError::StatedPose {
                    file: fail_file(),
                    given: pose.len(),
                    joints: n,
                });
            }
            finite.all("stated_pose", pose)?;
        }
        let flange = match (raw.convention, raw.flange) {
            (Convention::Modified, Some(f)) => {
                finite.all("flange", &[f.a, f.alpha, f.d])?;
                Some(f)
            }
            (Convention::Standard, None) => None,
            (convention, _) => {
                return Err(RobotFileError::Flange {
                    file: fail_file(),
                    convention,
                })
            }
        };
        let base = Self::parse_base(file, &finite, raw.base)?;
        let joints = raw
            .joint
            .into_iter()
            .enumerate()
            .map(|(i, j)| Self::parse_joint(file, &finite, i + 1, j))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(RobotSpec {
            file: file.to_string(),
            name: raw.name,
            source: raw.source,
            convention: raw.convention,
            flange,
            base,
            tool: Vector3::from(raw.tool),
            stated_pose: raw.stated_pose,
            joints,
        })
    }

    fn parse_base(
        file: &str,
        finite: &Finite,
        raw: Option<RawBase>,
    ) -> Result<Frame, RobotFileError> {
        let Some(raw) = raw else {
            return Ok(Frame::identity());
        };
        let translation = raw.translation.unwrap_or([0.0; 3]);
        finite.all("base.translation", &translation)?;
        let rot = match (raw.rotation, raw.matrix) {
            (Some(_), Some(_)) => {
                return Err(RobotFileError::TwoRotations {
                    file: file.to_string(),
                })
            }
            (Some(list), None) => {
                let mut rot = Matrix3::identity();
                for (k, r) in list.iter().enumerate() {
                    finite.check(|| format!("base.rotation[{k}].angle"), r.angle)?;
                    rot *= r.matrix();
                }
                rot
            }
            (None, Some(rows)) => {
                for (k, row) in rows.iter().enumerate() {
                    finite.all(&format!("base.matrix[{k}]"), row)?;
                }
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
            origin: Vector3::from(translation),
        })
    }

    fn parse_joint(
        file: &str,
        finite: &Finite,
        joint: usize,
        j: RawJoint,
    ) -> Result<JointSpec, RobotFileError> {
        let number = |name: &str, v: f64| finite.check(|| format!("joint {joint}: {name}"), v);
        let optional = |name: &str, v: Option<f64>, unlimited: f64| match v {
            Some(v) => number(name, v),
            None => Ok(unlimited),
        };
        let limit = |field: &'static str, value: f64, ok: bool, requirement: &'static str| {
            if ok {
                Ok(value)
            } else {
                Err(RobotFileError::Limit {
                    file: file.to_string(),
                    joint,
                    field,
                    value,
                    requirement,
                })
            }
        };
        let inf = f64::INFINITY;
        let row = DhRow {
            a: number("a", j.a)?,
            alpha: number("alpha", j.alpha)?,
            d: number("d", j.d)?,
        };
        let offset = optional("offset", j.offset, 0.0)?;
        let theta_min = optional("theta_min", j.theta_min, -inf)?;
        let theta_max = optional("theta_max", j.theta_max, inf)?;
        if theta_min >= theta_max {
            return Err(RobotFileError::EmptyRange {
                file: file.to_string(),
                joint,
                min: theta_min,
                max: theta_max,
            });
        }
        let velocity_max = optional("velocity_max", j.velocity_max, inf)?;
        let velocity_max = limit("velocity_max", velocity_max, velocity_max > 0.0, "> 0")?;
        let velocity_min = optional("velocity_min", j.velocity_min, -velocity_max)?;
        let velocity_min = limit("velocity_min", velocity_min, velocity_min < 0.0, "< 0")?;
        let acceleration_max = optional("acceleration_max", j.acceleration_max, inf)?;
        let acceleration_max = limit(
            "acceleration_max",
            acceleration_max,
            acceleration_max > 0.0,
            "> 0",
        )?;
        if let Some(link) = &j.link {
            Self::check_link(file, finite, joint, link)?;
        }
        Ok(JointSpec {
            row,
            offset,
            theta_min,
            theta_max,
            velocity_min,
            velocity_max,
            acceleration_max,
            link: j.link,
        })
    }

    fn check_link(
        file: &str,
        finite: &Finite,
        joint: usize,
        link: &LinkInertia,
    ) -> Result<(), RobotFileError> {
        let bad = |field: &'static str, problem: &'static str| {
            Err(RobotFileError::Link {
                file: file.to_string(),
                joint,
                field,
                problem,
            })
        };
        finite.check(|| format!("joint {joint}: link.mass"), link.mass)?;
        finite.all(
            &format!("joint {joint}: link.center_of_mass"),
            &link.center_of_mass,
        )?;
        finite.all(&format!("joint {joint}: link.inertia"), &link.inertia)?;
        if link.mass <= 0.0 {
            return bad("mass", "not positive");
        }
        let [ixx, iyy, izz, ixy, iyz, ixz] = link.inertia;
        let tensor = Matrix3::new(ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz);
        let scale = tensor.norm().max(f64::MIN_POSITIVE);
        if tensor.symmetric_eigenvalues().min() < -1e-12 * scale {
            return bad("inertia", "not positive semi-definite");
        }
        Ok(())
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
/// [`RobotForm::parse_named`] refuses unknown and missing fields, non-finite numbers and a name
/// that is not a slug; [`UrdfRobotSpec::build`] reads the URDF (through the `inputs` reader,
/// inside the robot file's directory) and refuses its errors ([`crate::urdf`]), joint vectors
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
            inputs::toml_error::from_str(text).map_err(|source| RobotFileError::Syntax {
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
        if !is_slug(&self.name) {
            return Err(RobotFileError::Name {
                file: file.to_string(),
                name: self.name.clone(),
            });
        }
        if self.name != stem {
            return Err(RobotFileError::NameNotStem {
                file: file.to_string(),
                name: self.name.clone(),
                stem: stem.to_string(),
            });
        }
        let finite = Finite { file };
        finite.all("tool", &self.tool.unwrap_or_default())?;
        finite.all(
            "stated_pose",
            self.stated_pose.as_deref().unwrap_or_default(),
        )?;
        finite.all(
            "velocity_max",
            self.velocity_max.as_deref().unwrap_or_default(),
        )?;
        Ok(())
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
