//! The code revision of a source tree, as the build script computes it (`reproduce/build.rs`
//! includes this file; the library compiles it too, for its tests). Std only.
//!
//! - **Clean checkout:** the commit, `git rev-parse --short=12 HEAD` (12 hex digits).
//! - **Dirty checkout** (git reports a change, untracked files included, in the sources):
//!   `<commit>-dirty-<hash>`, the hash of the sources as they are, so two different edits of
//!   one commit never count as the same revision.
//! - **No git** (a copied tree, a container build without `.git`, no git installed):
//!   `src-<hash>`.
//!
//! The sources ([`sources`]) are the root `Cargo.toml` and `Cargo.lock` and, in each member
//! directory (a directory of the root holding a `Cargo.toml`), its `Cargo.toml`, `build.rs`,
//! and everything under `src/`, `data/` and `assets/`: what the binary is compiled from. The
//! hash is FNV-1a 64 (`hash`, passed in) over every source's relative path and content, in
//! the order of the paths, as 16 hex digits. Symbolic links are not followed: a link counts
//! with the path it holds as its content (a link committed to `/` or `/dev/zero` would
//! otherwise make the build hash the whole file system or read without end), and a FIFO or a
//! device is no source. Nothing depends on the directory listing's
//! order, the machine or the time; "unknown" is never a revision.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Per member directory: what of it is a source (files, or directories taken whole).
pub const MEMBER_SOURCES: [&str; 5] = ["Cargo.toml", "build.rs", "src", "data", "assets"];

/// The root's own sources.
pub const ROOT_SOURCES: [&str; 2] = ["Cargo.toml", "Cargo.lock"];

/// The source paths of the tree at `root` that exist (files or directories, relative),
/// sorted: [`ROOT_SOURCES`], then each member's [`MEMBER_SOURCES`].
pub fn source_roots(root: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = ROOT_SOURCES.iter().map(PathBuf::from).collect();
    let mut members: Vec<PathBuf> = std::fs::read_dir(root)
        .into_iter()
        .flatten()
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .map(|e| PathBuf::from(e.file_name()))
        .filter(|m| root.join(m).join("Cargo.toml").is_file())
        .collect();
    members.sort();
    for m in members {
        out.extend(MEMBER_SOURCES.iter().map(|s| m.join(s)));
    }
    out.retain(|p| root.join(p).exists());
    out
}

/// Every source file of the tree at `root` (relative, `/`-separated), sorted.
pub fn sources(root: &Path) -> Vec<String> {
    fn walk(root: &Path, rel: &Path, out: &mut Vec<String>) {
        let path = root.join(rel);
        let Ok(t) = std::fs::symlink_metadata(&path).map(|m| m.file_type()) else {
            return;
        };
        if t.is_dir() {
            for e in std::fs::read_dir(&path).into_iter().flatten().flatten() {
                walk(root, &rel.join(e.file_name()), out);
            }
        } else if t.is_file() || t.is_symlink() {
            out.push(
                rel.components()
                    .map(|c| c.as_os_str().to_string_lossy())
                    .collect::<Vec<_>>()
                    .join("/"),
            );
        }
    }
    let mut out = Vec::new();
    for r in source_roots(root) {
        walk(root, &r, &mut out);
    }
    out.sort();
    out
}

/// The hash of the sources of `root` ([`sources`]): 16 hex digits.
pub fn sources_hash(root: &Path, hash: fn(&[u8]) -> u64) -> String {
    let mut bytes = Vec::new();
    for rel in sources(root) {
        bytes.extend(rel.as_bytes());
        bytes.push(0);
        bytes.extend(content(&root.join(&rel)));
        bytes.push(0);
    }
    format!("{:016x}", hash(&bytes))
}

/// A source's content: a regular file's bytes, a symbolic link's target path (not followed).
fn content(path: &Path) -> Vec<u8> {
    match std::fs::read_link(path) {
        Ok(target) => target.to_string_lossy().into_owned().into_bytes(),
        Err(_) => std::fs::read(path).unwrap_or_default(),
    }
}

/// `git -C root args`: its standard output when it succeeded.
fn git(root: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .arg("-C")
        .arg(root)
        .args(args)
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// The revision of the tree at `root` (the rules of the module doc).
pub fn revision(root: &Path, hash: fn(&[u8]) -> u64) -> String {
    let Some(commit) = git(root, &["rev-parse", "--short=12", "HEAD"]) else {
        return format!("src-{}", sources_hash(root, hash));
    };
    let mut status = vec!["status", "--porcelain", "--untracked-files=all", "--"];
    let roots: Vec<String> = source_roots(root)
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    status.extend(roots.iter().map(String::as_str));
    match git(root, &status) {
        Some(changes) if changes.is_empty() => commit,
        _ => format!("{commit}-dirty-{}", sources_hash(root, hash)),
    }
}

/// The git files whose change changes [`revision`] besides the sources: `HEAD`, the branch it
/// names and `packed-refs` (those that exist), for the build script's `rerun-if-changed`.
pub fn git_files(root: &Path) -> Vec<PathBuf> {
    let mut names = vec!["HEAD".to_string(), "packed-refs".to_string()];
    names.extend(git(root, &["symbolic-ref", "-q", "HEAD"]));
    names
        .iter()
        .filter_map(|n| git(root, &["rev-parse", "--git-path", n]))
        .map(|p| root.join(p))
        .filter(|p| p.exists())
        .collect()
}
