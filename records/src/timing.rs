//! `results/leaderboard-timing.csv`: the runs whose times are compared (the leaderboard's, and
//! the runs the papers publish a MATLAB time for) timed alone, one [`TimingRow`] per run.
//!
//! The reproduction runs everything in parallel on every core, so the `sim_s` and `wall_s` of
//! `results/runs.csv` include whatever the neighbouring runs did to the caches and the clock.
//! After it, each timed run is run again [`REPETITIONS`] times, one run at a time on one
//! thread, and the median, minimum and maximum of its simulation time (`sim_s`) and whole-run
//! time (`wall_s`) are kept, with the machine (as `reproduce::cost::machine` reads it)
//! and the code revision. The leaderboard ranks by the median ([`Timings::sim_s`]); the spread
//! (max − min) / median says how much one repetition can be trusted.
//!
//! The times are the only columns of the suite that are not deterministic: the repetitions
//! recompute the same run (the same counts, drifts and scores as `runs.csv`).

use crate::table::Row;
use serde::{Deserialize, Serialize};
use spec::ids::{ExperimentId, SolverId, VariantId};
use spec::RunKey;
use std::collections::BTreeMap;

/// The file name inside `results/`.
pub const FILE: &str = "leaderboard-timing.csv";

/// Repetitions per timed run: the median of three drops one outlier (a run slowed by whatever
/// else the machine did) at three times a run's cost; the minimum and maximum show the spread.
pub const REPETITIONS: usize = 3;

/// One run timed alone.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TimingRow {
    /// The run's experiment id.
    pub experiment: ExperimentId,
    /// The run's variant id.
    pub variant_id: VariantId,
    /// The run's solver id.
    pub solver_id: SolverId,
    /// Times the run was repeated alone ([`REPETITIONS`]).
    pub repetitions: usize,
    /// Simulation time (s, `sim_s` of a run): median, minimum and maximum.
    pub sim_s_median: f64,
    /// Fastest repetition's simulation time (s).
    pub sim_s_min: f64,
    /// Slowest repetition's simulation time (s).
    pub sim_s_max: f64,
    /// Whole-run time (s, `wall_s`: with the observation and scoring).
    pub wall_s_median: f64,
    /// Fastest repetition's whole-run time (s).
    pub wall_s_min: f64,
    /// Slowest repetition's whole-run time (s).
    pub wall_s_max: f64,
    /// CPU model and logical cores (`reproduce::cost::machine`).
    pub machine: String,
    /// Logical cores available.
    pub cores: usize,
    /// The code revision timed (as `runs.csv`'s `git_rev`).
    pub git_rev: String,
}

impl Row for TimingRow {}

/// Median, minimum and maximum of non-empty samples (the median of an even count is the mean
/// of the middle two).
pub fn summary(samples: &[f64]) -> (f64, f64, f64) {
    assert!(!samples.is_empty(), "no timing samples");
    let mut v = samples.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    let median = if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    };
    (median, v[0], v[n - 1])
}

impl TimingRow {
    /// The row of `key` from its repetitions' (`sim_s`, `wall_s`).
    pub fn from_samples(
        key: &RunKey,
        samples: &[(f64, f64)],
        machine: &str,
        cores: usize,
        git_rev: &str,
    ) -> Self {
        let sim: Vec<f64> = samples.iter().map(|s| s.0).collect();
        let wall: Vec<f64> = samples.iter().map(|s| s.1).collect();
        let (sim_s_median, sim_s_min, sim_s_max) = summary(&sim);
        let (wall_s_median, wall_s_min, wall_s_max) = summary(&wall);
        TimingRow {
            experiment: key.experiment.clone(),
            variant_id: key.variant.clone(),
            solver_id: key.solver.clone(),
            repetitions: samples.len(),
            sim_s_median,
            sim_s_min,
            sim_s_max,
            wall_s_median,
            wall_s_min,
            wall_s_max,
            machine: machine.to_string(),
            cores,
            git_rev: git_rev.to_string(),
        }
    }

    /// The run's identity.
    pub fn key(&self) -> RunKey {
        RunKey::new(
            self.experiment.clone(),
            self.variant_id.clone(),
            self.solver_id.clone(),
        )
    }

    /// (max − min) / median of `sim_s` (0 for a zero median).
    pub fn sim_spread(&self) -> f64 {
        spread(self.sim_s_min, self.sim_s_max, self.sim_s_median)
    }

    /// (max − min) / median of `wall_s`.
    pub fn wall_spread(&self) -> f64 {
        spread(self.wall_s_min, self.wall_s_max, self.wall_s_median)
    }
}

fn spread(min: f64, max: f64, median: f64) -> f64 {
    if median > 0.0 {
        (max - min) / median
    } else {
        0.0
    }
}

/// The alone-timed runs by key.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Timings {
    rows: BTreeMap<RunKey, TimingRow>,
}

impl Timings {
    /// The timings of `rows`, by key (a later row of a key replaces an earlier one).
    pub fn new(rows: Vec<TimingRow>) -> Self {
        Timings {
            rows: rows.into_iter().map(|r| (r.key(), r)).collect(),
        }
    }

    /// The row of `key`, if it was timed.
    pub fn get(&self, key: &RunKey) -> Option<&TimingRow> {
        self.rows.get(key)
    }

    /// The median `sim_s` of `key` timed alone.
    pub fn sim_s(&self, key: &RunKey) -> Option<f64> {
        self.get(key).map(|r| r.sim_s_median)
    }

    /// Whether no run was timed.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Every row, sorted by key.
    pub fn rows(&self) -> impl Iterator<Item = &TimingRow> {
        self.rows.values()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_min_max_and_spread() {
        assert_eq!(summary(&[3.0, 1.0, 2.0]), (2.0, 1.0, 3.0));
        assert_eq!(summary(&[4.0, 1.0]), (2.5, 1.0, 4.0));
        let key = RunKey::from_ids("e", "v", "s").unwrap();
        let r = TimingRow::from_samples(&key, &[(0.2, 1.0), (0.1, 3.0), (0.4, 2.0)], "cpu", 2, "r");
        assert_eq!((r.sim_s_median, r.sim_s_min, r.sim_s_max), (0.2, 0.1, 0.4));
        assert_eq!((r.wall_s_median, r.repetitions), (2.0, 3));
        assert!((r.sim_spread() - 1.5).abs() < 1e-12);
        assert_eq!(r.key(), key);
    }
}
