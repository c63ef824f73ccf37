//! A test hook for kill safety. With `DRIFTBENCH_KILL_AFTER=N` (a whole number) in the
//! environment, the process aborts right after its N-th durable step, as a SIGKILL would stop it
//! there (no destructor runs, nothing more is written): a file renamed into place
//! ([`crate::write_atomic`], which every table, trace and manifest goes through), a line
//! appended to the journal or to its seal, a file of the journal or the shard removed. Without
//! the variable (or with a value that is not a whole number) nothing changes but a count.
//! `reproduce/tests/shards.rs` kills a shard at every such step in turn and checks that the
//! next start resumes it and that the merge equals an unsharded run.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;

/// The environment variable of the hook.
pub const VAR: &str = "DRIFTBENCH_KILL_AFTER";

/// Counts one durable step; aborts the process when it is the step `DRIFTBENCH_KILL_AFTER`
/// names.
pub fn passed() {
    static AFTER: OnceLock<Option<usize>> = OnceLock::new();
    static STEPS: AtomicUsize = AtomicUsize::new(0);
    let after = AFTER.get_or_init(|| std::env::var(VAR).ok().and_then(|v| v.parse().ok()));
    let step = STEPS.fetch_add(1, Ordering::SeqCst) + 1;
    if *after == Some(step) {
        eprintln!("{VAR}={step}: killed after durable step {step}");
        std::process::abort();
    }
}
