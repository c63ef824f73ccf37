//! What the control experiments' noise floor says (`results/control-noise.csv` and the
//! `class_under_noise` column of `results/cycles-trend.csv`, written by crate `control`, whose
//! `noise_floor` module defines the relative change r = |m' - m| / |m| under its rounding-noise
//! probe): how many rows keep max |x - x*| bit for bit, how many move it below [`LISTED`] or
//! at least by it, which rows those are, and which many-cycles runs change class, built into
//! the report model ([`crate::report_model::Control`]); the report's control page formats it.

use records::control::{ControlRow, NoiseRow, TrendRow};

/// A noise floor of at least this much is listed row by row: the report shows three
/// significant digits (`sci`), and a noise floor of 1e-3 or more reaches them.
pub const LISTED: f64 = 1e-3;

/// The noise floor of max |x - x*| over the rows of the control table.
#[derive(Clone, Debug, PartialEq)]
pub struct NoiseSummary<'a> {
    /// Rows with a noise floor.
    pub rows: usize,
    /// Rows whose max |x - x*| is the same bit for bit under the probe (r = 0).
    pub exact: usize,
    /// Rows with 0 < r < [`LISTED`].
    pub below: usize,
    /// Rows with r >= [`LISTED`].
    pub at_least: usize,
    /// Rows with no defined r.
    pub undefined: usize,
    /// Rows whose probe ended with another status than the run.
    pub status_changes: usize,
    /// The rows with r >= [`LISTED`] or another status under the probe, largest r first
    /// (undefined first of all), each beside its control-table row (same key) where there is
    /// one.
    pub listed: Vec<(&'a NoiseRow, Option<&'a ControlRow>)>,
}

/// The control-table row of `runs` that `n` is the noise floor of (the same key).
fn row_of<'a>(runs: &'a [ControlRow], n: &NoiseRow) -> Option<&'a ControlRow> {
    runs.iter().find(|r| {
        r.task == n.task && r.method == n.method && r.h_ms == n.h_ms && r.substeps == n.substeps
    })
}

/// Whether `n`'s probe ended with another status than its run among `runs`.
fn status_changed(runs: &[ControlRow], n: &NoiseRow) -> bool {
    row_of(runs, n).is_some_and(|r| r.status != n.status_under_noise)
}

/// The summary of the noise floor `noise` of the control table's rows `runs`.
pub(crate) fn summarise<'a>(runs: &'a [ControlRow], noise: &'a [NoiseRow]) -> NoiseSummary<'a> {
    let count =
        |f: &dyn Fn(Option<f64>) -> bool| noise.iter().filter(|n| f(n.max_dx_noise)).count();
    let mut listed: Vec<&NoiseRow> = noise
        .iter()
        .filter(|n| n.max_dx_noise.is_some_and(|r| r >= LISTED) || status_changed(runs, n))
        .collect();
    let key = |n: &NoiseRow| n.max_dx_noise.unwrap_or(f64::INFINITY);
    listed.sort_by(|a, b| key(b).total_cmp(&key(a)));
    NoiseSummary {
        rows: noise.len(),
        exact: count(&|r| r == Some(0.0)),
        below: count(&|r| r.is_some_and(|r| r > 0.0 && r < LISTED)),
        at_least: count(&|r| r.is_some_and(|r| r >= LISTED)),
        undefined: count(&|r| r.is_none()),
        status_changes: noise.iter().filter(|n| status_changed(runs, n)).count(),
        listed: listed.into_iter().map(|n| (n, row_of(runs, n))).collect(),
    }
}

/// The many-cycles runs of `trends` whose class changes under the probe, and how many runs
/// have a class as run or under the probe.
pub(crate) fn trend_changes(trends: &[TrendRow]) -> (Vec<&TrendRow>, usize) {
    let changed = trends
        .iter()
        .filter(|r| r.class != r.class_under_noise)
        .collect();
    let classed = trends
        .iter()
        .filter(|r| r.class.is_some() || r.class_under_noise.is_some())
        .count();
    (changed, classed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fixtures::{control_row, noise_row as noise};
    use records::control::{ControlStatus, TrendClass};

    fn row(method: &str) -> ControlRow {
        control_row(method, 1e-3)
    }

    #[test]
    fn the_summary_counts_the_rows_and_lists_the_noisy_ones_largest_first() {
        // A bit for bit, B and E listed, C undefined, D below the listing's bound but listed for
        // its status.
        let runs: Vec<ControlRow> = ["A", "B", "C", "D", "E"].map(row).to_vec();
        let ok = ControlStatus::Ok;
        let noise = vec![
            noise(&runs[0], Some(0.0), ok),
            noise(&runs[1], Some(0.09), ok),
            noise(&runs[2], None, ok),
            noise(&runs[3], Some(3e-5), ControlStatus::Diverged),
            noise(&runs[4], Some(LISTED), ok),
        ];
        let s = summarise(&runs, &noise);
        assert_eq!(
            (
                s.rows,
                s.exact,
                s.below,
                s.at_least,
                s.undefined,
                s.status_changes
            ),
            (5, 1, 1, 2, 1, 1)
        );
        let listed: Vec<&str> = s.listed.iter().map(|(n, _)| n.method.as_str()).collect();
        assert_eq!(listed, ["B", "E", "D"]);
        assert!(s.listed.iter().all(|(n, r)| r.unwrap().method == n.method));
    }

    #[test]
    fn the_classes_that_change_under_the_probe() {
        let trend = |method: &str, class, under| TrendRow {
            task: "e / v".to_string(),
            scheme: "s".to_string(),
            method: method.to_string(),
            h_ms: Some(1.0),
            status: ControlStatus::Ok,
            failure: None,
            cycles: 20,
            drift_first: Some(0.1),
            drift_last: Some(0.2),
            rate: Some(0.01),
            class,
            class_under_noise: under,
            rate_noise: Some(0.0),
        };
        let rows = [
            trend("A", Some(TrendClass::Bounded), Some(TrendClass::Bounded)),
            trend(
                "B",
                Some(TrendClass::Bounded),
                Some(TrendClass::Accumulating),
            ),
            trend("C", None, None),
            trend("D", Some(TrendClass::LimitCycle), None),
        ];
        let (changed, classed) = trend_changes(&rows);
        let methods: Vec<&str> = changed.iter().map(|r| r.method.as_str()).collect();
        assert_eq!((methods, classed), (vec!["B", "D"], 3));
    }
}
