//! A [`Chain`] from a URDF (parsed by the `urdf-rs` crate): the serial path from a named base
//! link to a named tip link (`docs/robots.md`, "URDF chains").
//!
//! # What is read
//!
//! - **The path.** The joints from `base` down to `tip`, each the one joint whose child is the
//!   next link. Every link may be the child of at most one joint (a tree), and `tip` must lie
//!   below `base`.
//! - **Joints.** `revolute` (position limits `lower`, `upper`), `continuous` (no position
//!   limits), `prismatic` (limits in m), and `fixed`: a fixed joint's origin is folded into the
//!   origin of the next moving joint, or, after the last one, into the tool frame. `floating`,
//!   `planar` and `spherical` joints and `mimic` joints on the path are refused. Velocity and
//!   effort limits come from `<limit velocity effort>`; a zero there (urdf-rs reads a missing
//!   `<limit>` as zeros) leaves the velocity or effort unlimited. `<dynamics>`,
//!   `<calibration>` and `<safety_controller>` are not read.
//! - **Origins and axes.** `<origin xyz rpy>` is `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` (the
//!   URDF convention; a URDF 1.1 `quat_xyzw` is converted by urdf-rs); `<axis xyz>` (default
//!   `(1, 0, 0)`) is normalised.
//! - **Inertials.** The body a moving joint moves is its child link together with every link
//!   attached to that link by fixed joints only, on the path or off it (a flange, a hand, a
//!   sensor). Their `<inertial>`s (mass `m_k`, centre `c_k` and tensor `I_k` in the inertial
//!   frame `(R_k, c_k)` placed in the body frame by the fixed joints) are merged:
//!   `m = sum m_k`, `c = sum m_k c_k / m`, `I = sum (R_k I_k R_k' + m_k (|d_k|^2 E - d_k d_k'))`
//!   with `d_k = c_k - c` (parallel axes). Links that do not move (fixed to `base` before the
//!   first moving joint) and branches hung by a moving joint off the path (a gripper's fingers,
//!   say) are not part of the chain: their masses do not enter `H`, `c`, `g`. A link without
//!   `<inertial>` is massless.
//! - **Tool point.** The tool frame is the tip link's frame translated by the caller's tool
//!   offset (in the tip frame).
//!
//! # Hostile files
//!
//! The bytes are read through the `inputs` crate ([`inputs::Kind::Urdf`]: a regular file,
//! inside its directory, at most its cap); [`parse`] refuses text above [`MAX_FILE_BYTES`], and
//! elements nested deeper than [`MAX_DEPTH`] before urdf-rs sees the text (its XML reader
//! recurses once per level, so ten thousand nested elements, even inside an ignored
//! `<gazebo>`, would overflow the stack): a linear scan that allocates nothing and skips
//! comments, CDATA sections, processing instructions, declarations such as `<!DOCTYPE ...>`
//! and quoted attribute values, and counts a self-closing `<x/>` as a level. After parsing it
//! refuses more than [`MAX_JOINTS`] `<joint>` elements, two `<link>` or two `<joint>` elements
//! of one name, and, on every joint and every link's `<inertial>` (on the path or not), an
//! `<origin>` whose `xyz` or `rpy` is not finite or whose `xyz` is beyond
//! [`crate::MAX_LENGTH`] of zero (the bound of a robot file's lengths). An axis is normalised
//! by its largest entry first, so that `1e308 1e308 0` is the unit `(1, 1, 0) / sqrt 2`
//! ([`Chain::new`]). No error quotes the file: a parse error says that urdf-rs could not read
//! it (its message, which may quote the file, is not shown); a missing link lists at most
//! [`MAX_LISTED_LINKS`] of the file's link names, each cut to [`MAX_NAME_CHARS`] characters
//! and escaped, as is the name of a duplicated link or joint or of an origin's owner.

use std::collections::HashMap;
use std::path::Path;

use nalgebra::{Matrix3, Vector3};

use crate::chain::{Chain, ChainError, ChainJoint, JointKind, JointRange};
use crate::dh::Frame;
use crate::file_rules::MAX_LENGTH;
use crate::rigid_body::RigidBody;

/// The largest URDF text parsed (bytes), the cap of [`inputs::Kind::Urdf`].
pub const MAX_FILE_BYTES: u64 = 16 << 20;

/// The most `<joint>` elements a URDF may have (the whole file, not only the path).
pub const MAX_JOINTS: usize = 1000;

