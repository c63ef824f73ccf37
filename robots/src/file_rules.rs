//! The rules of a DH robot file ([`crate::robot_file`]) that need no linear algebra: the file's
//! schema as written ([`RawFile`]) and [`check`], its structural and range checks. The library
//! reads every robot file through them, and the build script (`robots/build.rs`, which includes
//! this file by path and so may use only the standard library, `serde`, `toml` and `thiserror`)
//! runs them on every built-in file `robots/data/*.toml`: a built-in file that breaks one fails
//! the build, naming the file and the field.
//!
//! The two checks that need `nalgebra` stay in [`crate::robot_file`] and run only when the file
//! is read: a `base.matrix` must be a rotation, and a link's inertia tensor positive
//! semi-definite.
//!
//! # Rules
//!
//! A file has at most [`MAX_FILE_BYTES`] bytes; `name` is a slug of at most [`MAX_NAME_LEN`]
//! characters; it has [`MIN_JOINTS`] to [`MAX_JOINTS`] joints; every number is finite (an
//! unlimited bound is written by omitting it); every length (`tool`, `base.translation`, a
//! joint's or the flange row's `a` and `d`, a link's `center_of_mass`) is within
//! [`MAX_LENGTH`] of zero; `stated_pose` has one angle per joint; a
//! `modified` table has a flange row and a `standard` one none; a base gives `rotation` or
//! `matrix`, not both; per joint `theta_min < theta_max`, `velocity_max > 0`,
//! `velocity_min < 0` (default `-velocity_max`), `acceleration_max > 0`, and a link's
//! `mass > 0`. No error quotes the file's text, only field names and numbers.

use serde::Deserialize;

/// Largest robot file accepted (bytes): 1 MiB.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// The fewest joints a robot file may have.
pub const MIN_JOINTS: usize = 2;
/// The most joints a robot file may have.
pub const MAX_JOINTS: usize = 1000;

/// Longest model name accepted (characters).
pub const MAX_NAME_LEN: usize = 64;

/// The largest length a robot file or a URDF may state, per coordinate (m): a DH row's `a` and
/// `d`, a tool point, a base translation, a link's centre of mass, a URDF joint's or inertial's
/// `<origin xyz>`. An arm's links are metres long, so a larger value is a typing error
/// (millimetres written as metres, a stray exponent), not an arm: `1e308` would pass as finite
/// and only fail the run (an infinite Jacobian, an infeasible QP). The same bound holds an
/// experiment's own tool offset and base translation and a path's size (`spec::MAX_OFFSET`,
/// which `robots` holds equal to this one at compile time: the build script that includes this
/// file links no `spec`).
pub const MAX_LENGTH: f64 = 10.0;

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

/// Mass properties of the link a joint moves (parsed and validated, not used: a data robot has
/// kinematics only).
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

/// One joint of a checked file: its DH row, offset, limits (infinite where unlimited) and
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

/// The DH robot file as written, before the rules.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFile {
    pub name: String,
    pub source: String,
    pub convention: Convention,
    pub tool: [f64; 3],
    pub stated_pose: Option<Vec<f64>>,
    pub flange: Option<DhRow>,
    pub base: Option<RawBase>,
    pub joint: Vec<RawJoint>,
}

/// The `[base]` table as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBase {
    pub translation: Option<[f64; 3]>,
    pub rotation: Option<Vec<ElementaryRotation>>,
    pub matrix: Option<[[f64; 3]; 3]>,
}

/// One `[[joint]]` table as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawJoint {
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

