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
use crate::paths::Path;

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
    /// J and Jdot (3 x n column-major each), allocated with the term.
    scratch: Mutex<(Vec<f64>, Vec<f64>)>,
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
            scratch: Mutex::new((vec![0.0; 3 * n], vec![0.0; 3 * n])),
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
        let (jac, jdot) = &mut *scratch;
        self.robot.jacobian(state.theta, jac);
        self.write_rows(jac, slot.equality, &mut qp.a);
        let pp = self.path.at(state.t);
        let f = self.robot.position(state.theta);
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
        let (jac, jdot) = &mut *scratch;
        self.robot.jacobian_dot(state.theta, state.thetadot, jdot);
        self.write_rows(jdot, slot.equality, &mut out.qp.a);
        self.robot.jacobian(state.theta, jac);
        let jthd = times(jac, state.thetadot);
        let pp = self.path.at(state.t);
        let bdot = pp.rddot + (pp.rdot - jthd) * k_p;
        for (k, &axis) in self.axes.iter().enumerate() {
            out.qp.b[slot.equality + k] = bdot[axis];
        }
    }
}
