//! Every integration-test file runs. A crate that sets `autotests = false` (most of the
//! workspace: one test binary per crate, issue 29) builds only the `[[test]]` targets its
//! `Cargo.toml` names, and the modules those declare; a file of `tests/` that neither names
//! nor declares is never compiled, so its tests pass by never running. (One did:
//! `presentation_renders.rs`, the check that the report's pages compute nothing.)

use std::collections::BTreeSet;
use std::path::Path;

use crate::common::repo_root;

/// The files of `tests/` (directly in it, `*.rs`) that no test target reaches: not the path
/// of a `[[test]]` of `manifest`, and not declared as `mod NAME;` in a file of `tests/`.
/// `files` maps a file name (`x.rs`) to its text.
fn orphans(manifest: &toml::Table, files: &[(String, String)]) -> Vec<String> {
    let targets: BTreeSet<String> = manifest
        .get("test")
        .and_then(toml::Value::as_array)
        .into_iter()
        .flatten()
        .filter_map(|t| t.get("path").and_then(toml::Value::as_str))
        .filter_map(|p| p.strip_prefix("tests/"))
        .map(str::to_string)
        .collect();
    let declared: BTreeSet<String> = files
        .iter()
        .flat_map(|(_, text)| text.lines())
        .filter_map(|line| {
            let line = line.trim();
            let rest = line
                .strip_prefix("pub mod ")
                .or_else(|| line.strip_prefix("mod "))?;
            rest.strip_suffix(';').map(|name| format!("{name}.rs"))
        })
        .collect();
    files
        .iter()
        .map(|(name, _)| name)
        .filter(|name| !targets.contains(*name) && !declared.contains(*name))
        .cloned()
        .collect()
}

fn rust_files(dir: &Path) -> Vec<(String, String)> {
    let mut files: Vec<(String, String)> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "rs"))
        .map(|p| {
            let text = std::fs::read_to_string(&p)
                .unwrap_or_else(|e| panic!("{}: cannot read: {e}", p.display()));
            let name = p.file_name().expect("a file name").to_string_lossy().into();
            (name, text)
        })
        .collect();
    files.sort();
    files
}

#[test]
fn a_file_no_target_reaches_is_found() {
    let manifest: toml::Table = "[package]\nautotests = false\n[[test]]\nname = \"integration\"\npath = \"tests/integration.rs\"\n"
        .parse()
        .expect("a manifest");
    let files = vec![
        (
            "integration.rs".to_string(),
            "mod cli;\n  mod hostile;\n".to_string(),
        ),
        ("cli.rs".to_string(), String::new()),
        ("hostile.rs".to_string(), String::new()),
        (
            "forgotten.rs".to_string(),
            "#[test]\nfn t() {}\n".to_string(),
        ),
    ];
    assert_eq!(orphans(&manifest, &files), vec!["forgotten.rs".to_string()]);
}

#[test]
fn every_integration_test_file_is_in_a_test_target() {
    let root = repo_root();
    let workspace: toml::Table = std::fs::read_to_string(root.join("Cargo.toml"))
        .expect("the root Cargo.toml")
        .parse()
        .expect("the root Cargo.toml parses");
    let members = workspace["workspace"]["members"]
        .as_array()
        .expect("[workspace] members");
    let mut checked = 0;
    let mut found = Vec::new();
    for member in members {
        let dir = root.join(member.as_str().expect("a member is a path"));
        let manifest: toml::Table = std::fs::read_to_string(dir.join("Cargo.toml"))
            .expect("a member's Cargo.toml")
            .parse()
            .expect("a member's Cargo.toml parses");
        let autotests = manifest["package"]
            .get("autotests")
            .and_then(toml::Value::as_bool)
            .unwrap_or(true);
        if autotests {
            continue;
        }
        checked += 1;
        for name in orphans(&manifest, &rust_files(&dir.join("tests"))) {
            found.push(format!("  {}/tests/{name}", member.as_str().unwrap_or("?")));
        }
    }
    assert!(
        checked >= 5,
        "only {checked} crates with autotests = false were found"
    );
    assert!(
        found.is_empty(),
        "test files that no test target compiles (add `mod NAME;` to the crate's tests/integration.rs):\n{}",
        found.join("\n")
    );
}
