//! The noise floor of a run's results: how far each deterministic metric moves under the
//! rounding-noise probe (module `rounding`: the same run with its joint angles moved by one ulp
//! after every tick), as a relative change.
//!
//! For a metric m of a run and m' of its probe,
//!
//!   r(m, m') = 0                  when m = m' (the same number, or both empty),
//!   r(m, m') = |m' - m| / |m|     when both are finite and m != 0,
//!   r(m, m') = empty              otherwise: only one is empty, either is not finite, or
//!                                 m = 0 != m' (no relative change is defined).
//!
//! A metric whose r is 1e-p is reproducible to about its first p significant digits: the
//! digits beyond are rounding noise, which another order of the same floating-point operations
//! may change. The row of a run is [`records::control::NoiseRow`]; counts (ticks, iterations,
//! products) are compared as numbers too.

use records::control::{ControlRow, NoiseRow};

/// r(m, `probe`) of module docs, for `m` the run's value and `probe` the probe's.
pub(crate) fn relative_change(m: Option<f64>, probe: Option<f64>) -> Option<f64> {
    match (m, probe) {
        (None, None) => Some(0.0),
        (Some(a), Some(b)) if a == b => Some(0.0),
        (Some(a), Some(b)) if a.is_finite() && b.is_finite() && a != 0.0 => {
            Some((b - a).abs() / a.abs())
        }
        _ => None,
    }
}

/// The noise floor of the run of `row`, from the row of its probe `probe` (module docs).
pub(crate) fn noise_row(row: &ControlRow, probe: &ControlRow) -> NoiseRow {
    let r = |a: f64, b: f64| relative_change(Some(a), Some(b));
    let count = |v: usize| v as f64;
    NoiseRow {
        task: row.task.clone(),
        paper: row.paper.clone(),
        scheme: row.scheme.clone(),
        method: row.method.clone(),
        family: row.family,
        h_ms: row.h_ms,
        substeps: row.substeps,
        status_under_noise: probe.status,
        stopped_at_noise: relative_change(row.stopped_at, probe.stopped_at),
        ticks_noise: r(count(row.ticks), count(probe.ticks)),
        max_track_err_noise: r(row.max_track_err, probe.max_track_err),
        rms_track_err_noise: r(row.rms_track_err, probe.rms_track_err),
        max_dx_noise: r(row.max_dx, probe.max_dx),
        rms_dx_noise: r(row.rms_dx, probe.rms_dx),
        max_dx_settled_noise: r(row.max_dx_settled, probe.max_dx_settled),
        drift_noise: relative_change(row.drift, probe.drift),
        products_mean_noise: relative_change(row.products_mean, probe.products_mean),
        products_max_noise: relative_change(
            row.products_max.map(|p| p as f64),
            probe.products_max.map(|p| p as f64),
        ),
        iterations_mean_noise: r(row.iterations_mean, probe.iterations_mean),
        iterations_max_noise: r(
            f64::from(row.iterations_max),
            f64::from(probe.iterations_max),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_change_of_numbers_and_its_edge_cases() {
        // Equal, both empty, both zero (of either sign): no change.
        assert_eq!(relative_change(Some(0.25), Some(0.25)), Some(0.0));
        assert_eq!(relative_change(None, None), Some(0.0));
        assert_eq!(relative_change(Some(0.0), Some(-0.0)), Some(0.0));
        // |m' - m| / |m|, relative to the run's value, of either sign.
        assert_eq!(relative_change(Some(2.0), Some(2.5)), Some(0.25));
        assert_eq!(relative_change(Some(-2.0), Some(-1.5)), Some(0.25));
        assert_eq!(relative_change(Some(2.5), Some(2.0)), Some(0.2));
        assert_eq!(
            relative_change(Some(1.0), Some(1.0f64.next_up())),
            Some(f64::EPSILON)
        );
        // Undefined: one side empty, m = 0 != m', a value not finite.
        assert_eq!(relative_change(Some(1.0), None), None);
        assert_eq!(relative_change(None, Some(1.0)), None);
        assert_eq!(relative_change(Some(0.0), Some(1e-300)), None);
        assert_eq!(relative_change(Some(f64::NAN), Some(f64::NAN)), None);
        assert_eq!(relative_change(Some(1.0), Some(f64::NAN)), None);
        assert_eq!(relative_change(Some(f64::INFINITY), Some(1.0)), None);
        assert_eq!(relative_change(Some(1.0), Some(f64::INFINITY)), None);
    }

    #[test]
    fn a_rows_noise_floor_compares_each_metric_with_the_probes() {
        let row = ControlRow {
            task: "e / v".to_string(),
            paper: "p".to_string(),
            scheme: "s".to_string(),
            method: "M4".to_string(),
            family: records::control::Family::Numerical,
            h_ms: 1.0,
            substeps: 1,
            status: records::control::ControlStatus::Ok,
            stopped_at: None,
            ticks: 100,
            solve_p50_us: 1.0,
            solve_p99_us: 2.0,
            solve_max_us: 3.0,
            tick_p50_us: 1.0,
            tick_p99_us: 2.0,
            tick_max_us: 3.0,
            max_track_err: 1e-3,
            rms_track_err: 5e-4,
            max_dx: 1e-9,
            rms_dx: 2e-10,
            max_dx_settled: 0.0,
            drift: Some(0.5),
            products_mean: Some(10.0),
            products_max: Some(40),
            iterations_mean: 4.0,
            iterations_max: 10,
        };
        let probe = ControlRow {
            status: records::control::ControlStatus::Diverged,
            stopped_at: Some(0.05),
            ticks: 50,
            solve_p50_us: 7.0,
            max_dx: 1.5e-9,
            max_dx_settled: 1e-12,
            drift: None,
            products_max: Some(50),
            iterations_max: 12,
            ..row.clone()
        };
        let n = noise_row(&row, &probe);
        assert_eq!(
            (n.task.as_str(), n.method.as_str(), n.h_ms, n.substeps),
            ("e / v", "M4", 1.0, 1)
        );
        assert_eq!(
            n.status_under_noise,
            records::control::ControlStatus::Diverged
        );
        assert_eq!(n.stopped_at_noise, None);
        assert_eq!(n.ticks_noise, Some(0.5));
        assert_eq!(n.max_track_err_noise, Some(0.0));
        assert_eq!(n.rms_track_err_noise, Some(0.0));
        assert_eq!(n.max_dx_noise, relative_change(Some(1e-9), Some(1.5e-9)));
        assert!((n.max_dx_noise.unwrap() - 0.5).abs() < 1e-15);
        assert_eq!(n.rms_dx_noise, Some(0.0));
        assert_eq!(n.max_dx_settled_noise, None);
        assert_eq!(n.drift_noise, None);
        assert_eq!(n.products_mean_noise, Some(0.0));
        assert_eq!(n.products_max_noise, Some(0.25));
        assert_eq!(n.iterations_mean_noise, Some(0.0));
        assert_eq!(n.iterations_max_noise, Some(0.2));
    }
}
