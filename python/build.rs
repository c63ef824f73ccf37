//! Embeds the project data the package needs outside a checkout (`src/packaged.rs`): every
//! file of the experiment files (`experiments/`), the papers (`papers/`) and the committed
//! results the leaderboard ranks against (`results/runs.csv`, `results/leaderboard.csv`,
//! `results/leaderboard-timing.csv`), read from the repository itself, so that the data has one
//! source: the repository's files, embedded anew whenever one changes. (The robot files,
//! `robots/data/`, are already in the library: the `robots` crate embeds them.)
//!
//! Writes `$OUT_DIR/packaged.rs`: `FILES`, a slice of `(path relative to the project root with
//! '/' separators, include_bytes!(absolute path))` sorted by path, and `DIGEST`, the SHA-256 of
//! the paths and contents (the name of the directory the data is unpacked into).

use sha2::{Digest, Sha256};
use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The directories embedded whole, relative to the project root.
const DIRS: [&str; 2] = ["experiments", "papers"];
/// The single files embedded, relative to the project root.
const FILES: [&str; 3] = [
    "results/runs.csv",
    "results/leaderboard.csv",
    "results/leaderboard-timing.csv",
];

/// Every file under `dir` (hidden entries skipped), as (relative path, absolute path).
fn walk(root: &Path, dir: &Path, out: &mut Vec<(String, PathBuf)>) -> Result<(), Box<dyn Error>> {
    for entry in std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))? {
        let path = entry?.path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .ok_or_else(|| format!("file name is not UTF-8: {}", path.display()))?;
        if name.starts_with('.') {
            continue;
        }
        if path.is_dir() {
            walk(root, &path, out)?;
        } else {
            out.push((relative(root, &path)?, path));
        }
    }
    Ok(())
}

/// `path` relative to `root`, with '/' separators.
fn relative(root: &Path, path: &Path) -> Result<String, Box<dyn Error>> {
    let parts: Option<Vec<&str>> = path
        .strip_prefix(root)?
        .components()
        .map(|c| c.as_os_str().to_str())
        .collect();
    Ok(parts
        .ok_or_else(|| format!("path is not UTF-8: {}", path.display()))?
        .join("/"))
}

fn main() -> Result<(), Box<dyn Error>> {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR")?);
    let root = manifest
        .parent()
        .ok_or("the python crate has no parent directory")?
        .to_path_buf();
    let mut files = Vec::new();
    for dir in DIRS {
        let full = root.join(dir);
        println!("cargo:rerun-if-changed={}", full.display());
        walk(&root, &full, &mut files)?;
    }
    for file in FILES {
        let full = root.join(file);
        println!("cargo:rerun-if-changed={}", full.display());
        if !full.is_file() {
            return Err(format!(
                "{}: missing; the package embeds it (build from a driftbench checkout)",
                full.display()
            )
            .into());
        }
        files.push((file.to_string(), full));
    }
    files.sort();
    let mut digest = Sha256::new();
    let mut out =
        String::from("/// The embedded files: (path under the project root, contents).\n");
    out.push_str("pub const FILES: &[(&str, &[u8])] = &[\n");
    for (rel, full) in &files {
        let bytes = std::fs::read(full).map_err(|e| format!("{}: {e}", full.display()))?;
        digest.update((rel.len() as u64).to_le_bytes());
        digest.update(rel.as_bytes());
        digest.update((bytes.len() as u64).to_le_bytes());
        digest.update(&bytes);
        let full = full
            .to_str()
            .ok_or_else(|| format!("path is not UTF-8: {}", full.display()))?;
        writeln!(out, "    ({rel:?}, include_bytes!({full:?})),")?;
    }
    out.push_str("];\n");
    let hex: String = digest
        .finalize()
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    writeln!(
        out,
        "/// SHA-256 of the embedded paths and contents.\npub const DIGEST: &str = {hex:?};"
    )?;
    std::fs::write(
        PathBuf::from(std::env::var("OUT_DIR")?).join("packaged.rs"),
        out,
    )?;
    Ok(())
}
