//! The tracking equality: one row of A x = b per selected task axis k (x, y or z of the tool
//! position f(theta); all three by default, x and y for a planar task). With J_k the k-th row of
//! the position Jacobian and r*, rdot*, rddot* the path:
//!
//! - velocity level (x[..n] = thetadot): J_k thetadot = rdot*_k + k_p (r*_k - f_k(theta)), k_p >=
//!   0 (robio2018 (12), jia2019 (2.18), zhong2021 (2.17) print k_p = 0; kong2019 (14), (22) take
//!   k_p > 0). Time derivative: Adot_k = Jdot_k, bdot_k = rddot*_k + k_p (rdot*_k - J_k thetadot).
//! - acceleration level (x[..n] = thetaddot): J_k thetaddot = b_k with b = rddot* - Jdot
//!   thetadot + rho_v (rdot* - J thetadot) + rho_p (r* - f(theta)), zhang2018 (2.6). No exact
//!   derivative (it would need J-double-dot and the path's jerk): such a scheme takes the
//!   central difference.
//!
//! The pose task adds three rows for the tool frame's orientation, on a robot with the
//! [`robots::Orientation`] capability (rotation R(theta), angular Jacobian J_w with omega = J_w
//! thetadot, its derivative Jdot_w). The desired orientation R_d is constant (the start pose's,
//! R(theta_ref), or given as a rotation vector phi_d, R_d = exp(skew(phi_d))), so omega_d = 0. The
//! orientation error is the rotation vector (log map) of R_d R^T,
//!
//! ```text
//! e_o = log(R_d R^T)   (world frame, |e_o| <= pi),   R_d = exp(skew(e_o)) R,
//! ```
//!
//! the world-frame turn that takes the tool frame to R_d. With E = R_d R^T, Edot = -E skew(omega),
//! so de_o/dt = -Jr^{-1}(e_o) omega, Jr^{-1}(phi) = I + skew(phi) / 2 + c(|phi|) skew(phi)^2, c(a) =
//! 1/a^2 - (1 + cos a) / (2 a sin a) (-> 1/12 as a -> 0), the inverse right Jacobian of SO(3).
//! The orientation rows, after the position axes:
//!
//! - velocity level: J_w thetadot = k_p e_o (the same gain k_p as the position rows). Closed
//!   loop: de_o/dt = -k_p Jr^{-1}(e_o) e_o = -k_p e_o (skew(e_o) e_o = 0): the error decays as
//!   exp(-k_p t). Time derivative: Adot = Jdot_w, bdot = -k_p Jr^{-1}(e_o) J_w thetadot.
//! - acceleration level: J_w thetaddot = -Jdot_w thetadot - rho_v J_w thetadot + rho_p e_o, the
//!   rotational analogue of zhang2018 (2.6) with omega_d = 0 (no exact derivative).
//!
//! A planar arm moves its tool in a plane: the 3-row task has a zero row (the third row of J
//! vanishes), so the QP's equality is rank-deficient and an exact solver must fall back; the
//! planar task keeps the two rows that the arm can follow.

use std::sync::{Arc, Mutex};

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use qp::Qp;
use robots::Robot;

use super::{DotOut, Slot, State, Term};
use crate::paths::{Path, PathPoint};

/// The feedback of the tracking equality, by level (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Feedback {
    /// Velocity level: position gain k_p.
    Velocity {
        /// k_p >= 0.
        k_p: f64,
    },
    /// Acceleration level: zhang2018 (2.6)'s gains.
    Acceleration {
        /// Velocity gain rho_v > 0.
        rho_v: f64,
        /// Position gain rho_p > 0.
        rho_p: f64,
    },
}

/// The task axes' names, by index.
pub const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// The tracking equality (module docs).
pub struct Tracking {
    robot: Arc<dyn Robot>,
    path: Arc<dyn Path>,
    /// The selected axes (indices into x, y, z), one equality row each.
    axes: Vec<usize>,
    /// Whether `axes` is x, y, z in order (the rows are then J's rows as they are).
    all_axes: bool,
    feedback: Feedback,
    /// The desired orientation R_d of the pose task (None: position rows only).
    target: Option<Matrix3<f64>>,
    /// J, Jdot and the instant they were evaluated at, allocated with the term.
    scratch: Mutex<Scratch>,
}

