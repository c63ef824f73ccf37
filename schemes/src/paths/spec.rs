//! Building a path from its serde-readable description.
//!
//! | name | built as | default scale (m) | provenance of the scale | T in paths.md (s) |
//! |---|---|---|---|---|
//! | `four-leaf-clover` | [`CurveShape::FourLeafClover`], a | 0.15 | assumed | 5 |
//! | `five-point-star` | [`CurveShape::FivePointStar`], a | 0.08 | group's code | 5 |
//! | `star-lines` | [`GlobalPolyline::pentagram`], R | 0.08 | assumed | 5 |
//! | `ping` | [`PING`] strokes, box size s | 0.15 | assumed | 15 |
//! | `dai` | [`DAI`] strokes, box size s | 0.15 | assumed | 15 |
//! | `butterfly` | [`CurveShape::Butterfly`] (closing correction), a | 0.035 | group's code | 8 |
//! | `cardioid` | [`CurveShape::Cardioid`], a | 0.05 | assumed | 8 |
//! | `triangle` | [`StrokePath::triangle`], side | 0.1 | paper | 9 |
//! | `circle` | [`CurveShape::Circle`], r | 0.05 | paper | 9 |
//!
//! `scale`, when given, replaces the default size (a, R, s, side or r).

use super::characters::{DAI, PING};
use super::curve::{ClosedCurve, CurveShape};
use super::error::PathError;
use super::polyline_global::GlobalPolyline;
use super::reversed::Reversed;
use super::stroke::StrokePath;
use super::Path;
use nalgebra::Vector3;

/// A path as experiment files describe it.
#[derive(Clone, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct PathSpec {
    /// One of [`PATH_NAMES`].
    pub name: String,
    /// Task duration T in seconds.
    pub duration: f64,
    /// Size override (a, R, s, side or r in metres); `None` uses [`default_scale`].
    #[serde(default)]
    pub scale: Option<f64>,
    /// Travel the path backwards (same curve, opposite orientation; see [`Reversed`]).
    #[serde(default)]
    pub reverse: bool,
}

/// Every path name [`build_path`] accepts.
pub const PATH_NAMES: &[&str] = &[
    "four-leaf-clover",
    "five-point-star",
    "star-lines",
    "ping",
    "dai",
    "butterfly",
    "cardioid",
    "triangle",
    "circle",
];

/// (name, default scale, provenance of the scale, duration in paths.md), in [`PATH_NAMES`] order.
const TABLE: [(&str, f64, &str, f64); 9] = [
    ("four-leaf-clover", 0.15, "assumed", 5.0),
    ("five-point-star", 0.08, "group's code", 5.0),
    ("star-lines", 0.08, "assumed", 5.0),
    ("ping", 0.15, "assumed", 15.0),
    ("dai", 0.15, "assumed", 15.0),
    ("butterfly", 0.035, "group's code", 8.0),
    ("cardioid", 0.05, "assumed", 8.0),
    ("triangle", 0.1, "paper", 9.0),
    ("circle", 0.05, "paper", 9.0),
];

fn entry(name: &str) -> Option<&'static (&'static str, f64, &'static str, f64)> {
    TABLE.iter().find(|e| e.0 == name)
}

/// The size paths.md gives the path (a, R, s, side or r in metres), `None` for an unknown name.
pub fn default_scale(name: &str) -> Option<f64> {
    entry(name).map(|e| e.1)
}

/// Where the default size comes from: `"assumed"` (a free parameter of the reproduction, to be
/// swept), `"group's code"` or `"paper"`; `None` for an unknown name.
pub fn scale_provenance(name: &str) -> Option<&'static str> {
    entry(name).map(|e| e.2)
}

/// The duration T paths.md lists for the path, `None` for an unknown name.
pub fn default_duration(name: &str) -> Option<f64> {
    entry(name).map(|e| e.3)
}

/// Builds the path `spec` describes, starting (and ending) at `start`.
///
/// Errors name the offending field: unknown `name`, non-positive or non-finite `duration` or
/// `scale`, or a non-finite `start`.
pub fn build_path(spec: &PathSpec, start: Vector3<f64>) -> Result<Box<dyn Path>, PathError> {
    let default =
        default_scale(&spec.name).ok_or_else(|| PathError::UnknownName(spec.name.clone()))?;
    let duration = spec.duration;
    if !(duration.is_finite() && duration > 0.0) {
        return Err(PathError::NonPositiveDuration(duration));
    }
    let size = spec.scale.unwrap_or(default);
    if !(size.is_finite() && size > 0.0) {
        return Err(PathError::NonPositiveScale(size));
    }
    if !start.iter().all(|x| x.is_finite()) {
        return Err(PathError::NonFinitePoint);
    }
    let curve =
        |shape| Ok(Box::new(ClosedCurve::new(shape, size, start, duration)) as Box<dyn Path>);
    let forward: Result<Box<dyn Path>, PathError> = match spec.name.as_str() {
        "four-leaf-clover" => curve(CurveShape::FourLeafClover),
        "five-point-star" => curve(CurveShape::FivePointStar),
        "butterfly" => curve(CurveShape::Butterfly),
        "cardioid" => curve(CurveShape::Cardioid),
        "circle" => curve(CurveShape::Circle),
        "star-lines" => Ok(Box::new(GlobalPolyline::pentagram(start, size, duration)?)),
        "ping" => Ok(Box::new(PING.path(start, size, duration)?)),
        "dai" => Ok(Box::new(DAI.path(start, size, duration)?)),
        "triangle" => Ok(Box::new(StrokePath::triangle(start, size, duration)?)),
        other => unreachable!("{other} is in TABLE but has no constructor"),
    };
    let forward = forward?;
    Ok(if spec.reverse {
        Box::new(Reversed::new(forward))
    } else {
        forward
    })
}
