//! The regression gate: a fresh run of every experiment against the committed
//! `results/runs.csv`.
//!
//! - every committed run is still produced, with the same status;
//! - every run that completed still completes, and its drift (per joint and norm) and max
//!   position error agree with the committed numbers to a relative 1e-6 (absolute 1e-12): the
//!   simulation is deterministic, so anything beyond floating-point noise is a change;
//! - every neural run completes without divergence at the default tolerances, except the runs
//!   whose divergence is itself the finding (listed below with the reason);
//! - two fresh runs of the same jobs give identical rows, timing columns aside.

use reproduce::experiment::{load_dir, SolverChoice};
use reproduce::results::{read_runs, RunRow};
use reproduce::runner::run_jobs;

/// Runs that diverge by design of the experiment (the paper's own claim or a documented
/// finding), as (experiment prefix, variant prefix, solver prefix, why).
const EXPECTED_DIVERGENCE: &[(&str, &str, &str, &str)] = &[
    (
        "zhang2018-",
        "MTN",
        "",
        "minimum torque norm: joint velocities diverge (zhang2018 Figs 2-3)",
    ),
    (
        "zhang2018-",
        "HL-JDF (zeta=0.8)",
        "FP-CDNN (perturbed",
        "fixed-gain network under the reference perturbation",
    ),
    (
        "jia2019-clover",
        "MVN [jaco2 physical limits]",
        "",
        "clover at T = 5 s exceeds Kinova's physical joint-speed limits",
    ),
];

fn expected_to_diverge(r: &RunRow) -> bool {
    EXPECTED_DIVERGENCE.iter().any(|(e, v, s, _)| {
        r.experiment.starts_with(e) && r.variant.starts_with(v) && r.solver.starts_with(s)
    })
}

fn close(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() <= 1e-12 + 1e-6 * a.abs().max(b.abs()),
        (None, None) => true,
        _ => false,
    }
}

#[test]
fn fresh_run_matches_the_committed_results() {
    let root = reproduce::workspace_root();
    let committed =
        read_runs(&root.join("results/runs.csv")).expect("results/runs.csv is committed");
    let files = load_dir(&root.join("experiments")).unwrap();
    let jobs: Vec<_> = files.iter().flat_map(|f| f.jobs()).collect();
    let fresh: Vec<RunRow> = run_jobs(&jobs, false)
        .iter()
        .map(|r| RunRow::from_record(r, "test"))
        .collect();

    let mut problems = Vec::new();
    for c in &committed {
        let Some(f) = fresh.iter().find(|f| f.key() == c.key()) else {
            problems.push(format!("{:?}: committed run no longer produced", c.key()));
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
        if c.status == "ok" {
            let pairs = [
                ("drift_1", c.drift_1, f.drift_1),
                ("drift_2", c.drift_2, f.drift_2),
                ("drift_3", c.drift_3, f.drift_3),
                ("drift_4", c.drift_4, f.drift_4),
                ("drift_5", c.drift_5, f.drift_5),
                ("drift_6", c.drift_6, f.drift_6),
                ("drift_norm", c.drift_norm, f.drift_norm),
                ("max_pos_err", c.max_pos_err, f.max_pos_err),
            ];
            for (name, a, b) in pairs {
                if !close(a, b) {
                    problems.push(format!("{:?}: {name} {a:?} -> {b:?}", c.key()));
                }
            }
        }
    }
    for f in &fresh {
        if !committed.iter().any(|c| c.key() == f.key()) {
            problems.push(format!(
                "{:?}: new run not in results/runs.csv (run the reproduction and commit)",
                f.key()
            ));
        }
        let neural = f.solver != SolverChoice::Exact.label();
        if neural && f.status != "ok" && !expected_to_diverge(f) {
            problems.push(format!("{:?}: neural run failed: {}", f.key(), f.failure));
        }
    }
    assert!(
        problems.is_empty(),
        "{} regressions:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn two_runs_give_identical_rows() {
    let root = reproduce::workspace_root();
    let files = load_dir(&root.join("experiments")).unwrap();
    let jobs: Vec<_> = files
        .iter()
        .flat_map(|f| f.jobs())
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
                ..RunRow::from_record(r, "test")
            })
            .collect()
    };
    let (a, b) = (rows(0), rows(1));
    assert_eq!(a, b);
}
