//! A directory the program owns ([`OwnedDir`]: every path checked) together with the manifest
//! of what it wrote there ([`crate::integrity`]). Every write and every removal goes through it:
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
//!
//! **What is held.** Not the manifest: the saved one is read by streaming and looked up by
//! bisection ([`crate::integrity::Manifest`]). What the process changed since the last save
//! is held as a sorted map of at most [`CHANGES`] entries (a file's new fingerprint, or its
//! removal); a fuller map is written to a temporary file of the directory (a *spill*, the
//! manifest's own format, a removal as an entry of empty hash) and dropped, and once
//! [`FANOUT`] spills of one size are there they are merged into one (tiers, so that an entry
//! is rewritten about log_FANOUT(n / CHANGES) times, not once per spill). A look-up asks the
//! changes, then the spills newest first, then the saved manifest; a save writes the merge of
//! the saved manifest, the spills and the changes (a k-way merge of sorted streams, the latest
//! source winning a path) as the new manifest, atomically, and drops the spills. So a merge
//! that copies a million traces holds [`CHANGES`] entries and a few dozen open spills, not a
//! million entries. A spill is a temporary file of the program's own name
//! (`crate::results_dir::is_own_tmp`): one a killed process left is removed at the next open of
//! `results/` or `report/`, and it was never the manifest, so a kill loses what a kill before
//! the save always lost (the manifest still describes the previous step).

use crate::integrity::{Entries, Fingerprint, IntegrityError, Manifest, Mismatch, FILE};
use crate::owned_dir::{OwnedDir, PathError};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The most changes held in memory before they are spilled (module docs): ~0.25 KB each.
pub const CHANGES: usize = 2048;

/// How many spills of one tier are merged into one of the next (module docs).
pub const FANOUT: usize = 16;

/// A removal, as a spill writes it: an entry of empty hash (a real one is 64 hex digits).
const REMOVED: &str = "";

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
    state: Mutex<State>,
}

/// The manifest as this process sees it (module docs): the saved one, the spills and the
/// changes since the last save.
#[derive(Debug)]
struct State {
    /// The revision the next save records.
    git_rev: String,
    /// The saved manifest, read by streaming (`None`: there was none).
    saved: Option<Manifest>,
    /// Earlier changes written out, oldest first.
    spills: Vec<Spill>,
    /// The latest changes: a path's fingerprint, or `None` for its removal.
    changes: BTreeMap<String, Option<Fingerprint>>,
}

/// Changes written to a temporary file of the directory (module docs), removed when dropped.
#[derive(Debug)]
struct Spill {
    /// Its tier: 0 for changes spilled, t + 1 for [`FANOUT`] spills of tier t merged.
    tier: u32,
    path: PathBuf,
    manifest: Manifest,
}

impl Drop for Spill {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// A source of changes for a merge: a manifest's entries (a removal read from a spill), or
/// the changes held.
type Source<'a> =
    Box<dyn Iterator<Item = Result<(String, Option<Fingerprint>), IntegrityError>> + 'a>;

/// The entries of a spill, a removal as `None`.
fn spilled(entries: Entries<'_>) -> Source<'_> {
    Box::new(entries.map(|e| {
        e.map(|(file, f)| {
            let change = (f.sha256 != REMOVED).then_some(f);
            (file, change)
        })
    }))
}

/// Sources in increasing order of paths merged into one such stream, the last source that
/// has a path giving its change (a later source is a later change). Memory: a head per
/// source.
struct Merge<'a> {
    sources: Vec<Source<'a>>,
    heads: Vec<Option<(String, Option<Fingerprint>)>>,
    failed: bool,
}

impl<'a> Merge<'a> {
    fn new(mut sources: Vec<Source<'a>>) -> Result<Self, IntegrityError> {
        let heads = sources
            .iter_mut()
            .map(|s| s.next().transpose())
            .collect::<Result<_, _>>()?;
        Ok(Self {
            sources,
            heads,
            failed: false,
        })
    }

