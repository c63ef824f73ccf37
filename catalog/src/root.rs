//! The project root: the directory holding `experiments/` (the inputs), `results/` and
//! `report/` (the outputs). Nothing is baked in at compile time: the binary finds the root from
//! its working directory upwards (as git finds `.git`), or is told it with `--root`, so an
//! installed `reproduce` works on any checkout or on a directory of one's own experiments.

use std::path::{Path, PathBuf};

/// No directory with an `experiments/` folder at or above the start.
#[derive(Debug, thiserror::Error)]
#[error(
    "no project root at or above {}: none of these directories has an experiments/ folder; run \
     from inside a driftbench checkout (or a directory with experiments/*.toml) or pass --root DIR",
    start.display()
)]
pub struct RootNotFound {
    /// The directory the search started from.
    pub start: PathBuf,
}

/// The nearest directory at or above `start` that has an `experiments/` folder.
pub fn find_root(start: &Path) -> Result<PathBuf, RootNotFound> {
    start
        .ancestors()
        .find(|dir| dir.join("experiments").is_dir())
        .map(Path::to_path_buf)
        .ok_or_else(|| RootNotFound {
            start: start.to_path_buf(),
        })
}

/// [`find_root`] from the process's working directory (tests run in their crate's directory, inside
/// the workspace, so they find the workspace root).
pub fn root_from_current_dir() -> Result<PathBuf, RootNotFound> {
    let cwd = std::env::current_dir().map_err(|_| RootNotFound {
        start: PathBuf::from("."),
    })?;
    find_root(&cwd)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_root_is_found_from_any_directory_below_it() {
        let base = inputs::Scratch::dir("root");
        let deep = base.join("experiments").join("a").join("b");
        std::fs::create_dir_all(&deep).unwrap();
        assert_eq!(find_root(&deep).unwrap(), base.path());
        assert_eq!(find_root(&base).unwrap(), base.path());
        let outside = inputs::Scratch::dir("none");
        if outside.ancestors().all(|d| !d.join("experiments").is_dir()) {
            let e = find_root(&outside).unwrap_err().to_string();
            assert!(e.contains("--root") && e.contains("experiments/"), "{e}");
        }
    }
}