/// The deepest element nesting a URDF may have (`<robot>` is level 1). A robot's own elements
/// nest five deep (`<robot><link><visual><geometry><mesh/>`); simulator extensions a few more.
pub const MAX_DEPTH: usize = 64;

/// The most link names an error lists.
pub const MAX_LISTED_LINKS: usize = 20;

/// The longest link or joint name an error shows (characters; longer ones are cut).
pub const MAX_NAME_CHARS: usize = 64;

/// Which part of a URDF becomes the chain.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainEnds<'a> {
    /// The link the chain starts from (its frame is the chain's base frame).
    pub base: &'a str,
    /// The link the chain ends at.
    pub tip: &'a str,
    /// The tool point in the tip link's frame (m).
    pub tool: Vector3<f64>,
}

/// Why a URDF did not give a chain. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum UrdfChainError {
    /// The file could not be read (not found, a link out of its directory, not a regular file,
    /// too large, not UTF-8).
    #[error(transparent)]
    Input(#[from] inputs::InputError),
    /// The text is larger than `MAX_FILE_BYTES`.
    #[error("{file}: {bytes} bytes; a URDF may have at most {limit} bytes")]
    TooLarge {
        /// The URDF.
        file: String,
        /// Its size (bytes).
        bytes: u64,
        /// `MAX_FILE_BYTES`.
        limit: u64,
    },
    /// Elements nested deeper than [`MAX_DEPTH`] (refused before parsing).
    #[error(
        "{file}: elements nested more than {limit} levels deep; a URDF may nest at most {limit} \
         (a robot's own elements nest about 5)"
    )]
    TooDeep {
        /// The URDF.
        file: String,
        /// [`MAX_DEPTH`].
        limit: usize,
    },
    /// urdf-rs could not read the file.
    #[error(
        "{file}: not a URDF that urdf-rs can read (malformed XML, a missing required element \
         or attribute such as a joint's <parent>, <child> or type, or a number that does not \
         parse); the parser's message is not shown as it may quote the file"
    )]
    Syntax {
        /// The URDF.
        file: String,
    },
    /// More `<joint>` elements than [`MAX_JOINTS`].
    #[error("{file}: {joints} joints; a URDF may have at most {limit}")]
    TooManyJoints {
        /// The URDF.
        file: String,
        /// The number of `<joint>` elements.
        joints: usize,
        /// [`MAX_JOINTS`].
        limit: usize,
    },
    /// Two `<link>` or two `<joint>` elements have the same name.
    #[error(
        "{file}: <{element}> elements {first} and {second} (counted from 1 in file order) are \
         both named {name:?}; each {element} name must be unique"
    )]
    Duplicate {
        /// The URDF.
        file: String,
        /// `link` or `joint`.
        element: &'static str,
        /// The name (cut to `MAX_NAME_CHARS`).
        name: String,
        /// The first element of that name, from 1 among the file's elements of its kind.
        first: usize,
        /// The second.
        second: usize,
    },
    /// An `<origin>` entry is NaN or infinite.
    #[error("{file}: {owner}: <origin {field}> entry {index} = {value} is not a finite number")]
    OriginNotFinite {
        /// The URDF.
        file: String,
        /// `joint "<name>"` or `link "<name>" <inertial>` (the name cut and escaped).
        owner: String,
        /// `xyz` or `rpy`.
        field: &'static str,
        /// The entry, from 0.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// An `<origin xyz>` entry is beyond [`crate::MAX_LENGTH`].
    #[error(
        "{file}: {owner}: <origin xyz> entry {index} = {value:e} m is outside [-{limit}, \
         {limit}] m (a length in a robot is at most {limit} m per coordinate)"
    )]
    TooLong {
        /// The URDF.
        file: String,
        /// `joint "<name>"` or `link "<name>" <inertial>` (the name cut and escaped).
        owner: String,
        /// The entry, from 0.
        index: usize,
        /// Its value (m).
        value: f64,
        /// [`crate::MAX_LENGTH`].
        limit: f64,
    },
    /// The base or tip link is not a link of the file.
    #[error("{file}: no link {name:?} (the {end} link); the file's links are: {valid}")]
    UnknownLink {
        /// The URDF.
        file: String,
        /// `base` or `tip`.
        end: &'static str,
        /// The name asked for (cut to `MAX_NAME_CHARS`).
        name: String,
        /// The file's link names, at most [`MAX_LISTED_LINKS`], escaped and cut.
        valid: String,
    },
    /// A joint names a parent or child link that the file does not declare.
    #[error("{file}: joint {joint:?} names link {link:?}, which has no <link> element")]
    UndeclaredLink {
        /// The URDF.
        file: String,
        /// The joint (cut).
        joint: String,
        /// The link (cut).
        link: String,
    },
    /// A link is the child of two joints: the file is not a tree.
    #[error("{file}: link {link:?} is the child of two joints; a URDF must be a tree")]
    TwoParents {
        /// The URDF.
        file: String,
        /// The link (cut to `MAX_NAME_CHARS`).
        link: String,
    },
    /// Following parent links from `link` comes back to it.
    #[error("{file}: the joints form a cycle through link {link:?}; a URDF must be a tree")]
    Cycle {
        /// The URDF.
        file: String,
        /// A link on the cycle (cut).
        link: String,
    },
    /// The tip is not below the base: the path would branch up and down through the tree.
    #[error(
        "{file}: link {tip:?} is not below link {base:?}; a chain runs from the base down to \
         the tip (the tip's ancestors are: {ancestors})"
    )]
    NotBelow {
        /// The URDF.
        file: String,
        /// The base link (cut).
        base: String,
        /// The tip link (cut).
        tip: String,
        /// The tip's ancestors, nearest first, at most [`MAX_LISTED_LINKS`], escaped and cut.
        ancestors: String,
    },
    /// A joint on the path is of a type a serial chain does not have.
    #[error(
        "{file}: joint {joint:?} is {kind}; a chain has revolute, continuous, prismatic and \
         fixed joints"
    )]
    Unsupported {
        /// The URDF.
        file: String,
        /// The joint (cut).
        joint: String,
        /// `floating`, `planar`, `spherical` or `a mimic joint`.
        kind: &'static str,
    },
    /// The path's joints do not make a valid chain (no moving joint, bad limits or inertials).
    #[error("{file}: base {base:?} to tip {tip:?}: {source}")]
    Chain {
        /// The URDF.
        file: String,
        /// The base link (cut).
        base: String,
        /// The tip link (cut).
        tip: String,
        /// What is wrong.
        #[source]
        source: Box<ChainError>,
    },
}

