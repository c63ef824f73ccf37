//! Building a path from its serde-readable description.
//!
//! | name | built as | default scale (m) | provenance of the scale | T in docs/paths.md (s) |
//! |---|---|---|---|---|
//! | `four-leaf-clover` | [`CurveShape::FourLeafClover`], a | 0.15 | assumed | 5 |
//! | `five-point-star` | [`CurveShape::FivePointStar`], a | 0.08 | group's code | 5 |
//! | `star-lines` | [`GlobalPolyline::pentagram`], R | 0.08 | assumed | 5 |
//! | `ping` | [`PING`] strokes, box size s | 0.15 | assumed | 15 |
//! | `dai` | [`DAI`] strokes, box size s | 0.15 | assumed | 15 |
//! | `butterfly` | [`CurveShape::Butterfly`] (closing correction), a | 0.035 | group's code | 8 |
//! | `butterfly-as-printed` | [`CurveShape::ButterflyAsPrinted`] (ends a/32 short in y), a | 0.035 | group's code | 8 |
//! | `cardioid` | [`CurveShape::Cardioid`], a | 0.05 | assumed | 8 |
//! | `triangle` | [`StrokePath::triangle`], side | 0.1 | paper | 9 |
//! | `circle` | [`CurveShape::Circle`], r | 0.05 | paper | 9 |
//!
//! `scale`, when given, replaces the default size (a, R, s, side or r).
//!
//! **Pose** (the papers do not state where or how the figure is drawn; these make it a sweepable
//! parameter). With every field at its default the figure lies in the base x-y plane through
//! the start point, starts where its definition starts, and the path is built exactly as
//! without these fields.
//! - `rotation`, `tilt_x`, `tilt_y` (rad): offsets from the start point are mapped by
//!   R = Ry(tilt_y) Rx(tilt_x) Rz(rotation), so the drawing plane has normal R e_z (see
//!   [`super::pose`]); applies to every path.
//! - `phase` (fraction of the cycle in [0, 1)): the tip starts a fraction `phase` further along
//!   the closed figure, dr_p(phi) = dr(phi + 2 pi phase) - dr(2 pi phase) for the closed curves
//!   ([`ClosedCurve::with_phase`]), the arc-length shift of the tour for `star-lines`
//!   ([`super::polyline_global::shift_closed_loop`]); the start (and end) point is unchanged,
//!   the curve is placed differently around it. Not defined (an error) for the stroke paths
//!   and `butterfly-as-printed`.
//!
//! `reverse` is applied last (it commutes with the pose).

use super::characters::{DAI, PING};
use super::curve::{ClosedCurve, CurveShape};
use super::error::PathError;
use super::polyline_global::GlobalPolyline;
use super::pose::Posed;
use super::reversed::Reversed;
use super::stroke::StrokePath;
use super::Path;
use nalgebra::Vector3;

/// A path as experiment files describe it.
#[derive(Clone, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct PathSpec {
    /// One of [`super::PATH_NAMES`].
    pub name: String,
    /// Task duration T in seconds.
    pub duration: f64,
    /// Size override (a, R, s, side or r in metres); `None` uses [`default_scale`].
    #[serde(default)]
    pub scale: Option<f64>,
    /// Travel the path backwards (same curve, opposite orientation; see [`Reversed`]).
    #[serde(default)]
    pub reverse: bool,
    /// In-plane rotation (rad) of the figure about the plane normal (e_z before tilting).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub rotation: f64,
    /// Tilt (rad) of the drawing plane about the base x axis (applied after `rotation`).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub tilt_x: f64,
    /// Tilt (rad) of the drawing plane about the base y axis (applied last):
    /// R = Ry(tilt_y) Rx(tilt_x) Rz(rotation), plane normal R e_z; the default plane is the
    /// base x-y plane.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub tilt_y: f64,
    /// Where on a closed figure the tip starts, as a fraction of the cycle in [0, 1).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub phase: f64,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl PathSpec {
    /// The path `name` run in `duration` seconds at its default size, pose and direction.
    pub fn new(name: impl Into<String>, duration: f64) -> Self {
        Self {
            name: name.into(),
            duration,
            scale: None,
            reverse: false,
            rotation: 0.0,
            tilt_x: 0.0,
            tilt_y: 0.0,
            phase: 0.0,
        }
    }

    /// Whether `rotation`, `tilt_x` and `tilt_y` are all zero (no pose wrapper is built).
    pub fn is_unrotated(&self) -> bool {
        self.rotation == 0.0 && self.tilt_x == 0.0 && self.tilt_y == 0.0
    }
}

