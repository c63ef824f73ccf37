//! Embeds every robot file `data/*.toml` in the library (`robots::data_robot::builtin_files`):
//! dropping a new file into `robots/data/` registers it on the next build, without Rust.
//!
//! Writes `$OUT_DIR/builtin_robots.rs`, a slice of `(file name, include_str!(absolute path))`
//! sorted by file name, so the order (and so `robot_names()`) does not depend on the directory
//! listing. Only regular files inside `data/` are embedded (`inputs::embed`, included here by
//! path and tested there): a symbolic link or any other kind of entry named `*.toml`, or a
//! `data/` that leads outside the crate, fails the build, naming it (`include_str!` would
//! follow a link to a file outside the checkout and compile its content into the binary). The
//! files' content is validated when the library first reads it (`robots::registry`): an
//! invalid built-in file fails only the lookups of its own robot, naming the file and field.

// Only `files` and `Walk::Top` of it are used here (the rest serves the Python package's
// build).
#[allow(dead_code)]
#[path = "../inputs/src/embed.rs"]
mod embed;

use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The build fails with the error's message (`main` returning an error would show its
/// `Debug` form).
fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), Box<dyn Error>> {
    println!("cargo:rerun-if-changed=data");
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR")?);
    let files = embed::files(
        &root,
        Path::new("data"),
        embed::Walk::Top { extension: "toml" },
    )?;
    let mut out = String::from("&[\n");
    for file in &files {
        let name = file.relative.trim_start_matches("data/");
        writeln!(out, "    ({name:?}, include_str!({:?})),", file.absolute)?;
    }
    out.push_str("]\n");
    let dest = PathBuf::from(std::env::var("OUT_DIR")?).join("builtin_robots.rs");
    std::fs::write(dest, out)?;
    Ok(())
}
