//! jia2019's path check: the clover's size and orientation are assumed (docs/paths.md), so the
//! report sets Table 2 beside the exact column of `jia2019-clover-sweep` (forward and reversed
//! clover, a = 0.1, 0.15, 0.2 m): per-joint sign agreement with the paper and the drift norm
//! ratio, computed from the rows.

use super::markdown::{sci, Table};
use records::index::{completed, metric, Runs};
use records::papers::Papers;

/// The sweep experiment.
const SWEEP: &str = "jia2019-clover-sweep";
/// Table 2's columns as (published experiment, the end of our variant ids: the swept phi, tau).
const COLUMNS: [(&str, &str); 3] = [
    ("clover-mvn", "-phi-1.0-tau-0.0"),
    ("clover-mvn-invm", "-phi-0.2-tau-0.0"),
    ("clover-vltco", "-phi-0.2-tau-0.4"),
];
const JOINTS: [&str; 6] = [
    "drift_1", "drift_2", "drift_3", "drift_4", "drift_5", "drift_6",
];

/// Table 2's drift of one column and joint.
fn published(papers: &Papers, experiment: &str, joint: &str) -> Option<f64> {
    papers
        .values
        .iter()
        .find(|v| {
            v.paper == "jia2019"
                && v.table == "T2"
                && v.experiment == experiment
                && v.metric == joint
        })
        .map(|v| v.value)
}

/// The markdown section, or an empty string when the sweep was not run.
pub fn clover_sweep(runs: &Runs, papers: &Papers) -> String {
    let rows: Vec<_> = runs.of_experiment(SWEEP).collect();
    if rows.is_empty() {
        return String::new();
    }
    let mut t = Table::new([
        "variant (exact column)",
        "drift norm",
        "paper's norm",
        "ratio",
        "signs as the paper",
        "peak |θ̇| (rad/s)",
    ]);
    for r in rows {
        let Some((paper_experiment, _)) = COLUMNS
            .iter()
            .find(|(_, suffix)| r.variant_id.ends_with(suffix))
        else {
            continue;
        };
        let paper: Vec<f64> = JOINTS
            .iter()
            .filter_map(|j| published(papers, paper_experiment, j))
            .collect();
        let paper_norm = paper.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !completed(r) {
            t.push([
                r.variant.clone(),
                format!("failed at t = {}", sci(r.failed_at.unwrap_or(0.0))),
                sci(paper_norm),
                String::new(),
                String::new(),
                String::new(),
            ]);
            continue;
        }
        let ours: Vec<f64> = JOINTS.iter().filter_map(|j| metric(r, j)).collect();
        let same = ours
            .iter()
            .zip(&paper)
            .filter(|(o, p)| o.signum() == p.signum())
            .count();
        let norm = r.drift_norm.unwrap_or(f64::NAN);
        t.push([
            r.variant.clone(),
            sci(norm),
            sci(paper_norm),
            sci(norm / paper_norm),
            format!("{same} of {}", paper.len()),
            sci(r.peak_thetadot.unwrap_or(f64::NAN)),
        ]);
    }
    format!(
        "\n### Path direction and size (`{SWEEP}`)\n\n\
         The clover's size (a = 0.15 m) and orientation are assumptions (docs/paths.md). Travelling the same \
         curve backwards, and scaling it, moves Table 2's drifts as below (exact column; the drift is \
         the scheme's, the solver adds < 1 %). A peak |θ̇| of 1.5 rad/s means the velocity bound is active.\n\n{}",
        t.render()
    )
}
