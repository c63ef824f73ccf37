//! Embeds every robot file `data/*.toml` in the library (`robots::builtin_files`):
//! dropping a new file into `robots/data/` registers it on the next build, without Rust.
//!
//! Writes `$OUT_DIR/builtin_robots.rs`, a slice of `(file name, include_str!(absolute path))`
//! sorted by file name, so the order (and so `robot_names()`) does not depend on the directory
//! listing. Only regular files inside `data/` are embedded (`inputs::embed`, included here by
//! path and tested there): a symbolic link or any other kind of entry named `*.toml`, or a
//! `data/` that leads outside the crate, fails the build, naming it (`include_str!` would
//! follow a link to a file outside the checkout and compile its content into the binary). The
//! files' content must pass the rules of `src/file_rules.rs` (included here by path, as the
//! library uses it): a built-in file with a missing or unknown field, a non-finite number, an
//! empty joint range, fewer than two joints, ... fails the build, naming the file and the
//! field and never quoting the file. (The two checks that need `nalgebra`, a base matrix that
//! is a rotation and a positive semi-definite link inertia, run only when the library reads
//! the file, and a failure there fails only the lookups of its own robot.)

// Only `files` and `Walk::Top` of it are used here (the rest serves the Python package's
// build).
#[allow(dead_code)]
#[path = "../inputs/src/embed.rs"]
mod embed;

// The library's robot-file rules and TOML error (which never quotes the file); the parts the
// library alone uses are unused here.
#[allow(dead_code)]
#[path = "src/file_rules.rs"]
mod file_rules;
#[allow(dead_code)]
#[path = "../inputs/src/toml_error.rs"]
mod toml_error;
// The TOML error shows the keys and values it quotes as every error does (crate settings'
// `shown`, which it reaches through its parent module, as in crate inputs), without a build
// dependency on settings.
#[allow(dead_code)]
#[path = "../settings/src/shown.rs"]
mod shown_text;
use shown_text::{is_control_or_format, shown, SHOWN_MAX_CHARS};

use std::error::Error;
use std::fmt::Write as _;
use std::io::Read as _;
use std::path::{Path, PathBuf};

/// Why a built-in robot file fails the build (naming it as the library does,
/// `robots/data/NAME.toml`).
#[derive(Debug, thiserror::Error)]
enum BuiltinError {
    #[error("{file}: {source}")]
    Syntax {
        file: String,
        source: toml_error::TomlError,
    },
    #[error("{file}: {source}")]
    Rule {
        file: String,
        source: file_rules::RuleError,
    },
    #[error("{file}: cannot read it as UTF-8 text: {source}")]
    Read {
        file: String,
        source: std::io::Error,
    },
}

/// The build fails with the error's message (`main` returning an error would show its
/// `Debug` form).
fn main() {
    println!("cargo:rerun-if-changed=data");
    let run = || -> Result<(), Box<dyn Error>> {
        let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR")?);
        embed_robots(&root, &PathBuf::from(std::env::var("OUT_DIR")?))
    };
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

/// Checks every robot file `root/data/*.toml` and writes `out_dir/builtin_robots.rs`
/// embedding them (module documentation).
pub(crate) fn embed_robots(root: &Path, out_dir: &Path) -> Result<(), Box<dyn Error>> {
    let files = embed::files(
        root,
        Path::new("data"),
        embed::Walk::Top { extension: "toml" },
    )?;
    let mut out = String::from("&[\n");
    for file in &files {
        let name = file.relative.trim_start_matches("data/");
        check_builtin(name, Path::new(&file.absolute))?;
        writeln!(out, "    ({name:?}, include_str!({:?})),", file.absolute)?;
    }
    out.push_str("]\n");
    std::fs::write(out_dir.join("builtin_robots.rs"), out)?;
    Ok(())
}

/// The rules of `file_rules` on the built-in file `name` at `path` (a regular file), its name
/// its stem. At most one byte more than a robot file may have is read.
fn check_builtin(name: &str, path: &Path) -> Result<(), BuiltinError> {
    let file = format!("robots/data/{name}");
    let mut text = String::new();
    std::fs::File::open(path)
        .and_then(|f| {
            f.take(file_rules::MAX_FILE_BYTES + 1)
                .read_to_string(&mut text)
        })
        .map_err(|source| BuiltinError::Read {
            file: file.clone(),
            source,
        })?;
    let rule = |source| BuiltinError::Rule {
        file: file.clone(),
        source,
    };
    file_rules::check_size(&text).map_err(rule)?;
    let raw: file_rules::RawFile =
        toml_error::from_str(&text).map_err(|source| BuiltinError::Syntax {
            file: file.clone(),
            source,
        })?;
    let stem = name.strip_suffix(".toml").unwrap_or(name);
    file_rules::check(&raw, Some(stem)).map_err(rule)?;
    Ok(())
}
