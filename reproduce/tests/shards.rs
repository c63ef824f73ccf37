//! Cluster runs as a user runs them: shards as separate processes, merged; a shard killed
//! (SIGKILL) mid-run, started again and merged, against one process; a merge with a shard
//! missing; a shard directory of another selection or sweep refused at the start; K and N from
//! a Slurm array that does not tell N.

use crate::common;

use common::{ok, reproduce};
use std::path::PathBuf;
use store::read_runs;

/// A fresh scratch directory, removed when dropped.
fn temp(name: &str) -> inputs::Scratch {
    inputs::Scratch::dir(&format!("shards-{name}"))
}

/// A cheap selection: kong2019's exact columns (12 runs, well under a second each).
const SELECTION: [&str; 3] = ["--paper", "kong2019", "--exact-only"];

#[test]
fn three_shards_merged_equal_one_unsharded_run_and_a_missing_shard_is_named() {
    let base = temp("merge");
    let whole = base.join("whole");
    ok(reproduce()
        .args(SELECTION)
        .args(["--skip-explain", "--results-dir"])
        .arg(&whole)
        .output()
        .unwrap());
    let shard_dirs: Vec<PathBuf> = (1..=3).map(|k| base.join(format!("s{k}"))).collect();
    let children: Vec<_> = shard_dirs
        .iter()
        .enumerate()
        .map(|(i, d)| {
            reproduce()
                .args(["shard", &format!("{}/3", i + 1)])
                .args(SELECTION)
                .arg("--results-dir")
                .arg(d)
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    for c in children {
        ok(c.wait_with_output().unwrap());
    }
    for d in &shard_dirs {
        assert!(d.join("shard.toml").exists());
        assert!(!d.join("journal.csv").exists());
    }

    // A shard missing: exit 2, the missing runs and their shard named, nothing written.
    let partial = base.join("partial");
    let out = reproduce()
        .arg("merge")
        .args([&shard_dirs[0], &shard_dirs[2]])
        .arg("--results-dir")
        .arg(&partial)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    let missing = read_runs(&shard_dirs[1].join("runs.csv")).unwrap();
    assert!(!missing.is_empty());
    assert!(err.contains("shard(s) 2 of 3 not given"), "{err}");
    for r in &missing {
        let key = format!("{}  (shard 2/3", r.key());
        assert!(err.contains(&key), "{key} not in {err}");
    }
    assert!(!partial.join("runs.csv").exists());

    // Merging a shard twice: duplicates are named.
    let out = reproduce()
        .arg("merge")
        .args([
            &shard_dirs[0],
            &shard_dirs[1],
            &shard_dirs[2],
            &shard_dirs[1],
        ])
        .arg("--results-dir")
        .arg(&partial)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("in more than one shard"));

    let merged = base.join("merged");
    ok(reproduce()
        .arg("merge")
        .args(&shard_dirs)
        .arg("--results-dir")
        .arg(&merged)
        .output()
        .unwrap());
    common::assert_same_results(&merged, &whole, 12);
}

/// Pre-emption that saves work: a shard killed (SIGKILL) once it has checkpointed some runs,
/// started again, runs only its unfinished runs (through the journal of its directory), writes
/// no duplicate row and its manifest only at the end; and it merges, equal to one process: the
/// same cells but the timing columns, byte-identical traces.
#[test]
fn a_shard_killed_mid_run_resumes_and_merges_equal_to_one_process() {
    let base = temp("resume");
    let (experiments, results) = (base.join("experiments"), base.join("shard"));
    std::fs::create_dir_all(&experiments).unwrap();
    // The slow run of `common::RESUME_EXPERIMENT` and three quick ones (a sweep).
    std::fs::write(
        experiments.join("kong2019.toml"),
        format!(
            "{}{}",
            common::RESUME_EXPERIMENT,
            r#"[[experiment.variant]]
label = "ZNN"
exact = false
scheme = { kind = "kong2019-znn", k_p = 1.0 }
solvers = [{ kind = "znn", gamma = 1.0 }]
sweep = { "scheme.mu" = [1, 2, 4] }
"#
        ),
    )
    .unwrap();
    let run = || {
        let mut c = reproduce();
        c.args(["shard", "1/1", "--threads", "2", "--experiments-dir"])
            .arg(&experiments)
            .arg("--results-dir")
            .arg(&results)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped());
        c
    };
    common::kill_after_checkpoints(run, &results, 3);
    assert!(
        !results.join("shard.toml").exists(),
        "an unfinished shard has no manifest"
    );

    common::resume_completes(run, &results, 3, 4);
    let manifest = store::shard::Manifest::read(&results).unwrap();
    assert_eq!((manifest.shard, manifest.shards, manifest.runs), (1, 1, 4));
    assert_eq!(manifest.git_rev, reproduce::REVISION);

    // The resumed shard merges (its manifest covers the folded runs' traces) ...
    let merged = base.join("merged");
    ok(reproduce()
        .arg("merge")
        .arg(&results)
        .arg("--experiments-dir")
        .arg(&experiments)
        .arg("--results-dir")
        .arg(&merged)
        .output()
        .unwrap());
    // ... into what one process writes.
    let whole = base.join("whole");
    ok(reproduce()
        .args(["--paper", "kong2019", "--skip-explain", "--experiments-dir"])
        .arg(&experiments)
        .arg("--results-dir")
        .arg(&whole)
        .output()
        .unwrap());
    common::assert_same_results(&merged, &whole, 4);
}

