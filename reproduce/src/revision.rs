//! The code revision the binary was built from ([`REVISION`]), embedded at build time by
//! `build.rs` by the rules of `source` (the build script's module, compiled into the library
//! for its tests alone): it needs no git checkout at run time, so a binary in
//! a container image or a copied tree still knows it, and two different trees never share
//! one. Rows, journals, shard manifests and result manifests carry it; resume and merge
//! compare it.

#[cfg(test)]
mod source;

/// The revision of the sources this binary was built from.
pub const REVISION: &str = env!("DRIFTBENCH_REVISION");

#[cfg(test)]
mod tests {
    use super::source::{git_files, revision, sources, sources_hash};
    use super::REVISION;
    use std::path::Path;
    use std::process::Command;
    use store::fnv1a64;

    fn hex(s: &str, n: usize) -> bool {
        s.len() == n && s.bytes().all(|b| b.is_ascii_hexdigit())
    }

    /// The shapes [`source::revision`] can give.
    fn well_formed(rev: &str) -> bool {
        match rev.split_once("-dirty-") {
            Some((commit, hash)) => hex(commit, 12) && hex(hash, 16),
            None => rev
                .strip_prefix("src-")
                .map_or(hex(rev, 12), |h| hex(h, 16)),
        }
    }

    #[test]
    fn the_embedded_revision_is_well_formed_and_never_unknown() {
        assert!(well_formed(REVISION), "{REVISION}");
        assert!(!REVISION.contains("unknown"));
    }

    fn write(root: &Path, rel: &str, text: &str) {
        let p = root.join(rel);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, text).unwrap();
    }

    /// A small workspace: a root manifest and lock, one member, and files that are not sources;
    /// removed when dropped.
    fn tree(name: &str) -> inputs::Scratch {
        let root = inputs::Scratch::unmade(&format!("revision-{name}"));
        write(&root, "Cargo.toml", "[workspace]\nmembers = [\"a\"]\n");
        write(&root, "Cargo.lock", "version = 4\n");
        write(&root, "a/Cargo.toml", "[package]\nname = \"a\"\n");
        write(&root, "a/src/lib.rs", "pub fn f() {}\n");
        write(&root, "a/data/arm.toml", "dof = 3\n");
        write(&root, "a/tests/t.rs", "\n");
        write(&root, "results/runs.csv", "h\n");
        root
    }

    /// Whether `root` lies inside a git checkout.
    fn in_git(root: &Path) -> bool {
        Command::new("git")
            .arg("-C")
            .arg(root)
            .args(["rev-parse", "HEAD"])
            .output()
            .is_ok_and(|o| o.status.success())
    }

    #[test]
    fn the_build_script_watches_head_in_a_checkout_and_nothing_without_git() {
        let root = tree("git-files");
        if !in_git(&root) {
            assert_eq!(git_files(&root), Vec::<std::path::PathBuf>::new());
        }
        drop(root);
        let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        if in_git(&workspace) {
            let files = git_files(&workspace);
            assert!(files.iter().any(|p| p.ends_with("HEAD")), "{files:?}");
            assert!(files.iter().all(|p| p.exists()), "{files:?}");
        }
    }

    #[test]
    fn without_git_the_revision_is_the_hash_of_the_sources() {
        let root = tree("nogit");
        if in_git(&root) {
            eprintln!("skipped: the temporary directory lies inside a git checkout");
            return;
        }
        assert_eq!(
            sources(&root),
            [
                "Cargo.lock",
                "Cargo.toml",
                "a/Cargo.toml",
                "a/data/arm.toml",
                "a/src/lib.rs"
            ]
        );
        let first = revision(&root, fnv1a64);
        assert!(first.starts_with("src-") && well_formed(&first), "{first}");
        assert_eq!(revision(&root, fnv1a64), first, "repeatable");
        // What is not a source does not change it; a source does, and so does a new one.
        write(&root, "results/runs.csv", "h\n1\n");
        write(&root, "a/tests/t.rs", "// more\n");
        assert_eq!(revision(&root, fnv1a64), first);
        write(&root, "a/src/lib.rs", "pub fn f() { }\n");
        let edited = revision(&root, fnv1a64);
        assert_ne!(edited, first);
        write(&root, "a/src/new.rs", "\n");
        let added = revision(&root, fnv1a64);
        assert_ne!(added, edited);
        // A symbolic link is not followed: one to the root of the file system or to
        // /dev/zero is hashed by the path it holds, at once; changing where it points is a
        // change. A FIFO is no source (reading it would wait for a writer).
        #[cfg(unix)]
        {
            let src = root.join("a/src");
            std::os::unix::fs::symlink("/", src.join("everything")).unwrap();
            std::os::unix::fs::symlink("/dev/zero", src.join("zero.rs")).unwrap();
            let made = Command::new("mkfifo")
                .arg(src.join("pipe.rs"))
                .status()
                .unwrap();
            assert!(made.success());
            let (tx, rx) = std::sync::mpsc::channel();
            let at = root.to_path_buf();
            std::thread::spawn(move || {
                let _ = tx.send((sources(&at), revision(&at, fnv1a64)));
            });
            let (listed, linked) = rx
                .recv_timeout(std::time::Duration::from_secs(10))
                .expect("the sources were hashed within 10 s");
            assert!(
                listed.contains(&"a/src/everything".to_string())
                    && listed.contains(&"a/src/zero.rs".to_string())
                    && !listed.iter().any(|s| s.contains("pipe")),
                "{listed:?}"
            );
            assert_ne!(linked, added);
            std::fs::remove_file(src.join("zero.rs")).unwrap();
            std::os::unix::fs::symlink("/dev/null", src.join("zero.rs")).unwrap();
            assert_ne!(revision(&root, fnv1a64), linked);
        }
    }

    #[test]
    fn in_a_checkout_the_revision_is_the_commit_and_a_dirty_tree_adds_its_hash() {
        let root = tree("git");
        let git = |args: &[&str]| {
            Command::new("git")
                .arg("-C")
                .arg(&root)
                .args(["-c", "user.name=t", "-c", "user.email=t@example.org"])
                .args(args)
                .output()
                .is_ok_and(|o| o.status.success())
        };
        if !git(&["init", "-q"]) {
            eprintln!("skipped: git is not installed");
            return;
        }
        assert!(git(&["add", "."]) && git(&["commit", "-q", "-m", "one"]));
        let clean = revision(&root, fnv1a64);
        assert!(hex(&clean, 12), "{clean}");
        // Outside the sources, a change (tracked or not) leaves the tree clean.
        write(&root, "results/runs.csv", "h\n1\n");
        write(&root, "results-shard-1-of-2/runs.csv", "h\n");
        assert_eq!(revision(&root, fnv1a64), clean);
        // An untracked source makes it dirty, with the hash of the sources as they are.
        write(&root, "a/src/new.rs", "\n");
        let dirty = revision(&root, fnv1a64);
        assert_eq!(
            dirty,
            format!("{clean}-dirty-{}", sources_hash(&root, fnv1a64))
        );
        // Another edit of the same commit is another revision.
        write(&root, "a/src/new.rs", "// other\n");
        let other = revision(&root, fnv1a64);
        assert!(other.starts_with(&format!("{clean}-dirty-")) && other != dirty);
    }
}
