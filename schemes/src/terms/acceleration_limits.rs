//! The joint-acceleration limits, and the joint-velocity limits converted to the acceleration
//! level, as bounds on the command thetaddot (acceleration level). With a > 0 the largest
//! acceleration (rad/s^2, every joint) and, when given, the gain mu > 0 of the conversion:
//!
//! ```text
//! -a <= thetaddot_i <= a                                          (acceleration limits)
//! mu (thetadot-_i - thetadot_i) <= thetaddot_i <= mu (thetadot+_i - thetadot_i)   (velocity)
//! l_i = max(l_i, clamp(mu (thetadot-_i - thetadot_i), -a, a))
//! u_i = min(u_i, clamp(mu (thetadot+_i - thetadot_i), -a, a))
//! ```
//!
//! The velocity branch is the acceleration-level form of the bound conversion (one level up
//! from [`super::bound_conversion`]: d/dt (thetadot+ - thetadot) >= -mu (thetadot+ - thetadot),
//! so a joint approaching its velocity limit is slowed at the rate mu and a joint beyond it
//! is brought back). It is clamped into [-a, a]: the acceleration limit is physical and wins,
//! and since thetadot- < thetadot+ the term's own l_i <= u_i always (a joint beyond its
//! velocity limit is decelerated at a). Without mu the bounds are -a, a.
//!
//! Time derivative along the motion: 0 on the constant branch, -mu thetaddot_i on the velocity
//! branch, and at the clamp's kink the right-hand derivative.

use std::sync::Arc;

use qp::Qp;
use robots::Robot;

use super::{DotOut, Footprint, Slot, State, Term};

/// The acceleration limits (module docs).
pub struct AccelerationLimits {
    /// The robot whose velocity limits are converted.
    pub robot: Arc<dyn Robot>,
    /// The largest joint acceleration a > 0 (rad/s^2).
    pub a_max: f64,
    /// The conversion gain mu > 0 of the velocity limits (None: acceleration limits only).
    pub velocity_gain: Option<f64>,
}

impl AccelerationLimits {
    /// The bounds (l_i, u_i) of joint `i` at `thetadot` (module docs).
    fn bounds(&self, i: usize, thetadot: f64) -> (f64, f64) {
        let a = self.a_max;
        match self.velocity_gain {
            None => (-a, a),
            Some(mu) => {
                let limits = self.robot.limits();
                (
                    (mu * (limits.thetadot_min[i] - thetadot)).clamp(-a, a),
                    (mu * (limits.thetadot_max[i] - thetadot)).clamp(-a, a),
                )
            }
        }
    }

    /// The right-hand derivative of clamp(v, -a, a) where v moves at `slope`.
    fn clamp_dot(&self, v: f64, slope: f64) -> f64 {
        let a = self.a_max;
        if v > -a && v < a {
            slope
        } else if v == -a {
            slope.max(0.0)
        } else if v == a {
            slope.min(0.0)
        } else {
            0.0
        }
    }
}

impl Term for AccelerationLimits {
    fn describe(&self) -> String {
        match self.velocity_gain {
            None => format!(
                "acceleration-limits (a={}): l[..n] = max(l, -a), u[..n] = min(u, a)",
                self.a_max
            ),
            Some(mu) => format!(
                "acceleration-limits (a={}, mu={mu}): l_i = max(l_i, clamp(mu (thetadot-_i - \
                 thetadot_i), -a, a)), u_i = min(u_i, clamp(mu (thetadot+_i - thetadot_i), -a, a))",
                self.a_max
            ),
        }
    }

    fn footprint(&self) -> Footprint {
        Footprint {
            bounds: true,
            ..Default::default()
        }
    }

    fn write(&self, state: &State<'_>, _slot: Slot, qp: &mut Qp) {
        for (i, &v) in state.thetadot.iter().enumerate() {
            let (lo, hi) = self.bounds(i, v);
            qp.lower[i] = qp.lower[i].max(lo);
            qp.upper[i] = qp.upper[i].min(hi);
        }
    }

    fn has_dot(&self) -> bool {
        true
    }

    fn write_dot(&self, state: &State<'_>, _slot: Slot, out: &mut DotOut<'_>) {
        for (i, &v) in state.thetadot.iter().enumerate() {
            let (lo, hi) = self.bounds(i, v);
            let (lo_dot, hi_dot) = match self.velocity_gain {
                None => (0.0, 0.0),
                Some(mu) => {
                    let limits = self.robot.limits();
                    let slope = -mu * state.thetaddot[i];
                    (
                        self.clamp_dot(mu * (limits.thetadot_min[i] - v), slope),
                        self.clamp_dot(mu * (limits.thetadot_max[i] - v), slope),
                    )
                }
            };
            out.merge_lower(i, lo, lo_dot);
            out.merge_upper(i, hi, hi_dot);
        }
    }
}