/// A shard directory serves one shard of one selection: started for another selection, or
/// after its sweep was edited, the shard refuses before anything runs and the directory is
/// left as it was; a manifest no shard could write (`shards = 0`) is refused by the merge.
#[test]
fn a_shard_directory_of_another_selection_or_sweep_is_refused_at_the_start() {
    let base = temp("binding");
    let (experiments, dir) = (base.join("experiments"), base.join("shard"));
    std::fs::create_dir_all(&experiments).unwrap();
    let file = experiments.join("kong2019.toml");
    std::fs::write(&file, common::CHEAP_EXPERIMENT).unwrap();
    let shard = |extra: &[&str]| {
        reproduce()
            .args(["shard", "1/1", "--experiments-dir"])
            .arg(&experiments)
            .arg("--results-dir")
            .arg(&dir)
            .args(extra)
            .output()
            .unwrap()
    };
    ok(shard(&[]));
    let before = std::fs::read(dir.join("runs.csv")).unwrap();
    let refused = |out: std::process::Output, wants: &[&str]| {
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(out.status.code(), Some(2), "{err}");
        for w in wants {
            assert!(err.contains(w), "{w} not in {err}");
        }
        assert_eq!(std::fs::read(dir.join("runs.csv")).unwrap(), before);
        assert!(
            dir.join("shard.toml").exists(),
            "the finished shard is kept"
        );
    };
    refused(
        shard(&["--exact-only"]),
        &["bound to another shard", "--exact-only", "--results-dir"],
    );
    // The sweep edited: other experiment files.
    std::fs::write(
        &file,
        format!(
            "{}{}",
            common::CHEAP_EXPERIMENT,
            r#"[[experiment.variant]]
label = "ZNN swept"
scheme = { kind = "kong2019-znn", k_p = 1.0 }
sweep = { "scheme.mu" = [1, 2] }
"#
        ),
    )
    .unwrap();
    refused(
        shard(&[]),
        &["bound to another shard", "other experiment files"],
    );
    std::fs::write(&file, common::CHEAP_EXPERIMENT).unwrap();
    // Another K/N given the same directory.
    let out = reproduce()
        .args(["shard", "1/2", "--experiments-dir"])
        .arg(&experiments)
        .arg("--results-dir")
        .arg(&dir)
        .output()
        .unwrap();
    refused(out, &["it is shard 1/1's, this is shard 1/2"]);
    // The same shard started again resumes in its own directory.
    ok(shard(&[]));

    // shards = 0 in shard.toml: refused, naming the file and the field (no panic).
    let manifest = dir.join("shard.toml");
    let text = std::fs::read_to_string(&manifest).unwrap();
    std::fs::write(&manifest, text.replace("shards = 1", "shards = 0")).unwrap();
    let out = reproduce()
        .arg("merge")
        .arg(&dir)
        .arg("--experiments-dir")
        .arg(&experiments)
        .arg("--results-dir")
        .arg(base.join("merged"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("shard.toml") && err.contains("`shards = 0`"),
        "{err}"
    );
    assert!(!base.join("merged").join("runs.csv").exists());
}

/// `--shard auto` in a resubmitted Slurm task (`sbatch --array=2`: one task, MIN = MAX = 2)
/// does not guess N: it is refused naming the variables, and runs shard 2 of N once N is said.
#[test]
fn a_resubmitted_slurm_task_needs_the_number_of_shards() {
    let auto = |extra: &[(&str, &str)]| {
        let mut c = reproduce();
        for v in [
            "SLURM_ARRAY_TASK_ID",
            "SLURM_ARRAY_TASK_MIN",
            "SLURM_ARRAY_TASK_MAX",
            "SLURM_ARRAY_TASK_COUNT",
            "DRIFTBENCH_SHARDS",
            "JOB_COMPLETION_INDEX",
        ] {
            c.env_remove(v);
        }
        c.envs([
            ("SLURM_ARRAY_TASK_ID", "2"),
            ("SLURM_ARRAY_TASK_MIN", "2"),
            ("SLURM_ARRAY_TASK_MAX", "2"),
            ("SLURM_ARRAY_TASK_COUNT", "1"),
        ])
        .envs(extra.iter().copied())
        .args(["list", "--shard", "auto"])
        .args(SELECTION)
        .output()
        .unwrap()
    };
    let out = auto(&[]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    for v in [
        "SLURM_ARRAY_TASK_ID=2",
        "SLURM_ARRAY_TASK_COUNT=1",
        "--shards N",
        "DRIFTBENCH_SHARDS",
    ] {
        assert!(err.contains(v), "{v} not in {err}");
    }
    let out = ok(auto(&[("DRIFTBENCH_SHARDS", "3")]));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("shard 2/3:"), "{err}");
}

/// The binary names the revision it was built from (embedded at build time), the one its
/// rows and manifests carry.
#[test]
fn the_binary_knows_its_revision() {
    let out = ok(reproduce().arg("--version").output().unwrap());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(&format!("(revision {})", reproduce::REVISION)),
        "{text}"
    );
    assert!(!text.contains("unknown"), "{text}");
}

