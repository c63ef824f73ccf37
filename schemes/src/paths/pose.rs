//! A path's pose: the drawing plane's orientation about the start point.
//!
//! Every path is defined by an offset dr(t) = r_inner(t) - r_start in the base x-y plane. The
//! pose maps it by one rotation
//!
//! ```text
//! R = Ry(tilt_y) Rx(tilt_x) Rz(rotation)
//! r(t)     = r_start + R (r_inner(t) - r_start)
//! rdot(t)  = R rdot_inner(t)
//! rddot(t) = R rddot_inner(t)
//! ```
//!
//! so `rotation` turns the figure in its own plane (about the normal e_z before tilting), then
//! `tilt_x` and `tilt_y` tip the plane about the base x and y axes. The drawing plane passes
//! through r_start with normal n = R e_z; with every angle 0 it is the base x-y plane and
//! [`super::build_path`] does not wrap the path at all (the default path is computed exactly as
//! without a pose). R is orthogonal, so distances from the start point, speeds and the shape
//! are preserved; R is constant, so the derivatives carry over unchanged, and the start and end
//! points (r_inner = r_start) and the rests at both ends stay where they were.

use super::{Path, PathPoint};
use nalgebra::{Matrix3, Rotation3, Vector3};

/// R = Ry(tilt_y) Rx(tilt_x) Rz(rotation) (angles in radians).
pub fn pose_rotation(rotation: f64, tilt_x: f64, tilt_y: f64) -> Matrix3<f64> {
    let rz = Rotation3::from_axis_angle(&Vector3::z_axis(), rotation);
    let rx = Rotation3::from_axis_angle(&Vector3::x_axis(), tilt_x);
    let ry = Rotation3::from_axis_angle(&Vector3::y_axis(), tilt_y);
    (ry * rx * rz).into_inner()
}

/// `inner` rotated about `start` by a fixed rotation R (precomputed at construction).
pub struct Posed {
    inner: Box<dyn Path>,
    start: Vector3<f64>,
    rotation: Matrix3<f64>,
}

impl Posed {
    /// `inner` (which starts at `start`) with its offsets from `start` mapped by
    /// R = [`pose_rotation`]`(rotation, tilt_x, tilt_y)`.
    pub fn new(
        inner: Box<dyn Path>,
        start: Vector3<f64>,
        rotation: f64,
        tilt_x: f64,
        tilt_y: f64,
    ) -> Self {
        Self {
            inner,
            start,
            rotation: pose_rotation(rotation, tilt_x, tilt_y),
        }
    }

    /// The rotation R.
    pub fn rotation(&self) -> &Matrix3<f64> {
        &self.rotation
    }

    /// The drawing plane's unit normal R e_z.
    pub fn normal(&self) -> Vector3<f64> {
        self.rotation.column(2).into_owned()
    }
}

impl Path for Posed {
    fn duration(&self) -> f64 {
        self.inner.duration()
    }

    fn at(&self, t: f64) -> PathPoint {
        let p = self.inner.at(t);
        PathPoint {
            r: self.start + self.rotation * (p.r - self.start),
            rdot: self.rotation * p.rdot,
            rddot: self.rotation * p.rddot,
        }
    }

    fn breakpoints(&self) -> &[f64] {
        self.inner.breakpoints()
    }
}
