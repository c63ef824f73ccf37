//! The percentile of a set of values, the one definition of the workspace: the leaderboard's
//! medians and 95th percentiles, the cost harness's summaries (`results/dof-cost.csv`) and the
//! control loop's tick latencies all use it.
//!
//! The p-quantile (0 <= p <= 1) is linearly interpolated between the closest ranks, numpy's
//! default (`numpy.percentile(..., method="linear")`): with the values sorted, v_0 <= ... <=
//! v_{n-1}, position pos = p (n - 1), lo = floor(pos),
//!
//! ```text
//! percentile(v, p) = v_lo + (pos - lo) (v_{lo+1} - v_lo)      (v_n read as v_{n-1}),
//! ```
//!
//! so the median of an even count is the mean of the two middle values, and the Python package
//! (numpy) computes the same numbers from the same rows.

/// The `p`-quantile of `values` (any order; `p` clamped to [0, 1]); NaN for no values.
pub fn percentile(values: &[f64], p: f64) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n => {
            let pos = p.clamp(0.0, 1.0) * (n - 1) as f64;
            let lo = pos.floor() as usize;
            let hi = (lo + 1).min(n - 1);
            v[lo] + (pos - lo as f64) * (v[hi] - v[lo])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1.0)
    }

    #[test]
    fn percentiles_interpolate_between_ranks() {
        let v = [5.0, 1.0, 4.0, 2.0, 3.0];
        assert!(close(percentile(&v, 0.5), 3.0));
        // position 0.95 * 4 = 3.8: 4 + 0.8 (5 - 4).
        assert!(close(percentile(&v, 0.95), 4.8));
        assert!(close(percentile(&[7.0], 0.95), 7.0));
        // Even count: the mean of the middle two; the extremes are p = 0 and 1.
        assert!(close(percentile(&[4.0, 1.0, 3.0, 2.0], 0.5), 2.5));
        assert_eq!((percentile(&v, 0.0), percentile(&v, 1.0)), (1.0, 5.0));
        assert!(percentile(&[], 0.5).is_nan());
    }
}
