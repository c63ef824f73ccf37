//! `benches/results/throughput.csv` and `throughput-profile.csv`: one thread's throughput on a
//! kong2019 ZNN sweep at two revisions, side by side, and where a right-hand side's time goes
//! (both written by `benches/throughput/kong2019_sweep.sh`, which alternates the revisions pass
//! by pass on one pinned CPU).
//!
//! A revision's throughput is the median over its passes of runs / user CPU seconds (the
//! process's, observation and scoring included); its cost per right-hand side (RHS) the median
//! of user CPU seconds / RHS evaluations. The speed-up is new / old throughput; issue 43's target
//! is at least [`TARGET_SPEEDUP`]. Instruction counts are kept where the machine exposes them.
//!
//! The profile splits the new revision's samples into parts: `rhs` (the coupled right-hand
//! side: kinematics, path, QP assembly, the network and its KKT solve), `integrator`, `observer`
//! and `other`; each category's CPU time per RHS is its share times the pass's user CPU seconds
//! over its RHS evaluations. The RHS part is the floor a run's RHS count requires; the rest is
//! what a run spends beyond it.

use records::table::Row;
use serde::{Deserialize, Serialize};

/// The throughput file's name inside `benches/results/`.
pub const FILE: &str = "throughput.csv";
/// The profile file's name inside `benches/results/`.
pub const PROFILE_FILE: &str = "throughput-profile.csv";
/// Issue 43's target: new / old runs per CPU second.
pub const TARGET_SPEEDUP: f64 = 2.0;
/// The profile's part that is the right-hand side itself (the floor).
pub const RHS_PART: &str = "rhs";

/// One pass of one revision.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ThroughputRow {
    /// `old` or `new`.
    pub revision: String,
    /// The revision's commit (12 hex digits).
    pub commit: String,
    /// The pass (1-based).
    pub pass: usize,
    /// Runs of the sweep.
    pub runs: usize,
    /// User CPU seconds of the process.
    pub user_s: f64,
    /// Wall seconds of the process.
    pub wall_s: f64,
    /// User-space instructions (empty where the machine has no hardware counters).
    pub instructions: Option<f64>,
    /// User-space cycles (empty as `instructions`).
    pub cycles: Option<f64>,
    /// RHS evaluations over the runs.
    pub rhs_evals: f64,
    /// Accepted steps over the runs.
    pub steps: f64,
    /// Sum of the runs' `sim_s`.
    pub sum_sim_s: f64,
    /// Sum of the runs' `wall_s`.
    pub sum_wall_s: f64,
    /// The load average before the pass.
    pub load1: f64,
}

impl Row for ThroughputRow {}

/// One category of the profile.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ThroughputProfileRow {
    /// `rhs`, `integrator`, `observer` or `other`.
    pub part: String,
    /// What the samples were doing.
    pub category: String,
    /// Samples in the category.
    pub samples: usize,
    /// Its share of the samples.
    pub share: f64,
    /// Its CPU time per RHS evaluation (us).
    pub cpu_us_per_rhs: f64,
    /// User CPU seconds of the profiled pass.
    pub user_s: f64,
    /// RHS evaluations of the profiled pass.
    pub rhs_evals: f64,
    /// The profiled revision.
    pub git_rev: String,
}

impl Row for ThroughputProfileRow {}

/// One revision's medians over its passes.
#[derive(Clone, Debug, PartialEq)]
pub struct Side {
    /// The commit.
    pub commit: String,
    /// Passes.
    pub passes: usize,
    /// Runs of the sweep.
    pub runs: usize,
    /// Median user CPU seconds.
    pub user_s: f64,
    /// Median runs per user CPU second.
    pub runs_per_cpu_s: f64,
    /// Median user CPU microseconds per RHS evaluation.
    pub cpu_us_per_rhs: f64,
    /// RHS evaluations per run (of the first pass; every pass runs the same sweep).
    pub rhs_per_run: f64,
    /// Median instructions, where measured.
    pub instructions: Option<f64>,
}

/// The median of `v` (NaN when empty).
pub(crate) fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

/// The medians of the passes of `revision` (`old` or `new`), None without any.
pub fn side(rows: &[ThroughputRow], revision: &str) -> Option<Side> {
    let mine: Vec<&ThroughputRow> = rows.iter().filter(|r| r.revision == revision).collect();
    let first = mine.first()?;
    let instructions: Vec<f64> = mine.iter().filter_map(|r| r.instructions).collect();
    Some(Side {
        commit: first.commit.clone(),
        passes: mine.len(),
        runs: first.runs,
        user_s: median(mine.iter().map(|r| r.user_s).collect()),
        runs_per_cpu_s: median(mine.iter().map(|r| r.runs as f64 / r.user_s).collect()),
        cpu_us_per_rhs: median(mine.iter().map(|r| 1e6 * r.user_s / r.rhs_evals).collect()),
        rhs_per_run: first.rhs_evals / first.runs as f64,
        instructions: (!instructions.is_empty()).then(|| median(instructions)),
    })
}

/// new / old runs per CPU second.
pub fn speedup(old: &Side, new: &Side) -> f64 {
    new.runs_per_cpu_s / old.runs_per_cpu_s
}

/// The profile's CPU microseconds per RHS of the RHS itself (the floor) and of everything.
pub fn floor_and_total(profile: &[ThroughputProfileRow]) -> (f64, f64) {
    let total = profile.iter().map(|r| r.cpu_us_per_rhs).sum();
    let floor = profile
        .iter()
        .filter(|r| r.part == RHS_PART)
        .map(|r| r.cpu_us_per_rhs)
        .sum();
    (floor, total)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(revision: &str, pass: usize, user_s: f64) -> ThroughputRow {
        ThroughputRow {
            revision: revision.into(),
            commit: format!("{revision}-commit"),
            pass,
            runs: 100,
            user_s,
            wall_s: 2.0 * user_s,
            instructions: None,
            cycles: None,
            rhs_evals: 1e6,
            steps: 1e5,
            sum_sim_s: user_s,
            sum_wall_s: user_s,
            load1: 1.0,
        }
    }

    #[test]
    fn medians_over_passes_and_the_ratio_are_new_over_old() {
        let rows = [
            row("old", 1, 10.0),
            row("new", 1, 4.0),
            row("old", 2, 12.0),
            row("new", 2, 6.0),
            row("old", 3, 50.0),
            row("new", 3, 5.0),
        ];
        let old = side(&rows, "old").unwrap();
        let new = side(&rows, "new").unwrap();
        assert_eq!((old.passes, old.user_s), (3, 12.0));
        assert_eq!(new.user_s, 5.0);
        assert_eq!(old.runs_per_cpu_s, 100.0 / 12.0);
        assert_eq!(new.cpu_us_per_rhs, 5.0);
        assert!((speedup(&old, &new) - 12.0 / 5.0).abs() < 1e-12);
        assert!(side(&rows, "other").is_none());
    }

    #[test]
    fn the_floor_is_the_rhs_part_alone() {
        let p = |part: &str, us: f64| ThroughputProfileRow {
            part: part.into(),
            category: "c".into(),
            samples: 1,
            share: 0.25,
            cpu_us_per_rhs: us,
            user_s: 1.0,
            rhs_evals: 1.0,
            git_rev: "abc".into(),
        };
        let profile = [
            p("rhs", 0.5),
            p("rhs", 0.25),
            p("observer", 1.0),
            p("integrator", 0.25),
        ];
        assert_eq!(floor_and_total(&profile), (0.75, 2.0));
    }
}
