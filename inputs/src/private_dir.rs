//! A directory the program keeps for itself outside a checkout (the Python package's unpacked
//! data, `$XDG_CACHE_HOME/driftbench/data-<digest>`): a cache another user, a poisoned CI cache
//! or the shared temporary directory may have prepared in its place.
//!
//! [`sync`] fills such a directory with known files, and
//! - creates every directory it needs owner-only (mode 0700), and a marker file
//!   ([`MARKER`]) in the directory it created;
//! - before writing into or reading from a directory, looks at it without following links
//!   (`lstat`): a symbolic link, anything but a directory, a directory another user owns or
//!   other users may write, and a directory without the marker (one it did not create) are
//!   refused ([`PrivateDirError`]), so nothing is written through a link to elsewhere;
//! - writes a file only where its content differs, to a temporary file renamed over it (a link
//!   there is replaced, never written through), and deletes nothing: a file or link it did
//!   not write is an error naming it, for the user to remove.

use std::io::Write;
use std::path::{Path, PathBuf};

/// The file that marks a directory [`sync`] created.
pub const MARKER: &str = ".driftbench-private";

/// The prefix of [`sync`]'s in-flight files (another process may be writing them).
const TMP_MARK: &str = ".driftbench-tmp-";

/// Why a private directory is not used.
#[derive(Debug, thiserror::Error)]
pub enum PrivateDirError {
    #[error("{}: is a symbolic link; a private directory is not followed through a link (remove it)", path.display())]
    Link { path: PathBuf },
    #[error("{}: is {found}, not a directory", path.display())]
    NotDirectory { path: PathBuf, found: &'static str },
    #[error("{}: is owned by user {owner}, not by this user ({uid}); it is not used", path.display())]
    NotOwned { path: PathBuf, owner: u32, uid: u32 },
    #[error("{}: other users may write it (mode {mode:o}); it is not used", path.display())]
    Shared { path: PathBuf, mode: u32 },
    #[error("{}: was not created by driftbench (it has no {MARKER}); it is not used: remove it", path.display())]
    Foreign { path: PathBuf },
    #[error("{}: driftbench did not write it, and deletes nothing it did not write: remove it", path.display())]
    Unknown { path: PathBuf },
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> PrivateDirError + '_ {
    move |source| PrivateDirError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Makes `dir` hold exactly `files` (relative paths with `/`, and their bytes) besides its
/// marker and in-flight files (module docs). `dir`'s parent is created (owner-only) where
/// missing, and checked like `dir` except for the marker; the directories above it are the
/// user's.
pub fn sync(dir: &Path, files: &[(&str, &[u8])]) -> Result<(), PrivateDirError> {
    if let Some(parent) = dir.parent().filter(|p| !p.as_os_str().is_empty()) {
        if let Some(above) = parent.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(above).map_err(io(above))?;
        }
        own_dir(parent)?;
    }
    if own_dir(dir)? {
        create_new(&dir.join(MARKER), b"")?;
    }
    match kind_of(&dir.join(MARKER))? {
        Some(Kind::File) => {}
        _ => {
            return Err(PrivateDirError::Foreign {
                path: dir.to_path_buf(),
            })
        }
    }
    for (rel, bytes) in files {
        let mut path = dir.to_path_buf();
        let parts: Vec<&str> = rel.split('/').collect();
        for part in &parts[..parts.len() - 1] {
            path.push(part);
            own_dir(&path)?;
        }
        path.push(parts[parts.len() - 1]);
        write_if_changed(&path, bytes)?;
    }
    let known: std::collections::HashSet<PathBuf> = files
        .iter()
        .map(|(rel, _)| rel.split('/').fold(dir.to_path_buf(), |p, s| p.join(s)))
        .chain(std::iter::once(dir.join(MARKER)))
        .collect();
    check_entries(dir, &known)
}

/// What an entry is, looked at without following a link.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    File,
    Dir,
    Link,
    Other(&'static str),
}

/// `path`'s [`Kind`] (`lstat`), `None` when it does not exist.
fn kind_of(path: &Path) -> Result<Option<Kind>, PrivateDirError> {
    match std::fs::symlink_metadata(path) {
        Ok(m) => Ok(Some(kind(&m.file_type()))),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(io(path)(e)),
    }
}

fn kind(t: &std::fs::FileType) -> Kind {
    if t.is_symlink() {
        Kind::Link
    } else if t.is_dir() {
        Kind::Dir
    } else if t.is_file() {
        Kind::File
    } else {
        Kind::Other("not a regular file or directory")
    }
}

/// Creates `dir` owner-only if it does not exist (true), else checks that it is a directory,
/// not a link, this user's and not writable by others (false).
fn own_dir(dir: &Path) -> Result<bool, PrivateDirError> {
    match kind_of(dir)? {
        None => {
            create_private_dir(dir)?;
            Ok(true)
        }
        Some(Kind::Link) => Err(PrivateDirError::Link {
            path: dir.to_path_buf(),
        }),
        Some(Kind::Dir) => {
            check_owner(dir)?;
            Ok(false)
        }
        Some(Kind::File) => Err(PrivateDirError::NotDirectory {
            path: dir.to_path_buf(),
            found: "a file",
        }),
        Some(Kind::Other(found)) => Err(PrivateDirError::NotDirectory {
            path: dir.to_path_buf(),
            found,
        }),
    }
}

#[cfg(unix)]
fn create_private_dir(dir: &Path) -> Result<(), PrivateDirError> {
    use std::os::unix::fs::DirBuilderExt;
    std::fs::DirBuilder::new()
        .mode(0o700)
        .create(dir)
        .map_err(io(dir))
}

#[cfg(not(unix))]
fn create_private_dir(dir: &Path) -> Result<(), PrivateDirError> {
    std::fs::create_dir(dir).map_err(io(dir))
}

/// The directory `dir` (already known not to be a link) belongs to this user, and no other
/// user may write it.
#[cfg(unix)]
fn check_owner(dir: &Path) -> Result<(), PrivateDirError> {
    use std::os::unix::fs::MetadataExt;
    let m = std::fs::symlink_metadata(dir).map_err(io(dir))?;
    // SAFETY: geteuid has no preconditions and cannot fail.
    let uid = unsafe { libc::geteuid() };
    if m.uid() != uid {
        return Err(PrivateDirError::NotOwned {
            path: dir.to_path_buf(),
            owner: m.uid(),
            uid,
        });
    }
    let mode = m.mode() & 0o7777;
    if mode & 0o022 != 0 {
        return Err(PrivateDirError::Shared {
            path: dir.to_path_buf(),
            mode,
        });
    }
    Ok(())
}

#[cfg(not(unix))]
fn check_owner(_dir: &Path) -> Result<(), PrivateDirError> {
    Ok(())
}

/// Creates the file `path` with `bytes`, failing if anything is there (owner-only).
fn create_new(path: &Path, bytes: &[u8]) -> Result<(), PrivateDirError> {
    let mut options = std::fs::OpenOptions::new();
    options.write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.mode(0o600);
    }
    let mut file = options.open(path).map_err(io(path))?;
    file.write_all(bytes).map_err(io(path))
}

