//! driftbench's reproduction layer: experiment files, the coupled arm + solver simulation,
//! metrics, the score against the exact optimum, and the committed results.

pub mod coupled;
pub mod experiment;
pub mod explain;
pub mod figures;
pub mod gate;
pub mod journal;
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

/// The current git revision, with `-dirty` when the code differs from it (any tracked file
/// outside `results/` and `report/`, which a run itself rewrites), or "unknown" outside a
/// checkout.
pub fn git_revision() -> String {
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .current_dir(workspace_root())
            .output()
            .ok()
    };
    let Some(rev) = git(&["rev-parse", "--short=12", "HEAD"])
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    else {
        return "unknown".to_string();
    };
    let dirty = git(&[
        "diff",
        "--quiet",
        "HEAD",
        "--",
        ".",
        ":(exclude)results",
        ":(exclude)report",
    ])
    .is_some_and(|o| o.status.code() == Some(1));
    if dirty {
        format!("{rev}-dirty")
    } else {
        rev
    }
}
