//! What the binary's process tests share: starting `reproduce`, and killing a run once it has
//! checkpointed some runs.

use std::path::Path;
use std::process::Command;

/// The `reproduce` binary, started in the workspace root.
pub fn reproduce() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_reproduce"));
    c.current_dir(simulation::root::from_current_dir().unwrap());
    c
}

/// Starts `run()`, waits until the journal of `results` holds `rows` rows (after its header),
/// kills the process and checks that it was killed with exactly those rows checkpointed and no
/// runs.csv written.
pub fn kill_after_checkpoints(run: impl Fn() -> Command, results: &Path, rows: usize) {
    let mut first = run().spawn().unwrap();
    let journal = records::journal::path(results);
    let lines = || {
        std::fs::read_to_string(&journal)
            .map(|t| t.lines().count())
            .unwrap_or(0)
    };
    let started = std::time::Instant::now();
    while lines() < rows + 1 && started.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    first.kill().unwrap();
    let _ = first.wait();
    assert_eq!(
        lines(),
        rows + 1,
        "the {rows} quick runs are checkpointed before the kill"
    );
    assert!(!results.join("runs.csv").exists());
}
