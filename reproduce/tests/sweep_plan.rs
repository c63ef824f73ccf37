//! A sweep of 10^7 runs is loaded from its plan and one shard of it planned in proportion to
//! the shard (issue 43 item 2, docs/cluster.md "Shard planning by index"): no variant of the
//! sweep is made but the shard's (and the few the load checks), so loading and listing
//! `--shard 5/10000` take a bounded number of allocations and seconds, where expanding the
//! sweep took more than 10^7 allocations and gigabytes; and whether a run key is described is
//! decided from its names, so `shard 5/10000` runs in proportion to the shard too.

use std::time::{Duration, Instant};

/// kong2019's exact column with mu swept over [1, 2] in `runs - 1` steps: `runs` runs.
fn sweep(runs: usize) -> String {
    format!(
        r#"{}[[experiment.variant]]
label = "ZNN"
scheme = {{ kind = "znn-rmp", mu = 1.0, k_p = 1.0 }}
sweep = {{ "scheme.mu" = {{ from = 1.0, to = 2.0, step = {} }} }}
"#,
        fixtures::katana_circle("a sweep of 10^7 runs", "kong2019-plan", 0.05, ""),
        1.0 / (runs - 1) as f64
    )
}

const RUNS: usize = 10_000_001;

/// Shard 5 of 10,000: runs 4, 10,004, ..., 9,990,004.
#[test]
fn a_shard_of_a_sweep_of_ten_million_runs_is_planned_from_its_axes() {
    let text = sweep(RUNS);
    let started = Instant::now();
    let ((variants, keys), allocations) = alloc_count::count_with(|| {
        let file = reproduce::experiments_from_toml(&text).unwrap();
        let e = &file.experiments[0];
        assert_eq!(e.variants.run_count(false), RUNS);
        let keys: Vec<String> = file
            .runs_at(0, false, (4..RUNS).step_by(10_000))
            .map(|r| r.unwrap().spec.key().to_string())
            .collect();
        (e.variants.len(), keys)
    });
    let took = started.elapsed();
    assert_eq!(variants, RUNS);
    assert_eq!(keys.len(), 1000);
    assert!(keys[0].contains("mu-1.0000004"), "{}", keys[0]);
    assert!(keys[999].contains("mu-1.9990004"), "{}", keys[999]);
    assert!(
        allocations < 1_000_000,
        "{allocations} allocations: the sweep was expanded"
    );
    assert!(took < Duration::from_secs(60), "{took:?}");
}

/// The same through the binary: `reproduce list --shard 5/10000` lists the shard's 1,000
/// runs, each line its key and label, in well under a minute.
#[test]
fn list_shard_of_a_sweep_of_ten_million_runs_is_fast() {
    let root = inputs::Scratch::unmade("sweep-plan");
    std::fs::create_dir_all(root.join("experiments")).unwrap();
    std::fs::write(root.join("experiments/kong2019.toml"), sweep(RUNS)).unwrap();
    let started = Instant::now();
    let out = crate::common::reproduce()
        .current_dir(&root)
        .args(["list", "--shard", "5/10000"])
        .output()
        .unwrap();
    let took = started.elapsed();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 2 + 1000, "{stdout}");
    assert!(lines[1].ends_with(": 1000 runs"), "{}", lines[1]);
    assert!(
        lines[2].contains("znn-mu-1.0000004 / exact") && lines[2].contains("ZNN [mu=1.0000004]"),
        "{}",
        lines[2]
    );
    assert!(took < Duration::from_secs(60), "{took:?}");
}