/// A name as errors show it: at most [`MAX_NAME_CHARS`] characters (escaped by `{:?}`).
fn shown(name: &str) -> String {
    let mut s: String = name.chars().take(MAX_NAME_CHARS).collect();
    if name.chars().count() > MAX_NAME_CHARS {
        s.push_str("...");
    }
    s
}

/// At most [`MAX_LISTED_LINKS`] names, escaped, cut and comma-separated, with the count left
/// off.
fn listed<'a>(names: impl ExactSizeIterator<Item = &'a str>) -> String {
    let total = names.len();
    let mut out: Vec<String> = names
        .take(MAX_LISTED_LINKS)
        .map(|n| format!("{:?}", shown(n)))
        .collect();
    if total > MAX_LISTED_LINKS {
        out.push(format!("and {} more", total - MAX_LISTED_LINKS));
    }
    out.join(", ")
}

/// Whether the elements of the XML `text` nest deeper than `limit` (`<robot>` is level 1): one
/// pass over the bytes that allocates nothing. It reads markup as urdf-rs's XML reader
/// (RustyXML) does, so that nothing it skips can hide an element from the reader: a comment
/// ends at its first `-->`, a CDATA section at its first `]]>`, a processing instruction at
/// the first `>` after a `?`, a declaration such as `<!DOCTYPE ...>` at its first `>`, an end
/// tag at its `>`; in a start tag a quote opens an attribute value only after a name and `=`
/// (the value may hold `>`), and `/>` closes the element at once (a level, left again). Where
/// the reader would stop at an error inside a start tag, the scan counts the element as opened
/// and goes on from there, so it may count more levels than the reader builds, never fewer.
fn nests_deeper_than(text: &str, limit: usize) -> bool {
    /// Where in a start tag the scan is (the reader's states).
    #[derive(Clone, Copy)]
    enum Tag {
        Name,
        Between,
        Attribute { spaced: bool },
        Delimiter,
        Value(u8),
        Close,
    }
    let b = text.as_bytes();
    let n = b.len();
    // The first index at or after `from` holding `byte` (`n` if none).
    let find = |from: usize, byte: u8| {
        b.get(from..)
            .and_then(|rest| rest.iter().position(|&c| c == byte))
            .map_or(n, |k| from + k)
    };
    // The index just past the first `end` at or after `from` (`n` if none).
    let past = |from: usize, end: &[u8]| {
        b.get(from..)
            .and_then(|rest| rest.windows(end.len()).position(|w| w == end))
            .map_or(n, |k| from + k + end.len())
    };
    let space = |c: u8| matches!(c, b' ' | b'\t' | b'\r' | b'\n');
    let mut depth = 0usize;
    let mut i = find(0, b'<');
    while i < n {
        let rest = &b[i..];
        if rest.starts_with(b"<!--") {
            i = past(i + 4, b"-->");
        } else if rest.starts_with(b"<![CDATA[") {
            i = past(i + 9, b"]]>");
        } else if rest.starts_with(b"<!") {
            i = find(i + 2, b'>').saturating_add(1);
        } else if rest.starts_with(b"<?") {
            i = find(find(i + 2, b'?'), b'>').saturating_add(1);
        } else if rest.starts_with(b"</") {
            depth = depth.saturating_sub(1);
            i = find(i + 2, b'>').saturating_add(1);
        } else {
            // A start tag; its first character (whatever it is) begins the name.
            let mut state = Tag::Name;
            let mut j = i + 2;
            let mut opens = true;
            while j < n {
                let c = b[j];
                state = match (state, c) {
                    (Tag::Name | Tag::Between, b'>') => break,
                    (Tag::Name | Tag::Between, b'/') => Tag::Close,
                    (Tag::Name, c) if space(c) => Tag::Between,
                    (Tag::Name, _) => Tag::Name,
                    (Tag::Between, c) if space(c) => Tag::Between,
                    (Tag::Between, _) => Tag::Attribute { spaced: false },
                    (Tag::Attribute { .. }, b'=') => Tag::Delimiter,
                    (Tag::Attribute { .. }, c) if space(c) => Tag::Attribute { spaced: true },
                    (Tag::Attribute { spaced: false }, _) => Tag::Attribute { spaced: false },
                    (Tag::Delimiter, c) if space(c) => Tag::Delimiter,
                    (Tag::Delimiter, b'"' | b'\'') => Tag::Value(c),
                    (Tag::Value(q), c) if c == q => Tag::Between,
                    (Tag::Value(q), _) => Tag::Value(q),
                    (Tag::Close, b'>') => {
                        opens = false;
                        break;
                    }
                    // The reader stops here with an error: count the element, read on from
                    // this character.
                    (Tag::Attribute { spaced: true } | Tag::Delimiter | Tag::Close, _) => {
                        j -= 1;
                        break;
                    }
                };
                j += 1;
            }
            // A self-closing element is a level too, closed at once.
            if depth + 1 > limit {
                return true;
            }
            if opens {
                depth += 1;
            }
            i = j.saturating_add(1);
        }
        i = find(i, b'<');
    }
    false
}

