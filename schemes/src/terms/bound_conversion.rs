//! The conversion of the joint-angle limits theta- <= theta <= theta+ into bounds on thetadot,
//! intersected with the joint-velocity limits (velocity level), gain kappa > 0 (jia2019
//! (2.15)-(2.16)), upsilon (zhong2021 (2.14)-(2.15), robio2018 (9)-(10)):
//!
//! ```text
//! zeta-_i = max{gain (theta-_i - theta_i), thetadot-_i}
//! zeta+_i = min{gain (theta+_i - theta_i), thetadot+_i}
//! l[..n] = max(l[..n], zeta-),  u[..n] = min(u[..n], zeta+)
//! ```
//!
//! ([`crate::joint_limits`]; zhong2021's piecewise form is the same law, tested). As theta_i
//! nears theta+_i, zeta+_i falls linearly to 0 and below 0 beyond the limit. Where the papers
//! write these bounds as rows of G (zhong2021 (2.18)), the scheme's `bounds = "rows"` writes
//! every bound so ([`spec::BoundPlacement`]). Time derivative: -gain thetadot_i on
//! the joint-angle branch, 0 on the velocity branch, right-hand at the kink.

use std::sync::Arc;

use qp::Qp;
use robots::Robot;

use super::{DotOut, Footprint, Slot, State, Term};
use crate::joint_limits::{merged_bound, merged_bound_dot};

/// The bound conversion (module docs).
pub struct BoundConversion {
    /// The robot whose limits are converted.
    pub robot: Arc<dyn Robot>,
    /// Gain kappa (jia2019) or upsilon (zhong2021, robio2018), > 0.
    pub gain: f64,
}

impl Term for BoundConversion {
    fn describe(&self) -> String {
        format!(
            "bound-conversion (gain={}): l_i = max(l_i, gain (theta-_i - theta_i), thetadot-_i), \
             u_i = min(u_i, gain (theta+_i - theta_i), thetadot+_i)",
            self.gain
        )
    }

    fn footprint(&self) -> Footprint {
        Footprint {
            bounds: true,
            ..Default::default()
        }
    }

    fn write(&self, state: &State<'_>, _slot: Slot, qp: &mut Qp) {
        let limits = self.robot.limits();
        for (i, &th) in state.theta.iter().enumerate() {
            let (lo, hi) = merged_bound(limits, i, th, self.gain);
            qp.lower[i] = qp.lower[i].max(lo);
            qp.upper[i] = qp.upper[i].min(hi);
        }
    }

    fn has_dot(&self) -> bool {
        true
    }

    fn write_dot(&self, state: &State<'_>, _slot: Slot, out: &mut DotOut<'_>) {
        let limits = self.robot.limits();
        for (i, (&th, &v)) in state.theta.iter().zip(state.thetadot).enumerate() {
            let (lo, hi) = merged_bound(limits, i, th, self.gain);
            let (lo_dot, hi_dot) = merged_bound_dot(limits, i, th, v, self.gain);
            out.merge_lower(i, lo, lo_dot);
            out.merge_upper(i, hi, hi_dot);
        }
    }
}
