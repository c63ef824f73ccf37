//! Embeds every robot file `data/*.toml` in the library (`robots::data_robot::builtin_files`):
//! dropping a new file into `robots/data/` registers it on the next build, without Rust.
//!
//! Writes `$OUT_DIR/builtin_robots.rs`, a slice of `(file name, include_str!(absolute path))`
//! sorted by file name, so the order (and so `robot_names()`) does not depend on the directory
//! listing. Only regular files inside `data/` are embedded: a symbolic link or any other kind
//! of entry named `*.toml` fails the build, naming it (`include_str!` would follow a link to a
//! file outside the checkout and compile its content into the binary). The files' content is
//! validated when the library first reads it (`robots::registry`): an invalid built-in file
//! fails only the lookups of its own robot, naming the file and field.

use std::error::Error;
use std::fmt::Write as _;
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn Error>> {
    println!("cargo:rerun-if-changed=data");
    let dir = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR")?).join("data");
    let dir = dir.canonicalize()?;
    let mut files = Vec::new();
    for entry in std::fs::read_dir(&dir)? {
        let entry = entry?;
        let path = entry.path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        // `file_type` of a directory entry does not follow a symbolic link.
        if !entry.file_type()?.is_file() {
            return Err(format!(
                "robots/data/{}: not a regular file (a symbolic link or a special file); a \
                 built-in robot file must be a regular file inside robots/data/",
                entry.file_name().to_string_lossy()
            )
            .into());
        }
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
