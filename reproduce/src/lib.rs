//! driftbench's reproduction layer: experiment files, the coupled arm + solver simulation,
//! metrics, the score against the exact optimum, and the committed results.

pub mod coupled;
pub mod experiment;
pub mod explain;
pub mod figures;
pub mod gate;
pub mod metrics;
pub mod report;
pub mod results;
pub mod robot_registry;
pub mod run;
pub mod runner;

use std::path::PathBuf;

/// The workspace root (where `experiments/`, `results/` and `report/` live).
pub fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("reproduce/ sits in the workspace")
        .to_path_buf()
}

/// The current git revision, or "unknown" outside a checkout.
pub fn git_revision() -> String {
    std::process::Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .current_dir(workspace_root())
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "unknown".to_string())
}