    fn step(&mut self) -> Result<Option<(String, Option<Fingerprint>)>, IntegrityError> {
        let Some(least) = self
            .heads
            .iter()
            .flatten()
            .map(|(file, _)| file)
            .min()
            .cloned()
        else {
            return Ok(None);
        };
        let mut latest = None;
        for (head, source) in self.heads.iter_mut().zip(&mut self.sources) {
            if head.as_ref().is_some_and(|(file, _)| *file == least) {
                latest = head.take();
                *head = source.next().transpose()?;
            }
        }
        Ok(latest)
    }
}

impl Iterator for Merge<'_> {
    type Item = Result<(String, Option<Fingerprint>), IntegrityError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let step = self.step();
        self.failed = step.is_err();
        step.transpose()
    }
}

impl State {
    /// The saved manifest, the spills and the changes as one sorted stream from the path
    /// `from` on, each path's latest change (removals included).
    fn merged(&mut self, from: &str) -> Result<Merge<'_>, IntegrityError> {
        let mut sources: Vec<Source> = Vec::with_capacity(self.spills.len() + 2);
        if let Some(saved) = &mut self.saved {
            sources.push(Box::new(
                saved
                    .entries_from(from)?
                    .map(|e| e.map(|(k, f)| (k, Some(f)))),
            ));
        }
        for spill in &mut self.spills {
            sources.push(spilled(spill.manifest.entries_from(from)?));
        }
        sources.push(Box::new(
            self.changes
                .range::<str, _>((std::ops::Bound::Included(from), std::ops::Bound::Unbounded))
                .map(|(k, c)| Ok((k.clone(), c.clone()))),
        ));
        Merge::new(sources)
    }

    /// The listed entry of `file`: the latest change, else the saved manifest's.
    fn get(&mut self, file: &str) -> Result<Option<Fingerprint>, IntegrityError> {
        if let Some(change) = self.changes.get(file) {
            return Ok(change.clone());
        }
        for spill in self.spills.iter_mut().rev() {
            if let Some(f) = spill.manifest.get(file)? {
                return Ok((f.sha256 != REMOVED).then_some(f));
            }
        }
        match &mut self.saved {
            Some(saved) => saved.get(file),
            None => Ok(None),
        }
    }

    /// Records a change of `file` in `dir`, spilling the changes when they are [`CHANGES`].
    fn change(
        &mut self,
        dir: &Path,
        file: String,
        change: Option<Fingerprint>,
    ) -> Result<(), IntegrityError> {
        self.changes.insert(file, change);
        if self.changes.len() >= CHANGES {
            self.spill(dir)?;
        }
        Ok(())
    }

    /// Writes the changes to a spill and merges the last [`FANOUT`] spills while they are of
    /// one tier (module docs).
    fn spill(&mut self, dir: &Path) -> Result<(), IntegrityError> {
        let changes: Source = Box::new(
            self.changes
                .iter()
                .map(|(file, change)| Ok((file.clone(), change.clone()))),
        );
        let spill = write_spill(dir, 0, changes)?;
        self.changes.clear();
        self.spills.push(spill);
        loop {
            let n = self.spills.len();
            let tier = self.spills[n - 1].tier;
            if n < FANOUT || self.spills[n - FANOUT..].iter().any(|s| s.tier != tier) {
                return Ok(());
            }
            let mut merged = self.spills.split_off(n - FANOUT);
            match merge_spills(dir, tier + 1, &mut merged) {
                // The merged spills' files are removed as they are dropped.
                Ok(spill) => self.spills.push(spill),
                Err(e) => {
                    self.spills.append(&mut merged);
                    return Err(e);
                }
            }
        }
    }

    /// Saves the manifest of `dir`: the merge of everything, removals left out (module
    /// docs); then the saved manifest is the new one, with no spill and no change.
    fn save(&mut self, dir: &Path) -> Result<(), IntegrityError> {
        let git_rev = self.git_rev.clone();
        let entries = self
            .merged("")?
            .filter_map(|e| e.map(|(k, c)| c.map(|f| (k, f))).transpose());
        crate::integrity::write(dir, &git_rev, entries)?;
        self.saved = Manifest::open_file(dir, FILE)?;
        self.spills.clear();
        self.changes.clear();
        Ok(())
    }
}

