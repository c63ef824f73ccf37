//! A trajectory made in Octave is scored, and the score agrees with driftbench's own run of the
//! same network on the same task.
//!
//! `examples/octave/znn_circle.m` writes, from the papers' equations alone, kong2019's ZNN
//! repetitive scheme (22) on the Katana 6M180 tracing the circle, solved by a linear zeroing
//! network (the task "kong2019-circle / znn-eq22", network `ZNN`), integrated by `ode45` at
//! RelTol 1e-10. `reproduce score` scores its CSV; the suite runs its own `ZNN` on the task
//! at RelTol 1e-10 / AbsTol 1e-12 (the committed run uses 1e-6, whose integration error on the
//! small drifts of joints 1-4 is ~1e-7 rad). Agreement, [`DRIFT_TOLERANCE`]: every joint's
//! drift within 1e-9 rad (joints 1-4 drift 3e-6 to 6e-6 rad: a wrong link length, path size or
//! gain moves them by far more), the position error of both below [`POSITION_TOLERANCE`] (a
//! wrong robot or path puts the Octave arm millimetres off the task's path) and the largest
//! |x - x*| (at t = 0, where both networks start from x = 0) equal to 1e-9 relative.
//!
//! The same trajectory written as a MAT-file (`save -v7`, variables t and y) scores exactly as
//! the CSV (both carry every digit).
//!
//! Octave is run as `octave-cli` (Debian's `octave` package; `.ci/run` installs it). Without
//! it the test says it is skipped, and why, and passes, except where `DRIFTBENCH_REQUIRE_OCTAVE`
//! is set (`.ci/run` sets it): there a missing Octave fails the test, so CI cannot pass
//! vacuously.

use records::RunRow;
use reproduce::load_experiments;
use simulation::run_job;
use simulation::run_row;
use spec::SolverChoice;
use std::path::{Path, PathBuf};
use std::process::Command;

const TASK: &str = "kong2019-circle / znn-eq22";
/// |drift_i(Octave) - drift_i(driftbench)| for every joint, rad.
const DRIFT_TOLERANCE: f64 = 1e-9;
/// Maximum position error of either trajectory against the task's path, m.
const POSITION_TOLERANCE: f64 = 1e-9;
/// Relative difference of the largest |x - x*|.
const SCORE_TOLERANCE: f64 = 1e-9;

fn octave() -> Option<PathBuf> {
    ["octave-cli", "octave"].iter().find_map(|name| {
        let ok = Command::new(name)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success());
        ok.then(|| PathBuf::from(name))
    })
}

/// Runs the Octave example, writing its trajectory to `out`.
fn run_octave(octave: &Path, root: &Path, out: &Path) {
    let script = format!(
        "addpath('{}'); znn_circle('{}')",
        root.join("examples/octave").display(),
        out.display()
    );
    let o = Command::new(octave)
        .args(["--no-gui", "--quiet", "--no-init-file", "--eval", &script])
        .output()
        .unwrap();
    assert!(
        o.status.success() && out.exists(),
        "octave failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// `reproduce score FILE --task TASK`, and the row it wrote.
fn score(root: &Path, file: &Path, out: &Path) -> RunRow {
    let o = Command::new(env!("CARGO_BIN_EXE_reproduce"))
        .current_dir(root)
        .arg("score")
        .arg(file)
        .args(["--task", TASK])
        .arg("--score-out")
        .arg(out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut rows: Vec<RunRow> = store::table::read(&out.join("scores.csv")).unwrap();
    assert_eq!(rows.len(), 1);
    rows.remove(0)
}

/// driftbench's own run of the task's `ZNN` at tight tolerances.
fn own_run(root: &Path) -> RunRow {
    let mut job = load_experiments(&root.join("experiments"))
        .unwrap()
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .find(|j| j.task().to_string() == TASK && j.solver != SolverChoice::Exact)
        .unwrap();
    job.integrator.rtol = 1e-10;
    job.integrator.atol = 1e-12;
    run_row(&run_job(&job), "test")
}

#[test]
fn an_octave_trajectory_scores_as_driftbench_own_run() {
    let Some(octave) = octave() else {
        assert!(
            std::env::var_os("DRIFTBENCH_REQUIRE_OCTAVE").is_none(),
            "DRIFTBENCH_REQUIRE_OCTAVE is set but neither octave-cli nor octave is installed"
        );
        eprintln!(
            "skipped: neither octave-cli nor octave is installed (Debian: apt-get install octave; .ci/run installs it)"
        );
        return;
    };
    let root = catalog::root_from_current_dir().unwrap();
    let dir = inputs::Scratch::dir("octave");
    let file = dir.join("znn_circle.csv");
    run_octave(&octave, &root, &file);
    let scored = score(&root, &file, &dir.join("out"));
    let mat = dir.join("znn_circle.mat");
    run_octave(&octave, &root, &mat);
    let scored_mat = score(&root, &mat, &dir.join("out-mat"));
    assert_eq!(scored_mat.drift, scored.drift);
    assert_eq!(scored_mat.score_max_dx, scored.score_max_dx);
    assert_eq!(scored_mat.solver, "trajectory znn_circle.mat");
    let own = own_run(&root);
    drop(dir);

    assert_eq!(scored.drift.len(), own.drift.len());
    for (i, (a, b)) in scored.drift.iter().zip(&own.drift).enumerate() {
        assert!(
            (a - b).abs() <= DRIFT_TOLERANCE,
            "joint {}: Octave's drift {a:e}, driftbench's {b:e} (tolerance {DRIFT_TOLERANCE:e} rad)",
            i + 1
        );
    }
    for (who, row) in [("Octave", &scored), ("driftbench", &own)] {
        let err = row.max_pos_err.unwrap();
        assert!(
            err <= POSITION_TOLERANCE,
            "{who}'s max position error {err:e} m (tolerance {POSITION_TOLERANCE:e})"
        );
    }
    let (a, b) = (scored.score_max_dx.unwrap(), own.score_max_dx.unwrap());
    assert!(
        (a - b).abs() <= SCORE_TOLERANCE * b,
        "max |x - x*|: Octave {a:e}, driftbench {b:e}"
    );
}