/// (name, default scale, provenance of the scale, duration in docs/paths.md), in
/// [`super::PATH_NAMES`] order.
const TABLE: [(&str, f64, &str, f64); 10] = [
    ("four-leaf-clover", 0.15, "assumed", 5.0),
    ("five-point-star", 0.08, "group's code", 5.0),
    ("star-lines", 0.08, "assumed", 5.0),
    ("ping", 0.15, "assumed", 15.0),
    ("dai", 0.15, "assumed", 15.0),
    ("butterfly", 0.035, "group's code", 8.0),
    ("butterfly-as-printed", 0.035, "group's code", 8.0),
    ("cardioid", 0.05, "assumed", 8.0),
    ("triangle", 0.1, "paper", 9.0),
    ("circle", 0.05, "paper", 9.0),
];

fn entry(name: &str) -> Option<&'static (&'static str, f64, &'static str, f64)> {
    TABLE.iter().find(|e| e.0 == name)
}

/// The size docs/paths.md gives the path (a, R, s, side or r in metres), `None` for an unknown name.
pub fn default_scale(name: &str) -> Option<f64> {
    entry(name).map(|e| e.1)
}

/// Where the default size comes from: `"assumed"` (a free parameter of the reproduction, to be
/// swept), `"group's code"` or `"paper"`; `None` for an unknown name.
pub fn scale_provenance(name: &str) -> Option<&'static str> {
    entry(name).map(|e| e.2)
}

/// The duration T docs/paths.md lists for the path, `None` for an unknown name.
pub fn default_duration(name: &str) -> Option<f64> {
    entry(name).map(|e| e.3)
}

/// Whether a non-zero `phase` is accepted for the path `name`: the closed figures (not the
/// stroke paths ping, dai, triangle, nor the butterfly as printed, which does not close).
pub fn phase_supported(name: &str) -> bool {
    !matches!(name, "ping" | "dai" | "triangle" | "butterfly-as-printed")
}

/// Builds the path `spec` describes, starting (and ending) at `start`.
///
/// Errors name the offending field: unknown `name`, non-positive or non-finite `duration` or
/// `scale`, a non-finite `rotation`, `tilt_x` or `tilt_y`, a `phase` outside [0, 1) or non-zero
/// for a path without a cycle to shift, or a non-finite `start`.
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
    for (field, value) in [
        ("rotation", spec.rotation),
        ("tilt_x", spec.tilt_x),
        ("tilt_y", spec.tilt_y),
    ] {
        if !value.is_finite() {
            return Err(PathError::NonFinitePose { field, value });
        }
    }
    let phase = spec.phase;
    if !(0.0..1.0).contains(&phase) {
        return Err(PathError::PhaseOutOfRange(phase));
    }
    if !start.iter().all(|x| x.is_finite()) {
        return Err(PathError::NonFinitePoint);
    }
    if phase != 0.0 && !phase_supported(&spec.name) {
        return Err(PathError::PhaseNotSupported(spec.name.clone()));
    }
    let curve = |shape| -> Result<Box<dyn Path>, PathError> {
        let c = ClosedCurve::new(shape, size, start, duration);
        Ok(Box::new(if phase == 0.0 {
            c
        } else {
            c.with_phase(phase)?
        }))
    };
    let forward: Result<Box<dyn Path>, PathError> = match spec.name.as_str() {
        "four-leaf-clover" => curve(CurveShape::FourLeafClover),
        "five-point-star" => curve(CurveShape::FivePointStar),
        "butterfly" => curve(CurveShape::Butterfly),
        "butterfly-as-printed" => curve(CurveShape::ButterflyAsPrinted),
        "cardioid" => curve(CurveShape::Cardioid),
        "circle" => curve(CurveShape::Circle),
        "star-lines" if phase == 0.0 => {
            Ok(Box::new(GlobalPolyline::pentagram(start, size, duration)?))
        }
        "star-lines" => Ok(Box::new(GlobalPolyline::pentagram_with_phase(
            start, size, duration, phase,
        )?)),
        "ping" => Ok(Box::new(PING.path(start, size, duration)?)),
        "dai" => Ok(Box::new(DAI.path(start, size, duration)?)),
        "triangle" => Ok(Box::new(StrokePath::triangle(start, size, duration)?)),
        other => unreachable!("{other} is in TABLE but has no constructor"),
    };
    let mut forward = forward?;
    if !spec.is_unrotated() {
        forward = Box::new(Posed::new(
            forward,
            start,
            spec.rotation,
            spec.tilt_x,
            spec.tilt_y,
        ));
    }
    Ok(if spec.reverse {
        Box::new(Reversed::new(forward))
    } else {
        forward
    })
}
