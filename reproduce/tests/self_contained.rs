//! The repository is self-contained: no tracked file refers to the specification or the papers
//! outside it (the `shared` directory beside the repository, which a clone does not have).
//! What the code relies on is written down in `docs/` (see the README's "Documents").
//!
//! Every file `git ls-files` lists is searched (a directory walk without `target/` and hidden
//! directories when git is not available), except binary files (PNG, or any file with a NUL byte).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The forbidden references, assembled at run time so that this file does not contain them.
fn forbidden() -> Vec<String> {
    let shared = "shared";
    vec![
        format!("{shared}/{}", "spec"),
        format!("{shared}/{}", "papers"),
        format!("../{shared}"),
        format!("/work/{shared}"),
    ]
}

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("reproduce/ has a parent")
        .to_path_buf()
}

/// The repository's tracked files (relative paths), from git, or from a directory walk.
fn tracked_files(root: &Path) -> Vec<PathBuf> {
    let git = Command::new("git")
        .arg("-C")
        .arg(root)
        .args(["ls-files", "-z"])
        .output();
    if let Ok(out) = git {
        if out.status.success() && !out.stdout.is_empty() {
            return out
                .stdout
                .split(|&b| b == 0)
                .filter(|p| !p.is_empty())
                .map(|p| PathBuf::from(String::from_utf8_lossy(p).into_owned()))
                .collect();
        }
    }
    let mut files = Vec::new();
    let mut stack = vec![PathBuf::new()];
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(root.join(&dir)) else {
            continue;
        };
        for entry in entries.flatten() {
            let name = entry.file_name();
            let name = name.to_string_lossy();
            if name.starts_with('.') || (dir.as_os_str().is_empty() && name == "target") {
                continue;
            }
            let rel = dir.join(&*name);
            match entry.file_type() {
                Ok(t) if t.is_dir() => stack.push(rel),
                Ok(t) if t.is_file() => files.push(rel),
                _ => {}
            }
        }
    }
    files
}

/// `path:line: text` for every line of `text` that holds one of `patterns`.
fn offending_lines(path: &Path, text: &str, patterns: &[String]) -> Vec<String> {
    text.lines()
        .enumerate()
        .filter(|(_, line)| patterns.iter().any(|p| line.contains(p.as_str())))
        .map(|(i, line)| format!("{}:{}: {}", path.display(), i + 1, line.trim()))
        .collect()
}

#[test]
fn the_patterns_catch_what_they_must() {
    let patterns = forbidden();
    let hits = |s: &str| offending_lines(Path::new("x"), s, &patterns).len();
    let shared = "shared";
    assert_eq!(hits(&format!("see `{shared}/spec/paths.md`")), 1);
    assert_eq!(hits(&format!("full texts in ../{shared}/papers/")), 1);
    assert_eq!(hits(&format!("the spec (`{shared}/spec/`) decides")), 1);
    assert_eq!(hits(&format!("/work/{shared}/spec/robots.md")), 1);
    assert_eq!(
        hits("see `docs/paths.md`; a shared file system; spec.rs"),
        0
    );
}

#[test]
fn no_tracked_file_refers_outside_the_repository() {
    let root = repo_root();
    let patterns = forbidden();
    let files = tracked_files(&root);
    assert!(
        files.iter().any(|f| f == Path::new("README.md")),
        "no files found under {}",
        root.display()
    );
    let mut offending = Vec::new();
    for rel in &files {
        if rel
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("png"))
        {
            continue;
        }
        // A tracked file deleted in the working tree (or unreadable) has nothing to check.
        let Ok(bytes) = std::fs::read(root.join(rel)) else {
            continue;
        };
        if bytes.contains(&0) {
            continue; // binary
        }
        offending.extend(offending_lines(
            rel,
            &String::from_utf8_lossy(&bytes),
            &patterns,
        ));
    }
    assert!(
        offending.is_empty(),
        "{} line(s) refer to files outside the repository; cite docs/ instead \
         (docs/experiments.md, docs/robots.md, docs/paths.md, docs/group-code.md):\n{}",
        offending.len(),
        offending.join("\n")
    );
}