/// Whether a run key of the 10^7-run sweep is described is decided from its names
/// (catalog::RunLookup, what a shard's pruning and resume and a merge's checks ask): the
/// shard's 1,000 keys are found, with whether they keep their trace, and keys near them
/// (another digit, another solver, an extra token) are not, in a bounded number of
/// allocations and seconds, where making every run's key took ~5 minutes and 160 MB.
#[test]
fn the_keys_of_a_sweep_of_ten_million_runs_are_decided_from_its_axes() {
    let text = sweep(RUNS);
    let file = reproduce::experiments_from_toml(&text).unwrap();
    let keys: Vec<spec::RunKey> = file
        .runs_at(0, false, (4..RUNS).step_by(10_000))
        .map(|r| r.unwrap().spec.key())
        .collect();
    let files = [file];
    let started = Instant::now();
    let (found, allocations) = alloc_count::count_with(|| {
        let lookup = catalog::RunLookup::new(&files);
        let mut found = [0usize; 2];
        for key in &keys {
            found[0] +=
                usize::from(lookup.find(key).unwrap() == catalog::Found::Run { keeps_trace: true });
            let variant = key.variant.as_str();
            for (v, s) in [
                (variant.replace("mu-1.", "mu-3."), "exact"),
                (format!("{variant}-0"), "exact"),
                (variant.to_string(), "znn"),
            ] {
                let near = spec::RunKey::from_ids(key.experiment.as_str(), &v, s).unwrap();
                found[1] += usize::from(lookup.find(&near).unwrap() != catalog::Found::NoRun);
            }
        }
        found
    });
    let took = started.elapsed();
    assert_eq!(found, [1000, 0]);
    assert!(
        allocations < 1_000_000,
        "{allocations} allocations: the sweep's runs were made"
    );
    assert!(took < Duration::from_secs(60), "{took:?}");
}

/// The same through the binary: `reproduce shard 5/10000` of the 10^7-run sweep prunes and
/// resumes by the keys' names and runs its 1,000 runs alone, in well under a minute (it made
/// every run's key of the sweep first before: ~5 minutes of CPU and 160 MB), and started
/// again it runs none of them.
#[test]
fn a_shard_of_a_sweep_of_ten_million_runs_runs_in_proportion_to_the_shard() {
    let root = inputs::Scratch::unmade("sweep-shard");
    std::fs::create_dir_all(root.join("experiments")).unwrap();
    let text = sweep(RUNS).replace("sweep = ", "traces = \"none\"\nsweep = ");
    std::fs::write(root.join("experiments/kong2019.toml"), text).unwrap();
    for (start, said) in [
        (0, "shard 5/10000 done"),
        (1, "resuming: 1000 of the selected runs"),
    ] {
        let started = Instant::now();
        let out = crate::common::reproduce()
            .current_dir(&root)
            .args(["shard", "5/10000", "--threads", "1"])
            .output()
            .unwrap();
        let took = started.elapsed();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "start {start}: {err}");
        assert!(err.contains(said), "start {start}: {err}");
        assert!(took < Duration::from_secs(60), "start {start}: {took:?}");
    }
    let rows = std::fs::read_to_string(root.join("results-shard-5-of-10000/runs.csv")).unwrap();
    assert_eq!(rows.lines().count(), 1 + 1000);
}

/// A shard of a sweep with variants that fail their checks when made (a label past 100 bytes,
/// off the lines the load checks) stops with exit 2 naming the first of its own, before it
/// runs anything: it makes its runs in a pass before the first run. (Another shard's variant
/// is that shard's to refuse: a shard makes no variant but its own.)
#[test]
fn a_shard_stops_before_running_at_a_variant_that_fails_when_made() {
    let root = inputs::Scratch::unmade("sweep-made");
    std::fs::create_dir_all(root.join("experiments")).unwrap();
    let text = sweep(100_001).replace(
        "label = \"ZNN\"",
        &format!("label = \"{}\"", "L".repeat(90)),
    );
    std::fs::write(root.join("experiments/kong2019.toml"), text).unwrap();
    let out = crate::common::reproduce()
        .current_dir(&root)
        .args(["shard", "2/50000", "--threads", "1"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("kong2019.toml")
            && err.contains("variant[1] (")
            && err.contains("field `label`"),
        "{err}"
    );
    // Nothing ran: no run was checkpointed.
    let journal = root.join("results-shard-2-of-50000/journal.csv");
    assert!(
        !journal.exists() || std::fs::read_to_string(&journal).unwrap().lines().count() <= 1,
        "a run was checkpointed"
    );
}
