//! The sign-power e -> abs(e)^r sgn(e) and its smoothed form, shared by kong2019's finite-time
//! scheme (its c(e), kong2019 (5)) and the finite-time networks' activation (kong2019 (6), (20)).
//!
//! The smoothed form e (e^2 + delta^2)^((r - 1)/2) is analytic for delta > 0, odd, monotone for
//! r > 0, and tends to abs(e)^r sgn(e) as delta -> 0; its slope is
//! (e^2 + delta^2)^((r - 3)/2) (r e^2 + delta^2).

/// Smoothed sign-power e (e^2 + delta^2)^((r - 1)/2) (exact abs(e)^r sgn(e) for delta = 0).
#[inline]
pub fn sign_power(e: f64, r: f64, delta: f64) -> f64 {
    if delta > 0.0 {
        e * (e * e + delta * delta).powf(0.5 * (r - 1.0))
    } else if e == 0.0 {
        0.0
    } else {
        e.abs().powf(r).copysign(e)
    }
}

/// d/de of [`sign_power()`].
#[inline]
pub fn sign_power_slope(e: f64, r: f64, delta: f64) -> f64 {
    if delta > 0.0 {
        let s = e * e + delta * delta;
        s.powf(0.5 * (r - 3.0)) * (r * e * e + delta * delta)
    } else {
        r * e.abs().max(SIGN_POWER_MIN_ABS).powf(r - 1.0)
    }
}

/// Floor on abs(e) where the sign-power slope r abs(e)^(r-1) is evaluated (r < 1 makes it
/// infinite at 0).
pub const SIGN_POWER_MIN_ABS: f64 = 1e-12;