/// Writes `bytes` to `path` unless the regular file there holds them already: to an in-flight
/// file renamed over it. A link or anything but a regular file at `path` is refused.
fn write_if_changed(path: &Path, bytes: &[u8]) -> Result<(), PrivateDirError> {
    match kind_of(path)? {
        Some(Kind::File) if std::fs::read(path).map_err(io(path))? == bytes => return Ok(()),
        Some(Kind::File) | None => {}
        Some(Kind::Link) => {
            return Err(PrivateDirError::Link {
                path: path.to_path_buf(),
            })
        }
        Some(_) => {
            return Err(PrivateDirError::Unknown {
                path: path.to_path_buf(),
            })
        }
    }
    let parent = path.parent().unwrap_or(Path::new("."));
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    // Not ending in the file's own extension: a file left by a crashed process is never read
    // as an experiment file.
    let tmp = parent.join(format!(
        "{TMP_MARK}{}-{}.partial",
        std::process::id(),
        name.unwrap_or_default()
    ));
    let _ = std::fs::remove_file(&tmp);
    create_new(&tmp, bytes)?;
    std::fs::rename(&tmp, path).map_err(io(path))
}

/// Every entry under `dir` (not following links) is a directory, a `known` file or an
/// in-flight file; anything else is an error naming it.
fn check_entries(
    dir: &Path,
    known: &std::collections::HashSet<PathBuf>,
) -> Result<(), PrivateDirError> {
    for entry in std::fs::read_dir(dir).map_err(io(dir))? {
        let entry = entry.map_err(io(dir))?;
        let path = entry.path();
        let in_flight = entry.file_name().to_string_lossy().starts_with(TMP_MARK);
        match kind(&entry.file_type().map_err(io(&path))?) {
            Kind::Dir => {
                check_owner(&path)?;
                check_entries(&path, known)?;
            }
            Kind::File if in_flight || known.contains(&path) => {}
            Kind::Link => return Err(PrivateDirError::Link { path }),
            _ => return Err(PrivateDirError::Unknown { path }),
        }
    }
    Ok(())
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::os::unix::fs::PermissionsExt;

    /// A scratch base directory, removed at the end.
    fn scratch(name: &str) -> crate::Scratch {
        crate::Scratch::dir(&format!("private-{name}"))
    }

    const FILES: [(&str, &[u8]); 2] = [("a.toml", b"a = 1\n"), ("sub/b.csv", b"x\n1\n")];

    fn mode(p: &Path) -> u32 {
        std::fs::symlink_metadata(p).unwrap().permissions().mode() & 0o777
    }

    #[test]
    fn a_new_directory_is_owner_only_and_an_edit_is_undone() {
        let s = scratch("new");
        let dir = s.join("cache/driftbench/data-1");
        sync(&dir, &FILES).unwrap();
        assert_eq!(std::fs::read(dir.join("sub/b.csv")).unwrap(), b"x\n1\n");
        for d in [dir.parent().unwrap(), &dir, &dir.join("sub")] {
            assert_eq!(mode(d), 0o700, "{}", d.display());
        }
        std::fs::write(dir.join("a.toml"), "edited").unwrap();
        sync(&dir, &FILES).unwrap();
        assert_eq!(std::fs::read(dir.join("a.toml")).unwrap(), b"a = 1\n");
    }

    /// The cache linked to another directory: nothing is written there or deleted from it.
    #[test]
    fn a_linked_directory_is_refused_and_left_as_it_is() {
        let s = scratch("linked");
        let elsewhere = s.join("elsewhere");
        std::fs::create_dir_all(elsewhere.join("sub")).unwrap();
        std::fs::write(elsewhere.join("precious"), "keep").unwrap();
        std::fs::write(elsewhere.join(MARKER), "").unwrap();
        let parent = s.join("cache/driftbench");
        std::fs::create_dir_all(&parent).unwrap();
        std::fs::set_permissions(&parent, std::fs::Permissions::from_mode(0o700)).unwrap();
        let dir = parent.join("data-1");
        std::os::unix::fs::symlink(&elsewhere, &dir).unwrap();
        let e = sync(&dir, &FILES).unwrap_err();
        assert!(matches!(e, PrivateDirError::Link { .. }), "{e}");
        assert!(e.to_string().contains("is a symbolic link"), "{e}");
        assert_eq!(std::fs::read(elsewhere.join("precious")).unwrap(), b"keep");
        assert!(!elsewhere.join("a.toml").exists());
        // A subdirectory linked elsewhere, in a directory it created.
        std::fs::remove_file(&dir).unwrap();
        sync(&dir, &FILES).unwrap();
        std::fs::remove_dir_all(dir.join("sub")).unwrap();
        std::os::unix::fs::symlink(elsewhere.join("sub"), dir.join("sub")).unwrap();
        assert!(matches!(
            sync(&dir, &FILES),
            Err(PrivateDirError::Link { .. })
        ));
        assert!(!elsewhere.join("sub/b.csv").exists());
        // A known file linked elsewhere is not written through.
        std::fs::remove_file(dir.join("sub")).unwrap();
        std::fs::remove_file(dir.join("a.toml")).unwrap();
        std::os::unix::fs::symlink(elsewhere.join("precious"), dir.join("a.toml")).unwrap();
        assert!(matches!(
            sync(&dir, &FILES),
            Err(PrivateDirError::Link { .. })
        ));
        assert_eq!(std::fs::read(elsewhere.join("precious")).unwrap(), b"keep");
    }

    #[test]
    fn a_directory_it_did_not_create_or_others_may_write_is_refused() {
        let s = scratch("foreign");
        let dir = s.join("cache/driftbench/data-1");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::set_permissions(
            dir.parent().unwrap(),
            std::fs::Permissions::from_mode(0o700),
        )
        .unwrap();
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700)).unwrap();
        std::fs::write(dir.join("a.toml"), "planted").unwrap();
        let e = sync(&dir, &FILES).unwrap_err();
        assert!(matches!(e, PrivateDirError::Foreign { .. }), "{e}");
        assert_eq!(std::fs::read(dir.join("a.toml")).unwrap(), b"planted");
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o777)).unwrap();
        assert!(matches!(
            sync(&dir, &FILES),
            Err(PrivateDirError::Shared { mode: 0o777, .. })
        ));
    }

    #[test]
    fn a_file_it_did_not_write_is_named_not_deleted() {
        let s = scratch("unknown");
        let dir = s.join("cache/driftbench/data-1");
        sync(&dir, &FILES).unwrap();
        std::fs::write(dir.join("sub/extra.toml"), "mine").unwrap();
        let e = sync(&dir, &FILES).unwrap_err();
        assert!(
            matches!(&e, PrivateDirError::Unknown { path } if path.ends_with("sub/extra.toml")),
            "{e}"
        );
        assert_eq!(std::fs::read(dir.join("sub/extra.toml")).unwrap(), b"mine");
    }
}
