//! `reproduce score FILE --task ID`: a trajectory written as CSV (here the trace of the
//! suite's own ZNN run) is scored with the run's drift, and its row, trace and figure are
//! written under --score-out; a task that does not exist is refused with the library's message.

use reproduce::load_experiments;
use simulation::run_job;
use simulation::Outcome;
use spec::SolverChoice;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The binary, in the workspace root.
fn reproduce() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_reproduce"));
    c.current_dir(catalog::root_from_current_dir().unwrap());
    c
}

#[test]
fn a_trajectory_file_is_scored_on_its_task() {
    let root = catalog::root_from_current_dir().unwrap();
    let job = load_experiments(&root.join("experiments"))
        .unwrap()
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .find(|j| {
            j.task().to_string() == "kong2019-circle / znn-eq22" && j.solver != SolverChoice::Exact
        })
        .unwrap();
    let run = run_job(&job).run;
    let Outcome::Completed(metrics) = &run.outcome else {
        panic!("{:?}", run.outcome)
    };
    let dir = inputs::Scratch::dir("score");
    let n = job.theta0.len();
    let mut csv = String::from("t");
    for i in 1..=n {
        csv.push_str(&format!(",theta_{i}"));
    }
    csv.push('\n');
    for p in &run.trace {
        csv.push_str(&format!("{:e}", p.t));
        for v in &p.theta {
            csv.push_str(&format!(",{v:e}"));
        }
        csv.push('\n');
    }
    let file = dir.join("znn.csv");
    std::fs::write(&file, csv).unwrap();
    let out = dir.join("out");
    let ok = reproduce()
        .arg("score")
        .arg(&file)
        .args(["--task", &job.task().to_string()])
        .arg("--score-out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let rows: Vec<records::RunRow> = store::table::read(&out.join("scores.csv")).unwrap();
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0].drift, metrics.drift);
    assert_eq!(rows[0].solver, "trajectory znn.csv");
    assert!(rows[0].score_rms_dx.is_some());
    assert_eq!(rows[0].solver_id, "trajectory");
    let mut figures: Vec<String> = std::fs::read_dir(out.join("figures"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    figures.sort();
    assert_eq!(
        figures,
        [
            "kong2019-circle__znn-eq22__trajectory.png",
            "kong2019-circle__znn-eq22__trajectory.svg"
        ]
    );
    // No warning about the trajectory.
    let stderr = String::from_utf8_lossy(&ok.stderr);
    assert!(!stderr.contains("warning"), "{stderr}");

    // The subcommand, with a global option after it and from outside the project: the same
    // file on another task of the same arm and start is scored, and warned as far off it; the
    // file rounded to 7 digits (as a short format writes it) is warned as rounded.
    let rounded = dir.join("rounded.csv");
    let seven_digits: String = std::fs::read_to_string(&file)
        .unwrap()
        .lines()
        .map(|line| match line.starts_with('t') {
            true => format!("{line}\n"),
            false => {
                let cells: Vec<String> = line
                    .split(',')
                    .map(|c| format!("{:.6e}", c.parse::<f64>().unwrap()))
                    .collect();
                format!("{}\n", cells.join(","))
            }
        })
        .collect();
    std::fs::write(&rounded, seven_digits).unwrap();
    for (task, trajectory, name, warned) in [
        (
            "kong2019-triangle / znn-eq22",
            &file,
            "trajectory",
            "is this the right task?",
        ),
        (
            "kong2019-circle / znn-eq22",
            &rounded,
            "rounded",
            "the samples look rounded",
        ),
    ] {
        let scored = Command::new(env!("CARGO_BIN_EXE_reproduce"))
            .current_dir(&dir)
            .arg("score")
            .arg(trajectory)
            .args(["--task", task, "--name", name, "--out"])
            .arg(&out)
            .arg("--root")
            .arg(&root)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&scored.stderr);
        assert!(scored.status.success(), "{task}: {err}");
        assert!(err.contains(warned), "{task}: {err}");
    }

    // One row per task and file: another file under the same task and name is refused, and
    // the first file's row and trace stay as they were (it used to replace them).
    let trace = out.join("traces/kong2019-circle/znn-eq22__trajectory.csv");
    let before = (
        std::fs::read(out.join("scores.csv")).unwrap(),
        std::fs::read(&trace).unwrap(),
    );
    let taken = reproduce()
        .arg("score")
        .arg(&rounded)
        .args(["--task", "kong2019-circle / znn-eq22", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&taken.stderr);
    assert_eq!(taken.status.code(), Some(2), "{err}");
    assert!(
        err.contains(
            "holds the score of another file (\"trajectory znn.csv\"); give this one its own --name"
        ),
        "{err}"
    );
    assert_eq!(
        before,
        (
            std::fs::read(out.join("scores.csv")).unwrap(),
            std::fs::read(&trace).unwrap()
        )
    );
    // The same file again replaces its own row.
    let again = reproduce()
        .arg("score")
        .arg(&file)
        .args(["--task", "kong2019-circle / znn-eq22", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );

    let refused = reproduce()
        .arg("score")
        .arg(&file)
        .args(["--task", "nope / nope"])
        .arg("--score-out")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(refused.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("no task \"nope / nope\""));

    // A second name keeps its own row beside the first; a name that is not a slug, and an
    // out directory this program seals (results/), are refused before anything is written.
    let task = job.task().to_string();
    let named = reproduce()
        .arg("score")
        .arg(&file)
        .args(["--task", &task, "--name", "octave-znn", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        named.status.success(),
        "{}",
        String::from_utf8_lossy(&named.stderr)
    );
    let rows: Vec<records::RunRow> = store::table::read(&out.join("scores.csv")).unwrap();
    let ids: Vec<&str> = rows
        .iter()
        .filter(|r| r.experiment == job.experiment)
        .map(|r| r.solver_id.as_str())
        .collect();
    assert_eq!(ids, ["octave-znn", "rounded", "trajectory"]);
    for (args, said) in [
        (vec!["--name", "Octave ZNN"], "a slug"),
        (
            vec!["--name", "exact"],
            "the exact column's solver id is reserved",
        ),
        (
            vec!["--out", "results"],
            "sealed by this program's manifest.toml",
        ),
        (
            vec!["--out", "results/traces/x"],
            "sealed by this program's manifest.toml",
        ),
    ] {
        let before = std::fs::read(root.join("results/runs.csv")).unwrap();
        let out = reproduce()
            .arg("score")
            .arg(&file)
            .args(["--task", &task])
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(said), "{args:?}: {err}");
        assert_eq!(
            std::fs::read(root.join("results/runs.csv")).unwrap(),
            before
        );
        assert!(!root.join("results/traces/x").exists());
    }
    // An out directory whose traces/<experiment> or figures/ is a symbolic link elsewhere:
    // refused before anything is written, there or in the out directory.
    let elsewhere = dir.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    for link in [
        Path::new("traces").join(&job.experiment),
        PathBuf::from("figures"),
    ] {
        let linked = dir.join("linked");
        let _ = std::fs::remove_dir_all(&linked);
        std::fs::create_dir_all(linked.join("traces")).unwrap();
        std::os::unix::fs::symlink(&elsewhere, linked.join(&link)).unwrap();
        let out = reproduce()
            .arg("score")
            .arg(&file)
            .args(["--task", &task, "--out"])
            .arg(&linked)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{link:?}: {err}");
        assert!(err.contains("leads outside"), "{link:?}: {err}");
        assert_eq!(std::fs::read_dir(&elsewhere).unwrap().count(), 0);
        assert!(
            !linked.join("scores.csv").exists(),
            "{link:?}: scores.csv written"
        );
    }
}
