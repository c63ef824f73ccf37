//! The front door is narrow (issue 42, item 4): a module is private unless a sibling crate
//! needs it as a module, and a crate's public surface is the items re-exported at its root
//! plus the few public modules that are a vocabulary of their own (`spec::ids`,
//! `records::table`, `store::shard`, `solvers::neural`, analysis's verdict modules, ...).
//! This test counts the `pub mod` declarations in every member's `src/` and holds each crate
//! to a ceiling, so the count only goes down: a new public module needs its ceiling raised
//! here, in the same change, and a reason to be one.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The most `pub mod` declarations each member's `src/` may hold (`pub(crate) mod` and `mod`
/// are not counted). Counted when the rule was applied; lower a ceiling when a module goes
/// private.
const CEILINGS: [(&str, usize); 23] = [
    ("qp", 0),
    ("decimal", 0),
    ("inputs", 4),
    ("robots", 0),
    ("schemes", 1),
    ("settings", 3),
    ("spec", 1),
    ("catalog", 0),
    ("solvers", 11),
    ("simulation", 0),
    ("control", 0),
    ("records", 5),
    ("store", 9),
    // + report_model::{why, performance}: two sections of the report model, each a vocabulary
    // presentation renders.
    ("analysis", 26),
    ("explain", 3),
    ("presentation", 7),
    // options (what a program builds to call `reproduce::run`), cost (the cost harness the
    // benches time), phases (the phase table's schema the benches read).
    ("reproduce", 3),
    ("benches", 21),
    ("python", 0),
    // The facade's designed front door: a prelude and one module per task (robot, qp, solver,
    // run, results, score).
    ("driftbench", 7),
    ("fixtures", 0),
    ("alloc-count", 0),
    ("examples/outside-solver", 0),
];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The workspace's members, as `Cargo.toml` lists them.
fn members() -> Vec<String> {
    let path = root().join("Cargo.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: cannot read: {e}", path.display()));
    let table: toml::Table = text
        .parse()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    table["workspace"]["members"]
        .as_array()
        .expect("workspace.members is a list")
        .iter()
        .map(|m| m.as_str().expect("a member is a path").to_string())
        .collect()
}

/// The `.rs` files under `dir`, recursively (none if `dir` does not exist).
fn sources(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for entry in entries {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            out.extend(sources(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out
}

/// Whether `line` declares a public module: `pub mod name;` or `pub mod name {`, attributes
/// and indentation aside.
fn declares_pub_mod(line: &str) -> bool {
    let Some(rest) = line.trim_start().strip_prefix("pub mod ") else {
        return false;
    };
    let name: String = rest
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    !name.is_empty()
        && matches!(
            rest[name.len()..].trim_start().chars().next(),
            Some(';' | '{')
        )
}

/// `pub mod` declarations per member, as `file:line` lists.
fn public_modules() -> BTreeMap<String, Vec<String>> {
    let root = root();
    members()
        .into_iter()
        .map(|member| {
            let mut found = Vec::new();
            for file in sources(&root.join(&member).join("src")) {
                let text = std::fs::read_to_string(&file)
                    .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
                for (i, line) in text.lines().enumerate() {
                    if declares_pub_mod(line) {
                        found.push(format!("{}:{}", file.display(), i + 1));
                    }
                }
            }
            (member, found)
        })
        .collect()
}

#[test]
fn the_declaration_reader_tells_public_modules_from_others() {
    assert!(declares_pub_mod("pub mod ids;"));
    assert!(declares_pub_mod("    pub mod tests {"));
    assert!(!declares_pub_mod("pub(crate) mod terms;"));
    assert!(!declares_pub_mod("mod error;"));
    assert!(!declares_pub_mod("//! pub mod in prose"));
    assert!(!declares_pub_mod("pub mod"));
}

#[test]
fn every_member_has_a_ceiling() {
    let ceilings: BTreeMap<&str, usize> = CEILINGS.into_iter().collect();
    for member in members() {
        assert!(
            ceilings.contains_key(member.as_str()),
            "workspace member `{member}` has no ceiling of public modules in \
             reproduce/tests/public_modules.rs: add one"
        );
    }
    assert_eq!(ceilings.len(), members().len(), "a ceiling names no member");
}

#[test]
fn no_crate_has_more_public_modules_than_its_ceiling() {
    let ceilings: BTreeMap<&str, usize> = CEILINGS.into_iter().collect();
    let found = public_modules();
    let mut over = Vec::new();
    for (member, declarations) in &found {
        let ceiling = ceilings.get(member.as_str()).copied().unwrap_or(0);
        if declarations.len() > ceiling {
            over.push(format!(
                "{member}: {} `pub mod` (ceiling {ceiling}): {}",
                declarations.len(),
                declarations.join(", ")
            ));
        }
    }
    assert!(
        over.is_empty(),
        "more public modules than the ceiling (make the module private and re-export what \
         other crates use at the crate root, or raise the ceiling with a reason):\n{}",
        over.join("\n")
    );
    // The engine's bottom crates, the catalog and the control experiments keep every module
    // private.
    for member in ["qp", "robots", "simulation", "catalog", "control"] {
        assert_eq!(found[member].len(), 0, "{member}: {:?}", found[member]);
    }
}

#[test]
fn the_layout_page_states_the_ceilings_total() {
    let total: usize = CEILINGS.iter().map(|(_, n)| n).sum();
    let path = root().join("docs/reference/layout.md");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: cannot read: {e}", path.display()));
    let flat = text.split_whitespace().collect::<Vec<_>>().join(" ");
    let said = format!("a ceiling of `pub mod`s ({total} in all");
    assert!(
        flat.contains(&said),
        "{}: does not say \"{said}\"",
        path.display()
    );
}
