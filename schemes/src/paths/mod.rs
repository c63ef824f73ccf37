//! Desired end-effector paths r*(t), rdot*(t), rddot*(t) (see `docs/paths.md`).
//!
//! # Mathematics
//!
//! **Time law** ([`RestToRest`]). Every path is driven by the rest-to-rest fraction
//! s(t) = sin^2(pi t / (2T)), sdot = (pi / 2T) sin(pi t / T), sddot = (pi^2 / 2T^2) cos(pi t / T),
//! which runs 0 -> 1 with zero speed at t = 0 and t = T. The group's time law is phi = 2 pi s:
//! phi(t) = 2 pi sin^2(pi t / (2T)), phidot = (pi^2 / T) sin(pi t / T), phiddot = (pi^3 / T^2) cos(pi t / T).
//!
//! **Closed curves** ([`ClosedCurve`]). r*(t) = r_start + dr(phi(t)) with dr(0) = 0 = dr(2 pi) and dr, dr', dr''
//! analytic in phi; the chain rule gives rdot = dr'(phi) phidot and rddot = dr''(phi) phidot^2 + dr'(phi) phiddot.
//!
//! **Stroke paths** ([`StrokePath`], [`Character`]). Polylines P0 -> P1 -> ... -> P0; segment k is the
//! rest-to-rest move r = P_k + (P_{k+1} - P_k) s_k(t - t_k) with s_k the fraction above over
//! Delta_k = T L_k / sum(L). Every segment has the same peak speed (pi/2) sum(L) / T and the speed is zero
//! at every corner; the acceleration jumps there.
//!
//! **Globally timed polylines** ([`GlobalPolyline`], the `star-lines` pentagram). The polyline is run
//! with one time law over its whole arc length: arc-length fraction s(t) = phi(t) / 2 pi, so corners are
//! passed at speed (the velocity changes direction there; the acceleration has a delta).
//!
//! **Construction** ([`build_path`]). `spec::PathSpec` names a path, its duration and optionally its size;
//! [`build_path`] turns it into a boxed [`Path`]. Evaluation never allocates: segment tables are
//! built once at construction. Outside [0, T] every path rests at its end point (zero velocity and
//! acceleration); at t = 0 and t = T exactly the analytic values are returned (the acceleration
//! there is generally non-zero because sddot(0) = pi^2 / 2T^2).
//!
//! **Pose** ([`Posed`]). By default planar paths lie in the base frame's x-y plane through
//! r_start (z stays r_start.z). A path's specification may rotate the figure in its plane and tilt the
//! plane: r = r_start + R (r_inner - r_start), rdot = R rdot_inner, rddot = R rddot_inner with
//! the constant R = Ry(tilt_y) Rx(tilt_x) Rz(rotation), plane normal R e_z. It may also start a
//! closed figure elsewhere on its cycle (`phase` p): dr_p(phi) = dr(phi + 2 pi p) - dr(2 pi p)
//! for the closed curves, an arc-length shift of the tour for `star-lines`; the start point is
//! unchanged. Default poses build the path exactly as without them.

mod build;
mod characters;
mod curve;
mod cyclic;
mod polyline_global;
mod pose;
mod reversed;
mod stroke;
mod time_law;

pub use build::build_path;
pub use characters::{Character, DAI, PING};
pub use curve::{ClosedCurve, CurveShape};
pub use cyclic::Cyclic;
pub use polyline_global::{shift_closed_loop, GlobalPolyline};
pub use pose::{pose_rotation, Posed};
pub use reversed::Reversed;
pub use stroke::{StrokePath, StrokeSegment};
pub use time_law::{Fraction, RestToRest};

use nalgebra::Vector3;

/// Desired position, velocity and acceleration of the task point at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathPoint {
    /// Desired position r*(t) of the task point (m).
    pub r: Vector3<f64>,
    /// Desired velocity rdot*(t) (m/s).
    pub rdot: Vector3<f64>,
    /// Desired acceleration rddot*(t) (m/s^2).
    pub rddot: Vector3<f64>,
}

/// A desired path, analytic in t on [0, T].
pub trait Path: Send + Sync {
    /// Task duration T.
    fn duration(&self) -> f64;
    /// r*(t), rdot*(t), rddot*(t): a function of t alone (the tracking term asks once per
    /// instant and reuses the answer).
    fn at(&self, t: f64) -> PathPoint;
    /// Interior instants in (0, T), ascending, where rdot or rddot is discontinuous (corners of
    /// polylines). Integrators should stop there; the smooth curves have none.
    fn breakpoints(&self) -> &[f64] {
        &[]
    }
}
