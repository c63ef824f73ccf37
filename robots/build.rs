//! Embeds every robot file `data/*.toml` in the library (`robots::data_robot::builtin_files`):
//! dropping a new file into `robots/data/` registers it on the next build, without Rust.
//!
//! Writes `$OUT_DIR/builtin_robots.rs`, a slice of `(file name, include_str!(absolute path))`
//! sorted by file name, so the order (and so `robot_names()`) does not depend on the directory
//! listing.

use std::error::Error;
use std::fmt::Write as _;
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn Error>> {
    println!("cargo:rerun-if-changed=data");
    let dir = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR")?).join("data");
    let mut files = Vec::new();
    for entry in std::fs::read_dir(&dir)? {
        let path = entry?.path();
        if path.extension().is_some_and(|e| e == "toml") {
            let name = path
                .file_name()
                .and_then(|n| n.to_str())
                .ok_or_else(|| format!("robot file name is not UTF-8: {}", path.display()))?
                .to_string();
            let full = path
                .to_str()
                .ok_or_else(|| format!("robot file path is not UTF-8: {}", path.display()))?
                .to_string();
            files.push((name, full));
        }
    }
    files.sort();
    let mut out = String::from("&[\n");
    for (name, full) in &files {
        writeln!(out, "    ({name:?}, include_str!({full:?})),")?;
    }
    out.push_str("]\n");
    let dest = PathBuf::from(std::env::var("OUT_DIR")?).join("builtin_robots.rs");
    std::fs::write(dest, out)?;
    Ok(())
}
