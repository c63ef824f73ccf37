//! `benches/results/speedup.csv`: every run of the papers timed alone under an earlier revision of
//! driftbench and under this one (written by `benches/speedup/papers.sh OLD_CHECKOUT OLD_BINARY`,
//! which alternates the two revisions pass by pass on one pinned CPU and matches their rows with
//! `benches/speedup/compare.py`).
//!
//! One [`SpeedupRow`] per run both revisions have. Times are medians over the passes, in
//! seconds: `sim_s` is the integration (the network's, or the exact column's), `wall_s` the whole
//! run (observation and scoring included). A speed-up is old / new. Both revisions' status and
//! drift norm ‖θ(T) − θ(0)‖ (rad) are kept, so that a reader can check that what was computed
//! did not change with the speed.

use records::table::Row;
use serde::{Deserialize, Serialize};

/// The file name inside `benches/results/`.
pub const FILE: &str = "speedup.csv";

/// One row of `benches/results/speedup.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SpeedupRow {
    /// The paper id.
    pub paper: String,
    /// The experiment id.
    pub experiment: String,
    /// The variant's display label (the earlier revision has no ids).
    pub variant: String,
    /// The solver's display label at this revision.
    pub solver: String,
    /// The earlier revision (12 hex digits).
    pub old_rev: String,
    /// This revision, as measured.
    pub new_rev: String,
    /// Passes per revision the medians are over.
    pub passes: usize,
    /// Median simulation time under the earlier revision (s).
    pub old_sim_s: f64,
    /// Median simulation time under this revision (s).
    pub new_sim_s: f64,
    /// old_sim_s / new_sim_s; empty when a median is missing or the new one is 0.
    pub sim_speedup: Option<f64>,
    /// Median whole-run time under the earlier revision (s).
    pub old_wall_s: f64,
    /// Median whole-run time under this revision (s).
    pub new_wall_s: f64,
    /// old_wall_s / new_wall_s; empty as `sim_speedup`.
    pub wall_speedup: Option<f64>,
    /// The run's status under the earlier revision (`ok` or `failed`).
    pub old_status: String,
    /// The run's status under this revision.
    pub new_status: String,
    /// Empty for a failed run.
    pub old_drift_norm: Option<f64>,
    /// The drift norm under this revision (rad); empty for a failed run.
    pub new_drift_norm: Option<f64>,
}

impl Row for SpeedupRow {}

/// One paper's runs together.
#[derive(Clone, Debug, PartialEq)]
pub struct PaperSpeedup {
    /// The paper id.
    pub paper: String,
    /// The paper's runs both revisions have.
    pub runs: usize,
    /// Sums over the runs of the median times, old and new (s).
    pub old_sim_s: f64,
    /// Sum of the new median simulation times (s).
    pub new_sim_s: f64,
    /// Sum of the old median whole-run times (s).
    pub old_wall_s: f64,
    /// Sum of the new median whole-run times (s).
    pub new_wall_s: f64,
    /// The smallest, median and largest per-run simulation speed-up.
    pub min_sim_speedup: f64,
    /// The median per-run simulation speed-up (NaN without any).
    pub median_sim_speedup: f64,
    /// The largest per-run simulation speed-up (NaN without any).
    pub max_sim_speedup: f64,
    /// Runs whose status differs between the revisions.
    pub status_changes: usize,
    /// The largest |new - old| drift norm (rad) over runs completed at both.
    pub max_drift_change: f64,
}

/// Per paper, in the order the papers first appear in `rows`.
pub fn by_paper(rows: &[SpeedupRow]) -> Vec<PaperSpeedup> {
    records::table::distinct(rows, |r| &r.paper)
        .into_iter()
        .map(|paper| {
            let runs: Vec<&SpeedupRow> = rows.iter().filter(|r| r.paper == paper).collect();
            let sum = |f: fn(&SpeedupRow) -> f64| runs.iter().map(|r| f(r)).sum::<f64>();
            let mut ratios: Vec<f64> = runs.iter().filter_map(|r| r.sim_speedup).collect();
            ratios.sort_by(f64::total_cmp);
            PaperSpeedup {
                paper: paper.to_string(),
                runs: runs.len(),
                old_sim_s: sum(|r| r.old_sim_s),
                new_sim_s: sum(|r| r.new_sim_s),
                old_wall_s: sum(|r| r.old_wall_s),
                new_wall_s: sum(|r| r.new_wall_s),
                min_sim_speedup: ratios.first().copied().unwrap_or(f64::NAN),
                median_sim_speedup: records::percentile(&ratios, 0.5),
                max_sim_speedup: ratios.last().copied().unwrap_or(f64::NAN),
                status_changes: runs.iter().filter(|r| r.old_status != r.new_status).count(),
                max_drift_change: runs
                    .iter()
                    .filter_map(|r| Some((r.new_drift_norm? - r.old_drift_norm?).abs()))
                    .fold(0.0, f64::max),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(paper: &str, old: f64, new: f64, drifts: (Option<f64>, Option<f64>)) -> SpeedupRow {
        SpeedupRow {
            paper: paper.into(),
            experiment: "e".into(),
            variant: "v".into(),
            solver: "s".into(),
            old_rev: "a".into(),
            new_rev: "b".into(),
            passes: 3,
            old_sim_s: old,
            new_sim_s: new,
            sim_speedup: Some(old / new),
            old_wall_s: 2.0 * old,
            new_wall_s: 2.0 * new,
            wall_speedup: Some(old / new),
            old_status: "ok".into(),
            new_status: if drifts.1.is_some() { "ok" } else { "failed" }.into(),
            old_drift_norm: drifts.0,
            new_drift_norm: drifts.1,
        }
    }

    #[test]
    fn sums_ratios_and_changes_per_paper() {
        let rows = [
            row("p", 3.0, 1.0, (Some(0.5), Some(0.5 + 1e-9))),
            row("q", 1.0, 1.0, (Some(0.1), None)),
            row("p", 1.0, 2.0, (Some(0.2), Some(0.2))),
            row("p", 4.0, 1.0, (None, Some(0.3))),
        ];
        let s = by_paper(&rows);
        assert_eq!(s.len(), 2);
        assert_eq!((s[0].paper.as_str(), s[0].runs), ("p", 3));
        assert_eq!((s[0].old_sim_s, s[0].new_sim_s), (8.0, 4.0));
        assert_eq!((s[0].old_wall_s, s[0].new_wall_s), (16.0, 8.0));
        assert_eq!(
            (
                s[0].min_sim_speedup,
                s[0].median_sim_speedup,
                s[0].max_sim_speedup
            ),
            (0.5, 3.0, 4.0)
        );
        assert!((s[0].max_drift_change - 1e-9).abs() < 1e-15);
        assert_eq!(s[0].status_changes, 0);
        assert_eq!((s[1].status_changes, s[1].max_drift_change), (1, 0.0));
    }
}
