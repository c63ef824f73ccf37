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
//! [`piecewise_bound`] implements that form literally (extended beyond [theta-, theta+] by the
//! same branches); it equals [`merged_bound`] for every theta whenever thetadot- <= 0 <=
//! thetadot+ (tested). Unlimited joints (infinite theta+-) keep the plain velocity limits.
//!
//! As theta_i approaches theta+_i, zeta+_i falls linearly to 0 (and below 0 beyond the limit,
//! pushing the joint back); the bounds never exceed the velocity limits.

use robots::JointLimits;

/// (zeta-_i, zeta+_i) of jia2019 (2.15)–(2.16) for joint `i` at angle `theta` with gain kappa
/// (or zhong2021's upsilon).
#[inline]
pub fn merged_bound(limits: &JointLimits, i: usize, theta: f64, gain: f64) -> (f64, f64) {
    (
        (gain * (limits.theta_min[i] - theta)).max(limits.thetadot_min[i]),
        (gain * (limits.theta_max[i] - theta)).min(limits.thetadot_max[i]),
    )
}

/// zhong2021's piecewise form (2.14)–(2.15) of the same bound for joint `i`, as printed.
pub fn piecewise_bound(limits: &JointLimits, i: usize, theta: f64, upsilon: f64) -> (f64, f64) {
    let xi1 = limits.theta_min[i] - limits.thetadot_min[i] / upsilon;
    let xi2 = limits.theta_max[i] - limits.thetadot_max[i] / upsilon;
    let lo = if theta <= xi1 {
        upsilon * (limits.theta_min[i] - theta)
    } else {
        limits.thetadot_min[i]
    };
    let hi = if theta <= xi2 {
        limits.thetadot_max[i]
    } else {
        upsilon * (limits.theta_max[i] - theta)
    };
    (lo, hi)
}

/// Time derivatives of (zeta-_i, zeta+_i) when joint `i` moves at `thetadot`: -gain thetadot
/// on the joint-angle branch, 0 on the velocity-limit branch. At the switch point (a kink) the
/// right-hand derivative (forward in time) is returned: for max{a, b} with a = b,
/// max{a', b'} = max{-gain thetadot, 0}; for min, min{-gain thetadot, 0}.
pub fn merged_bound_dot(
    limits: &JointLimits,
    i: usize,
    theta: f64,
    thetadot: f64,
    gain: f64,
) -> (f64, f64) {
    let d = -gain * thetadot;
    let a = gain * (limits.theta_min[i] - theta);
    let b = limits.thetadot_min[i];
    let lo = if !a.is_finite() {
        0.0
    } else if a > b {
        d
    } else if a < b {
        0.0
    } else {
        d.max(0.0)
    };
    let a = gain * (limits.theta_max[i] - theta);
    let b = limits.thetadot_max[i];
    let hi = if !a.is_finite() {
        0.0
    } else if a < b {
        d
    } else if a > b {
        0.0
    } else {
        d.min(0.0)
    };
    (lo, hi)
}
