//! A robot with an experiment's own tool offset and base transform ([`Mounted`]): the same arm
//! holding a longer pen, or bolted to the table at another place and angle, without a new
//! robot file. The mount is validated when it is made ([`Mount::new`]).
//!
//! # Mathematics
//!
//! The wrapped model gives its task point f, position Jacobian J and dJ/dt, and, where it has
//! the [`Orientation`] capability, its tool frame's rotation R, angular Jacobian J_w and
//! dJ_w/dt. The mount is a tool offset t (m, in that tool frame, added to the model's task
//! point) and a base transform (B, b): the mounted world from the model's world, B a rotation,
//! b a translation. With r = R t (the offset in the model's world; dr/dtheta_j = J_w,j x r,
//! since dR/dt = omega x R, column by column) and omega = J_w thetadot:
//!
//! ```text
//! f'      = B (f + r) + b
//! J'_j    = B (J_j + J_w,j x r)
//! Jdot'_j = B (Jdot_j + Jdot_w,j x r + J_w,j x (omega x r))
//! R'      = B R,    J_w' = B J_w,    Jdot_w' = B Jdot_w.
//! ```
//!
//! A zero offset needs no orientation (r = 0); a non-zero one on a model without it (the
//! Katana's closed form, the n-link family) is refused ([`MountError::NoOrientation`]).
//!
//! **Dynamics.** The tool point carries no mass and the base transform is rigid, so H and c
//! are the model's. g is the model's own only while gravity keeps its direction in the model's
//! world: the model computes it with gravity (0, 0, -9.81) m/s^2 there, while in the mounted
//! world gravity is that vector, which is B^T (0, 0, -9.81) in the model's. So a base that
//! turns the vertical (B e_z != e_z: a roll or a pitch) is refused for dynamics
//! ([`MountError::TiltedGravity`]); a yaw and any translation are exact.
//!
//! # Buffers
//!
//! J_w and dJ_w/dt are written into one buffer per thread that grows to the largest joint
//! count seen and is reused (taken out while in use, so nesting is safe): no allocation per
//! evaluation once it has grown.

use std::cell::Cell;
use std::sync::Arc;

use nalgebra::{Matrix3, Vector3};

use crate::dh::Frame;
use crate::{Dynamics, JointLimits, Orientation, Robot};
use spec::MountError;

/// The largest tool offset or base translation, per coordinate (m): an arm's reach is metres,
/// so a larger value is a typing error (millimetres written as metres), not a mount. The one
/// bound of an experiment's lengths, crate `spec`'s (a path's size is held to it too), and of
/// every length a robot file or URDF states ([`crate::MAX_LENGTH`], written out in
/// `file_rules.rs` for the build script, which links no `spec`; held equal below).
pub use spec::MAX_OFFSET;

const _: () = assert!(crate::file_rules::MAX_LENGTH == MAX_OFFSET);

/// The largest base angle, per coordinate (rad): 2 pi, every rotation once.
pub const MAX_ANGLE: f64 = 2.0 * std::f64::consts::PI;

/// How far B e_z may be from e_z (a rotation about z, up to rounding) for dynamics.
const VERTICAL_TOL: f64 = 1e-12;

/// A tool offset and a base transform (module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mount {
    tool: Vector3<f64>,
    base: Frame,
}

impl Mount {
    /// The mount of tool offset `tool` (m, in the model's tool frame) and base
    /// `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` (`rpy = [roll, pitch, yaw]`, rad; the URDF
    /// convention, [`Frame::from_xyz_rpy`]); every entry finite, offsets within
    /// [`MAX_OFFSET`], angles within `MAX_ANGLE`.
    pub fn new(tool: [f64; 3], xyz: [f64; 3], rpy: [f64; 3]) -> Result<Self, MountError> {
        for (field, values, max, unit) in [
            ("tool", tool, MAX_OFFSET, "m"),
            ("base.xyz", xyz, MAX_OFFSET, "m"),
            ("base.rpy", rpy, MAX_ANGLE, "rad"),
        ] {
            for (index, &value) in values.iter().enumerate() {
                if !value.is_finite() {
                    return Err(MountError::NotFinite { field, index });
                }
                if value.abs() > max {
                    return Err(MountError::OutOfRange {
                        field,
                        index,
                        value,
                        max,
                        unit,
                    });
                }
            }
        }
        Ok(Mount {
            tool: Vector3::from(tool),
            base: Frame::from_xyz_rpy(xyz, rpy),
        })
    }

    /// The tool offset t (m, in the model's tool frame).
    pub fn tool(&self) -> Vector3<f64> {
        self.tool
    }

