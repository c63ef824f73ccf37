//! Embeds the project data the package needs outside a checkout (`src/packaged.rs`): every
//! file of the experiment files (`experiments/`), the papers (`papers/`) and the committed
//! results the leaderboard ranks against (`results/runs.csv`, `results/leaderboard.csv`,
//! `results/leaderboard-timing.csv`), read from the repository itself, so that the data has one
//! source: the repository's files, embedded anew whenever one changes. (The robot files,
//! `robots/data/`, are already in the library: the `robots` crate embeds them.)
//!
//! Writes `$OUT_DIR/packaged.rs`: `FILES`, a slice of `(path relative to the project root with
//! '/' separators, include_bytes!(absolute path))` sorted by path, and `DIGEST`, the SHA-256 of
//! the paths and contents (the name of the directory the data is unpacked into). Only regular
//! files inside the checkout are embedded (`inputs::embed`, included here by path): a symbolic
//! link or a special file among them, or a directory that leads outside, fails the build,
//! naming it (`include_bytes!` would follow a link to a secret and put it in the package).

// Walks whole trees here (`Walk::Top` serves the robots' build).
#[allow(dead_code)]
#[path = "../inputs/src/embed.rs"]
mod embed;

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

/// The build fails with the error's message (`main` returning an error would show its
/// `Debug` form).
fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), Box<dyn Error>> {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR")?);
    let root = manifest
        .parent()
        .ok_or("the python crate has no parent directory")?
        .to_path_buf();
    let mut files = Vec::new();
    for dir in DIRS {
        println!("cargo:rerun-if-changed={}", root.join(dir).display());
        files.extend(embed::files(&root, Path::new(dir), embed::Walk::Tree)?);
    }
    for file in FILES {
        let full = root.join(file);
        println!("cargo:rerun-if-changed={}", full.display());
        files.push(embed::file(&root, Path::new(file)).map_err(|e| {
            format!("{e} (the package embeds it: build from a driftbench checkout)")
        })?);
    }
    files.sort();
    let mut digest = Sha256::new();
    let mut out =
        String::from("/// The embedded files: (path under the project root, contents).\n");
    out.push_str("pub const FILES: &[(&str, &[u8])] = &[\n");
    for embed::Embedded {
        relative: rel,
        absolute: full,
    } in &files
    {
        let bytes = std::fs::read(full).map_err(|e| format!("{full}: {e}"))?;
        digest.update((rel.len() as u64).to_le_bytes());
        digest.update(rel.as_bytes());
        digest.update((bytes.len() as u64).to_le_bytes());
        digest.update(&bytes);
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
