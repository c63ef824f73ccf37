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
//! A planar arm moves its tool in a plane: the 3-row task has a zero row (the third row of J
//! vanishes), so the QP's equality is rank-deficient and an exact solver must fall back; the
//! planar task keeps the two rows that the arm can follow.

use std::sync::{Arc, Mutex};

use nalgebra::Vector3;
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
    feedback: Feedback,
    /// J, Jdot and the instant they were evaluated at, allocated with the term.
    scratch: Mutex<Scratch>,
}

/// The term's buffers: J and Jdot (3 x n column-major each) and, from the last
/// [`Term::write`], the instant (t, theta) with its J and path point r*(t), rdot*(t),
/// rddot*(t). A network's right-hand side asks for the QP and then for its time derivative at
/// the same instant; [`Term::write_dot`] reuses J and the path point when (t, theta) are the
/// same bit for bit, so each is evaluated once per right-hand side, and the numbers are those
/// a fresh evaluation gives.
struct Scratch {
    jac: Vec<f64>,
    jdot: Vec<f64>,
    /// Whether `jac` and `point` hold the values at (`t`, `theta`).
    valid: bool,
    t: f64,
    theta: Vec<f64>,
    point: PathPoint,
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

    /// Records that `jac` and `point` are the values at (t, theta).
    fn remember(&mut self, t: f64, theta: &[f64], point: PathPoint) {
        self.t = t;
        self.theta.copy_from_slice(theta);
        self.point = point;
        self.valid = true;
    }
}

/// y = a x for a 3 x n column-major `a`, summed column by column in joint order.
fn times(a: &[f64], x: &[f64]) -> Vector3<f64> {
    let mut y = Vector3::zeros();
    for (j, v) in x.iter().enumerate() {
        for i in 0..3 {
            y[i] += a[3 * j + i] * v;
        }
    }
    y
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
            axes,
            feedback,
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
            }),
        }
    }

    /// Writes the selected rows of a 3 x n column-major matrix into A (or Adot) from `row`.
    fn write_rows(&self, m: &[f64], row: usize, a: &mut nalgebra::DMatrix<f64>) {
        let n = self.robot.dof();
        for (k, &axis) in self.axes.iter().enumerate() {
            for j in 0..n {
                a[(row + k, j)] = m[3 * j + axis];
            }
        }
    }
}

impl Term for Tracking {
    fn describe(&self) -> String {
        let axes: Vec<&str> = self.axes.iter().map(|&k| AXIS_NAMES[k]).collect();
        let axes = axes.join(", ");
        match self.feedback {
            Feedback::Velocity { k_p } => format!(
                "tracking (axes {axes}, k_p={k_p}): A[k, ..n] = J_k, b_k = rdot*_k + k_p (r*_k - f_k)"
            ),
            Feedback::Acceleration { rho_v, rho_p } => format!(
                "tracking (axes {axes}, rho_v={rho_v}, rho_p={rho_p}): A[k, ..n] = J_k, b_k = \
                 rddot*_k - (Jdot thetadot)_k + rho_v (rdot*_k - (J thetadot)_k) + rho_p (r*_k - f_k)"
            ),
        }
    }

    fn footprint(&self) -> super::Footprint {
        super::Footprint {
            equalities: self.axes.len(),
            ..Default::default()
        }
    }

    fn write(&self, state: &State<'_>, slot: Slot, qp: &mut Qp) {
        let mut scratch = self
            .scratch
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let scratch = &mut *scratch;
        let f = self.robot.position_jacobian(state.theta, &mut scratch.jac);
        let (jac, jdot) = (&scratch.jac, &mut scratch.jdot);
        self.write_rows(jac, slot.equality, &mut qp.a);
        let pp = self.path.at(state.t);
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
        scratch.remember(state.t, state.theta, pp);
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
            let point = self.path.at(state.t);
            scratch.remember(state.t, state.theta, point);
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
    }
}
