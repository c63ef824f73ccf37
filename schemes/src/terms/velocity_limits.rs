//! The joint-velocity limits thetadot- <= thetadot <= thetadot+ as bounds (velocity level):
//! l[..n] = max(l[..n], thetadot-), u[..n] = min(u[..n], thetadot+) (robio2018 (9), jia2019
//! (2.13)). Constant: time derivative 0. [`super::bound_conversion`] includes them already.

use std::sync::Arc;

use qp::Qp;
use robots::Robot;

use super::{DotOut, Footprint, Slot, State, Term};

/// The velocity limits (module docs).
pub struct VelocityLimits {
    /// The robot whose limits bound the command.
    pub robot: Arc<dyn Robot>,
}

impl Term for VelocityLimits {
    fn describe(&self) -> String {
        "velocity-limits: l[..n] = max(l, thetadot-), u[..n] = min(u, thetadot+)".to_string()
    }

    fn footprint(&self) -> Footprint {
        Footprint {
            bounds: true,
            ..Default::default()
        }
    }

    fn write(&self, _state: &State<'_>, _slot: Slot, qp: &mut Qp) {
        let limits = self.robot.limits();
        for i in 0..self.robot.dof() {
            qp.lower[i] = qp.lower[i].max(limits.thetadot_min[i]);
            qp.upper[i] = qp.upper[i].min(limits.thetadot_max[i]);
        }
    }

    fn has_dot(&self) -> bool {
        true
    }

    fn write_dot(&self, _state: &State<'_>, _slot: Slot, out: &mut DotOut<'_>) {
        let limits = self.robot.limits();
        for i in 0..self.robot.dof() {
            out.merge_lower(i, limits.thetadot_min[i], 0.0);
            out.merge_upper(i, limits.thetadot_max[i], 0.0);
        }
    }
}
