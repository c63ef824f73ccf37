//! A test's scratch space under the system's temporary directory, removed when the test ends,
//! whether it passes, fails or panics: every test of the workspace that writes outside the
//! checkout writes through one [`Scratch`]. Test code, compiled into the crate for the reason
//! the hostile-file kit is (`hostile.rs`): the crates' tests reach it through `inputs`, which
//! every crate with such tests already links (or takes as a dev-dependency), without a feature.

use std::ffi::OsStr;
use std::ops::Deref;
use std::path::{Path, PathBuf};

/// `<temp>/driftbench-<name>-<pid>` (`<temp>` the system's temporary directory, `<pid>` this
/// process's id), removed with all it holds when the guard is dropped: at the end of the test's
/// scope, and while a panic unwinds it. A former process's leftover of the same name is removed
/// first.
///
/// `name` must be unique among the tests of one test binary (they run on parallel threads):
/// the test's name, or a tag of it. The guard dereferences to the path (`scratch.join(..)`).
#[derive(Debug)]
pub struct Scratch {
    path: PathBuf,
}

impl Scratch {
    /// An empty directory, created before anything is written into it.
    ///
    /// # Panics
    ///
    /// When the directory cannot be created.
    pub fn dir(name: &str) -> Scratch {
        let scratch = Scratch::unmade(name);
        if let Err(e) = std::fs::create_dir_all(&scratch.path) {
            panic!("{}: {e}", scratch.path.display());
        }
        scratch
    }

    /// The path with nothing at it, for a test whose subject creates it (a results directory
    /// a run makes, a file the test writes): whatever is there when the guard is dropped, a
    /// directory or a file, is removed.
    pub fn unmade(name: &str) -> Scratch {
        let path = std::env::temp_dir().join(format!("driftbench-{name}-{}", std::process::id()));
        remove(&path);
        Scratch { path }
    }

    /// The path (also reached by dereferencing the guard).
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Deref for Scratch {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

/// For a command's argument (`Command::arg(&scratch)`).
impl AsRef<OsStr> for Scratch {
    fn as_ref(&self) -> &OsStr {
        self.path.as_os_str()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        remove(&self.path);
    }
}

/// Removes what is at `path`: a directory with all it holds, or a file or symbolic link (never
/// followed). Nothing there, or a removal that fails, is not an error: a scratch path left
/// behind loses nothing, and a drop must not panic while a panic unwinds.
fn remove(path: &Path) {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_dir() => {
            let _ = std::fs::remove_dir_all(path);
        }
        Ok(_) => {
            let _ = std::fs::remove_file(path);
        }
        Err(_) => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scratch_directory_is_removed_with_what_it_holds_when_dropped() {
        let s = Scratch::dir("scratch-dir");
        let path = s.to_path_buf();
        assert!(path.is_dir());
        assert!(path
            .file_name()
            .unwrap()
            .to_str()
            .unwrap()
            .ends_with(&format!("-{}", std::process::id())));
        std::fs::create_dir_all(s.join("a/b")).unwrap();
        std::fs::write(s.join("a/b/c.txt"), "c").unwrap();
        drop(s);
        assert!(!path.exists());
        // A leftover of a former run of the same name is emptied.
        std::fs::create_dir_all(&path).unwrap();
        std::fs::write(path.join("old.txt"), "old").unwrap();
        let s = Scratch::dir("scratch-dir");
        assert_eq!(std::fs::read_dir(&*s).unwrap().count(), 0);
    }

    #[test]
    fn a_scratch_path_is_removed_when_a_test_panics() {
        let file = Scratch::unmade("scratch-panic-file").to_path_buf();
        let dir = Scratch::unmade("scratch-panic-dir").to_path_buf();
        let panicked = std::panic::catch_unwind(|| {
            let f = Scratch::unmade("scratch-panic-file");
            assert!(!f.exists());
            std::fs::write(&*f, "x").unwrap();
            let d = Scratch::dir("scratch-panic-dir");
            std::fs::write(d.join("x"), "x").unwrap();
            panic!("the test fails");
        });
        assert!(panicked.is_err());
        assert!(!file.exists() && !dir.exists());
    }
}
