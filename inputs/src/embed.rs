//! What a build may compile into a binary. `include_str!` and `include_bytes!` read whatever a
//! path leads to, a symbolic link to a secret outside the checkout included, and put it in the
//! binary (and in every message that shows it). So a build embeds a file only if it is a
//! regular file, reached without a symbolic link from a directory that lies inside the
//! checkout: [`files`] lists a directory's embeddable files and refuses the directory when any
//! entry it would embed is a link or a special file, naming it; [`file()`] checks one file.
//!
//! The build scripts of `robots` (the built-in robot files, `robots/data/*.toml`) and
//! `driftbench-python` (the project data the package carries) include this file by path
//! (`#[path = "../inputs/src/embed.rs"]`), so that a build script does not compile this crate
//! and its TOML parser for the build machine; it uses the standard library and `thiserror`
//! only. (A hard link cannot be told from a file and is embedded like one.)

use std::path::{Path, PathBuf};

/// Why a build does not embed a file.
#[derive(Debug, thiserror::Error)]
pub enum EmbedError {
    /// A symbolic link, a FIFO, a device, a socket, or (for a single file) a directory.
    #[error("{}: is {found}, not a regular file; a build embeds only regular files, reached without a symbolic link, from inside {}: replace it by the file itself", path.display(), root.display())]
    NotRegular {
        path: PathBuf,
        root: PathBuf,
        found: &'static str,
    },
    /// A directory to embed from that, its links followed, lies outside the checkout.
    #[error("{}: leads outside {} (to {}); a build embeds nothing from outside the checkout", path.display(), root.display(), target.display())]
    Outside {
        path: PathBuf,
        root: PathBuf,
        target: PathBuf,
    },
    /// A path that is not UTF-8 (`include_bytes!` takes a string).
    #[error("{}: the path is not UTF-8", path.display())]
    NotUtf8 { path: PathBuf },
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
}

/// A file a build embeds.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Embedded {
    /// Its path relative to the checkout's root, with `/` separators.
    pub relative: String,
    /// Its absolute path (inside the canonical root), for `include_bytes!`.
    pub absolute: String,
}

/// Which entries of a directory [`files`] embeds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Walk {
    /// The entries of the directory itself whose name ends with this extension (`"toml"`);
    /// any other entry is left alone.
    Top { extension: &'static str },
    /// Every entry, in every subdirectory, except hidden ones (a name beginning with `.`).
    Tree,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> EmbedError + '_ {
    move |source| EmbedError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// The files of `root`/`dir` a build embeds, as `walk` selects them, sorted by relative path
/// (so their order does not depend on the directory listing). `dir` itself, its links
/// followed, must lie inside `root`; every selected entry must be a regular file or (with
/// [`Walk::Tree`]) a directory, neither reached through a symbolic link.
pub fn files(root: &Path, dir: &Path, walk: Walk) -> Result<Vec<Embedded>, EmbedError> {
    let root = root.canonicalize().map_err(io(root))?;
    let start = root.join(dir);
    let target = start.canonicalize().map_err(io(&start))?;
    if !target.starts_with(&root) {
        return Err(EmbedError::Outside {
            path: start,
            root,
            target,
        });
    }
    let mut out = Vec::new();
    collect(&root, &target, walk, &mut out)?;
    out.sort();
    Ok(out)
}

/// `root`/`path`, one file a build embeds: a regular file, not a symbolic link, in a directory
/// inside `root`.
pub fn file(root: &Path, path: &Path) -> Result<Embedded, EmbedError> {
    let root = root.canonicalize().map_err(io(root))?;
    let full = root.join(path);
    let (Some(parent), Some(name)) = (full.parent(), full.file_name()) else {
        return Err(EmbedError::NotRegular {
            path: full,
            root,
            found: "not a file",
        });
    };
    let parent = parent.canonicalize().map_err(io(parent))?;
    if !parent.starts_with(&root) {
        return Err(EmbedError::Outside {
            path: full,
            root,
            target: parent,
        });
    }
    let full = parent.join(name);
    match kind(&full)? {
        None => embedded(&root, &full),
        Some(found) => Err(EmbedError::NotRegular {
            path: full,
            root,
            found,
        }),
    }
}

/// Appends the files of `dir` (canonical, inside `root`) that `walk` selects.
fn collect(root: &Path, dir: &Path, walk: Walk, out: &mut Vec<Embedded>) -> Result<(), EmbedError> {
    for entry in std::fs::read_dir(dir).map_err(io(dir))? {
        let path = entry.map_err(io(dir))?.path();
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let selected = match walk {
            Walk::Top { extension } => path.extension().is_some_and(|e| e == extension),
            Walk::Tree => !name.starts_with('.'),
        };
        if !selected {
            continue;
        }
        match kind(&path)? {
            None => out.push(embedded(root, &path)?),
            Some("a directory") if walk == Walk::Tree => collect(root, &path, walk, out)?,
            Some(found) => {
                return Err(EmbedError::NotRegular {
                    path,
                    root: root.to_path_buf(),
                    found,
                })
            }
        }
    }
    Ok(())
}

/// `None` for a regular file; otherwise what `path` is, without following a link.
fn kind(path: &Path) -> Result<Option<&'static str>, EmbedError> {
    let t = std::fs::symlink_metadata(path)
        .map_err(io(path))?
        .file_type();
    Ok(if t.is_file() {
        None
    } else if t.is_symlink() {
        Some("a symbolic link")
    } else if t.is_dir() {
        Some("a directory")
    } else {
        Some("a special file (a FIFO, a device or a socket)")
    })
}