/// Refuses two elements of one name among `names` (in file order; `element` is `link` or
/// `joint`), naming both by their position.
fn unique_names<'a>(
    file: &str,
    element: &'static str,
    names: impl Iterator<Item = &'a str>,
) -> Result<(), UrdfChainError> {
    let mut seen: HashMap<&str, usize> = HashMap::new();
    for (k, name) in names.enumerate() {
        if let Some(&first) = seen.get(name) {
            return Err(UrdfChainError::Duplicate {
                file: file.to_string(),
                element,
                name: shown(name),
                first: first + 1,
                second: k + 1,
            });
        }
        seen.insert(name, k);
    }
    Ok(())
}

/// Refuses an `<origin>` of `owner` (`joint "<name>"`, ...) with an entry that is not finite,
/// or an `xyz` entry beyond [`MAX_LENGTH`].
fn check_origin(
    file: &str,
    owner: impl Fn() -> String,
    origin: &urdf_rs::Pose,
) -> Result<(), UrdfChainError> {
    for (field, values) in [("xyz", *origin.xyz), ("rpy", *origin.rpy)] {
        for (index, &value) in values.iter().enumerate() {
            if !value.is_finite() {
                return Err(UrdfChainError::OriginNotFinite {
                    file: file.to_string(),
                    owner: owner(),
                    field,
                    index,
                    value,
                });
            }
            if field == "xyz" && value.abs() > MAX_LENGTH {
                return Err(UrdfChainError::TooLong {
                    file: file.to_string(),
                    owner: owner(),
                    index,
                    value,
                    limit: MAX_LENGTH,
                });
            }
        }
    }
    Ok(())
}