/// The term's buffers: J and Jdot (3 x n column-major each) and, from the last
/// evaluation, the instant (t, theta) with its J, path point r*(t), rdot*(t), rddot*(t) and
/// (after a [`Term::write`]) f(theta). A network's right-hand side asks for the QP and then for
/// its time derivative at the same instant, and the run's observer asks for the QP again at an
/// accepted step, where an explicit Runge-Kutta method's last stage has just evaluated it:
/// [`Term::write_dot`] and [`Term::write`] reuse what they need when (t, theta) are the same bit
/// for bit, so each is evaluated once there, and the numbers are those a fresh evaluation
/// gives. A pose task overwrites `jac` with the angular Jacobian, so it is never kept valid.
struct Scratch {
    jac: Vec<f64>,
    jdot: Vec<f64>,
    /// Whether `jac` and `point` hold the values at (`t`, `theta`).
    valid: bool,
    t: f64,
    theta: Vec<f64>,
    point: PathPoint,
    /// The instant (its bits) `point` is the path's point at, whether or not `valid`: the
    /// point depends on t alone, so the stages of a Runge-Kutta step at one instant (the last
    /// two of Tsitouras 5(4), and the observer after them) ask the path once.
    point_t: Option<u64>,
    /// f(theta) at (`t`, `theta`), when the last evaluation there was a [`Term::write`].
    position: Option<Vector3<f64>>,
}

impl Scratch {
    /// Whether the cached J and path point are those of (t, theta), compared bit for bit
    /// (so that -0.0 and 0.0, or two NaNs, are never taken for each other).
    fn holds(&self, t: f64, theta: &[f64]) -> bool {
        self.valid
            && self.t.to_bits() == t.to_bits()
            && self.theta.len() == theta.len()
            && self
                .theta
                .iter()
                .zip(theta)
                .all(|(a, b)| a.to_bits() == b.to_bits())
    }

    /// Records that `jac` (and `position`, where given) are the values at (t, theta); `point`
    /// is t's already ([`Self::path_point`] was asked at t).
    fn remember(&mut self, t: f64, theta: &[f64], position: Option<Vector3<f64>>) {
        debug_assert_eq!(self.point_t, Some(t.to_bits()));
        self.t = t;
        self.theta.copy_from_slice(theta);
        self.position = position;
        self.valid = true;
    }

    /// The path's point at t: the one held where it is t's (bit for bit), else asked of `path`
    /// and held.
    fn path_point(&mut self, path: &dyn Path, t: f64) -> PathPoint {
        if self.point_t != Some(t.to_bits()) {
            self.point = path.at(t);
            self.point_t = Some(t.to_bits());
        }
        self.point
    }
}

/// The robot's [`robots::Orientation`] capability was asked of a pose task on a robot that has
/// none.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NoOrientation;

/// The skew matrix skew(v) of v (so skew(v) w = v x w).
fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// The rotation vector log(m) of a rotation matrix m (angle in [0, pi]), through the unit
/// quaternion (accurate up to a half turn).
pub fn rotation_log(m: &Matrix3<f64>) -> Vector3<f64> {
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*m)).scaled_axis()
}

/// The rotation exp(skew(phi)) of a rotation vector phi.
pub fn rotation_exp(phi: &Vector3<f64>) -> Matrix3<f64> {
    Rotation3::new(*phi).into_inner()
}

/// The inverse right Jacobian of SO(3), Jr^{-1}(phi) (module docs).
fn inverse_right_jacobian(phi: &Vector3<f64>) -> Matrix3<f64> {
    let a = phi.norm();
    let c = if a < 1e-4 {
        1.0 / 12.0 + a * a / 720.0
    } else {
        1.0 / (a * a) - (1.0 + a.cos()) / (2.0 * a * a.sin())
    };
    let k = skew(phi);
    Matrix3::identity() + k * 0.5 + k * k * c
}

/// The orientation error e_o = log(R_d R^T) toward `target` (R_d) of the tool frame of a robot
/// with orientation `o` at `theta` (module docs).
pub fn orientation_error(
    o: &dyn robots::Orientation,
    target: &Matrix3<f64>,
    theta: &[f64],
) -> Vector3<f64> {
    rotation_log(&(target * o.tool_rotation(theta).transpose()))
}

/// y = a x for a 3 x n column-major `a` (n = x's length), summed column by column in joint
/// order.
fn times(a: &[f64], x: &[f64]) -> Vector3<f64> {
    let mut y = [0.0; 3];
    for (column, v) in a[..3 * x.len()].chunks_exact(3).zip(x) {
        y[0] += column[0] * v;
        y[1] += column[1] * v;
        y[2] += column[2] * v;
    }
    Vector3::from(y)
}

