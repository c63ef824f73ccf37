//! The regression gate ([`analysis::gate`], its baseline, module `baseline` of crate `reproduce`): a fresh run of every experiment against the
//! committed `results/runs.csv`; and two fresh runs of the same jobs give identical rows,
//! timing columns aside.

use analysis::gate::compare;
use records::RunRow;
use reproduce::load_experiments;
use simulation::run_jobs;
use simulation::run_row;
use store::read_runs;

#[test]
fn fresh_run_matches_the_committed_results() {
    let root = catalog::root_from_current_dir().unwrap();
    let committed =
        read_runs(&root.join("results/runs.csv")).expect("results/runs.csv is committed");
    let files = load_experiments(&root.join("experiments")).unwrap();
    let jobs: Vec<_> = files.iter().flat_map(|f| f.jobs().unwrap()).collect();
    let fresh: Vec<RunRow> = run_jobs(&jobs, false)
        .iter()
        .map(|r| run_row(r, "test"))
        .collect();

    let problems = compare(&committed, &fresh, "results/runs.csv");
    assert!(
        problems.is_empty(),
        "{} regressions:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

/// The gate itself: a changed drift, a changed status and a missing run are each caught.
#[test]
fn the_gate_catches_changes() {
    let committed = read_runs(
        &catalog::root_from_current_dir()
            .unwrap()
            .join("results/runs.csv"),
    )
    .unwrap();
    assert!(compare(&committed, &committed, "test baseline").is_empty());
    let ok = committed
        .iter()
        .position(|r| r.completed() && r.drift_norm.is_some())
        .unwrap();
    let mut changed = committed.clone();
    changed[ok].drift[2] = changed[ok].drift[2] * (1.0 + 1e-4) + 1e-9;
    assert_eq!(
        compare(&committed, &changed, "test baseline").len(),
        1,
        "a drift change"
    );
    let mut failed = committed.clone();
    failed[ok].status = records::Status::Failed;
    assert!(
        !compare(&committed, &failed, "test baseline").is_empty(),
        "a status change"
    );
    let mut missing = committed.clone();
    missing.remove(ok);
    assert!(
        !compare(&committed, &missing, "test baseline").is_empty(),
        "a missing run"
    );
    // A run the baseline lacks is blamed on the baseline, by its name.
    let problems = compare(&missing, &committed, "my-baseline.csv");
    assert!(
        problems.len() == 1 && problems[0].contains("not in my-baseline.csv"),
        "{problems:?}"
    );
}

#[test]
fn two_runs_give_identical_rows() {
    let root = catalog::root_from_current_dir().unwrap();
    let files = load_experiments(&root.join("experiments")).unwrap();
    let jobs: Vec<_> = files
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .filter(|j| {
            [
                "jia2019-star",
                "zhong2021-clover-b",
                "zhang2018-cardioid-robust",
            ]
            .contains(&j.experiment.as_str())
        })
        .collect();
    assert!(jobs.len() >= 8);
    let rows = |_| -> Vec<RunRow> {
        run_jobs(&jobs, false)
            .iter()
            .map(|r| RunRow {
                wall_s: 0.0,
                sim_s: 0.0,
                observe_s: 0.0,
                ..run_row(r, "test")
            })
            .collect()
    };
    let (a, b) = (rows(0), rows(1));
    assert_eq!(a, b);
}
