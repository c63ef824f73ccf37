//! A directory the binary owns (`results/`, `report/`, a shard directory), and the only way to
//! turn a name read from a file into a path under it.
//!
//! Names come from places a user or an attacker can edit: a row of `runs.csv` names its
//! experiment, variant and solver, and those become `traces/<experiment>/<variant>__<solver>.csv`.
//! [`OwnedDir::resolve`] accepts a relative path only if
//!
//! 1. every component is a plain name (no `..`, no root, no prefix, no `.`), and
//! 2. every component that already exists, followed through symbolic links, stays inside the
//!    owned directory: the canonical form of each existing prefix must start with the canonical
//!    form of the root.
//!
//! So `../../x`, `/etc/x` and a `traces/<experiment>` that is a symbolic link to a directory
//! elsewhere are refused with a message naming the path and where it leads; a symbolic link
//! that stays inside the directory is followed. Files are replaced by renaming a temporary file
//! over them (`crate::runs::write_atomic`), which replaces a symbolic link itself rather than
//! writing through it, and a removal removes a link, never its target.

use std::path::{Component, Path, PathBuf};

/// A path that may not be written or deleted.
#[derive(Debug, thiserror::Error)]
pub enum PathError {
    /// The owned directory could not be created or resolved.
    #[error("{dir}: cannot create or open the directory: {source}")]
    Open {
        /// The directory, as given.
        dir: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The relative path is empty or has a component that is not a plain name (`..`, `.`, a
    /// root or a prefix).
    #[error("{dir}: refusing the name {name:?}: only plain names are allowed under a directory the program owns (no `..`, no absolute path, no `.`)")]
    NotPlain {
        /// The owned directory, as given.
        dir: PathBuf,
        /// The relative path refused.
        name: PathBuf,
    },
    /// A symbolic link on the way leads outside the owned directory.
    #[error("{path} leads outside {dir} (to {target}); the program writes only inside the directories it owns: remove or replace the symbolic link")]
    Escapes {
        /// The owned directory, as given.
        dir: PathBuf,
        /// The path asked for, under the directory as given.
        path: PathBuf,
        /// Where the link leads (canonical).
        target: PathBuf,
    },
    /// A component of the path could not be inspected or its link resolved.
    #[error("{path}: cannot inspect: {source}")]
    Inspect {
        /// The component's path (canonical prefix).
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}

/// A directory the program writes into, with every path under it checked.
#[derive(Clone, Debug)]
pub struct OwnedDir {
    /// As given (for messages).
    shown: PathBuf,
    /// Canonical (symbolic links resolved), for the containment check.
    canonical: PathBuf,
}

impl OwnedDir {
    /// Opens `dir`, creating it (and its parents) if absent.
    pub fn open(dir: &Path) -> Result<Self, PathError> {
        let open = |source| PathError::Open {
            dir: dir.to_path_buf(),
            source,
        };
        std::fs::create_dir_all(dir).map_err(open)?;
        let canonical = dir.canonicalize().map_err(open)?;
        Ok(Self {
            shown: dir.to_path_buf(),
            canonical,
        })
    }

    /// Opens `dir` (creating it) and checks that it lies inside `parent`'s directory tree once
    /// symbolic links are resolved: `report/` or `report/figures` that is a link elsewhere is
    /// refused.
    pub fn open_within(parent: &OwnedDir, rel: &Path) -> Result<Self, PathError> {
        let path = parent.resolve(rel)?;
        let dir = Self::open(&path)?;
        // Created by `open`: check again now that every component exists.
        parent.resolve(rel)?;
        Ok(dir)
    }

    /// The directory as given.
    pub fn path(&self) -> &Path {
        &self.shown
    }

    /// `self/rel`, after the checks of the module doc.
    pub fn resolve(&self, rel: &Path) -> Result<PathBuf, PathError> {
        let plain = rel.components().count() > 0
            && rel.components().all(|c| matches!(c, Component::Normal(_)));
        if !plain {
            return Err(PathError::NotPlain {
                dir: self.shown.clone(),
                name: rel.to_path_buf(),
            });
        }
        let mut at = self.canonical.clone();
        for c in rel.components() {
            at.push(c);
            match std::fs::symlink_metadata(&at) {
                Ok(meta) if meta.file_type().is_symlink() => {
                    let target = at.canonicalize().map_err(|source| PathError::Inspect {
                        path: at.clone(),
                        source,
                    })?;
                    if !target.starts_with(&self.canonical) {
                        return Err(PathError::Escapes {
                            dir: self.shown.clone(),
                            path: self.shown.join(rel),
                            target,
                        });
                    }
                    at = target;
                }
                Ok(_) => {}
                // The rest does not exist yet: it will be created inside `at`.
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => break,
                Err(source) => return Err(PathError::Inspect { path: at, source }),
            }
        }
        Ok(self.shown.join(rel))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("driftbench-owned-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn plain_names_only() {
        let base = scratch("plain");
        let dir = OwnedDir::open(&base.join("results")).unwrap();
        assert!(dir.resolve(Path::new("traces/e/v__s.csv")).is_ok());
        for bad in ["../x", "traces/../../x", "/etc/passwd", "./x", ""] {
            assert!(
                matches!(dir.resolve(Path::new(bad)), Err(PathError::NotPlain { .. })),
                "{bad}"
            );
        }
        let _ = std::fs::remove_dir_all(&base);
    }

    #[cfg(unix)]
    #[test]
    fn symbolic_links_that_leave_are_refused() {
        let base = scratch("links");
        let outside = scratch("links-elsewhere");
        std::fs::create_dir_all(&outside).unwrap();
        let dir = OwnedDir::open(&base.join("results")).unwrap();
        std::fs::create_dir_all(base.join("results/traces")).unwrap();
        std::os::unix::fs::symlink(&outside, base.join("results/traces/e")).unwrap();
        let err = dir.resolve(Path::new("traces/e/v__s.csv")).unwrap_err();
        assert!(matches!(err, PathError::Escapes { .. }), "{err}");
        assert!(err.to_string().contains("links-elsewhere"), "{err}");
        // A link that stays inside is followed.
        std::fs::create_dir_all(base.join("results/real")).unwrap();
        std::os::unix::fs::symlink(base.join("results/real"), base.join("results/inside")).unwrap();
        assert!(dir.resolve(Path::new("inside/x.csv")).is_ok());
        // The owned directory itself may be reached through a link (e.g. /tmp on macOS).
        std::os::unix::fs::symlink(&outside, base.join("report")).unwrap();
        let root = OwnedDir::open(&base).unwrap();
        assert!(matches!(
            OwnedDir::open_within(&root, Path::new("report")),
            Err(PathError::Escapes { .. })
        ));
        let _ = std::fs::remove_dir_all(&base);
        let _ = std::fs::remove_dir_all(&outside);
    }
}