/// A rule a robot file breaks (the caller names the file); joints are numbered from 1, base to
/// tip. No variant holds the file's text, only field names and numbers.
#[derive(Debug, thiserror::Error)]
pub enum RuleError {
    /// The file is larger than [`MAX_FILE_BYTES`] (refused before parsing).
    #[error("{bytes} bytes; a robot file may have at most {MAX_FILE_BYTES} bytes")]
    TooLarge {
        /// The file's size (bytes).
        bytes: u64,
    },
    /// The model name is not a slug or is longer than `MAX_NAME_LEN`.
    #[error(
        "field `name` is not a slug (lowercase ASCII letters and digits in words joined by \
         single '-', at most {MAX_NAME_LEN} characters)"
    )]
    Name,
    /// The model name differs from the file's stem.
    #[error("field `name` differs from the file's stem {stem:?}")]
    NameNotStem {
        /// The file's stem (its name without `.toml`).
        stem: String,
    },
    /// A number is NaN or infinite.
    #[error("{field} = {value} is not a finite number (omit a limit to leave it unlimited)")]
    NotFinite {
        /// Where the number is, e.g. `tool[2]` or `joint 3: theta_max`.
        field: String,
        /// The number.
        value: f64,
    },
    /// A length is finite but beyond [`MAX_LENGTH`] (m).
    #[error(
        "{field} = {value:e} m is outside [-{MAX_LENGTH}, {MAX_LENGTH}] m (a length in a robot \
         file is at most {MAX_LENGTH} m per coordinate)"
    )]
    TooLong {
        /// Where the length is, e.g. `tool[0]` or `joint 3: d`.
        field: String,
        /// The length (m).
        value: f64,
    },
    /// A joint's `theta_min` is not below its `theta_max`.
    #[error("joint {joint}: theta_min = {min} is not below theta_max = {max}")]
    EmptyRange {
        /// The joint.
        joint: usize,
        /// Its `theta_min` (rad).
        min: f64,
        /// Its `theta_max` (rad).
        max: f64,
    },
    /// A joint's velocity or acceleration limit has the wrong sign.
    #[error("joint {joint}: {field} = {value}, must be {requirement}")]
    Limit {
        /// The joint.
        joint: usize,
        /// The limit: `velocity_min`, `velocity_max` or `acceleration_max`.
        field: &'static str,
        /// Its value (rad/s or rad/s^2), given or defaulted.
        value: f64,
        /// What it must be: `> 0` or `< 0`.
        requirement: &'static str,
    },
    /// The table has too few or too many joints.
    #[error("field `joint`: {joints} joints; a robot file may have {MIN_JOINTS} to {MAX_JOINTS}")]
    JointCount {
        /// The number of `[[joint]]` tables.
        joints: usize,
    },
    /// A modified table without its flange row, or a standard table with one.
    #[error(
        "field `flange`: convention = \"modified\" needs the flange row flange = {{ a, alpha, d }}; \
         convention = \"standard\" takes none (the tool point is in frame N)"
    )]
    Flange {
        /// The table's convention.
        convention: Convention,
    },
    /// `stated_pose` has not one angle per joint.
    #[error("field `stated_pose`: {given} angles, the robot has {joints} joints")]
    StatedPose {
        /// The number of angles given.
        given: usize,
        /// The robot's joint count.
        joints: usize,
    },
    /// The base gives both `rotation` and `matrix`.
    #[error(
        "base: give the rotation as either `rotation` (elementary rotations) or `matrix`, not both"
    )]
    TwoRotations,
    /// A link's inertia is not physical: a non-positive mass, or (checked by
    /// [`crate::RobotSpec`]) an inertia tensor that is not positive semi-definite.
    #[error("joint {joint}: link.{field} is {problem}")]
    Link {
        /// The joint.
        joint: usize,
        /// The field: `mass` or `inertia`.
        field: &'static str,
        /// What is wrong with it.
        problem: &'static str,
    },
}

/// Refuses a text longer than [`MAX_FILE_BYTES`] (before it is parsed).
pub fn check_size(text: &str) -> Result<(), RuleError> {
    let bytes = text.len() as u64;
    if bytes > MAX_FILE_BYTES {
        return Err(RuleError::TooLarge { bytes });
    }
    Ok(())
}

/// Whether `name` is a slug: words of `[a-z0-9]` joined by single `-`, at most
/// [`MAX_NAME_LEN`] characters.
fn is_slug(name: &str) -> bool {
    name.len() <= MAX_NAME_LEN
        && name.split('-').all(|w| {
            !w.is_empty()
                && w.bytes()
                    .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit())
        })
}

/// Refuses a `name` that is not a slug or (with `stem`) differs from the file's stem.
pub fn check_name(name: &str, stem: Option<&str>) -> Result<(), RuleError> {
    if !is_slug(name) {
        return Err(RuleError::Name);
    }
    match stem {
        Some(stem) if stem != name => Err(RuleError::NameNotStem {
            stem: stem.to_string(),
        }),
        _ => Ok(()),
    }
}

/// `value` if it is finite; `field()` names it otherwise.
pub fn finite(field: impl FnOnce() -> String, value: f64) -> Result<f64, RuleError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(RuleError::NotFinite {
            field: field(),
            value,
        })
    }
}

/// Refuses the first non-finite entry of `values`, named `field[k]`.
pub fn all_finite(field: &str, values: &[f64]) -> Result<(), RuleError> {
    for (k, &v) in values.iter().enumerate() {
        finite(|| format!("{field}[{k}]"), v)?;
    }
    Ok(())
}

