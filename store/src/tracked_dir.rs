//! A directory the program owns ([`OwnedDir`]: every path checked) together with the manifest
//! of what it wrote there ([`Manifest`]). Every write and every removal goes through it:
//!
//! - [`TrackedDir::write`] writes atomically and records the file's fingerprint;
//! - [`TrackedDir::adopt`] records a file another layer wrote at a path obtained from
//!   [`TrackedDir::resolve`]; [`TrackedDir::adopt_sealed`] records one only if it still hashes
//!   to a fingerprint taken when it was written (the journal's seal of its traces);
//! - [`TrackedDir::remove`] deletes a file only if the manifest lists it and it still hashes to
//!   its entry: a file the program cannot prove it wrote, or one edited since, is left in place
//!   and reported;
//! - [`TrackedDir::save`] writes the manifest; call it at the end of each step that changed
//!   the directory;
//! - [`TrackedDir::commit`] writes a top-level table and saves the manifest as one step: a kill
//!   at any instant leaves the table and the saved manifest agreeing (the next
//!   [`TrackedDir::open`] finishes or undoes the commit), where a write then a save would leave
//!   the new table beside the old manifest, an edit in the eyes of the next start.
//!
//! Opening checks the listed files that a caller selects against their entries
//! ([`TrackedDir::open`]): a file edited, truncated or removed behind the program's back is an
//! error naming the file and what differs, unless the caller accepts edits
//! ([`Edits::Accept`]), in which case the present files are fingerprinted anew.

use crate::integrity::{Fingerprint, IntegrityError, Manifest, Mismatch, FILE};
use crate::owned_dir::{OwnedDir, PathError};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Whether files that differ from the manifest are an error.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Edits {
    /// Refuse (the default).
    Refuse,
    /// Deliberate edits (`--accept-edited`): take the files as they are.
    Accept,
}

/// A problem with a tracked directory.
#[derive(Debug, thiserror::Error)]
pub enum TrackedError {
    /// A path under the directory was refused.
    #[error(transparent)]
    Path(#[from] PathError),
    /// The manifest could not be read or written.
    #[error(transparent)]
    Integrity(#[from] IntegrityError),
    /// A file could not be written, read or removed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Listed files differ from the manifest (under [`Edits::Refuse`]).
    #[error("{dir}: {count} file(s) differ from what this program wrote ({dir}/{FILE}), so they were edited, truncated or replaced by hand:\n{list}\nnothing was run or written; restore them (e.g. `git checkout -- {dir}`) or, if the edit is deliberate, run again with --accept-edited")]
    Edited {
        /// The directory.
        dir: PathBuf,
        /// How many files differ.
        count: usize,
        /// One line per file and what differs.
        list: String,
    },
    /// The directory holds its guarded file (e.g. `runs.csv`) but no manifest.
    #[error("{dir}: holds {file} but no {FILE}, so this program cannot tell whether it wrote it or whether it was edited since; nothing was run or written; restore the directory from git, or run again with --accept-edited to take its files as they are")]
    Unsealed {
        /// The directory.
        dir: PathBuf,
        /// The guarded file it holds.
        file: String,
    },
}

/// What [`TrackedDir::remove`] did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Removal {
    /// Removed (listed, and still as the program wrote it).
    Removed,
    /// Not there (nothing to do).
    Absent,
    /// Left in place, with the reason.
    Kept(String),
}

/// A directory the program owns, with the manifest of what it wrote there.
#[derive(Debug)]
pub struct TrackedDir {
    dir: OwnedDir,
    manifest: Mutex<Manifest>,
}

impl TrackedDir {
    /// Opens `dir` (creating it). Listed files whose names `verify` accepts must match their
    /// entries ([`TrackedError::Edited`] otherwise, under [`Edits::Refuse`]); a directory that
    /// holds `guarded` (e.g. `runs.csv`) but no manifest is refused too. Under
    /// [`Edits::Accept`] the differing files are fingerprinted as they are. `git_rev` is recorded
    /// as the writer's revision at the next [`TrackedDir::save`].
    pub fn open(
        dir: &Path,
        git_rev: &str,
        edits: Edits,
        guarded: Option<&str>,
        verify: impl Fn(&str) -> bool,
    ) -> Result<Self, TrackedError> {
        let owned = OwnedDir::open(dir)?;
        let manifest = match Manifest::read(dir)? {
            Some(m) => m,
            None if edits == Edits::Refuse && guarded.is_some_and(|g| dir.join(g).exists()) => {
                return Err(TrackedError::Unsealed {
                    dir: dir.to_path_buf(),
                    file: guarded.unwrap_or_default().to_string(),
                })
            }
            None => Manifest::default(),
        };
        finish_commits(&owned, &manifest)?;
        let tracked = Self {
            dir: owned,
            manifest: Mutex::new(Manifest {
                git_rev: git_rev.to_string(),
                ..manifest
            }),
        };
        let mismatches = tracked.lock().mismatches(dir, &verify);
        match edits {
            Edits::Refuse if !mismatches.is_empty() => Err(TrackedError::Edited {
                dir: dir.to_path_buf(),
                count: mismatches.len(),
                list: mismatches
                    .iter()
                    .map(|m| format!("  {m}"))
                    .collect::<Vec<_>>()
                    .join("\n"),
            }),
            Edits::Refuse => Ok(tracked),
            Edits::Accept => {
                for m in &mismatches {
                    let file = match m {
                        Mismatch::Missing { file } | Mismatch::Changed { file, .. } => file,
                    };
                    tracked.adopt(Path::new(file))?;
                }
                Ok(tracked)
            }
        }
    }

