//! The trend of the drift over many cycles.
//!
//! With d_c = |theta(c T) - theta_0|_2 after cycle c = 1 ... K and the per-cycle change
//! delta_c = |theta(c T) - theta((c-1) T)|_2, the run is classed as
//!
//! - **limit cycle** when the motion repeats itself: the last change delta_K is below
//!   [`REPEAT_TOL`] rad or below 1e-3 of the first cycle's drift d_1;
//! - **accumulating** when the least-squares line d_c = a + b c through the second half of the
//!   cycles (c > K/2) rises by at least 10 % of d_K over that half (b (K - K/2) >= 0.1 d_K)
//!   and b > 0: the drift grows with the number of cycles, at the fitted rate b (rad/cycle);
//! - **bounded** otherwise (the drift neither settles to a repeat nor keeps growing).
//!
//! The fitted rate b is reported for every class.

pub use records::control::TrendClass;

/// The per-cycle change below which the motion repeats itself (rad).
pub const REPEAT_TOL: f64 = 1e-9;

/// A drift sequence's class and fitted rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trend {
    pub class: TrendClass,
    /// Slope b of the line through the second half (rad/cycle).
    pub rate: f64,
}

/// The least-squares slope of (c, d_c) over `points`.
fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx > 0.0 {
        sxy / sxx
    } else {
        0.0
    }
}

/// The trend of `drift` (d_1 ... d_K) with the per-cycle changes `change` (delta_1 ...
/// delta_K); `None` with fewer than three cycles.
pub fn classify(drift: &[f64], change: &[f64]) -> Option<Trend> {
    let k = drift.len();
    if k < 3 {
        return None;
    }
    let half: Vec<(f64, f64)> = drift
        .iter()
        .enumerate()
        .skip(k / 2)
        .map(|(i, d)| ((i + 1) as f64, *d))
        .collect();
    let rate = slope(&half);
    let last_change = change[k - 1];
    let class = if last_change <= REPEAT_TOL.max(1e-3 * drift[0]) {
        TrendClass::LimitCycle
    } else if rate > 0.0 && rate * half.len() as f64 >= 0.1 * drift[k - 1] {
        TrendClass::Accumulating
    } else {
        TrendClass::Bounded
    };
    Some(Trend { class, rate })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes() {
        let changes = |d: &[f64]| -> Vec<f64> {
            (0..d.len())
                .map(|i| (d[i] - if i == 0 { 0.0 } else { d[i - 1] }).abs())
                .collect()
        };
        let linear: Vec<f64> = (1..=20).map(|c| 0.01 * c as f64).collect();
        let t = classify(&linear, &changes(&linear)).unwrap();
        assert_eq!(t.class, TrendClass::Accumulating);
        assert!((t.rate - 0.01).abs() < 1e-12);
        let settled: Vec<f64> = (1..=20).map(|c| 0.1 * (1.0 - 0.2f64.powi(c))).collect();
        assert_eq!(
            classify(&settled, &changes(&settled)).unwrap().class,
            TrendClass::LimitCycle
        );
        let wobble: Vec<f64> = (1..=20).map(|c| 0.1 + 0.01 * (c as f64).sin()).collect();
        assert_eq!(
            classify(&wobble, &changes(&wobble)).unwrap().class,
            TrendClass::Bounded
        );
        assert!(classify(&[0.1, 0.2], &[0.1, 0.1]).is_none());
    }
}