/// `list --shard K/N` lists the shard's runs; the shards' lists partition the selection.
#[test]
fn shard_lists_partition_the_selection() {
    for k in 1..=3 {
        let shard = format!("{k}/3");
        let out = ok(reproduce()
            .args(["list", "--shard", &shard])
            .args(SELECTION)
            .output()
            .unwrap());
        assert!(
            String::from_utf8_lossy(&out.stdout).contains("exact"),
            "shard {shard}"
        );
    }
    let count = |extra: &[&str]| {
        let out = ok(reproduce()
            .arg("list")
            .args(SELECTION)
            .args(extra)
            .output()
            .unwrap());
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .filter(|l| l.split_whitespace().nth(2) == Some("exact"))
            .count()
    };
    let all = count(&[]);
    let parts: usize = (1..=3)
        .map(|k| count(&["--shard", &format!("{k}/3")]))
        .sum();
    assert_eq!(all, 12);
    assert_eq!(parts, all);
}

/// Kill safety at every durable step (store::kill_point: each rename, journal append and
/// removal is one): for every step N of a shard's first start, the shard is killed there, then
/// started again and killed at the N-th step of that start (which, as N grows, falls on every
/// step of the resume: the fold's runs.csv and manifest, the journal's removal, ...), then
/// started a third time without the hook. That start must finish without `--accept-edited`,
/// and the merge must equal one unsharded process. The shard runs two runs at a time
/// (`reproduce::SHARD_CHUNK_VAR`), so the fold between its chunks is killed at each of its
/// steps too. An experiment file added beside the selection's (another paper's) blocks neither
/// the shard's start nor its merge.
#[test]
fn a_shard_killed_after_any_durable_step_resumes_and_merges_equal_to_one_process() {
    let base = temp("kill-points");
    let experiments = base.join("experiments");
    std::fs::create_dir_all(&experiments).unwrap();
    std::fs::write(experiments.join("kong2019.toml"), three_cheap_runs()).unwrap();
    let whole = base.join("whole");
    ok(reproduce()
        .args(["--paper", "kong2019", "--skip-explain", "--experiments-dir"])
        .arg(&experiments)
        .arg("--results-dir")
        .arg(&whole)
        .output()
        .unwrap());
    let shard = |dir: &std::path::Path, kill_after: Option<usize>| {
        let mut c = reproduce();
        c.args(["shard", "1/1", "--paper", "kong2019", "--experiments-dir"])
            .arg(&experiments)
            .arg("--results-dir")
            .arg(dir)
            .env(reproduce::SHARD_CHUNK_VAR, "2");
        if let Some(n) = kill_after {
            c.env(store::KILL_POINT_VAR, n.to_string());
        }
        c.output().unwrap()
    };
    let killed = |out: &std::process::Output| {
        String::from_utf8_lossy(&out.stderr).contains("killed after durable step")
    };
    let mut step = 0;
    loop {
        step += 1;
        assert!(step < 200, "a clean start takes fewer durable steps");
        let dir = base.join(format!("shard-{step}"));
        let first = shard(&dir, Some(step));
        if !killed(&first) {
            ok(first);
            break;
        }
        let second = shard(&dir, Some(step));
        if !killed(&second) {
            ok(second);
        }
        ok(shard(&dir, None));
        // A finished shard holds one runs.csv: its parts were merged into it and removed.
        let parts: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains("runs.part-"))
            .collect();
        assert!(parts.is_empty(), "step {step}: {parts:?}");
        let merged = base.join(format!("merged-{step}"));
        ok(reproduce()
            .arg("merge")
            .arg(&dir)
            .arg("--experiments-dir")
            .arg(&experiments)
            .arg("--results-dir")
            .arg(&merged)
            .output()
            .unwrap());
        common::assert_same_results(&merged, &whole, 3);
    }
    assert!(step > 10, "only {step} durable steps in a shard of 3 runs");

    // Another paper's experiment file added beside: the finished shard starts again (running
    // nothing) and merges; the selection does not read that file.
    let dir = base.join("shard-1");
    std::fs::write(
        experiments.join("jia2019.toml"),
        common::CHEAP_EXPERIMENT
            .replace("paper = \"kong2019\"", "paper = \"jia2019\"")
            .replace("kong2019-cheap", "jia2019-cheap"),
    )
    .unwrap();
    let again = ok(shard(&dir, None));
    let err = String::from_utf8_lossy(&again.stderr);
    assert!(err.contains("the shard holds 3 of its runs"), "{err}");
    let merged = base.join("merged-beside");
    ok(reproduce()
        .arg("merge")
        .arg(&dir)
        .arg("--experiments-dir")
        .arg(&experiments)
        .arg("--results-dir")
        .arg(&merged)
        .output()
        .unwrap());
    common::assert_same_results(&merged, &whole, 3);
}

