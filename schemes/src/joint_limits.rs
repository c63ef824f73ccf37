//! Joint-angle limits merged with joint-velocity limits into bounds on thetadot.
//!
//! jia2019 eq. (2.14)–(2.16) (gain kappa) and zhong2021 eq. (2.13)–(2.15) (gain upsilon) turn
//! theta- <= theta <= theta+ into the velocity-level bound
//! `gain (theta- - theta) <= thetadot <= gain (theta+ - theta)` (2.14) and intersect it with
//! thetadot- <= thetadot <= thetadot+:
//!
//! ```text
//! zeta-_i = max{gain (theta-_i - theta_i), thetadot-_i}        jia2019 (2.15)
//! zeta+_i = min{gain (theta+_i - theta_i), thetadot+_i}        jia2019 (2.16)
//! ```
//!
//! zhong2021 writes the same law piecewise (2.14)–(2.15) with switch points
//! xi1 = theta-_i - thetadot-_i / upsilon and xi2 = theta+_i - thetadot+_i / upsilon:
//! zeta-_i = upsilon (theta-_i - theta_i) if theta_i <= xi1, else thetadot-_i;
//! zeta+_i = thetadot+_i if theta_i <= xi2, else upsilon (theta+_i - theta_i).
//! [`piecewise_bounds`] implements that form literally (extended beyond [theta-, theta+] by the
//! same branches); it equals [`merged_bounds`] for every theta whenever thetadot- <= 0 <=
//! thetadot+ (tested). Unlimited joints (infinite theta+-) keep the plain velocity limits.
//!
//! As theta_i approaches theta+_i, zeta+_i falls linearly to 0 (and below 0 beyond the limit,
//! pushing the joint back); the bounds never exceed the velocity limits.

use robots::JointLimits;

/// (zeta-, zeta+) of jia2019 (2.15)–(2.16) with gain kappa (or zhong2021's upsilon), written
/// into `lo` and `hi` (one entry per joint).
pub fn merged_bounds(
    limits: &JointLimits,
    theta: &[f64],
    gain: f64,
    lo: &mut [f64],
    hi: &mut [f64],
) {
    for i in 0..theta.len() {
        lo[i] = (gain * (limits.theta_min[i] - theta[i])).max(limits.thetadot_min[i]);
        hi[i] = (gain * (limits.theta_max[i] - theta[i])).min(limits.thetadot_max[i]);
    }
}

/// zhong2021's piecewise form (2.14)–(2.15) of the same bounds, as printed, written into `lo`
/// and `hi`.
pub fn piecewise_bounds(
    limits: &JointLimits,
    theta: &[f64],
    upsilon: f64,
    lo: &mut [f64],
    hi: &mut [f64],
) {
    for i in 0..theta.len() {
        let xi1 = limits.theta_min[i] - limits.thetadot_min[i] / upsilon;
        let xi2 = limits.theta_max[i] - limits.thetadot_max[i] / upsilon;
        lo[i] = if theta[i] <= xi1 {
            upsilon * (limits.theta_min[i] - theta[i])
        } else {
            limits.thetadot_min[i]
        };
        hi[i] = if theta[i] <= xi2 {
            limits.thetadot_max[i]
        } else {
            upsilon * (limits.theta_max[i] - theta[i])
        };
    }
}

/// Time derivatives of (zeta-, zeta+) when theta moves at thetadot: -gain thetadot_i on the
/// joint-angle branch, 0 on the velocity-limit branch. At the switch point (a kink) the
/// right-hand derivative (forward in time) is returned: for max{a, b} with a = b,
/// max{a', b'} = max{-gain thetadot_i, 0}; for min, min{-gain thetadot_i, 0}. Written into `lo`
/// and `hi`.
pub fn merged_bounds_dot(
    limits: &JointLimits,
    theta: &[f64],
    thetadot: &[f64],
    gain: f64,
    lo: &mut [f64],
    hi: &mut [f64],
) {
    for i in 0..theta.len() {
        let d = -gain * thetadot[i];
        let a = gain * (limits.theta_min[i] - theta[i]);
        let b = limits.thetadot_min[i];
        lo[i] = if !a.is_finite() {
            0.0
        } else if a > b {
            d
        } else if a < b {
            0.0
        } else {
            d.max(0.0)
        };
        let a = gain * (limits.theta_max[i] - theta[i]);
        let b = limits.thetadot_max[i];
        hi[i] = if !a.is_finite() {
            0.0
        } else if a < b {
            d
        } else if a > b {
            0.0
        } else {
            d.min(0.0)
        };
    }
}
