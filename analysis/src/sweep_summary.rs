//! A large sweep's summary for its page: how many runs, how many failed, the runs at its
//! extremes (largest and smallest drift norm ||theta(T) - theta(0)|| and position error
//! max_t |r*(t) - f(theta(t))|, over the completed runs that have the metric: [`extreme`]) and
//! its first failures in key order.

use records::RunRow;

/// The most failures a summary lists (the count gives the rest).
pub const LISTED_FAILURES: usize = 10;

/// Which extreme a run is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extreme {
    /// The largest drift norm.
    LargestDrift,
    /// The smallest drift norm.
    SmallestDrift,
    /// The largest position error.
    LargestError,
    /// The smallest position error.
    SmallestError,
}

impl Extreme {
    /// Every extreme, in the order a page lists them.
    pub const ALL: [Extreme; 4] = [
        Extreme::LargestDrift,
        Extreme::SmallestDrift,
        Extreme::LargestError,
        Extreme::SmallestError,
    ];

    /// The extreme in words.
    pub fn name(self) -> &'static str {
        match self {
            Extreme::LargestDrift => "largest drift norm",
            Extreme::SmallestDrift => "smallest drift norm",
            Extreme::LargestError => "largest position error",
            Extreme::SmallestError => "smallest position error",
        }
    }

    /// The metric it ranks by, and whether the largest value is the extreme.
    fn metric(self) -> (fn(&RunRow) -> Option<f64>, bool) {
        match self {
            Extreme::LargestDrift => (|r| r.drift_norm, true),
            Extreme::SmallestDrift => (|r| r.drift_norm, false),
            Extreme::LargestError => (|r| r.max_pos_err, true),
            Extreme::SmallestError => (|r| r.max_pos_err, false),
        }
    }
}

/// A sweep's summary (module docs).
#[derive(Clone, Debug)]
pub struct SweepSummary<'a> {
    /// The number of runs.
    pub runs: usize,
    /// The number of failed runs.
    pub failed: usize,
    /// Each extreme with its run (an extreme no completed run has a finite metric for is left
    /// out); the first run in key order wins a tie.
    pub extremes: Vec<(Extreme, &'a RunRow)>,
    /// The first [`LISTED_FAILURES`] failed runs, in the order given.
    pub failures: Vec<&'a RunRow>,
}

/// The index in `runs` of the run at extreme `e`: among the completed runs with a finite
/// metric, the largest or smallest; the first in the order given wins a tie; `None` when no
/// run qualifies.
pub fn extreme(runs: &[&RunRow], e: Extreme) -> Option<usize> {
    let (metric, largest) = e.metric();
    let mut best: Option<(usize, f64)> = None;
    for (i, r) in runs.iter().enumerate().filter(|(_, r)| r.completed()) {
        let Some(v) = metric(r).filter(|v| v.is_finite()) else {
            continue;
        };
        if best.is_none_or(|(_, b)| if largest { v > b } else { v < b }) {
            best = Some((i, v));
        }
    }
    best.map(|(i, _)| i)
}

/// The summary of `runs` (one experiment's, in key order).
pub fn summary<'a>(runs: &[&'a RunRow]) -> SweepSummary<'a> {
    let extremes = Extreme::ALL
        .into_iter()
        .filter_map(|e| Some((e, runs[extreme(runs, e)?])))
        .collect();
    let failed: Vec<&RunRow> = runs.iter().copied().filter(|r| !r.completed()).collect();
    SweepSummary {
        runs: runs.len(),
        failed: failed.len(),
        extremes,
        failures: failed.into_iter().take(LISTED_FAILURES).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use records::Status;
    use spec::RunKey;
    use spec::SolverKind;

    fn run(i: usize, drift: Option<f64>, error: Option<f64>, failed: bool) -> RunRow {
        let key = RunKey::parse(&format!("s / v{i} / exact")).unwrap();
        let mut r = RunRow::blank(&key, SolverKind::Exact);
        r.drift_norm = drift;
        r.max_pos_err = error;
        if failed {
            r.status = Status::Failed;
        }
        r
    }

    #[test]
    fn extremes_are_over_completed_runs_and_failures_are_capped() {
        let mut rows = vec![
            run(0, Some(2.0), Some(1e-3), false),
            run(1, Some(1.0), Some(5e-3), false),
            // A failed run's partial metrics are no extreme.
            run(2, Some(9.0), Some(1.0), true),
            run(3, Some(2.0), None, false),
            run(4, Some(f64::NAN), Some(1e-4), false),
        ];
        rows.extend((5..30).map(|i| run(i, None, None, true)));
        let refs: Vec<&RunRow> = rows.iter().collect();
        let s = summary(&refs);
        assert_eq!((s.runs, s.failed), (30, 26));
        let at = |e: Extreme| s.extremes.iter().find(|(x, _)| *x == e).unwrap().1;
        assert_eq!(
            at(Extreme::LargestDrift).variant_id.as_str(),
            "v0",
            "first of a tie"
        );
        assert_eq!(at(Extreme::SmallestDrift).variant_id.as_str(), "v1");
        assert_eq!(at(Extreme::LargestError).variant_id.as_str(), "v1");
        assert_eq!(at(Extreme::SmallestError).variant_id.as_str(), "v4");
        assert_eq!(s.failures.len(), LISTED_FAILURES);
        assert_eq!(s.failures[0].variant_id.as_str(), "v2");
        let none = summary(&[]);
        assert!(none.extremes.is_empty() && none.failures.is_empty());
    }
}
