//! The control experiments run in parallel (rayon's pool) and give what one thread gives: the
//! same rows in the same order, every column but the measured latencies, and the same noise
//! floor (the rounding-noise probes are deterministic, continuous time included). On a small budget
//! (10 ms, one swept period, three cycles) and kong2019's two tasks (a scratch experiments
//! directory with their file and a task set of its own).

use control::reproduce;
use inputs::Scratch;
use records::control::{ClaimCheck, ControlRow};
use std::path::Path;
use store::results_dir;

/// A scratch directory `name` under the system's temporary one, emptied, removed when dropped.
fn scratch(name: &str) -> Scratch {
    Scratch::dir(&format!("control-parallel-{name}"))
}

/// Runs the control experiments of `experiments` (its task set, at h = 10 ms instead of the
/// main period) on a pool of `threads` threads into a fresh directory, which is returned beside
/// the claim's check runs without their latencies (wall-clock).
fn run_on(threads: usize, experiments: &Path) -> (Scratch, Vec<ClaimCheck>) {
    let out = scratch(&format!("out-{threads}"));
    let mut set = catalog::load_task_set(experiments).unwrap();
    set.budget.h = 1e-2;
    let jobs: Vec<_> = catalog::load_dir(experiments)
        .unwrap()
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .collect();
    let summary = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| reproduce(&set, &jobs, &out, |_| {}))
        .unwrap();
    let mut checks = summary.claim_checks;
    for c in &mut checks {
        c.check_solve_p50_us = 0.0;
        c.numerical_solve_p50_us = 0.0;
    }
    (out, checks)
}

/// The rows of `results/control.csv` without the latencies (wall-clock).
fn control_rows(dir: &Path) -> Vec<ControlRow> {
    let mut rows: Vec<ControlRow> = store::control::read(dir, results_dir::CONTROL).unwrap();
    for r in &mut rows {
        for v in [
            &mut r.solve_p50_us,
            &mut r.solve_p99_us,
            &mut r.solve_max_us,
            &mut r.tick_p50_us,
            &mut r.tick_p99_us,
            &mut r.tick_max_us,
        ] {
            *v = 0.0;
        }
    }
    rows
}

#[test]
fn two_threads_give_the_rows_of_one() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let experiments = scratch("experiments");
    std::fs::copy(
        root.join("experiments").join("kong2019.toml"),
        experiments.join("kong2019.toml"),
    )
    .unwrap();
    let tasks = experiments.join(catalog::TASK_SET_FILE);
    std::fs::create_dir_all(tasks.parent().unwrap()).unwrap();
    std::fs::write(
        &tasks,
        "[[task]]\nexperiment = \"kong2019-circle\"\nvariant = \"znn-eq22\"\n\n\
         [[task]]\nexperiment = \"kong2019-circle\"\nvariant = \"finite-time-eq14\"\n\n\
         [budget]\nsweep_ms = [20.0]\ncycles = 3\ncheck_ticks = 20\ncheck_steps_factor = 2\n",
    )
    .unwrap();
    let ((one, checks_one), (two, checks_two)) = (run_on(1, &experiments), run_on(2, &experiments));
    let rows = control_rows(&one);
    // Two tasks, each: every numerical method of this build (OSQP only with the `osqp`
    // feature) and 2 network forms at h, 3 methods swept.
    let numerical = control::Numerical::all().len();
    assert_eq!(rows.len(), 2 * (numerical + 2 + 3), "{rows:#?}");
    assert_eq!(rows, control_rows(&two));
    assert_eq!(checks_one, checks_two);
    // A noise floor per row of control.csv, keyed as it is; a probe's class per trend.
    let noise: Vec<records::control::NoiseRow> =
        store::control::read(&one, results_dir::CONTROL_NOISE).unwrap();
    assert_eq!(noise.len(), rows.len());
    for (n, r) in noise.iter().zip(&rows) {
        assert_eq!(
            (&n.task, &n.method, n.h_ms, n.substeps),
            (&r.task, &r.method, r.h_ms, r.substeps)
        );
    }
    let trends: Vec<records::control::TrendRow> =
        store::control::read(&one, results_dir::CYCLES_TREND).unwrap();
    assert!(trends
        .iter()
        .any(|t| t.method == "exact (continuous)" && t.class_under_noise.is_some()));
    for file in [
        results_dir::CONTROL_NOISE,
        results_dir::CONTROL_STABILITY,
        results_dir::CYCLES,
        results_dir::CYCLES_TREND,
    ] {
        let (a, b) = (
            std::fs::read(one.join(file)).unwrap(),
            std::fs::read(two.join(file)).unwrap(),
        );
        assert!(!a.is_empty() && a == b, "{file} differs");
    }
}
