//! Errors from checking or building a path.

use std::fmt;

/// Why a path could not be built; each variant names the offending field.
#[derive(Clone, Debug, PartialEq)]
pub enum PathError {
    /// `name` is not one of [`super::PATH_NAMES`].
    UnknownName(String),
    /// `duration` is outside [[`super::MIN_DURATION`], [`super::MAX_DURATION`]] s (NaN
    /// included; [`super::PathSpec::validate`]).
    DurationOutOfRange(f64),
    /// The size (`scale`, or the name's default) is outside (0, [`crate::MAX_OFFSET`]] m (NaN
    /// included; [`super::PathSpec::validate`]).
    ScaleOutOfRange(f64),
    /// A path piece's own duration is not a positive finite number (the stroke and polyline
    /// constructors' check; a path described in a file meets [`PathError::DurationOutOfRange`]
    /// first).
    NonPositiveDuration(f64),
    /// The start point (or a polyline point) has a non-finite coordinate.
    NonFinitePoint,
    /// A polyline has no segment of positive length (all its points coincide).
    DegeneratePolyline,
    /// A pose angle (`rotation`, `tilt_x` or `tilt_y`, named by `field`) is not finite.
    NonFinitePose {
        /// The angle's field: `rotation`, `tilt_x` or `tilt_y`.
        field: &'static str,
        /// The value given (rad).
        value: f64,
    },
    /// `phase` is not in [0, 1).
    PhaseOutOfRange(f64),
    /// A non-zero `phase` was given for a path (named) that has no cycle to shift: the stroke
    /// paths (ping, dai, triangle) and the unclosed butterfly-as-printed.
    PhaseNotSupported(String),
}

impl fmt::Display for PathError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnknownName(name) => write!(
                f,
                "path `name`: unknown path {}; valid names: {}",
                settings::shown(name),
                super::PATH_NAMES.join(", ")
            ),
            Self::DurationOutOfRange(d) => write!(
                f,
                "path `duration` must be within [{}, {}] s, got {}",
                super::MIN_DURATION,
                super::MAX_DURATION,
                shown(*d)
            ),
            Self::ScaleOutOfRange(s) => write!(
                f,
                "path `scale` (the figure's size) must be within (0, {}] m, got {}",
                crate::MAX_OFFSET,
                shown(*s)
            ),
            Self::NonPositiveDuration(d) => {
                write!(
                    f,
                    "path `duration` must be positive and finite, got {}",
                    shown(*d)
                )
            }
            Self::NonFinitePoint => write!(
                f,
                "path start point (or a polyline point) has a non-finite coordinate"
            ),
            Self::DegeneratePolyline => {
                write!(f, "polyline path has no segment of positive length")
            }
            Self::NonFinitePose { field, value } => {
                write!(f, "path `{field}` must be finite (radians), got {value}")
            }
            Self::PhaseOutOfRange(p) => {
                write!(
                    f,
                    "path `phase` must be in [0, 1) (a fraction of the cycle), got {p}"
                )
            }
            Self::PhaseNotSupported(name) => write!(
                f,
                "path `phase` must be 0 for {name}: only closed curves and star-lines can start \
                 elsewhere on their cycle"
            ),
        }
    }
}

impl std::error::Error for PathError {}

/// A number as the errors show it: as Rust writes it where that is short (0.001, -1, 100000),
/// with an exponent where it would run to many digits (1e-300, not three hundred of them).
fn shown(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-4..1e7).contains(&a) {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}
