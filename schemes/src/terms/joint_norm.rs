//! The weighted norm of the joint command, w |x[..n]|^2 / 2 with w > 0, so P[..n, ..n] += w I.
//!
//! At the velocity level (`velocity-norm`, x[..n] = thetadot) it is the minimum velocity norm of
//! every velocity-level paper: robio2018 (4) and kong2019 (14), (22) with w = 1, jia2019
//! (2.17)'s phi (the VLTCO weight of ||thetadot||^2 / 2), zhong2021 (2.16)'s eta. At the
//! acceleration level (`acceleration-norm`, x[..n] = thetaddot) it is the zeta I part of
//! zhang2018 (2.5)'s W = zeta I + (1 - zeta) H^2 (with [`super::drift_damping`] it is
//! zeta ||thetaddot + sigma||^2 / 2 up to a constant). Its time derivative is 0.

use qp::Qp;

use super::{DotOut, Slot, State, Term};
use spec::Level;

/// w |x[..n]|^2 / 2 (module docs).
pub struct JointNorm {
    /// Joint count n.
    pub joints: usize,
    /// Weight w.
    pub weight: f64,
    /// Which command it weighs (names the term: velocity-norm or acceleration-norm).
    pub level: Level,
}

impl Term for JointNorm {
    fn describe(&self) -> String {
        let kind = match self.level {
            Level::Velocity => "velocity-norm",
            Level::Acceleration => "acceleration-norm",
        };
        format!("{kind} (w={}): P[..n, ..n] += w I", self.weight)
    }

    fn write(&self, _state: &State<'_>, _slot: Slot, qp: &mut Qp) {
        for i in 0..self.joints {
            qp.p[(i, i)] += self.weight;
        }
    }

    fn has_dot(&self) -> bool {
        true
    }

    fn write_dot(&self, _state: &State<'_>, _slot: Slot, _out: &mut DotOut<'_>) {}
}
