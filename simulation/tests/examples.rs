//! The runnable examples run, so they cannot rot: `cargo test` builds every example of the
//! package (examples/*.rs, see Cargo.toml) before it runs the tests, and this test runs each
//! binary and checks what it prints.

use std::path::PathBuf;
use std::process::Command;

/// `target/<profile>/examples/<name>`, beside this test's own `target/<profile>/deps/`.
fn example(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let profile_dir = exe
        .parent()
        .and_then(|deps| deps.parent())
        .expect("target/<profile>/deps/<test>");
    profile_dir.join("examples").join(name)
}

/// Runs the example `name` and returns what it printed.
fn run(name: &str) -> String {
    let path = example(name);
    assert!(
        path.exists(),
        "{} is not built: run the whole `cargo test --workspace --release` (it builds the \
         examples), or `cargo build --release --examples` first",
        path.display()
    );
    let out = Command::new(&path).output().expect("the example starts");
    assert!(
        out.status.success(),
        "{name} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// The numbers of the table row that starts with `label`.
fn row(out: &str, label: &str) -> Vec<f64> {
    let line = out
        .lines()
        .find(|l| l.starts_with(label))
        .unwrap_or_else(|| panic!("no row {label:?} in\n{out}"));
    line[label.len()..]
        .split_whitespace()
        .filter_map(|w| w.parse().ok())
        .collect()
}

#[test]
fn the_user_network_runs_and_is_scored_against_the_optimum() {
    let out = run("gnn_clover");
    let exact = row(&out, "exact");
    let lvi = row(&out, "LVI-PDNN");
    let gnn = row(&out, "GNN");
    // The exact column tracks to round-off; LVI-PDNN's drift is the scheme's (jia2019); the
    // penalty GNN lags: farther from x*, more drift.
    assert!(exact[1] < 1e-9, "{out}");
    assert!((lvi[0] - exact[0]).abs() < 1e-2 * exact[0], "{out}");
    assert!(gnn[2] > lvi[2] && gnn[0] > exact[0], "{out}");
}

#[test]
fn the_user_robot_runs_through_a_papers_scheme() {
    let out = run("user_robot");
    let exact = row(&out, "exact");
    let znn = row(&out, "ZNN");
    assert!(exact[1] < 1e-9 && znn[1] < 1e-5, "{out}");
    assert!((znn[0] - exact[0]).abs() < 1e-3 * exact[0], "{out}");
}
