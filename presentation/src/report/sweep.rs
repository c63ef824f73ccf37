//! A published table beside a sweep's runs (`[[sweep_check]]` of a paper's `paper.toml`,
//! `analysis::sweep_check`): where the paper's setup is an assumption the sweep varies, every
//! swept variant is set beside the published column its id matches: per-joint sign agreement
//! with the paper and the drift norm ratio, computed from the rows.

use super::markdown::{sci, Table};
use analysis::papers::Papers;
use analysis::sweep_check::SweepCheck;
use records::index::{completed, metric, Runs};

/// The published value of one column and metric of the check's table.
fn published(papers: &Papers, check: &SweepCheck, experiment: &str, metric: &str) -> Option<f64> {
    papers
        .values
        .iter()
        .find(|v| {
            v.paper == check.paper
                && v.table == check.table
                && v.experiment == experiment
                && v.metric == metric
        })
        .map(|v| v.value)
}

/// The markdown section, or an empty string when the sweep was not run.
pub fn section(check: &SweepCheck, runs: &Runs, papers: &Papers) -> String {
    let rows: Vec<_> = runs.of_experiment(&check.experiment).collect();
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
        let Some(column) = check.column_of(&r.variant_id) else {
            continue;
        };
        let paper: Vec<f64> = check
            .metrics
            .iter()
            .filter_map(|m| published(papers, check, &column.published_experiment, m))
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
        let ours: Vec<f64> = check.metrics.iter().filter_map(|m| metric(r, m)).collect();
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
        "\n### {} (`{}`)\n\n{}\n\n{}",
        check.heading,
        check.experiment,
        check.text,
        t.render()
    )
}