/// The first `n` columns of the column-major matrix `a` (A or Adot), each a slice of its
/// rows (a tracking term has at least one row).
fn a_columns(a: &mut nalgebra::DMatrix<f64>, n: usize) -> impl Iterator<Item = &mut [f64]> {
    let rows = a.nrows();
    a.as_mut_slice().chunks_exact_mut(rows).take(n)
}

/// Writes a 3 x n column-major matrix `m` into three rows of A (or Adot) from `row`: one copy
/// where A has those three rows only (kong2019's task), else three entries a column.
fn write_block(m: &[f64], row: usize, a: &mut nalgebra::DMatrix<f64>) {
    if a.nrows() == 3 {
        debug_assert_eq!(row, 0);
        a.as_mut_slice()[..m.len()].copy_from_slice(m);
        return;
    }
    for (column, mj) in a_columns(a, m.len() / 3).zip(m.chunks_exact(3)) {
        column[row..row + 3].copy_from_slice(mj);
    }
}

impl Tracking {
    /// The equality on `axes` (distinct indices 0..3, checked by the spec) of `robot`'s tool
    /// following `path`.
    pub fn new(
        robot: Arc<dyn Robot>,
        path: Arc<dyn Path>,
        axes: Vec<usize>,
        feedback: Feedback,
    ) -> Self {
        let n = robot.dof();
        Self {
            robot,
            path,
            all_axes: axes == [0, 1, 2],
            axes,
            feedback,
            target: None,
            scratch: Mutex::new(Scratch {
                jac: vec![0.0; 3 * n],
                jdot: vec![0.0; 3 * n],
                valid: false,
                t: f64::NAN,
                theta: vec![0.0; n],
                point: PathPoint {
                    r: Vector3::zeros(),
                    rdot: Vector3::zeros(),
                    rddot: Vector3::zeros(),
                },
                point_t: None,
                position: None,
            }),
        }
    }

    /// The pose task: the equality on `axes` plus three orientation rows toward `target` (R_d;
    /// module docs), on a robot with the orientation capability.
    pub fn with_orientation(
        robot: Arc<dyn Robot>,
        path: Arc<dyn Path>,
        axes: Vec<usize>,
        feedback: Feedback,
        target: Matrix3<f64>,
    ) -> Result<Self, NoOrientation> {
        if robot.orientation().is_none() {
            return Err(NoOrientation);
        }
        Ok(Self {
            target: Some(target),
            ..Self::new(robot, path, axes, feedback)
        })
    }

    /// The orientation capability of a pose task's robot (checked at construction).
    fn orientation(&self) -> &dyn robots::Orientation {
        self.robot
            .orientation()
            .expect("a pose task is built only on a robot with orientation")
    }

    /// Writes the selected rows of a 3 x n column-major matrix into A (or Adot) from `row`.
    fn write_rows(&self, m: &[f64], row: usize, a: &mut nalgebra::DMatrix<f64>) {
        if self.all_axes {
            write_block(m, row, a);
            return;
        }
        for (column, mj) in a_columns(a, m.len() / 3).zip(m.chunks_exact(3)) {
            for (k, &axis) in self.axes.iter().enumerate() {
                column[row + k] = mj[axis];
            }
        }
    }
}

impl Term for Tracking {
    fn describe(&self) -> String {
        let axes: Vec<&str> = self.axes.iter().map(|&k| AXIS_NAMES[k]).collect();
        let axes = axes.join(", ");
        let pose = if self.target.is_some() {
            match self.feedback {
                Feedback::Velocity { .. } => {
                    "; pose: A[o, ..n] = J_w, b_o = k_p log(R_d R^T) (R_d constant)"
                }
                Feedback::Acceleration { .. } => {
                    "; pose: A[o, ..n] = J_w, b_o = -Jdot_w thetadot - rho_v J_w thetadot + \
                     rho_p log(R_d R^T) (R_d constant)"
                }
            }
        } else {
            ""
        };
        let position = match self.feedback {
            Feedback::Velocity { k_p } => format!(
                "tracking (axes {axes}, k_p={k_p}): A[k, ..n] = J_k, b_k = rdot*_k + k_p (r*_k - f_k)"
            ),
            Feedback::Acceleration { rho_v, rho_p } => format!(
                "tracking (axes {axes}, rho_v={rho_v}, rho_p={rho_p}): A[k, ..n] = J_k, b_k = \
                 rddot*_k - (Jdot thetadot)_k + rho_v (rdot*_k - (J thetadot)_k) + rho_p (r*_k - f_k)"
            ),
        };
        format!("{position}{pose}")
    }

