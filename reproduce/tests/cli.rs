//! The binary's contract with its caller: ids typed at the command line, one writer at a
//! time, results that follow the experiment files, a killed run resumed, results outside the
//! project. The exit code of each kind of outcome is `exit_codes.rs`'.

use crate::common;

use common::reproduce;
use records::runs_csv;
use store::read_runs;
/// Ids are typed at the command line: a malformed paper, experiment, table, shard or task is
/// clap's usage error (exit 2, naming the valid form and pointing to `--help`) before any file is read; a well-formed one
/// that no file knows is refused once the files are read (exit 2, naming the known ones).
#[test]
fn malformed_ids_are_refused_by_clap_and_unknown_ones_by_the_files() {
    let refused = |args: &[&str], says: &[&str]| {
        let out = reproduce().args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        for s in says {
            assert!(err.contains(s), "{args:?}: {err}");
        }
        err
    };
    // Malformed: clap's usage error.
    for (args, says) in [
        (
            &["list", "--paper", "Kong2019"][..],
            "paper id \"Kong2019\" is not a slug",
        ),
        (&["list", "--experiment", "../x"], "experiment id \"../x\""),
        (
            &["infer", "--dry-run", "jia2019:"],
            "expected `all`, a paper",
        ),
        (
            &["infer", "--dry-run", "Jia2019:T2"],
            "paper id \"Jia2019\"",
        ),
        (&["list", "--shard", "3/2"], "K must be in 1..=2"),
        (&["shard", "x"], "expected K/N"),
        (&["score", "f.csv", "--task", "just-one"], "just-one"),
    ] {
        let err = refused(args, &["invalid value", says]);
        assert!(err.contains("try '--help'"), "{args:?}: {err}");
    }
    // Well formed but unknown: the files' check, naming the known ones.
    for (args, says) in [
        (
            &["list", "--paper", "nosuchpaper"][..],
            ["nosuchpaper", "kong2019"],
        ),
        (
            &["list", "--experiment", "kong2019-nosuch"],
            ["kong2019-nosuch", "kong2019-circle"],
        ),
        (
            &["infer", "--dry-run", "nosuchpaper"],
            ["nosuchpaper", "jia2019:T2"],
        ),
        (
            &["infer", "--dry-run", "jia2019:T9"],
            ["jia2019:T9", "jia2019:T2"],
        ),
    ] {
        let err = refused(args, &says);
        assert!(
            !err.contains("invalid value") && !err.contains("try '--help'"),
            "{args:?}: {err}"
        );
    }
}

/// One writer at a time: while another process holds the results directory's lock, a run
/// refuses at once (exit 2), naming the directory, and writes nothing.
#[test]
fn a_second_writer_refuses() {
    let base = inputs::Scratch::unmade("cli-lock");
    let dir = base.join("results");
    std::fs::create_dir_all(&dir).unwrap();
    let lock = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(dir.join(".lock"))
        .unwrap();
    lock.lock().unwrap();
    let out = reproduce()
        .args(["--experiment", "kong2019-circle-mu-sweep", "--results-dir"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("another reproduce is writing"));
    assert!(!dir.join("runs.csv").exists());
    drop(lock);
}

/// Results reflect the experiment files: a stored run that no file describes any more is
/// pruned, with its trace, and the run says so.
#[test]
fn runs_of_deleted_experiments_are_pruned() {
    let base = inputs::Scratch::unmade("cli-prune");
    let (experiments, results) = (base.join("experiments"), base.join("res"));
    std::fs::create_dir_all(&experiments).unwrap();
    std::fs::create_dir_all(&results).unwrap();
    std::fs::write(
        experiments.join("kong2019.toml"),
        common::CHEAP_EXPERIMENT.replace("kong2019-cheap", "kong2019-kept"),
    )
    .unwrap();
    let committed = read_runs(
        &catalog::root_from_current_dir()
            .unwrap()
            .join("results/runs.csv"),
    )
    .unwrap();
    let mut stale = committed[0].clone();
    stale.experiment = spec::ids::ExperimentId::new("kong2019-deleted").unwrap();
    std::fs::write(
        results.join("runs.csv"),
        runs_csv(&[stale.clone()]).unwrap(),
    )
    .unwrap();
    let trace_dir = results.join("traces").join("kong2019-deleted");
    std::fs::create_dir_all(&trace_dir).unwrap();
    let trace = trace_dir.join(format!("{}.csv", stale.key().stem()));
    std::fs::write(&trace, "t\n0\n").unwrap();

    // Written by hand, so taken as it is (--accept-edited); every stored run goes, which must
    // be said (--prune).
    let run = |extra: &[&str]| {
        reproduce()
            .args(["--experiments-dir"])
            .arg(&experiments)
            .arg("--results-dir")
            .arg(&results)
            .arg("--accept-edited")
            .args(extra)
            .output()
            .unwrap()
    };
    let out = run(&[]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--prune"));
    assert!(trace.exists());
    let out = run(&["--prune"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("pruned 1 stored run"));
    let rows = read_runs(&results.join("runs.csv")).unwrap();
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0].experiment, "kong2019-kept");
    assert!(!trace.exists());
}

/// A run killed (SIGKILL) half-way loses only what was running: the next start folds the
/// journal into runs.csv, does not redo the finished runs, and writes no duplicate row.
#[test]
fn a_killed_run_resumes_without_redoing_finished_runs() {
    let base = inputs::Scratch::unmade("cli-resume");
    let (experiments, results) = (base.join("experiments"), base.join("res"));
    std::fs::create_dir_all(&experiments).unwrap();
    std::fs::create_dir_all(&results).unwrap();
    // The slow run of `common::RESUME_EXPERIMENT` and three quick ones.
    let mut toml = String::from(common::RESUME_EXPERIMENT);
    for mu in [1, 2, 4] {
        toml.push_str(&format!(
            "[[experiment.variant]]\nlabel = \"ZNN mu={mu}\"\nexact = false\nscheme = {{ kind = \"kong2019-znn\", mu = {mu}.0, k_p = 1.0 }}\nsolvers = [{{ kind = \"znn\", gamma = 1.0 }}]\n"
        ));
    }
    std::fs::write(experiments.join("kong2019.toml"), toml).unwrap();
    let run = || {
        let mut c = reproduce();
        c.args(["--skip-explain", "--threads", "2", "--experiments-dir"])
            .arg(&experiments)
            .arg("--results-dir")
            .arg(&results)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped());
        c
    };
    common::kill_after_checkpoints(run, &results, 3);
    common::resume_completes(run, &results, 3, 4);
}

/// The audit's case: `--results-dir` outside the project runs, and its report is rendered
/// beside it (from the project's papers and experiment files), exit 0; nothing is read from
/// beside the results that is not there.
#[test]
fn a_results_directory_outside_the_project_gets_its_report() {
    let base = inputs::Scratch::unmade("elsewhere");
    let out = reproduce()
        .args([
            "run",
            "--experiment",
            "kong2019-circle",
            "--skip-explain",
            "--results-dir",
        ])
        .arg(base.join("results"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(base.join("results/runs.csv").is_file());
    let front = std::fs::read_to_string(base.join("report/REPORT.md")).unwrap();
    assert!(front.contains("kong2019"), "{front}");
    assert!(base.join("report/tasks/README.md").is_file());
}