    /// The base transform: the mounted world from the model's world.
    pub fn base(&self) -> &Frame {
        &self.base
    }

    /// Whether the base keeps the vertical (B e_z = e_z to rounding), as dynamics need.
    fn keeps_vertical(&self) -> bool {
        (self.base.rot.column(2) - Vector3::z()).norm() <= VERTICAL_TOL
    }
}

/// A robot model `R` with a [`Mount`] (module documentation): a [`Robot`], an [`Orientation`]
/// where the model has one, and [`Dynamics`] for a mounted dynamics model.
pub struct Mounted<R: ?Sized> {
    inner: Arc<R>,
    mount: Mount,
}

impl Mounted<dyn Robot> {
    /// `robot` with `mount`; refused if the mount has a tool offset and the robot no
    /// [`Orientation`].
    pub fn new(robot: Arc<dyn Robot>, mount: Mount) -> Result<Self, MountError> {
        Self::checked(robot, mount)
    }
}

impl Mounted<dyn Dynamics> {
    /// The dynamics model `dynamics` with `mount`: refused as [`Mounted::new`] refuses, and if
    /// the base turns the vertical ([`MountError::TiltedGravity`]).
    pub fn with_dynamics(dynamics: Arc<dyn Dynamics>, mount: Mount) -> Result<Self, MountError> {
        if !mount.keeps_vertical() {
            return Err(MountError::TiltedGravity {
                robot: dynamics.name().to_string(),
            });
        }
        Self::checked(dynamics, mount)
    }
}

impl<R: Robot + ?Sized> Mounted<R> {
    fn checked(inner: Arc<R>, mount: Mount) -> Result<Self, MountError> {
        if mount.tool != Vector3::zeros() && inner.orientation().is_none() {
            return Err(MountError::NoOrientation {
                robot: inner.name().to_string(),
            });
        }
        Ok(Mounted { inner, mount })
    }

    /// The model's orientation, when the mount needs it (a tool offset; [`Mounted::checked`]
    /// made sure the model has one).
    fn offset_orientation(&self) -> Option<&dyn Orientation> {
        if self.mount.tool == Vector3::zeros() {
            return None;
        }
        self.inner.orientation()
    }

    /// r = R t, the tool offset in the model's world.
    fn offset(&self, o: &dyn Orientation, theta: &[f64]) -> Vector3<f64> {
        o.tool_rotation(theta) * self.mount.tool
    }

    /// Turns the inner arm's J (in `jac`) into the mounted arm's: adds the tool offset's
    /// columns J_w,j x r, then rotates every column by the base. Returns r (zero without an
    /// offset), which the mounted position adds to the inner one.
    fn mount_jacobian(&self, theta: &[f64], jac: &mut [f64]) -> Vector3<f64> {
        let r = match self.offset_orientation() {
            Some(o) => {
                let r = self.offset(o, theta);
                with_scratch(jac.len(), |jw| {
                    o.angular_jacobian(theta, jw);
                    for (j, c) in jac.chunks_exact_mut(3).enumerate() {
                        let v = Vector3::new(c[0], c[1], c[2]) + column(jw, j).cross(&r);
                        c.copy_from_slice(v.as_slice());
                    }
                });
                r
            }
            None => Vector3::zeros(),
        };
        rotate_columns(&self.mount.base.rot, jac);
        r
    }
}

thread_local! {
    /// This thread's buffer of J_w and dJ_w/dt (module documentation).
    static SCRATCH: Cell<Vec<f64>> = const { Cell::new(Vec::new()) };
}

/// Runs `f` on this thread's buffer of at least `len` entries.
fn with_scratch<T>(len: usize, f: impl FnOnce(&mut [f64]) -> T) -> T {
    let mut buf = SCRATCH.take();
    if buf.len() < len {
        buf.resize(len, 0.0);
    }
    let out = f(&mut buf[..len]);
    SCRATCH.set(buf);
    out
}

/// Column `j` of a 3 x n column-major matrix.
fn column(m: &[f64], j: usize) -> Vector3<f64> {
    Vector3::new(m[3 * j], m[3 * j + 1], m[3 * j + 2])
}

/// Replaces every column c of the 3 x n column-major `m` by `rot c`.
fn rotate_columns(rot: &Matrix3<f64>, m: &mut [f64]) {
    for c in m.chunks_exact_mut(3) {
        let v = rot * Vector3::new(c[0], c[1], c[2]);
        c.copy_from_slice(v.as_slice());
    }
}

impl<R: Robot + ?Sized> Robot for Mounted<R> {
    fn name(&self) -> &str {
        self.inner.name()
    }

