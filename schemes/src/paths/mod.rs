//! Desired end-effector paths r*(t), rdot*(t), rddot*(t) (see `shared/spec/paths.md`).
//!
//! Common form: r*(t) = r_start + dr(phi(t)) with the group's time law
//! phi(t) = 2 pi sin^2(pi t / (2T)), so phi runs 0 -> 2 pi with zero speed at both ends.
//! Stroke paths (characters, triangle) are polylines with a rest-to-rest sin^2 law per segment.

use nalgebra::Vector3;

/// Desired position, velocity and acceleration of the task point at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathPoint {
    pub r: Vector3<f64>,
    pub rdot: Vector3<f64>,
    pub rddot: Vector3<f64>,
}

/// A desired path, analytic in t on [0, T].
pub trait Path: Send + Sync {
    /// Task duration T.
    fn duration(&self) -> f64;
    /// r*(t), rdot*(t), rddot*(t).
    fn at(&self, t: f64) -> PathPoint;
}
