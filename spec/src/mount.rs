//! A robot's mount as data: a tool offset and a base transform ([`MountSpec`], as an
//! experiment's `tool` and `base` give them) and why one is invalid or does not fit its robot
//! ([`MountError`]). Crate `robots` builds the mount (`robots::Mount::new`: the base
//! `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` with `rpy = [roll, pitch, yaw]`, the URDF
//! convention) and returns these errors.

/// The largest length an experiment file may give, per coordinate (m): a tool offset and a
/// base translation (crate `robots` bounds the mount with it when it is built), and a path's
/// size (`scale`, [`crate::PathSpec::validate`]). An arm's reach is metres, so a larger value
/// is a typing error (millimetres written as metres), not a mount or a figure.
pub const MAX_OFFSET: f64 = 10.0;

/// A tool offset and a base transform (module docs), each entry as given: the robot's mount
/// is built, and its entries bounded, when a run is built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MountSpec {
    /// The tool offset (m, in the robot model's tool frame).
    pub tool: [f64; 3],
    /// The base translation (m).
    pub xyz: [f64; 3],
    /// The base's roll, pitch and yaw (rad).
    pub rpy: [f64; 3],
}

/// Why a mount is invalid, or does not fit the robot; the field is the experiment file's.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MountError {
    /// An entry is NaN or infinite.
    #[error("`{field}[{index}]` is not a finite number")]
    NotFinite {
        /// `tool`, `base.xyz` or `base.rpy`.
        field: &'static str,
        /// The entry (from 0).
        index: usize,
    },
    /// An entry is outside its range.
    #[error("`{field}[{index}]` = {value}: must be within [-{max}, {max}] {unit}")]
    OutOfRange {
        /// `tool`, `base.xyz` or `base.rpy`.
        field: &'static str,
        /// The entry (from 0).
        index: usize,
        /// The value given.
        value: f64,
        /// The bound ([`MAX_OFFSET`] or `robots::MAX_ANGLE`).
        max: f64,
        /// `m` or `rad`.
        unit: &'static str,
    },
    /// A tool offset on a robot whose tool frame is not modelled.
    #[error(
        "`tool`: robot {} has no tool frame to offset its task point in (no \
         orientation: the DH robots and URDF robots have one, the Katana's closed form and the \
         n-link family do not)",
        settings::shown(robot)
    )]
    NoOrientation {
        /// The robot's name.
        robot: String,
    },
    /// A base that turns the vertical under a robot whose dynamics a scheme needs.
    #[error(
        "`base.rpy`: a roll or pitch turns gravity in robot {}'s frame, whose \
         dynamics take it along their base's -z; with a scheme that needs dynamics only a \
         rotation about z (yaw) is allowed",
        settings::shown(robot)
    )]
    TiltedGravity {
        /// The robot's name.
        robot: String,
    },
}

impl MountError {
    /// The experiment-file field at fault: `tool` or `base`.
    pub fn field(&self) -> &'static str {
        match self {
            MountError::NotFinite { field, .. } | MountError::OutOfRange { field, .. } => {
                if *field == "tool" {
                    "tool"
                } else {
                    "base"
                }
            }
            MountError::NoOrientation { .. } => "tool",
            MountError::TiltedGravity { .. } => "base",
        }
    }
}