/// `value` if it is a length: finite (else [`RuleError::NotFinite`]) and within
/// [`MAX_LENGTH`] of zero (else [`RuleError::TooLong`]); `field()` names it.
pub fn length(field: impl Fn() -> String, value: f64) -> Result<f64, RuleError> {
    finite(&field, value)?;
    if value.abs() > MAX_LENGTH {
        return Err(RuleError::TooLong {
            field: field(),
            value,
        });
    }
    Ok(value)
}

/// Refuses the first entry of `values` that is not a length ([`length`]), named `field[k]`.
pub fn all_lengths(field: &str, values: &[f64]) -> Result<(), RuleError> {
    for (k, &v) in values.iter().enumerate() {
        length(|| format!("{field}[{k}]"), v)?;
    }
    Ok(())
}

/// Every rule of the module documentation on `raw`, stem unchecked (with `stem`, the name must
/// be it); the joints with their limits resolved (infinite where unlimited, `velocity_min`
/// defaulting to `-velocity_max`).
pub fn check(raw: &RawFile, stem: Option<&str>) -> Result<Vec<JointSpec>, RuleError> {
    check_name(&raw.name, stem)?;
    let n = raw.joint.len();
    if !(MIN_JOINTS..=MAX_JOINTS).contains(&n) {
        return Err(RuleError::JointCount { joints: n });
    }
    all_lengths("tool", &raw.tool)?;
    if let Some(pose) = &raw.stated_pose {
        if pose.len() != n {
            return Err(RuleError::StatedPose {
                given: pose.len(),
                joints: n,
            });
        }
        all_finite("stated_pose", pose)?;
    }
    match (raw.convention, raw.flange) {
        (Convention::Modified, Some(f)) => {
            length(|| "flange.a".to_string(), f.a)?;
            finite(|| "flange.alpha".to_string(), f.alpha)?;
            length(|| "flange.d".to_string(), f.d)?;
        }
        (Convention::Standard, None) => {}
        (convention, _) => return Err(RuleError::Flange { convention }),
    }
    if let Some(base) = &raw.base {
        check_base(base)?;
    }
    raw.joint
        .iter()
        .enumerate()
        .map(|(i, j)| check_joint(i + 1, j))
        .collect()
}

fn check_base(base: &RawBase) -> Result<(), RuleError> {
    all_lengths("base.translation", &base.translation.unwrap_or_default())?;
    match (&base.rotation, &base.matrix) {
        (Some(_), Some(_)) => return Err(RuleError::TwoRotations),
        (Some(list), None) => {
            for (k, r) in list.iter().enumerate() {
                finite(|| format!("base.rotation[{k}].angle"), r.angle)?;
            }
        }
        (None, Some(rows)) => {
            for (k, row) in rows.iter().enumerate() {
                all_finite(&format!("base.matrix[{k}]"), row)?;
            }
        }
        (None, None) => {}
    }
    Ok(())
}

fn check_joint(joint: usize, j: &RawJoint) -> Result<JointSpec, RuleError> {
    let number = |name: &str, v: f64| finite(|| format!("joint {joint}: {name}"), v);
    let optional = |name: &str, v: Option<f64>, unlimited: f64| match v {
        Some(v) => number(name, v),
        None => Ok(unlimited),
    };
    let limit = |field: &'static str, value: f64, ok: bool, requirement: &'static str| {
        if ok {
            Ok(value)
        } else {
            Err(RuleError::Limit {
                joint,
                field,
                value,
                requirement,
            })
        }
    };
    let inf = f64::INFINITY;
    let metres = |name: &str, v: f64| length(|| format!("joint {joint}: {name}"), v);
    let row = DhRow {
        a: metres("a", j.a)?,
        alpha: number("alpha", j.alpha)?,
        d: metres("d", j.d)?,
    };
    let offset = optional("offset", j.offset, 0.0)?;
    let theta_min = optional("theta_min", j.theta_min, -inf)?;
    let theta_max = optional("theta_max", j.theta_max, inf)?;
    if theta_min >= theta_max {
        return Err(RuleError::EmptyRange {
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
        finite(|| format!("joint {joint}: link.mass"), link.mass)?;
        all_lengths(
            &format!("joint {joint}: link.center_of_mass"),
            &link.center_of_mass,
        )?;
        all_finite(&format!("joint {joint}: link.inertia"), &link.inertia)?;
        if link.mass <= 0.0 {
            return Err(RuleError::Link {
                joint,
                field: "mass",
                problem: "not positive",
            });
        }
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