    fn footprint(&self) -> super::Footprint {
        super::Footprint {
            equalities: self.axes.len() + if self.target.is_some() { 3 } else { 0 },
            ..Default::default()
        }
    }

    fn write(&self, state: &State<'_>, slot: Slot, qp: &mut Qp) {
        let mut scratch = self
            .scratch
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let scratch = &mut *scratch;
        let cached = match scratch.position {
            Some(f) if self.target.is_none() && scratch.holds(state.t, state.theta) => {
                Some((f, scratch.point))
            }
            _ => None,
        };
        let (f, pp) = match cached {
            Some(fp) => fp,
            None => {
                let f = self.robot.position_jacobian(state.theta, &mut scratch.jac);
                (f, scratch.path_point(&*self.path, state.t))
            }
        };
        let (jac, jdot) = (&scratch.jac, &mut scratch.jdot);
        self.write_rows(jac, slot.equality, &mut qp.a);
        let b = match self.feedback {
            Feedback::Velocity { k_p } => pp.rdot + (pp.r - f) * k_p,
            Feedback::Acceleration { rho_v, rho_p } => {
                self.robot.jacobian_dot(state.theta, state.thetadot, jdot);
                let jthd = times(jac, state.thetadot);
                pp.rddot - times(jdot, state.thetadot)
                    + (pp.rdot - jthd) * rho_v
                    + (pp.r - f) * rho_p
            }
        };
        for (k, &axis) in self.axes.iter().enumerate() {
            qp.b[slot.equality + k] = b[axis];
        }
        match &self.target {
            // The cache holds the position Jacobian; a pose task's rows overwrite `jac` with
            // the angular one, so its instant is never remembered, and an instant remembered
            // before no longer holds.
            None => scratch.remember(state.t, state.theta, Some(f)),
            Some(target) => {
                scratch.valid = false;
                let o = self.orientation();
                let row = slot.equality + self.axes.len();
                let e = orientation_error(o, target, state.theta);
                o.angular_jacobian(state.theta, &mut scratch.jac);
                write_block(&scratch.jac, row, &mut qp.a);
                let b = match self.feedback {
                    Feedback::Velocity { k_p } => e * k_p,
                    Feedback::Acceleration { rho_v, rho_p } => {
                        o.angular_jacobian_dot(state.theta, state.thetadot, &mut scratch.jdot);
                        -times(&scratch.jdot, state.thetadot)
                            - times(&scratch.jac, state.thetadot) * rho_v
                            + e * rho_p
                    }
                };
                for k in 0..3 {
                    qp.b[row + k] = b[k];
                }
            }
        }
    }

    fn has_dot(&self) -> bool {
        matches!(self.feedback, Feedback::Velocity { .. })
    }

    fn write_dot(&self, state: &State<'_>, slot: Slot, out: &mut DotOut<'_>) {
        let Feedback::Velocity { k_p } = self.feedback else {
            return;
        };
        let mut scratch = self
            .scratch
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let scratch = &mut *scratch;
        if !scratch.holds(state.t, state.theta) {
            self.robot.jacobian(state.theta, &mut scratch.jac);
            scratch.path_point(&*self.path, state.t);
            scratch.remember(state.t, state.theta, None);
        }
        self.robot
            .jacobian_dot(state.theta, state.thetadot, &mut scratch.jdot);
        self.write_rows(&scratch.jdot, slot.equality, &mut out.qp.a);
        let jthd = times(&scratch.jac, state.thetadot);
        let pp = scratch.point;
        let bdot = pp.rddot + (pp.rdot - jthd) * k_p;
        for (k, &axis) in self.axes.iter().enumerate() {
            out.qp.b[slot.equality + k] = bdot[axis];
        }
        if let Some(target) = &self.target {
            let o = self.orientation();
            let row = slot.equality + self.axes.len();
            o.angular_jacobian_dot(state.theta, state.thetadot, &mut scratch.jdot);
            write_block(&scratch.jdot, row, &mut out.qp.a);
            o.angular_jacobian(state.theta, &mut scratch.jac);
            // `jac` holds the angular Jacobian now, not the position one the cache stands for.
            scratch.valid = false;
            let e = orientation_error(o, target, state.theta);
            let bdot = -(inverse_right_jacobian(&e) * times(&scratch.jac, state.thetadot)) * k_p;
            for k in 0..3 {
                out.qp.b[row + k] = bdot[k];
            }
        }
    }
}
