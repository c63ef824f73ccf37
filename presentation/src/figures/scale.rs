//! Axis ranges: padded linear ranges, whole-decade log ranges that ignore zeros, and equal-aspect
//! ranges for the task-space path.

use std::ops::Range;

/// Fraction of the data span added on each side of a linear axis.
const PAD: f64 = 0.05;

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
/// unit-wide (or 10 %-wide) range around its value, no data gives [0, 1].
pub fn linear(values: impl IntoIterator<Item = f64>) -> Range<f64> {
    match extent(values) {
        None => 0.0..1.0,
        Some((lo, hi)) if hi - lo <= f64::EPSILON * hi.abs().max(lo.abs()).max(1e-300) => {
            let half = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            lo - half..hi + half
        }
        Some((lo, hi)) => {
            let pad = PAD * (hi - lo);
            lo - pad..hi + pad
        }
    }
}

/// A log axis from the decade below the smallest positive finite value to the decade above the
/// largest. Zeros and negatives are left out (they cannot be drawn on a log axis); with no
/// positive value the axis is [1e-16, 1].
pub fn log(values: impl IntoIterator<Item = f64>) -> Range<f64> {
    match extent(values.into_iter().filter(|v| *v > 0.0)) {
        None => 1e-16..1.0,
        Some((lo, hi)) => {
            let (lo, hi) = (lo.log10().floor(), hi.log10().ceil());
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
/// pixels along x as along y on a plot of `pixels` = (width, height).
pub fn equal_aspect(x: Range<f64>, y: Range<f64>, pixels: (u32, u32)) -> (Range<f64>, Range<f64>) {
    let (w, h) = (f64::from(pixels.0.max(1)), f64::from(pixels.1.max(1)));
    let per_pixel = ((x.end - x.start) / w).max((y.end - y.start) / h);
    let around = |r: Range<f64>, px: f64| {
        let (mid, half) = ((r.start + r.end) / 2.0, per_pixel * px / 2.0);
        mid - half..mid + half
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
    fn equal_aspect_gives_equal_metres_per_pixel() {
        let (x, y) = equal_aspect(0.0..1.0, 0.0..1.0, (200, 100));
        assert_eq!((x.end - x.start) / 200.0, (y.end - y.start) / 100.0);
        assert_eq!(y, 0.0..1.0);
    }
}
