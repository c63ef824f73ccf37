//! Building a path from its description ([`spec::PathSpec`], whose module lists the
//! names, each figure's size and its pose fields).
//!
//! | name | built as |
//! |---|---|
//! | `four-leaf-clover` | [`CurveShape::FourLeafClover`], a |
//! | `five-point-star` | [`CurveShape::FivePointStar`], a |
//! | `star-lines` | [`GlobalPolyline::pentagram`], R |
//! | `ping` | [`PING`] strokes, box size s |
//! | `dai` | [`DAI`] strokes, box size s |
//! | `butterfly` | [`CurveShape::Butterfly`] (closing correction), a |
//! | `butterfly-as-printed` | [`CurveShape::ButterflyAsPrinted`] (ends a/32 short in y), a |
//! | `cardioid` | [`CurveShape::Cardioid`], a |
//! | `triangle` | [`StrokePath::triangle`], side |
//! | `circle` | [`CurveShape::Circle`], r |
//!
//! The pose: offsets from the start point are mapped by R = Ry(tilt_y) Rx(tilt_x) Rz(rotation)
//! ([`super::pose`]); a `phase` p starts a closed curve a fraction p further along its cycle
//! ([`ClosedCurve::with_phase`]) and `star-lines` an arc-length fraction further
//! ([`super::polyline_global::shift_closed_loop`]); `reverse` ([`Reversed`]) is applied last
//! (it commutes with the pose).

use super::characters::{DAI, PING};
use super::curve::{ClosedCurve, CurveShape};
use super::polyline_global::GlobalPolyline;
use super::pose::Posed;
use super::reversed::Reversed;
use super::stroke::StrokePath;
use super::Path;
use nalgebra::Vector3;
use spec::{PathError, PathSpec};

/// Builds the path `spec` describes, starting (and ending) at `start`.
///
/// Errors name the offending field: those of [`PathSpec::validate`], or a non-finite `start`.
pub fn build_path(spec: &PathSpec, start: Vector3<f64>) -> Result<Box<dyn Path>, PathError> {
    spec.validate()?;
    if !start.iter().all(|x| x.is_finite()) {
        return Err(PathError::NonFinitePoint);
    }
    let (duration, size, phase) = (spec.duration, spec.size(), spec.phase);
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
        other => unreachable!("{other} passed the name check but has no constructor"),
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