/// Resume is cumulative: a shard whose every start is killed after a few durable steps (fewer
/// than a whole start takes) still finishes, each start keeping what the earlier ones finished
/// (a start that re-ran the runs folded by an earlier one would never end).
#[test]
fn a_shard_killed_every_few_steps_finishes_after_a_bounded_number_of_starts() {
    let base = temp("killed-often");
    let (experiments, dir) = (base.join("experiments"), base.join("shard"));
    std::fs::create_dir_all(&experiments).unwrap();
    std::fs::write(experiments.join("kong2019.toml"), three_cheap_runs()).unwrap();
    let mut starts = 0;
    loop {
        starts += 1;
        assert!(starts <= 8, "not finished after {} starts", starts - 1);
        let out = reproduce()
            .args(["shard", "1/1", "--experiments-dir"])
            .arg(&experiments)
            .arg("--results-dir")
            .arg(&dir)
            .env(store::KILL_POINT_VAR, "10")
            .output()
            .unwrap();
        if !String::from_utf8_lossy(&out.stderr).contains("killed after durable step") {
            ok(out);
            break;
        }
    }
    assert!(starts > 1, "the kill came before the shard's end");
    let manifest = store::shard::Manifest::read(&dir).unwrap();
    assert_eq!(manifest.runs, 3);
    assert_eq!(read_runs(&dir.join("runs.csv")).unwrap().len(), 3);
}

/// `common::CHEAP_EXPERIMENT` with two more variants (a sweep of mu): three cheap runs.
fn three_cheap_runs() -> String {
    format!(
        "{}{}",
        common::CHEAP_EXPERIMENT,
        r#"[[experiment.variant]]
label = "ZNN swept"
scheme = { kind = "kong2019-znn", k_p = 1.0 }
sweep = { "scheme.mu" = [1, 2] }
"#
    )
}