/// `spills` (oldest first) merged into a new spill of tier `tier` in `dir`.
fn merge_spills(dir: &Path, tier: u32, spills: &mut [Spill]) -> Result<Spill, IntegrityError> {
    let sources = spills
        .iter_mut()
        .map(|s| s.manifest.entries().map(spilled))
        .collect::<Result<Vec<_>, _>>()?;
    write_spill(dir, tier, Box::new(Merge::new(sources)?))
}

/// Writes the changes `source` (in order) to a new spill of tier `tier` in `dir`.
fn write_spill(dir: &Path, tier: u32, source: Source<'_>) -> Result<Spill, IntegrityError> {
    let path = crate::atomic::tmp_path(&dir.join(FILE));
    let entries = source.map(|e| {
        e.map(|(file, change)| {
            let f = change.unwrap_or(Fingerprint {
                lines: 0,
                bytes: 0,
                sha256: REMOVED.to_string(),
            });
            (file, f)
        })
    });
    crate::integrity::write_to(&path, "", entries, |path, write| {
        use std::io::Write as _;
        let mut out = std::io::BufWriter::with_capacity(64 * 1024, std::fs::File::create(path)?);
        write(&mut out)?;
        out.flush()
    })?;
    let name = path
        .file_name()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned();
    let opened = Manifest::open_file(dir, &name);
    let manifest = match opened {
        Ok(Some(manifest)) => manifest,
        Ok(None) => {
            return Err(IntegrityError::Write {
                path,
                message: "the spill written is gone".to_string(),
            })
        }
        Err(e) => {
            let _ = std::fs::remove_file(&path);
            return Err(e);
        }
    };
    Ok(Spill {
        tier,
        path,
        manifest,
    })
}