    fn dof(&self) -> usize {
        self.inner.dof()
    }

    fn position(&self, theta: &[f64]) -> Vector3<f64> {
        let r = self
            .offset_orientation()
            .map_or_else(Vector3::zeros, |o| self.offset(o, theta));
        self.mount
            .base
            .transform_point(&(self.inner.position(theta) + r))
    }

    fn jacobian(&self, theta: &[f64], jac: &mut [f64]) {
        self.inner.jacobian(theta, jac);
        self.mount_jacobian(theta, jac);
    }

    /// The inner arm's p and J from its one evaluation, then the mount's offset and base.
    fn position_jacobian(&self, theta: &[f64], jac: &mut [f64]) -> Vector3<f64> {
        let p = self.inner.position_jacobian(theta, jac);
        let r = self.mount_jacobian(theta, jac);
        self.mount.base.transform_point(&(p + r))
    }

    fn jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        self.inner.jacobian_dot(theta, thetadot, jdot);
        if let Some(o) = self.offset_orientation() {
            let r = self.offset(o, theta);
            let len = jdot.len();
            with_scratch(2 * len, |buf| {
                let (jw, jw_dot) = buf.split_at_mut(len);
                o.angular_jacobian(theta, jw);
                o.angular_jacobian_dot(theta, thetadot, jw_dot);
                let omega = thetadot
                    .iter()
                    .enumerate()
                    .fold(Vector3::zeros(), |w, (j, v)| w + column(jw, j) * *v);
                let rdot = omega.cross(&r);
                for (j, c) in jdot.chunks_exact_mut(3).enumerate() {
                    let v = Vector3::new(c[0], c[1], c[2])
                        + column(jw_dot, j).cross(&r)
                        + column(jw, j).cross(&rdot);
                    c.copy_from_slice(v.as_slice());
                }
            });
        }
        rotate_columns(&self.mount.base.rot, jdot);
    }

    fn limits(&self) -> &JointLimits {
        self.inner.limits()
    }

    fn orientation(&self) -> Option<&dyn Orientation> {
        self.inner.orientation().map(|_| self as &dyn Orientation)
    }

    /// The model's points in the mounted world, then the mounted task point where the tool
    /// offset moves it.
    fn skeleton(&self, theta: &[f64]) -> Vec<Vector3<f64>> {
        let base = &self.mount.base;
        let mut points: Vec<Vector3<f64>> = self
            .inner
            .skeleton(theta)
            .iter()
            .map(|p| base.transform_point(p))
            .collect();
        if self.offset_orientation().is_some() {
            points.push(self.position(theta));
        }
        points
    }
}

/// The model's tool frame turned by the base: R' = B R, J_w' = B J_w, dJ_w'/dt = B dJ_w/dt.
/// Asked only through [`Robot::orientation`], which gives it where the model has one.
impl<R: Robot + ?Sized> Orientation for Mounted<R> {
    fn tool_rotation(&self, theta: &[f64]) -> Matrix3<f64> {
        self.mount.base.rot * self.model_orientation().tool_rotation(theta)
    }

    fn angular_jacobian(&self, theta: &[f64], jac: &mut [f64]) {
        self.model_orientation().angular_jacobian(theta, jac);
        rotate_columns(&self.mount.base.rot, jac);
    }

    fn angular_jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        self.model_orientation()
            .angular_jacobian_dot(theta, thetadot, jdot);
        rotate_columns(&self.mount.base.rot, jdot);
    }
}

impl<R: Robot + ?Sized> Mounted<R> {
    /// The model's orientation; [`Robot::orientation`] gives this mounted one only where the
    /// model has it, so a caller reaches here only then.
    fn model_orientation(&self) -> &dyn Orientation {
        self.inner.orientation().expect(
            "Mounted::orientation gives the mounted orientation only where the model has one",
        )
    }
}

/// H, c and C are the model's; so is g, the base keeping the vertical
/// ([`Mounted::with_dynamics`]; module documentation).
impl Dynamics for Mounted<dyn Dynamics> {
    fn inertia(&self, theta: &[f64], h: &mut [f64]) {
        self.inner.inertia(theta, h)
    }

    fn coriolis(&self, theta: &[f64], thetadot: &[f64], c: &mut [f64]) {
        self.inner.coriolis(theta, thetadot, c)
    }

    fn coriolis_matrix(&self, theta: &[f64], thetadot: &[f64], cm: &mut [f64]) {
        self.inner.coriolis_matrix(theta, thetadot, cm)
    }

    fn gravity(&self, theta: &[f64], g: &mut [f64]) {
        self.inner.gravity(theta, g)
    }
}