/// Traces by choice (a sweep's `traces`): with `"none"` and with `{ every = 3 }`, one
/// process and two shards merged write a row for every run and the traces of the chosen runs
/// only (the sweep's runs 0 and 3 of five with every = 3; the experiment's run without a sweep
/// keeps its own); the merge equals the one process, and `check` against the merged rows
/// passes. A bad `traces` is refused at load (exit 2) naming the file, the field and choices.
#[test]
fn a_sweep_keeps_the_traces_it_chooses_unsharded_and_merged() {
    for (name, traces, kept) in [
        ("none", "\"none\"", vec![]),
        ("every", "{ every = 3 }", vec!["mu-1", "mu-4"]),
    ] {
        let base = temp(&format!("traces-{name}"));
        let experiments = base.join("experiments");
        std::fs::create_dir_all(&experiments).unwrap();
        std::fs::write(
            experiments.join("kong2019.toml"),
            format!(
                "{}[[experiment.variant]]\nid = \"s\"\nlabel = \"ZNN swept\"\nscheme = {{ kind = \"kong2019-znn\", k_p = 1.0 }}\ntraces = {traces}\nsweep = {{ \"scheme.mu\" = [1, 2, 3, 4, 5] }}\n",
                common::CHEAP_EXPERIMENT
            ),
        )
        .unwrap();
        let run = |args: &[&str], dir: &PathBuf| {
            ok(reproduce()
                .args(args)
                .args(["--paper", "kong2019", "--experiments-dir"])
                .arg(&experiments)
                .arg("--results-dir")
                .arg(dir)
                .output()
                .unwrap())
        };
        let whole = base.join("whole");
        run(&["--skip-explain"], &whole);
        let shards: Vec<PathBuf> = (1..=2).map(|k| base.join(format!("s{k}"))).collect();
        for (k, d) in shards.iter().enumerate() {
            run(&["shard", &format!("{}/2", k + 1)], d);
        }
        let merged = base.join("merged");
        ok(reproduce()
            .arg("merge")
            .args(&shards)
            .arg("--experiments-dir")
            .arg(&experiments)
            .arg("--results-dir")
            .arg(&merged)
            .output()
            .unwrap());
        let mut want: Vec<PathBuf> = kept
            .iter()
            .map(|v| PathBuf::from(format!("kong2019-cheap/s-{v}__exact.csv")))
            .collect();
        want.push(PathBuf::from("kong2019-cheap/znn-eq.-22__exact.csv"));
        want.sort();
        for dir in [&whole, &merged] {
            assert_eq!(read_runs(&dir.join("runs.csv")).unwrap().len(), 6, "{name}");
            let names: Vec<PathBuf> = common::traces(dir).into_iter().map(|(p, _)| p).collect();
            assert_eq!(names, want, "{name}: {}", dir.display());
        }
        assert_eq!(
            common::comparable(read_runs(&merged.join("runs.csv")).unwrap()),
            common::comparable(read_runs(&whole.join("runs.csv")).unwrap())
        );
        assert!(common::traces(&merged) == common::traces(&whole));
        // The merged rows are a baseline the same runs reproduce.
        ok(reproduce()
            .args(["check", "--paper", "kong2019", "--experiments-dir"])
            .arg(&experiments)
            .arg("--baseline")
            .arg(merged.join("runs.csv"))
            .output()
            .unwrap());
        // A shard started again runs nothing (its rows are done, with or without a trace).
        let again = reproduce()
            .args(["shard", "1/2", "--paper", "kong2019", "--experiments-dir"])
            .arg(&experiments)
            .arg("--results-dir")
            .arg(&shards[0])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&again.stderr);
        assert!(
            again.status.success() && err.contains("already done"),
            "{err}"
        );
    }
    let base = temp("traces-bad");
    let experiments = base.join("experiments");
    std::fs::create_dir_all(&experiments).unwrap();
    std::fs::write(
        experiments.join("kong2019.toml"),
        format!(
            "{}[[experiment.variant]]\nlabel = \"S\"\nscheme = {{ kind = \"kong2019-znn\", k_p = 1.0 }}\ntraces = \"some\"\nsweep = {{ \"scheme.mu\" = [1, 2] }}\n",
            common::CHEAP_EXPERIMENT
        ),
    )
    .unwrap();
    let out = reproduce()
        .args(["list", "--experiments-dir"])
        .arg(&experiments)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("kong2019.toml")
            && err.contains(
                "field `traces`: must be \"all\" (the default), \"none\" or { every = k }"
            ),
        "{err}"
    );
}
