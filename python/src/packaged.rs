//! The project data the package carries, for use outside a checkout: the experiment files,
//! the papers and the committed results the leaderboard ranks against, embedded in the
//! extension at build time from the repository's own files (`build.rs`).
//!
//! The library reads a project root from disk (the experiment files through the input
//! reader, `results/runs.csv`, `results/leaderboard-timing.csv`), so the embedded files are
//! unpacked once into a directory of the user's cache named after their digest,
//! `$XDG_CACHE_HOME/driftbench/data-<digest>` (else `~/.cache/...`, else the system's
//! temporary directory), and that directory is the root. Each process checks the unpacked
//! files against the embedded ones on first use, rewrites any that differ, and removes any
//! file the package did not put there, so an edit in the cache never reaches a run.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/packaged.rs"));
}

/// Where in-flight files are written before they are renamed into place (left alone by the
/// clean-up of unknown files, as another process may be writing them).
const TMP_MARK: &str = ".driftbench-tmp-";

/// The packaged data could not be unpacked.
#[derive(Debug, thiserror::Error)]
#[error(
    "the packaged project data could not be unpacked into {}: {source}; pass root= a \
     driftbench checkout instead",
    path.display()
)]
pub struct UnpackError {
    pub path: PathBuf,
    pub source: std::io::Error,
}

fn at(path: &Path) -> impl FnOnce(std::io::Error) -> UnpackError + '_ {
    move |source| UnpackError {
        path: path.to_path_buf(),
        source,
    }
}

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

/// `rel` (with '/' separators) under `dir`.
fn under(dir: &Path, rel: &str) -> PathBuf {
    rel.split('/')
        .fold(dir.to_path_buf(), |p, part| p.join(part))
}

/// Writes every embedded file under `dir` whose contents differ (atomically: a temporary file
/// renamed into place), then removes the files under `dir` that are not embedded.
fn unpack(dir: &Path) -> Result<(), UnpackError> {
    let mut known = std::collections::HashSet::new();
    for (rel, bytes) in embedded::FILES {
        let path = under(dir, rel);
        if std::fs::read(&path).ok().as_deref() != Some(*bytes) {
            let parent = path.parent().unwrap_or(dir);
            std::fs::create_dir_all(parent).map_err(at(parent))?;
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            // Not ending in the file's own extension: a file left by a crashed process is
            // never read as an experiment file.
            let tmp = parent.join(format!(
                "{TMP_MARK}{}-{}.partial",
                std::process::id(),
                name.unwrap_or_default()
            ));
            std::fs::write(&tmp, bytes).map_err(at(&tmp))?;
            std::fs::rename(&tmp, &path).map_err(at(&path))?;
        }
        known.insert(path);
    }
    remove_unknown(dir, &known)
}

/// Removes every file under `dir` that is not in `known` (in-flight files excepted).
fn remove_unknown(
    dir: &Path,
    known: &std::collections::HashSet<PathBuf>,
) -> Result<(), UnpackError> {
    for entry in std::fs::read_dir(dir).map_err(at(dir))? {
        let path = entry.map_err(at(dir))?.path();
        let in_flight = path
            .file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with(TMP_MARK));
        if path.is_dir() {
            remove_unknown(&path, known)?;
        } else if !in_flight && !known.contains(&path) {
            std::fs::remove_file(&path).map_err(at(&path))?;
        }
    }
    Ok(())
}

/// The root of the packaged data (unpacked on the first call of the process).
pub fn root() -> Result<PathBuf, UnpackError> {
    static ROOT: OnceLock<PathBuf> = OnceLock::new();
    if let Some(r) = ROOT.get() {
        return Ok(r.clone());
    }
    let dir = directory();
    unpack(&dir)?;
    Ok(ROOT.get_or_init(|| dir).clone())
}
