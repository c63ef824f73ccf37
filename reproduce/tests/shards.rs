//! Cluster runs as a user runs them: shards as separate processes, merged; a shard killed and
//! started again; a merge with a shard missing.

mod common;

use common::{ok, reproduce};
use records::runs::{read_runs, RunRow};
use std::path::{Path, PathBuf};

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("driftbench-shards-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A cheap selection: kong2019's exact columns (11 runs, well under a second each).
const SELECTION: [&str; 3] = ["--paper", "kong2019", "--exact-only"];

/// Rows without what differs between two runs of the same code: timing and revision.
fn comparable(mut rows: Vec<RunRow>) -> Vec<String> {
    for r in &mut rows {
        r.wall_s = 0.0;
        r.sim_s = 0.0;
        r.observe_s = 0.0;
        r.git_rev.clear();
    }
    rows.iter().map(|r| format!("{r:?}")).collect()
}

/// Every file under `dir/traces`, relative path and bytes.
fn traces(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    fn walk(base: &Path, d: &Path, out: &mut Vec<(PathBuf, Vec<u8>)>) {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(base, &p, out);
            } else {
                out.push((
                    p.strip_prefix(base).unwrap().to_path_buf(),
                    std::fs::read(&p).unwrap(),
                ));
            }
        }
    }
    let mut out = Vec::new();
    walk(&dir.join("traces"), &dir.join("traces"), &mut out);
    out.sort();
    out
}

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
    let want = read_runs(&whole.join("runs.csv")).unwrap();
    assert_eq!(want.len(), 11);
    assert_eq!(
        comparable(read_runs(&merged.join("runs.csv")).unwrap()),
        comparable(want)
    );
    let (t_whole, t_merged) = (traces(&whole), traces(&merged));
    assert_eq!(t_whole.len(), 11);
    assert!(t_whole == t_merged, "trace files differ");
    let _ = std::fs::remove_dir_all(&base);
}

/// A shard killed (SIGKILL) half-way and started again runs only its unfinished runs (through
/// the journal of its directory) and writes no duplicate row; its manifest appears only at
/// the end.
#[test]
fn a_killed_shard_resumes_without_redoing_finished_runs() {
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
    let _ = std::fs::remove_dir_all(&base);
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
