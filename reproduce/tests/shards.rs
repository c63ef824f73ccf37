//! Cluster runs as a user runs them: shards as separate processes, merged; a shard killed
//! (SIGKILL) mid-run, started again and merged, against one process; a merge with a shard
//! missing; a shard directory of another selection or sweep refused at the start; K and N from
//! a Slurm array that does not tell N.

use crate::common;

use common::{ok, reproduce};
use records::runs::read_runs;
use std::path::PathBuf;

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("driftbench-shards-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A cheap selection: kong2019's exact columns (11 runs, well under a second each).
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
                .args(SELECTION)
                .args(["--shard", &format!("{}/3", i + 1), "--results-dir"])
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
        .arg("--merge")
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
        .arg("--merge")
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
        .arg("--merge")
        .args(&shard_dirs)
        .arg("--results-dir")
        .arg(&merged)
        .output()
        .unwrap());
    common::assert_same_results(&merged, &whole, 11);
    let _ = std::fs::remove_dir_all(&base);
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
        c.args(["--shard", "1/1", "--threads", "2", "--experiments-dir"])
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
    let manifest = records::shard::Manifest::read(&results).unwrap();
    assert_eq!(
        (manifest.shard, manifest.shards, manifest.runs.len()),
        (1, 1, 4)
    );
    assert_eq!(manifest.git_rev, reproduce::revision::REVISION);

    // The resumed shard merges (its manifest covers the folded runs' traces) ...
    let merged = base.join("merged");
    ok(reproduce()
        .arg("--merge")
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
    let _ = std::fs::remove_dir_all(&base);
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
            .args(["--shard", "1/1", "--experiments-dir"])
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
        .args(["--shard", "1/2", "--experiments-dir"])
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
        .arg("--merge")
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
    let _ = std::fs::remove_dir_all(&base);
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
        .args(SELECTION)
        .args(["--list", "--shard", "auto"])
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
        text.contains(&format!("(revision {})", reproduce::revision::REVISION)),
        "{text}"
    );
    assert!(!text.contains("unknown"), "{text}");
}

/// `--shard K/N --list` lists the shard's runs; the shards' lists partition the selection.
#[test]
fn shard_lists_partition_the_selection() {
    let count = |extra: &[&str]| {
        let out = ok(reproduce()
            .args(SELECTION)
            .arg("--list")
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
    assert_eq!(all, 11);
    assert_eq!(parts, all);
}
