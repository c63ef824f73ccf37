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
//! over them (`crate::write_atomic`), which replaces a symbolic link itself rather than
//! writing through it, and a removal removes a link, never its target.

use std::path::{Component, Path, PathBuf};

/// The bytes of a file of a directory the program owns (a table, a trace, the journal, a file
/// a manifest lists), read as every input is ([`inputs::read()`], [`inputs::Kind::Owned`]): a
/// regular file (a FIFO or a device put in its place is refused at once, not waited on or read
/// without end), not through a symbolic link out of the directory it is in, at most 256 MiB.
/// The reader's error (naming the path and the rule, never the content) is returned as an
/// `io::Error` of kind `NotFound` for a missing file, so that callers treating a missing file
/// as absent still do, and `InvalidData` otherwise.
pub fn read_file(path: &Path) -> std::io::Result<Vec<u8>> {
    inputs::read(path, inputs::Kind::Owned, inputs::Origin::Named).map_err(io_error)
}

/// A file of a directory the program owns opened as a stream, by the rules of [`read_file`]
/// ([`inputs::open()`]): a table read row by row, in memory independent of its length.
pub fn open_file(path: &Path) -> std::io::Result<inputs::Capped> {
    inputs::open(path, inputs::Kind::Owned, inputs::Origin::Named).map_err(io_error)
}

/// The fingerprint of a file of a directory the program owns ([`open_file`]), read block by
/// block.
pub fn fingerprint(path: &Path) -> std::io::Result<crate::integrity::Fingerprint> {
    crate::integrity::Fingerprint::of_reader(open_file(path)?)
}

/// [`read_file`], as UTF-8 text.
pub fn read_text(path: &Path) -> std::io::Result<String> {
    inputs::read_text(path, inputs::Kind::Owned, inputs::Origin::Named).map_err(io_error)
}

/// The input reader's error as an `io::Error` ([`read_file`]).
pub(crate) fn io_error(e: inputs::InputError) -> std::io::Error {
    let kind = if e.is_not_found() {
        std::io::ErrorKind::NotFound
    } else {
        std::io::ErrorKind::InvalidData
    };
    std::io::Error::new(kind, e)
}

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
    #[error("{dir}: refusing the name {}: only plain names are allowed under a directory the program owns (no `..`, no absolute path, no `.`)", settings::shown(&name.to_string_lossy()))]
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

    /// A scratch path with nothing at it, removed (a directory or a file) when dropped.
    fn scratch(name: &str) -> inputs::Scratch {
        inputs::Scratch::unmade(&format!("owned-{name}"))
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
    }

    /// A FIFO, a link to `/dev/zero` and a link to a secret put in place of a file the
    /// program wrote (as a pull request or a shard from elsewhere can) are refused at once by
    /// every reader of an owned directory: the read, a table's read and the manifest's check
    /// at every start (which used to wait on the FIFO and read `/dev/zero` without end).
    #[cfg(unix)]
    #[test]
    fn a_fifo_or_a_link_out_in_place_of_a_written_file_is_refused_at_once() {
        let base = scratch("special");
        std::fs::create_dir_all(&base).unwrap();
        let secret = scratch("special-secret");
        std::fs::write(&secret, "SECRET_MARKER_0wn3d\n").unwrap();
        // mkfifo(3) in this process, not the mkfifo program: a child forked while another
        // test of this binary drops a results directory would hold its lock's descriptor until
        // exec, and that test's next open would find the directory locked.
        let fifo =
            std::ffi::CString::new(base.join("runs.csv").into_os_string().into_encoded_bytes())
                .unwrap();
        // SAFETY: a NUL-terminated path that outlives the call.
        assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o600) }, 0);
        std::os::unix::fs::symlink("/dev/zero", base.join("zero.csv")).unwrap();
        std::os::unix::fs::symlink(&secret, base.join("secret.csv")).unwrap();
        std::fs::write(base.join("ok.csv"), "a\n1\n").unwrap();
        let (tx, rx) = std::sync::mpsc::channel();
        let dir = base.to_path_buf();
        std::thread::spawn(move || {
            let names = ["runs.csv", "zero.csv", "secret.csv"];
            let errors: Vec<std::io::Error> = names
                .iter()
                .map(|n| read_file(&dir.join(n)).unwrap_err())
                .collect();
            let table = crate::table::read::<records::RunRow>(&dir.join("runs.csv"));
            let listed = crate::integrity::Fingerprint::of(b"a\n1\n");
            let mut files: Vec<&str> = names.iter().chain(&["ok.csv"]).copied().collect();
            files.sort_unstable();
            crate::integrity::write(
                &dir,
                "x",
                files.iter().map(|n| Ok((n.to_string(), listed.clone()))),
            )
            .unwrap();
            let mismatches = crate::integrity::Manifest::open(&dir)
                .unwrap()
                .unwrap()
                .mismatches(&dir, |_| true)
                .unwrap()
                .len();
            let missing = read_file(&dir.join("none.csv")).unwrap_err().kind();
            let _ = tx.send((errors, table.is_err(), mismatches, missing));
        });
        let (errors, table_refused, mismatches, missing) = rx
            .recv_timeout(std::time::Duration::from_secs(10))
            .expect("every read returned within 10 s");
        let shown: Vec<String> = errors.iter().map(|e| e.to_string()).collect();
        assert!(
            shown[0].contains("a FIFO, not a regular file"),
            "{}",
            shown[0]
        );
        assert!(shown[1].contains("leads outside"), "{}", shown[1]);
        assert!(
            shown[2].contains("leads outside") && !shown[2].contains("SECRET_MARKER"),
            "{}",
            shown[2]
        );
        assert!(errors
            .iter()
            .all(|e| e.kind() == std::io::ErrorKind::InvalidData));
        assert!(table_refused);
        assert_eq!(mismatches, 3, "the three planted files, not ok.csv");
        assert_eq!(missing, std::io::ErrorKind::NotFound);
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
    }
}
