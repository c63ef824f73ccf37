//! The project data the package carries, for use outside a checkout: the experiment files,
//! the papers and the committed results the leaderboard ranks against, embedded in the
//! extension at build time from the repository's own files (`build.rs`).
//!
//! The library reads a project root from disk (the experiment files through the input
//! reader, `results/runs.csv`, `results/leaderboard-timing.csv`), so the embedded files are
//! unpacked once into a directory of the user's cache named after their digest,
//! `$XDG_CACHE_HOME/driftbench/data-<digest>` (else `~/.cache/...`, else the system's
//! temporary directory), and that directory is the root. Each process checks the unpacked
//! files against the embedded ones on first use and rewrites any that differ, so an edit in
//! the cache never reaches a run. The directory is kept by `inputs::sync_private_dir`:
//! created owner-only, refused when it (or a directory or file in it) is a symbolic link, is
//! another user's or writable by others, or was not created by the package, and never
//! cleaned: a file the package did not write is an error naming it (a shared temporary
//! directory or a poisoned CI cache cannot lead it to write or delete files elsewhere).

use std::path::PathBuf;
use std::sync::OnceLock;

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/packaged.rs"));
}

/// The packaged data could not be unpacked.
#[derive(Debug, thiserror::Error)]
#[error("the packaged project data could not be unpacked: {0}; pass root= a driftbench checkout instead")]
pub struct UnpackError(#[from] inputs::PrivateDirError);

/// The directory the data is unpacked into (module docs).
fn directory() -> PathBuf {
    let cache = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .filter(|p| p.is_absolute())
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .filter(|p| p.is_absolute())
        .unwrap_or_else(std::env::temp_dir);
    cache
        .join("driftbench")
        .join(format!("data-{}", &embedded::DIGEST[..16]))
}

/// The root of the packaged data (unpacked on the first call of the process).
pub fn root() -> Result<PathBuf, UnpackError> {
    static ROOT: OnceLock<PathBuf> = OnceLock::new();
    if let Some(r) = ROOT.get() {
        return Ok(r.clone());
    }
    let dir = directory();
    inputs::sync_private_dir(&dir, embedded::FILES)?;
    Ok(ROOT.get_or_init(|| dir).clone())
}