fn embedded(root: &Path, path: &Path) -> Result<Embedded, EmbedError> {
    let not_utf8 = || EmbedError::NotUtf8 {
        path: path.to_path_buf(),
    };
    let parts: Option<Vec<&str>> = path
        .strip_prefix(root)
        .map_err(|_| not_utf8())?
        .components()
        .map(|c| c.as_os_str().to_str())
        .collect();
    Ok(Embedded {
        relative: parts.ok_or_else(not_utf8)?.join("/"),
        absolute: path.to_str().ok_or_else(not_utf8)?.to_string(),
    })
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::os::unix::fs::symlink;

    /// A scratch checkout `root/` (with `root/data/`) beside `outside/`. (`inputs::`, not
    /// `crate::`: robots' test of its build script compiles this module too.)
    struct Scratch(inputs::Scratch);

    impl Scratch {
        fn new(tag: &str) -> Self {
            let base = inputs::Scratch::dir(&format!("embed-{tag}"));
            std::fs::create_dir_all(base.join("root/data/sub")).unwrap();
            std::fs::create_dir_all(base.join("outside")).unwrap();
            std::fs::write(base.join("outside/secret.toml"), "SECRET").unwrap();
            std::fs::write(base.join("root/data/b.toml"), "b").unwrap();
            std::fs::write(base.join("root/data/a.toml"), "a").unwrap();
            std::fs::write(base.join("root/data/notes.txt"), "n").unwrap();
            std::fs::write(base.join("root/data/sub/c.csv"), "c").unwrap();
            std::fs::write(base.join("root/data/.hidden"), "h").unwrap();
            Scratch(base)
        }
        fn root(&self) -> PathBuf {
            self.0.join("root")
        }
        fn data(&self, name: &str) -> PathBuf {
            self.0.join("root/data").join(name)
        }
    }

    const TOML: Walk = Walk::Top { extension: "toml" };

    fn relative(files: &[Embedded]) -> Vec<&str> {
        files.iter().map(|f| f.relative.as_str()).collect()
    }

    fn refused(e: EmbedError, name: &str, found: &str) {
        assert!(
            matches!(&e, EmbedError::NotRegular { path, found: f, .. }
                if path.ends_with(name) && *f == found),
            "{e:?}"
        );
        assert!(e.to_string().contains("not a regular file"), "{e}");
    }

    #[test]
    fn regular_files_are_embedded_sorted_with_their_absolute_paths() {
        let s = Scratch::new("plain");
        let top = files(&s.root(), Path::new("data"), TOML).unwrap();
        assert_eq!(relative(&top), ["data/a.toml", "data/b.toml"]);
        let canonical = s.data("a.toml").canonicalize().unwrap();
        assert_eq!(top[0].absolute, canonical.to_str().unwrap());
        let tree = files(&s.root(), Path::new("data"), Walk::Tree).unwrap();
        assert_eq!(
            relative(&tree),
            [
                "data/a.toml",
                "data/b.toml",
                "data/notes.txt",
                "data/sub/c.csv"
            ]
        );
        assert_eq!(
            file(&s.root(), Path::new("data/sub/c.csv"))
                .unwrap()
                .relative,
            "data/sub/c.csv"
        );
    }

    #[test]
    fn a_linked_file_is_refused_wherever_it_leads() {
        let s = Scratch::new("link");
        // To a secret outside the checkout, and to a file inside it: a build embeds neither.
        symlink(s.0.join("outside/secret.toml"), s.data("evil.toml")).unwrap();
        refused(
            files(&s.root(), Path::new("data"), TOML).unwrap_err(),
            "evil.toml",
            "a symbolic link",
        );
        std::fs::remove_file(s.data("evil.toml")).unwrap();
        symlink(s.data("a.toml"), s.data("alias.toml")).unwrap();
        refused(
            files(&s.root(), Path::new("data"), Walk::Tree).unwrap_err(),
            "alias.toml",
            "a symbolic link",
        );
        refused(
            file(&s.root(), Path::new("data/alias.toml")).unwrap_err(),
            "alias.toml",
            "a symbolic link",
        );
        // A link the walk does not select is left alone.
        std::fs::remove_file(s.data("alias.toml")).unwrap();
        symlink(s.0.join("outside/secret.toml"), s.data("elsewhere.txt")).unwrap();
        assert_eq!(files(&s.root(), Path::new("data"), TOML).unwrap().len(), 2);
        refused(
            files(&s.root(), Path::new("data"), Walk::Tree).unwrap_err(),
            "elsewhere.txt",
            "a symbolic link",
        );
    }

    #[test]
    fn a_linked_directory_or_one_outside_the_checkout_is_refused() {
        let s = Scratch::new("dir");
        // A subdirectory that is a link: not walked into.
        symlink(s.0.join("outside"), s.data("linked")).unwrap();
        refused(
            files(&s.root(), Path::new("data"), Walk::Tree).unwrap_err(),
            "linked",
            "a symbolic link",
        );
        // The directory to embed from leads outside the checkout (a link, or `..`).
        let e = files(&s.root(), Path::new("data/linked"), TOML).unwrap_err();
        assert!(matches!(e, EmbedError::Outside { .. }), "{e:?}");
        let e = files(&s.root(), Path::new("../outside"), TOML).unwrap_err();
        assert!(matches!(e, EmbedError::Outside { .. }), "{e:?}");
        assert!(e.to_string().contains("leads outside"), "{e}");
        let e = file(&s.root(), Path::new("data/linked/secret.toml")).unwrap_err();
        assert!(matches!(e, EmbedError::Outside { .. }), "{e:?}");
        // A directory named as a file is not a file.
        refused(
            file(&s.root(), Path::new("data/sub")).unwrap_err(),
            "sub",
            "a directory",
        );
    }

    #[test]
    fn a_fifo_is_refused_not_read() {
        let s = Scratch::new("fifo");
        let made = std::process::Command::new("mkfifo")
            .arg(s.data("pipe.toml"))
            .status()
            .unwrap();
        assert!(made.success());
        refused(
            files(&s.root(), Path::new("data"), TOML).unwrap_err(),
            "pipe.toml",
            "a special file (a FIFO, a device or a socket)",
        );
    }
}
