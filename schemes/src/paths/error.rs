//! Errors from building a path.

use std::fmt;

/// Why a path could not be built; each variant names the offending field.
#[derive(Clone, Debug, PartialEq)]
pub enum PathError {
    /// `name` is not one of [`super::PATH_NAMES`].
    UnknownName(String),
    /// `duration` is not a positive finite number.
    NonPositiveDuration(f64),
    /// `scale` is not a positive finite number.
    NonPositiveScale(f64),
    /// The start point (or a polyline point) has a non-finite coordinate.
    NonFinitePoint,
    /// A polyline has no segment of positive length (all its points coincide).
    DegeneratePolyline,
}

impl fmt::Display for PathError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnknownName(name) => write!(
                f,
                "path `name`: unknown path {name:?}; valid names: {}",
                super::PATH_NAMES.join(", ")
            ),
            Self::NonPositiveDuration(d) => {
                write!(f, "path `duration` must be positive and finite, got {d}")
            }
            Self::NonPositiveScale(s) => {
                write!(f, "path `scale` must be positive and finite, got {s}")
            }
            Self::NonFinitePoint => write!(
                f,
                "path start point (or a polyline point) has a non-finite coordinate"
            ),
            Self::DegeneratePolyline => {
                write!(f, "polyline path has no segment of positive length")
            }
        }
    }
}

impl std::error::Error for PathError {}
