//! Axis ranges: padded linear ranges, whole-decade log ranges that ignore zeros, and equal-aspect
//! ranges for the task-space path.

use std::ops::Range;

/// Fraction of the data span added on each side of a linear axis.
const PAD: f64 = 0.05;

/// The largest magnitude an axis end may have: the span of any two ends is then finite
/// (plotters computes it for its key points, and loops forever on an infinite one).
pub const LIMIT: f64 = f64::MAX / 4.0;

/// The exponents a log axis may reach (10^308 is finite, 10^309 is not; 10^-307 is normal).
const LOG_EXPONENTS: (f64, f64) = (-307.0, 308.0);

/// The most decades a log axis spans: the ratio of its ends stays finite (plotters counts its
/// decades from that ratio, and loops for ever on an infinite count).
const MAX_DECADES: f64 = 300.0;

/// `range` with both ends within [-[`LIMIT`], [`LIMIT`]] and the start below the end: data
/// beyond the limit (finite values near f64::MAX) is clipped, never given an infinite span.
pub fn bounded(range: Range<f64>) -> Range<f64> {
    let clamp = |v: f64| {
        if v.is_nan() {
            0.0
        } else {
            v.clamp(-LIMIT, LIMIT)
        }
    };
    let (start, end) = (clamp(range.start), clamp(range.end));
    if start < end {
        start..end
    } else if end > 0.0 {
        end / 2.0..end
    } else if start < 0.0 {
        start..start / 2.0
    } else {
        -1.0..1.0
    }
}

