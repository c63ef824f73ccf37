//! The regression gate: a fresh run against the committed `results/runs.csv`.
//!
//! A fresh row is compared with the committed row of the same (experiment, variant, solver):
//! - the status must be the same (a run that completed must still complete, a run that failed
//!   is a recorded finding and must still fail);
//! - for completed runs the drift per joint and every measured metric (`records::index::MEASURED`:
//!   every number the report's claims and tables use, timings aside) must agree to a relative
//!   1e-6 (absolute 1e-12): the simulation is deterministic, so anything beyond floating-point
//!   noise across machines is a change of behaviour;
//! - every committed run must still be produced, and every fresh run must be committed;
//! - every neural run must complete, except those whose divergence is itself the finding
//!   (declared in the experiment files as `expected_failure`, recorded in each row).

use records::runs::RunRow;
use std::collections::HashSet;

/// Relative tolerance of the drift comparison.
pub const RELATIVE_TOLERANCE: f64 = 1e-6;

/// Whether `r` is one of the runs its experiment file expects to fail (`expected_failure`).
pub fn expected_to_diverge(r: &RunRow) -> bool {
    !r.expected_failure.is_empty()
}

fn close(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() <= 1e-12 + RELATIVE_TOLERANCE * a.abs().max(b.abs()),
        (None, None) => true,
        _ => false,
    }
}

/// Every difference between `committed` (read from the baseline called `baseline`, for the
/// messages) and `fresh` that the gate rejects, one line each. `committed` should hold the rows
/// of the same selection of runs as `fresh`. Linear in the rows (keys in hash maps).
pub fn compare(committed: &[RunRow], fresh: &[RunRow], baseline: &str) -> Vec<String> {
    let mut problems = Vec::new();
    let fresh_by_key: std::collections::HashMap<_, &RunRow> =
        fresh.iter().map(|f| (f.key(), f)).collect();
    let committed_keys: std::collections::HashSet<_> = committed.iter().map(RunRow::key).collect();
    for c in committed {
        let Some(&f) = fresh_by_key.get(&c.key()) else {
            problems.push(format!(
                "{:?}: in {baseline} but no longer produced",
                c.key()
            ));
            continue;
        };
        if f.status != c.status {
            problems.push(format!(
                "{:?}: status {} -> {} ({})",
                c.key(),
                c.status,
                f.status,
                f.failure
            ));
            continue;
        }
        if c.completed() {
            if c.drift.len() != f.drift.len() {
                problems.push(format!(
                    "{:?}: {} joint drifts -> {}",
                    c.key(),
                    c.drift.len(),
                    f.drift.len()
                ));
            }
            let joints = c
                .drift
                .iter()
                .zip(&f.drift)
                .enumerate()
                .map(|(i, (a, b))| (format!("drift_{}", i + 1), Some(*a), Some(*b)));
            let totals = records::index::MEASURED
                .iter()
                .map(|(name, column)| (name.to_string(), column(c), column(f)));
            for (name, a, b) in joints.chain(totals) {
                if !close(a, b) {
                    problems.push(format!("{:?}: {name} {a:?} -> {b:?}", c.key()));
                }
            }
        }
    }
    for f in fresh {
        if !committed_keys.contains(&f.key()) {
            problems.push(format!(
                "{:?}: new run, not in {baseline} (run the reproduction and commit results/)",
                f.key()
            ));
        }
        if !f.is_exact() && !f.completed() && !expected_to_diverge(f) {
            problems.push(format!("{:?}: neural run failed: {}", f.key(), f.failure));
        }
    }
    problems
}

/// [`compare`] on a selection: the baseline's rows of the experiments `fresh` covers (only
/// their exact rows with `exact_only`) against `fresh`.
pub fn compare_selection(
    baseline: Vec<RunRow>,
    fresh: &[RunRow],
    exact_only: bool,
    baseline_name: &str,
) -> Vec<String> {
    let experiments: HashSet<&str> = fresh.iter().map(|f| f.experiment.as_str()).collect();
    let committed: Vec<RunRow> = baseline
        .into_iter()
        .filter(|c| experiments.contains(c.experiment.as_str()))
        .filter(|c| !exact_only || c.is_exact())
        .collect();
    compare(&committed, fresh, baseline_name)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The audit's case: a doctored `final_pos_err` (which a kong2019 claim reads) is a gate
    /// difference, as is every other measured metric; a timing is not.
    #[test]
    fn every_measured_metric_is_compared_and_no_timing() {
        let mut row = RunRow::blank(
            "e",
            "v",
            "s",
            catalog::solver_kind::SolverKind::Network(catalog::network_kind::NetworkKind::Znn),
        );
        row.final_pos_err = Some(1e-5);
        row.score_rms_dx = Some(2e-4);
        let committed = vec![row.clone()];
        assert!(compare(&committed, &committed, "b").is_empty());
        let mut doctored = row.clone();
        doctored.final_pos_err = Some(0.99);
        let problems = compare(&committed, &[doctored], "b");
        assert_eq!(problems.len(), 1, "{problems:?}");
        assert!(problems[0].contains("final_pos_err"), "{problems:?}");
        let mut lost = row.clone();
        lost.score_rms_dx = None;
        assert!(compare(&committed, &[lost], "b")[0].contains("score_rms_dx"));
        let mut slower = row;
        slower.wall_s += 10.0;
        slower.sim_s += 10.0;
        assert!(compare(&committed, &[slower], "b").is_empty());
    }
}