/// The URDF pose `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` ([`Frame::from_xyz_rpy`]).
fn pose(p: &urdf_rs::Pose) -> Frame {
    Frame::from_xyz_rpy(*p.xyz, *p.rpy)
}

/// Reads the URDF at `path` through the `inputs` reader (found as `origin` says) and builds the
/// chain `ends` selects ([`parse`]).
pub fn read(
    path: &Path,
    origin: inputs::Origin,
    ends: &ChainEnds,
) -> Result<Chain, UrdfChainError> {
    let text = inputs::read_text(path, inputs::Kind::Urdf, origin)?;
    parse(&path.display().to_string(), &text, ends)
}

/// The chain from `ends.base` to `ends.tip` of the URDF `text` (module documentation); `file`
/// names it in errors.
pub fn parse(file: &str, text: &str, ends: &ChainEnds) -> Result<Chain, UrdfChainError> {
    let bytes = text.len() as u64;
    if bytes > MAX_FILE_BYTES {
        return Err(UrdfChainError::TooLarge {
            file: file.to_string(),
            bytes,
            limit: MAX_FILE_BYTES,
        });
    }
    if nests_deeper_than(text, MAX_DEPTH) {
        return Err(UrdfChainError::TooDeep {
            file: file.to_string(),
            limit: MAX_DEPTH,
        });
    }
    let robot = urdf_rs::read_from_string(text).map_err(|_| UrdfChainError::Syntax {
        file: file.to_string(),
    })?;
    if robot.joints.len() > MAX_JOINTS {
        return Err(UrdfChainError::TooManyJoints {
            file: file.to_string(),
            joints: robot.joints.len(),
            limit: MAX_JOINTS,
        });
    }
    unique_names(file, "link", robot.links.iter().map(|l| l.name.as_str()))?;
    unique_names(file, "joint", robot.joints.iter().map(|j| j.name.as_str()))?;
    for j in &robot.joints {
        check_origin(file, || format!("joint {:?}", shown(&j.name)), &j.origin)?;
    }
    for l in &robot.links {
        check_origin(
            file,
            || format!("link {:?} <inertial>", shown(&l.name)),
            &l.inertial.origin,
        )?;
    }
    let links: HashMap<&str, &urdf_rs::Link> =
        robot.links.iter().map(|l| (l.name.as_str(), l)).collect();
    for (end, name) in [("base", ends.base), ("tip", ends.tip)] {
        if !links.contains_key(name) {
            return Err(UrdfChainError::UnknownLink {
                file: file.to_string(),
                end,
                name: shown(name),
                valid: listed(robot.links.iter().map(|l| l.name.as_str())),
            });
        }
    }
    // The joint whose child each link is, and the joints hung from each link.
    let mut parent_joint: HashMap<&str, usize> = HashMap::new();
    let mut child_joints: HashMap<&str, Vec<usize>> = HashMap::new();
    for (k, j) in robot.joints.iter().enumerate() {
        for link in [&j.parent.link, &j.child.link] {
            if !links.contains_key(link.as_str()) {
                return Err(UrdfChainError::UndeclaredLink {
                    file: file.to_string(),
                    joint: shown(&j.name),
                    link: shown(link),
                });
            }
        }
        if parent_joint.insert(j.child.link.as_str(), k).is_some() {
            return Err(UrdfChainError::TwoParents {
                file: file.to_string(),
                link: shown(&j.child.link),
            });
        }
        child_joints
            .entry(j.parent.link.as_str())
            .or_default()
            .push(k);
    }
    for start in parent_joint.keys() {
        let mut link = *start;
        for _ in 0..=robot.joints.len() {
            match parent_joint.get(link) {
                Some(&k) => link = robot.joints[k].parent.link.as_str(),
                None => break,
            }
        }
        if parent_joint.contains_key(link) {
            return Err(UrdfChainError::Cycle {
                file: file.to_string(),
                link: shown(link),
            });
        }
    }
    // The path, tip up to base (a tree of at most MAX_JOINTS joints: at most that many steps).
    let mut path = Vec::new();
    let mut link = ends.tip;
    let mut ancestors = Vec::new();
    while link != ends.base {
        match parent_joint.get(link) {
            Some(&k) => {
                path.push(k);
                link = robot.joints[k].parent.link.as_str();
                ancestors.push(link);
            }
            _ => {
                return Err(UrdfChainError::NotBelow {
                    file: file.to_string(),
                    base: shown(ends.base),
                    tip: shown(ends.tip),
                    ancestors: listed(ancestors.into_iter()),
                })
            }
        }
    }
    path.reverse();
    let chain_error = |source| UrdfChainError::Chain {
        file: file.to_string(),
        base: shown(ends.base),
        tip: shown(ends.tip),
        source: Box::new(source),
    };
    let mut joints = Vec::new();
    let mut pending = Frame::identity();
    for &k in &path {
        let j = &robot.joints[k];
        let unsupported = |kind| UrdfChainError::Unsupported {
            file: file.to_string(),
            joint: shown(&j.name),
            kind,
        };
        let kind = match j.joint_type {
            urdf_rs::JointType::Fixed => {
                pending = pending.compose(&pose(&j.origin));
                continue;
            }
            urdf_rs::JointType::Revolute => JointKind::Revolute,
            urdf_rs::JointType::Continuous => JointKind::Continuous,
            urdf_rs::JointType::Prismatic => JointKind::Prismatic,
            urdf_rs::JointType::Floating => return Err(unsupported("floating")),
            urdf_rs::JointType::Planar => return Err(unsupported("planar")),
            urdf_rs::JointType::Spherical => return Err(unsupported("spherical")),
        };
        if j.mimic.is_some() {
            return Err(unsupported("a mimic joint"));
        }
        let unlimited_if_zero = |x: f64| if x == 0.0 { f64::INFINITY } else { x };
        let (position_min, position_max) = match kind {
            JointKind::Continuous => (f64::NEG_INFINITY, f64::INFINITY),
            _ => (j.limit.lower, j.limit.upper),
        };
        let velocity_max = unlimited_if_zero(j.limit.velocity);
        joints.push(ChainJoint {
            name: j.name.clone(),
            origin: pending.compose(&pose(&j.origin)),
            kind,
            axis: Vector3::from(*j.axis.xyz),
            limits: JointRange {
                position_min,
                position_max,
                velocity_min: -velocity_max,
                velocity_max,
                acceleration_max: f64::INFINITY,
                effort_max: unlimited_if_zero(j.limit.effort),
            },
            body: Some(rigid_body(&robot, &links, &child_joints, &j.child.link)),
        });
        pending = Frame::identity();
    }
    let tool = pending.compose(&Frame {
        rot: Matrix3::identity(),
        origin: ends.tool,
    });
    Chain::new(joints, tool).map_err(chain_error)
}