    /// Opens `parent/name` as [`TrackedDir::open`] does (nothing verified, nothing guarded),
    /// after checking that it lies inside `parent` once symbolic links are resolved: the report
    /// directory of a project, which must not lead elsewhere.
    pub fn open_within(parent: &Path, name: &str) -> Result<Self, TrackedError> {
        let parent = OwnedDir::open(parent)?;
        let dir = OwnedDir::open_within(&parent, Path::new(name))?;
        Self::open(dir.path(), "", Edits::Refuse, None, |_| false)
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Manifest> {
        // A panic while the lock was held leaves a consistent map (entries are replaced whole).
        self.manifest.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The directory as given.
    pub fn path(&self) -> &Path {
        self.dir.path()
    }

    /// The owned directory (for checking further directories inside it).
    pub fn owned(&self) -> &OwnedDir {
        &self.dir
    }

    /// `dir/rel`, checked ([`OwnedDir::resolve`]).
    pub fn resolve(&self, rel: &Path) -> Result<PathBuf, PathError> {
        self.dir.resolve(rel)
    }

    /// Writes `bytes` to `rel` atomically and records it.
    pub fn write(&self, rel: &Path, bytes: &[u8]) -> Result<(), TrackedError> {
        self.write_fingerprinted(rel, bytes).map(drop)
    }

    /// [`TrackedDir::write`], returning the fingerprint recorded (for a seal).
    pub fn write_fingerprinted(
        &self,
        rel: &Path,
        bytes: &[u8],
    ) -> Result<Fingerprint, TrackedError> {
        let path = self.resolve(rel)?;
        crate::atomic::write_atomic(&path, bytes).map_err(|source| TrackedError::Io {
            path: path.clone(),
            source,
        })?;
        let fingerprint = Fingerprint::of(bytes);
        self.lock().files.insert(key(rel), fingerprint.clone());
        Ok(fingerprint)
    }

    /// Records the file at `rel` as written by the program (another layer wrote it at a path
    /// from [`TrackedDir::resolve`]); a file that is not there is dropped from the manifest.
    pub fn adopt(&self, rel: &Path) -> Result<(), TrackedError> {
        let path = self.resolve(rel)?;
        match crate::owned_dir::fingerprint(&path) {
            Ok(found) => {
                self.lock().files.insert(key(rel), found);
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                self.lock().files.remove(&key(rel));
            }
            Err(source) => return Err(TrackedError::Io { path, source }),
        }
        Ok(())
    }

    /// Records the file at `rel` if it is there and its content still hashes to `sha256` (taken
    /// when the program wrote it, e.g. from the journal's seal); returns whether it did. A file
    /// missing or changed since is not recorded.
    pub fn adopt_sealed(&self, rel: &Path, sha256: &str) -> Result<bool, TrackedError> {
        let path = self.resolve(rel)?;
        let bytes = match crate::owned_dir::read_file(&path) {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(false),
            Err(source) => return Err(TrackedError::Io { path, source }),
        };
        let found = Fingerprint::of(&bytes);
        if found.sha256 != sha256 {
            return Ok(false);
        }
        self.lock().files.insert(key(rel), found);
        Ok(true)
    }

    /// Removes `rel` if the program can prove it wrote it (see the module doc).
    pub fn remove(&self, rel: &Path) -> Result<Removal, TrackedError> {
        let path = self.resolve(rel)?;
        let bytes = match crate::owned_dir::read_file(&path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                self.lock().files.remove(&key(rel));
                return Ok(Removal::Absent);
            }
            Err(source) => return Err(TrackedError::Io { path, source }),
        };
        let mut m = self.lock();
        match m.files.get(&key(rel)) {
            None => {
                return Ok(Removal::Kept(format!(
                    "{}: left in place: not written by this program (not in {FILE})",
                    path.display()
                )))
            }
            Some(f) if *f != Fingerprint::of(&bytes) => {
                return Ok(Removal::Kept(format!(
                    "{}: left in place: edited since this program wrote it",
                    path.display()
                )))
            }
            Some(_) => {}
        }
        std::fs::remove_file(&path).map_err(|source| TrackedError::Io {
            path: path.clone(),
            source,
        })?;
        m.files.remove(&key(rel));
        // An emptied sub-directory goes too (a non-empty one stays).
        if let Some(parent) = rel.parent().filter(|p| !p.as_os_str().is_empty()) {
            if let Ok(dir) = self.resolve(parent) {
                let _ = std::fs::remove_dir(dir);
            }
        }
        Ok(Removal::Removed)
    }

    /// The listed files whose names start with `prefix`.
    pub fn listed(&self, prefix: &str) -> Vec<String> {
        self.lock()
            .files
            .keys()
            .filter(|k| k.starts_with(prefix))
            .cloned()
            .collect()
    }

    /// Whether the manifest lists the file at `rel`.
    pub fn lists(&self, rel: &Path) -> bool {
        self.lock().files.contains_key(&key(rel))
    }

    /// Saves the manifest.
    pub fn save(&self) -> Result<(), TrackedError> {
        // Written under the lock, not from a copy: a copy is one more entry per file held.
        self.lock().write(self.path())?;
        Ok(())
    }

    /// Writes `bytes` to the top-level file `name` and saves the manifest, so that the file
    /// and the saved manifest agree whatever instant the process is killed at: the bytes go to
    /// `pending(name)` (atomically), the manifest is saved with `name`'s new fingerprint
    /// (the commit point), and the pending file is renamed over `name`. A kill before the save
    /// leaves the old file and the old manifest; a kill after it, the new manifest and the
    /// new file pending, which the next [`TrackedDir::open`] renames into place.
    pub fn commit(&self, name: &str, bytes: &[u8]) -> Result<(), TrackedError> {
        self.commit_with(name, |w| w.write_all(bytes))
    }

    /// [`TrackedDir::commit`] of what `write` writes, streamed (`atomic::write_atomic_with`)
    /// and fingerprinted block by block: a table far larger than memory is committed row by row.
    pub fn commit_with(
        &self,
        name: &str,
        write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
    ) -> Result<(), TrackedError> {
        let staged = self.resolve(Path::new(&pending(name)))?;
        let path = self.resolve(Path::new(name))?;
        let io = |path: &Path| {
            let path = path.to_path_buf();
            move |source| TrackedError::Io { path, source }
        };
        crate::atomic::write_atomic_with(&staged, write).map_err(io(&staged))?;
        let found = crate::owned_dir::fingerprint(&staged).map_err(io(&staged))?;
        self.lock().files.insert(name.to_string(), found);
        self.save()?;
        std::fs::rename(&staged, &path).map_err(io(&path))?;
        crate::kill_point::passed();
        Ok(())
    }
}

/// The name a top-level file `name` is written under until [`TrackedDir::commit`] renames it
/// into place: `.driftbench-commit.<name>` (not a temporary file of
/// [`crate::results_dir::is_own_tmp`], which a start removes before it could be finished).
pub fn pending(name: &str) -> String {
    format!(".driftbench-commit.{name}")
}

/// Finishes or undoes the commits ([`TrackedDir::commit`]) a kill interrupted in `dir`, whose
/// saved manifest is `manifest`: for each listed top-level file with a pending copy, the copy
/// is renamed over it if the manifest records the copy's content (the commit point was
/// passed), and removed otherwise (it was not: the file and the manifest still agree).
fn finish_commits(dir: &OwnedDir, manifest: &Manifest) -> Result<(), TrackedError> {
    for (name, listed) in manifest.files.iter().filter(|(k, _)| !k.contains('/')) {
        let staged = dir.resolve(Path::new(&pending(name)))?;
        let found = match crate::owned_dir::fingerprint(&staged) {
            Ok(found) => found,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => continue,
            Err(source) => {
                return Err(TrackedError::Io {
                    path: staged,
                    source,
                })
            }
        };
        let done = if found == *listed {
            std::fs::rename(&staged, dir.resolve(Path::new(name))?)
        } else {
            std::fs::remove_file(&staged)
        };
        done.map_err(|source| TrackedError::Io {
            path: staged,
            source,
        })?;
    }
    Ok(())
}

/// A manifest key: the relative path with `/`.
fn key(rel: &Path) -> String {
    rel.components()
        .map(|c| c.as_os_str().to_string_lossy())
        .collect::<Vec<_>>()
        .join("/")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn removes_only_what_it_wrote_unchanged() {
        let base = std::env::temp_dir().join(format!("driftbench-tracked-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        let t = TrackedDir::open(&base, "r1", Edits::Refuse, Some("runs.csv"), |_| true).unwrap();
        t.write(Path::new("traces/e/a.csv"), b"x\n").unwrap();
        t.write(Path::new("traces/e/b.csv"), b"y\n").unwrap();
        t.write(Path::new("runs.csv"), b"h\n1\n").unwrap();
        t.save().unwrap();
        std::fs::write(base.join("traces/e/user.csv"), b"mine").unwrap();
        std::fs::write(base.join("traces/e/b.csv"), b"edited").unwrap();
        assert_eq!(
            t.remove(Path::new("traces/e/a.csv")).unwrap(),
            Removal::Removed
        );
        assert!(matches!(
            t.remove(Path::new("traces/e/user.csv")).unwrap(),
            Removal::Kept(_)
        ));
        assert!(matches!(
            t.remove(Path::new("traces/e/b.csv")).unwrap(),
            Removal::Kept(_)
        ));
        assert!(base.join("traces/e/user.csv").exists() && base.join("traces/e/b.csv").exists());
        t.save().unwrap();
        drop(t);
        // Reopening finds the edit, unless it is accepted.
        let err =
            TrackedDir::open(&base, "r2", Edits::Refuse, Some("runs.csv"), |_| true).unwrap_err();
        assert!(err.to_string().contains("traces/e/b.csv"), "{err}");
        assert!(
            TrackedDir::open(&base, "r2", Edits::Refuse, Some("runs.csv"), |f| f
                == "runs.csv")
            .is_ok()
        );
        let t = TrackedDir::open(&base, "r2", Edits::Accept, Some("runs.csv"), |_| true).unwrap();
        t.save().unwrap();
        assert!(TrackedDir::open(&base, "r3", Edits::Refuse, Some("runs.csv"), |_| true).is_ok());
        // Without a manifest, a directory holding runs.csv is refused.
        std::fs::remove_file(base.join(FILE)).unwrap();
        let err =
            TrackedDir::open(&base, "r3", Edits::Refuse, Some("runs.csv"), |_| true).unwrap_err();
        assert!(matches!(err, TrackedError::Unsealed { .. }), "{err}");
        let _ = std::fs::remove_dir_all(&base);
    }

    /// A commit cut by a kill at each of its intermediate states, rebuilt on disk: the next
    /// open leaves the table and the manifest agreeing, the old table before the commit point
    /// (the manifest's save), the new one after it; a pending copy of a file the manifest does
    /// not list is left alone.
    #[test]
    fn a_commit_cut_at_any_state_is_finished_or_undone_on_open() {
        let base = std::env::temp_dir().join(format!("driftbench-commit-{}", std::process::id()));
        let open = || TrackedDir::open(&base, "r", Edits::Refuse, Some("runs.csv"), |_| true);
        let (old, new) = (b"h\n1\n".as_slice(), b"h\n1\n2\n".as_slice());
        let staged = base.join(pending("runs.csv"));
        // (state, table expected after the open)
        for cut in ["pending written", "manifest saved", "renamed"] {
            let _ = std::fs::remove_dir_all(&base);
            let t = open().unwrap();
            t.commit("runs.csv", old).unwrap();
            let before = std::fs::read(base.join(FILE)).unwrap();
            t.commit("runs.csv", new).unwrap();
            let after = std::fs::read(base.join(FILE)).unwrap();
            drop(t);
            std::fs::write(&staged, new).unwrap();
            match cut {
                "pending written" => {
                    std::fs::write(base.join("runs.csv"), old).unwrap();
                    std::fs::write(base.join(FILE), &before).unwrap();
                }
                "manifest saved" => std::fs::write(base.join("runs.csv"), old).unwrap(),
                _ => std::fs::remove_file(&staged).unwrap(),
            }
            assert_eq!(
                std::fs::read(base.join(FILE)).unwrap() == after,
                cut != "pending written"
            );
            open().unwrap_or_else(|e| panic!("{cut}: {e}"));
            let want = if cut == "pending written" { old } else { new };
            assert_eq!(std::fs::read(base.join("runs.csv")).unwrap(), want, "{cut}");
            assert!(!staged.exists(), "{cut}");
        }
        std::fs::write(base.join(pending("notes.txt")), b"a user's").unwrap();
        open().unwrap();
        assert!(base.join(pending("notes.txt")).exists());
        let _ = std::fs::remove_dir_all(&base);
    }
}