impl TrackedDir {
    /// Opens `dir` (creating it). Listed files whose names `verify` accepts must match their
    /// entries ([`TrackedError::Edited`] otherwise, under [`Edits::Refuse`]); a directory that
    /// holds `guarded` (e.g. `runs.csv`) but no manifest is refused too. Under
    /// [`Edits::Accept`] the differing files are fingerprinted as they are. `git_rev` is recorded
    /// as the writer's revision at the next [`TrackedDir::save`]. The manifest is read by
    /// streaming, once to check it and once for `verify`'s files.
    pub fn open(
        dir: &Path,
        git_rev: &str,
        edits: Edits,
        guarded: Option<&str>,
        verify: impl Fn(&str) -> bool,
    ) -> Result<Self, TrackedError> {
        let owned = OwnedDir::open(dir)?;
        let saved = match Manifest::open(dir)? {
            Some(m) => Some(m),
            None if edits == Edits::Refuse && guarded.is_some_and(|g| dir.join(g).exists()) => {
                return Err(TrackedError::Unsealed {
                    dir: dir.to_path_buf(),
                    file: guarded.unwrap_or_default().to_string(),
                })
            }
            None => None,
        };
        let mut state = State {
            git_rev: git_rev.to_string(),
            saved,
            spills: Vec::new(),
            changes: BTreeMap::new(),
        };
        finish_commits(&owned, &mut state)?;
        let mismatches = match &mut state.saved {
            Some(saved) => saved.mismatches(dir, &verify)?,
            None => Vec::new(),
        };
        let tracked = Self {
            dir: owned,
            state: Mutex::new(state),
        };
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

    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        // A panic while the lock was held leaves a consistent state (a change is recorded
        // whole; a spill is pushed once written).
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Records a change of the file at `rel`.
    fn change(&self, rel: &Path, change: Option<Fingerprint>) -> Result<(), TrackedError> {
        Ok(self.lock().change(self.path(), key(rel), change)?)
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
        self.change(rel, Some(fingerprint.clone()))?;
        Ok(fingerprint)
    }

    /// Records the file at `rel` as written by the program (another layer wrote it at a path
    /// from [`TrackedDir::resolve`]); a file that is not there is dropped from the manifest.
    pub fn adopt(&self, rel: &Path) -> Result<(), TrackedError> {
        let path = self.resolve(rel)?;
        match crate::owned_dir::fingerprint(&path) {
            Ok(found) => self.change(rel, Some(found)),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => self.change(rel, None),
            Err(source) => Err(TrackedError::Io { path, source }),
        }
    }

    /// Records the file at `rel` if it is there and its content still hashes to `sha256` (taken
    /// when the program wrote it, e.g. from the journal's seal); returns whether it did. A file
    /// missing or changed since is not recorded.
    pub fn adopt_sealed(&self, rel: &Path, sha256: &str) -> Result<bool, TrackedError> {
        let path = self.resolve(rel)?;
        let found = match crate::owned_dir::fingerprint(&path) {
            Ok(found) => found,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(false),
            Err(source) => return Err(TrackedError::Io { path, source }),
        };
        if found.sha256 != sha256 {
            return Ok(false);
        }
        self.change(rel, Some(found))?;
        Ok(true)
    }

    /// Removes `rel` if the program can prove it wrote it (see the module doc).
    pub fn remove(&self, rel: &Path) -> Result<Removal, TrackedError> {
        let path = self.resolve(rel)?;
        let found = match crate::owned_dir::fingerprint(&path) {
            Ok(found) => found,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                self.change(rel, None)?;
                return Ok(Removal::Absent);
            }
            Err(source) => return Err(TrackedError::Io { path, source }),
        };
        let mut state = self.lock();
        match state.get(&key(rel))? {
            None => {
                return Ok(Removal::Kept(format!(
                    "{}: left in place: not written by this program (not in {FILE})",
                    path.display()
                )))
            }
            Some(f) if f != found => {
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
        state.change(self.path(), key(rel), None)?;
        drop(state);
        // An emptied sub-directory goes too (a non-empty one stays).
        if let Some(parent) = rel.parent().filter(|p| !p.as_os_str().is_empty()) {
            if let Ok(dir) = self.resolve(parent) {
                let _ = std::fs::remove_dir(dir);
            }
        }
        Ok(Removal::Removed)
    }

    /// The listed files whose names start with `prefix`, in order (found by bisection and read
    /// in order: the files under a prefix, not the whole manifest).
    pub fn listed(&self, prefix: &str) -> Result<Vec<String>, TrackedError> {
        let mut state = self.lock();
        let mut out = Vec::new();
        for entry in state.merged(prefix)? {
            let (file, change) = entry?;
            if !file.starts_with(prefix) {
                break;
            }
            if change.is_some() {
                out.push(file);
            }
        }
        Ok(out)
    }

    /// Whether the manifest lists the file at `rel`.
    pub fn lists(&self, rel: &Path) -> Result<bool, TrackedError> {
        Ok(self.lock().get(&key(rel))?.is_some())
    }

    /// Saves the manifest (module docs: the saved one, the spills and the changes merged into
    /// a new one, written entry by entry).
    pub fn save(&self) -> Result<(), TrackedError> {
        let path = self.path().to_path_buf();
        self.lock().save(&path)?;
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
        self.change(Path::new(name), Some(found))?;
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
/// saved manifest is in `state`: for each pending copy of a top-level file the manifest
/// lists, the copy is renamed over the file if the manifest records the copy's content (the
/// commit point was passed), and removed otherwise (it was not: the file and the manifest
/// still agree). A pending copy of a file the manifest does not list is left alone.
fn finish_commits(dir: &OwnedDir, state: &mut State) -> Result<(), TrackedError> {
    let prefix = pending("");
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name.strip_prefix(&prefix)
                .filter(|n| !n.is_empty())
                .map(str::to_string)
        })
        .collect();
    names.sort();
    for name in names {
        let Some(listed) = state.get(&name)? else {
            continue;
        };
        let staged = dir.resolve(Path::new(&pending(&name)))?;
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
        let done = if found == listed {
            std::fs::rename(&staged, dir.resolve(Path::new(&name))?)
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

    /// Changes far more than [`CHANGES`] (paths changed again, removed, written again) are
    /// spilled and merged in tiers, never held past [`CHANGES`] nor kept in more than a few
    /// spills; looked up, listed and saved, they are the map of their latest changes; the
    /// saved manifest lists exactly the files not removed, and no spill is left behind.
    #[test]
    fn spilled_changes_read_as_the_map_of_their_latest() {
        let base = inputs::Scratch::dir("spills");
        let mut state = State {
            git_rev: "r".into(),
            saved: None,
            spills: Vec::new(),
            changes: BTreeMap::new(),
        };
        let mut model: BTreeMap<String, Option<Fingerprint>> = BTreeMap::new();
        let n = 2 * CHANGES * (FANOUT + 2);
        let mut most = 0;
        for i in 0..n {
            let file = format!("traces/e{}/v-{}.csv", i % 3, (i * 7919) % (n / 3));
            let change = (i % 11 != 0).then(|| Fingerprint::of(i.to_string().as_bytes()));
            state.change(&base, file.clone(), change.clone()).unwrap();
            model.insert(file, change);
            assert!(state.changes.len() < CHANGES);
            most = most.max(state.spills.len());
            if i == n / 2 {
                // A save half-way: later changes go on from the saved manifest.
                state.save(&base).unwrap();
            }
        }
        assert!(state.spills.iter().any(|s| s.tier > 0), "a tier was merged");
        assert!(most <= 2 * FANOUT, "{most} spills at once");
        for (file, change) in model.iter().step_by(53) {
            assert_eq!(state.get(file).unwrap(), *change, "{file}");
        }
        let present = |prefix: &str| -> Vec<String> {
            model
                .iter()
                .filter(|(k, c)| k.starts_with(prefix) && c.is_some())
                .map(|(k, _)| k.clone())
                .collect()
        };
        let listed: Vec<String> = state
            .merged("traces/e1/")
            .unwrap()
            .map(|e| e.unwrap())
            .take_while(|(k, _)| k.starts_with("traces/e1/"))
            .filter(|(_, c)| c.is_some())
            .map(|(k, _)| k)
            .collect();
        assert_eq!(listed, present("traces/e1/"));
        state.save(&base).unwrap();
        let saved: BTreeMap<String, Fingerprint> = state
            .saved
            .as_mut()
            .unwrap()
            .entries()
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap();
        let want: BTreeMap<String, Fingerprint> = model
            .into_iter()
            .filter_map(|(k, c)| c.map(|f| (k, f)))
            .collect();
        assert_eq!(saved, want);
        assert!(state.spills.is_empty() && state.changes.is_empty());
        let left: Vec<String> = std::fs::read_dir(&base)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|name| name != FILE)
            .collect();
        assert!(left.is_empty(), "{left:?}");
    }

    #[test]
    fn removes_only_what_it_wrote_unchanged() {
        let base = inputs::Scratch::unmade("tracked");
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
    }

    /// A commit cut by a kill at each of its intermediate states, rebuilt on disk: the next
    /// open leaves the table and the manifest agreeing, the old table before the commit point
    /// (the manifest's save), the new one after it; a pending copy of a file the manifest does
    /// not list is left alone.
    #[test]
    fn a_commit_cut_at_any_state_is_finished_or_undone_on_open() {
        let base = inputs::Scratch::unmade("commit");
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
    }
}
