//! Sweeps at scale: expanding, validating, listing and sharding 10^4, 10^5 and 10^6 runs, and
//! merging 10^5 stored rows, each timed once with the process's peak memory after it
//! (`VmHWM`). Every step is linear in the runs (hash maps, no pairwise scans), which this
//! bench shows as time per run staying flat across the three sizes. Listing and the shard
//! plan take the runs as they are made (as `reproduce list` does), so the peak after them
//! is the loaded file's; collecting every run as a `RunSpec`, as a run does, comes last.
//!
//! `cargo bench -p driftbench-benches --bench sweep_scale` (about a minute; the numbers are in
//! docs/cluster.md). Under `cargo test --benches` it runs the smallest size only.

use records::{merge_runs, RunRow};
use spec::RunSpec;
use std::time::Instant;

/// An experiment file whose one variant sweeps kong2019's mu over `n` values (exact column
/// only: one run per value).
fn sweep_file(n: usize) -> String {
    format!(
        r#"{}[[experiment.variant]]
label = "ZNN"
scheme = {{ kind = "znn-rmp", mu = 1.0, k_p = 1.0 }}
sweep = {{ "scheme.mu" = {{ from = 1, to = {n}, step = 1 }} }}
"#,
        fixtures::katana_circle("sweep at scale", "kong2019-scale", 9.0, "")
    )
}

/// Peak resident memory of this process so far, in MB (Linux; 0 elsewhere).
fn peak_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<f64>().ok())
        })
        .map_or(0.0, |kb| kb / 1024.0)
}

fn timed<T>(what: &str, n: usize, f: impl FnOnce() -> T) -> T {
    let t = Instant::now();
    let out = f();
    let s = t.elapsed().as_secs_f64();
    println!(
        "{what:<34} {n:>9} runs {s:>8.2} s {:>8.2} us/run   peak {:>7.0} MB",
        1e6 * s / n as f64,
        peak_mb()
    );
    out
}

fn main() {
    let full = std::env::args().any(|a| a == "--bench");
    let sizes: &[usize] = if full {
        &[10_000, 100_000, 1_000_000]
    } else {
        &[1_000]
    };
    for &n in sizes {
        let text = sweep_file(n);
        let file = timed("expand + validate (load)", n, || {
            reproduce::experiments_from_toml(&text).expect("a valid sweep")
        });
        // What `list` and `list --shards` do: the runs made as they are taken, none held.
        timed("jobs + keys, streamed (list)", n, || {
            let keys: usize = file
                .iter_jobs()
                .map(|j| j.expect("a valid sweep").key().to_string().len())
                .sum();
            assert!(keys > 0);
        });
        timed("shard plan (8 shards), counted", n, || {
            let total = file
                .experiments
                .iter()
                .map(|e| e.variants.run_count(false))
                .sum();
            store::shard::plan(total, 8)
        });
        // What a run (and a shard) holds: every run of the selection as a `RunSpec`.
        let jobs: Vec<RunSpec> = timed("jobs collected (a run's)", n, || {
            file.jobs().expect("a valid sweep")
        });
        if n <= 100_000 {
            let rows: Vec<RunRow> = jobs
                .iter()
                .map(|j| RunRow::blank(&j.key(), spec::SolverKind::Exact))
                .collect();
            let half = rows[..n / 2].to_vec();
            timed("merge_runs stored + fresh rows", n, || {
                merge_runs(rows, half).len()
            });
        }
    }
}