/// Smallest and largest finite value, if any.
fn extent(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold(None, |acc, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// A linear axis covering the finite `values` with a small margin; a constant series gets a
/// unit-wide (or 10 %-wide) range around its value, no data gives [0, 1]; [`bounded`].
pub fn linear(values: impl IntoIterator<Item = f64>) -> Range<f64> {
    bounded(match extent(values) {
        None => 0.0..1.0,
        Some((lo, hi)) if hi - lo <= f64::EPSILON * hi.abs().max(lo.abs()).max(1e-300) => {
            let half = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            lo - half..hi + half
        }
        Some((lo, hi)) => {
            let pad = PAD * (hi - lo);
            lo - pad..hi + pad
        }
    })
}

/// A log axis from the decade below the smallest positive finite value to the decade above the
/// largest. Zeros and negatives are left out (they cannot be drawn on a log axis); with no
/// positive value the axis is [1e-16, 1]. The decades stay within 10^-307 .. 10^308, at most
/// [`MAX_DECADES`] of them (the smallest values are then clipped).
pub fn log(values: impl IntoIterator<Item = f64>) -> Range<f64> {
    match extent(values.into_iter().filter(|v| *v > 0.0)) {
        None => 1e-16..1.0,
        Some((lo, hi)) => {
            let (min, max) = LOG_EXPONENTS;
            let lo = lo.log10().floor().clamp(min, max - 1.0);
            let hi = hi.log10().ceil().clamp(min, max);
            let lo = lo.max(hi - MAX_DECADES);
            10f64.powf(lo)..10f64.powf(if hi > lo { hi } else { lo + 1.0 })
        }
    }
}

/// Ticks of a log axis over `range` (from [`log`]): 1, 2 and 5 times each power of ten when the
/// range spans at most two decades, 1 and 3 times up to four, the powers of ten beyond.
pub fn log_ticks(range: &Range<f64>) -> Vec<f64> {
    let (lo, hi) = (range.start.log10().floor(), range.end.log10().ceil());
    let mantissas: &[f64] = match hi - lo {
        d if d <= 2.0 => &[1.0, 2.0, 5.0],
        d if d <= 4.0 => &[1.0, 3.0],
        _ => &[1.0],
    };
    let mut out = Vec::new();
    let mut e = lo;
    while e <= hi {
        for m in mantissas {
            // Parsed from its decimal form: 3e-4 exactly, not 3 * 1e-4 with its rounding.
            let v: f64 = format!("{m}e{e}").parse().unwrap_or(m * 10f64.powf(e));
            if v >= range.start * (1.0 - 1e-9) && v <= range.end * (1.0 + 1e-9) {
                out.push(v);
            }
        }
        e += 1.0;
    }
    out
}

/// Widens the shorter of two linear ranges (about its centre) so that one metre spans as many
/// pixels along x as along y on a plot of `pixels` = (width, height); [`bounded`].
pub fn equal_aspect(x: Range<f64>, y: Range<f64>, pixels: (u32, u32)) -> (Range<f64>, Range<f64>) {
    let (w, h) = (f64::from(pixels.0.max(1)), f64::from(pixels.1.max(1)));
    let per_pixel = ((x.end - x.start) / w).max((y.end - y.start) / h);
    let around = |r: Range<f64>, px: f64| {
        let (mid, half) = ((r.start + r.end) / 2.0, per_pixel * px / 2.0);
        bounded(mid - half..mid + half)
    };
    (around(x, w), around(y, h))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_ranges_skip_zeros_and_cover_whole_decades() {
        assert_eq!(log([0.0, 3e-7, 2e-4, f64::NAN]), 1e-7..1e-3);
        assert_eq!(log([0.0]), 1e-16..1.0);
        assert_eq!(log([1e-5]), 1e-5..1e-4);
    }

    #[test]
    fn log_ticks_are_dense_on_short_ranges() {
        assert_eq!(log_ticks(&(0.1..1.0)), vec![0.1, 0.2, 0.5, 1.0]);
        assert_eq!(log_ticks(&(1e-3..1e-1)).len(), 7);
        assert_eq!(
            log_ticks(&(1e-4..1.0)),
            vec![1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0]
        );
        assert_eq!(log_ticks(&(1e-9..1.0)).len(), 10);
    }

    #[test]
    fn linear_ranges_pad_and_survive_constants() {
        assert_eq!(linear([0.0, 10.0]), -0.5..10.5);
        assert_eq!(linear([0.0, 0.0]), -1.0..1.0);
        assert_eq!(linear([f64::INFINITY]), 0.0..1.0);
    }

    #[test]
    fn extreme_finite_values_give_finite_spans() {
        let finite_span = |r: &Range<f64>| (r.end - r.start).is_finite() && r.start < r.end;
        for values in [
            vec![9e307, -9e307],
            vec![f64::MAX, f64::MIN],
            vec![f64::MAX],
            vec![f64::MIN, f64::MIN],
            vec![1e300, 1e300 * 1.0000001],
        ] {
            let r = linear(values.iter().copied());
            assert!(finite_span(&r), "{values:?}: {r:?}");
            let (x, y) = equal_aspect(r.clone(), 0.0..1.0, (100, 400));
            assert!(
                finite_span(&x) && finite_span(&y),
                "{values:?}: {x:?} {y:?}"
            );
        }
        for values in [vec![f64::MAX], vec![f64::MIN_POSITIVE / 1e10, 1e300]] {
            let r = log(values.iter().copied());
            assert!(
                r.start > 0.0 && (r.end / r.start).is_finite() && r.start < r.end,
                "{r:?}"
            );
        }
        assert_eq!(bounded(0.0..f64::MAX), 0.0..LIMIT);
        assert_eq!(bounded(f64::NAN..f64::NAN), -1.0..1.0);
        // Ordinary data is untouched.
        assert_eq!(linear([0.0, 10.0]), -0.5..10.5);
    }

    #[test]
    fn equal_aspect_gives_equal_metres_per_pixel() {
        let (x, y) = equal_aspect(0.0..1.0, 0.0..1.0, (200, 100));
        assert_eq!((x.end - x.start) / 200.0, (y.end - y.start) / 100.0);
        assert_eq!(y, 0.0..1.0);
    }
}