/// The merged inertial of link `root` and every link attached below it by fixed joints only,
/// in `root`'s frame (module documentation, "Inertials").
fn rigid_body(
    robot: &urdf_rs::Robot,
    links: &HashMap<&str, &urdf_rs::Link>,
    child_joints: &HashMap<&str, Vec<usize>>,
    root: &str,
) -> RigidBody {
    // (link, its frame in root's frame), walked depth first; a tree (no cycle: checked by
    // `parse`), so each link once.
    let mut stack = vec![(root, Frame::identity())];
    let mut parts = Vec::new();
    while let Some((name, frame)) = stack.pop() {
        if let Some(link) = links.get(name) {
            // Every link a joint names is declared (checked by `parse`).
            let inertial = &link.inertial;
            let at = frame.compose(&pose(&inertial.origin));
            let i = &inertial.inertia;
            let tensor = Matrix3::new(
                i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz,
            );
            parts.push((
                inertial.mass.value,
                at.origin,
                at.rot * tensor * at.rot.transpose(),
            ));
        }
        for &k in child_joints.get(name).map_or(&[][..], Vec::as_slice) {
            let j = &robot.joints[k];
            if j.joint_type == urdf_rs::JointType::Fixed {
                stack.push((j.child.link.as_str(), frame.compose(&pose(&j.origin))));
            }
        }
    }
    let mass: f64 = parts.iter().map(|p| p.0).sum();
    let com = if mass > 0.0 {
        parts.iter().map(|p| p.1 * p.0).sum::<Vector3<f64>>() / mass
    } else {
        Vector3::zeros()
    };
    let inertia = parts
        .iter()
        .map(|(m, c, i)| {
            let d = c - com;
            i + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * *m
        })
        .sum();
    RigidBody { mass, com, inertia }
}
