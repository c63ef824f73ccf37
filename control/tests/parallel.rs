//! The control experiments run in parallel (rayon's pool) and give what one thread gives: the
//! same rows in the same order, every column but the measured latencies. On a small budget
//! (10 ms, one swept period, three cycles) and kong2019's two tasks (a scratch experiments
//! directory with their file and a task set of its own).

use control::{reproduce, Budget};
use records::control::{ClaimRow, ControlRow};
use records::results_dir;
use std::path::{Path, PathBuf};

/// A scratch directory `name` under the system's temporary one, emptied.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "driftbench-control-parallel-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the control experiments of `experiments` on a pool of `threads` threads into a fresh
/// directory, which is returned.
fn run_on(threads: usize, experiments: &Path) -> PathBuf {
    let out = scratch(&format!("out-{threads}"));
    let budget = Budget {
        h: 1e-2,
        sweep: vec![2e-2],
        cycles: 3,
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| reproduce(experiments, &out, &budget, |_| {}))
        .unwrap();
    out
}

/// The rows of `results/control.csv` without the latencies (wall-clock).
fn control_rows(dir: &Path) -> Vec<ControlRow> {
    let mut rows: Vec<ControlRow> = records::control::read(dir, results_dir::CONTROL).unwrap();
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

/// The rows of `results/control-claim.csv` without the latencies.
fn claim_rows(dir: &Path) -> Vec<ClaimRow> {
    let mut rows: Vec<ClaimRow> = records::control::read(dir, results_dir::CONTROL_CLAIM).unwrap();
    for r in &mut rows {
        r.check_solve_p50_us = 0.0;
        r.numerical_solve_p50_us = 0.0;
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
    let tasks = experiments.join(control::task::TASK_SET_FILE);
    std::fs::create_dir_all(tasks.parent().unwrap()).unwrap();
    std::fs::write(
        &tasks,
        "[[task]]\nexperiment = \"kong2019-circle\"\nvariant = \"znn-eq22\"\n\n\
         [[task]]\nexperiment = \"kong2019-circle\"\nvariant = \"finite-time-eq14\"\n",
    )
    .unwrap();
    let (one, two) = (run_on(1, &experiments), run_on(2, &experiments));
    let rows = control_rows(&one);
    // Two tasks, each: every numerical method of this build (OSQP only with the `osqp`
    // feature) and 2 network forms at h, 3 methods swept.
    let numerical = control::method::Numerical::all().len();
    assert_eq!(rows.len(), 2 * (numerical + 2 + 3), "{rows:#?}");
    assert_eq!(rows, control_rows(&two));
    assert_eq!(claim_rows(&one), claim_rows(&two));
    for file in [
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
    for dir in [experiments, one, two] {
        let _ = std::fs::remove_dir_all(dir);
    }
}
