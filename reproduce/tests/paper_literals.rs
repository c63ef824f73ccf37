//! A paper is data: no paper id, experiment id, variant id or variant label appears as a string
//! literal in library code. What the suite knows of a paper lives in `experiments/*.toml`,
//! `papers/<paper>/` and `experiments/control/tasks.toml`; code reads it from there, so
//! renaming a paper's variant or adding a fifth paper never needs a code change.
//!
//! Searched: every string literal (plain, escaped and raw) in the `src/` of every workspace
//! member (read from the root `Cargo.toml`), outside comments and outside the trailing
//! `#[cfg(test)] mod tests` (tests may name the data they test). The names come from the data
//! itself: the paper ids of `experiments/*.toml` and `papers/`, and the experiment, variant
//! (id and label) of every run the experiment files describe.
//!
//! - A paper id or an experiment id must not occur inside any literal (they contain a year or a
//!   dash, so a match is never an accident of English), except as a citation in the canonical
//!   form `jia2019 (2.17)` or `zhong2021 §1` / `zhong2021 refs. [26]`: where code cites the
//!   equation it implements, the citation is the provenance the standards ask for;
//! - a variant id or label must not *be* a literal. A label that is also the name of a scheme or
//!   solver ("VLTCO", "ZNN") is exempt: those name code (the schemes' and networks'
//!   implementations print their own names), not a paper's data.
//!
//! Exempt files ([`EXEMPT`]), each with its reason.

use crate::common;

use common::{lex, library_files, library_part, repo_root};
use std::collections::BTreeSet;
use std::path::Path;

/// Files whose literals are not searched, with the reason.
const EXEMPT: &[(&str, &str)] = &[
    (
        "spec/src/scheme.rs",
        "the paper-named kind tags (`kind = \"jia2019\"`) are serde aliases of the canonical \
         kinds, kept so that older experiment files still read: code, not data about the paper",
    ),
    (
        "records/src/dof_cost.rs",
        "the paper-named scheme ids of dof-cost.csv files written before the kinds were renamed, \
         read as the canonical kinds: code, not data about the paper",
    ),
    (
        "benches/src/telemetry/page/throughput.rs",
        "the throughput benchmark measures one named sweep (benches/throughput/kong2019_sweep.sh, \
         issue 43's kong2019 ZNN sweep), and its page says which: a measurement of the suite's \
         speed, not data about the paper",
    ),
    (
        "fixtures/src/lib.rs",
        "test fixtures shared by several crates' tests (a dev-dependency only, never linked into \
         a program): its experiment-file template is a test's file, and tests may name the data \
         they test",
    ),
    (
        "solvers/src/random_qp.rs",
        "the random QP shapes are the papers' schemes' QP forms, named after them (the benches \
         group by that name)",
    ),
];

/// The names the data declares.
struct Names {
    /// Paper and experiment ids: forbidden inside any literal.
    inside: BTreeSet<String>,
    /// Variant ids and labels: forbidden as a whole literal.
    whole: BTreeSet<String>,
}

fn names(root: &Path) -> Names {
    let files =
        reproduce::load_experiments(&root.join("experiments")).expect("the experiment files load");
    let mut inside = BTreeSet::new();
    let mut whole = BTreeSet::new();
    let mut code_names = BTreeSet::new();
    for f in &files {
        for job in f.jobs().unwrap() {
            inside.insert(job.paper.clone());
            inside.insert(job.experiment.to_string());
            whole.insert(job.variant_id.to_string());
            whole.insert(job.variant.clone());
            code_names.insert(job.scheme.display_name());
            if let Some(head) = job.scheme.display_name().split(" (").next() {
                code_names.insert(head.to_string());
            }
            code_names.insert(job.solver.label());
        }
    }
    for entry in std::fs::read_dir(root.join("papers"))
        .expect("papers/")
        .flatten()
    {
        inside.insert(entry.file_name().to_string_lossy().into_owned());
    }
    // Experiment files that are not a paper's (the cross-paper and the group's code) carry a
    // plain word as their `paper`: such a word is a role in the code, only a dashed or dated id
    // is searched inside literals.
    inside.retain(|n| n.contains('-') || n.chars().any(|c| c.is_ascii_digit()));
    whole.retain(|n| !code_names.contains(n) && n.len() > 2);
    Names { inside, whole }
}

/// Whether `name` occurs in `lit` other than as a citation (`name (2.17)`, `name §1`,
/// `name refs. [26]`).
fn names_outside_citations(lit: &str, name: &str) -> bool {
    lit.match_indices(name).any(|(i, _)| {
        let after = &lit[i + name.len()..];
        let cited = after
            .strip_prefix(" (")
            .is_some_and(|r| r.starts_with(|c: char| c.is_ascii_digit()))
            || after.starts_with(" §")
            || after.starts_with(" refs. [")
            || after.starts_with(" ref. [");
        !cited
    })
}

#[test]
fn a_citation_is_not_a_use() {
    assert!(!names_outside_citations(
        "see jia2019 (2.17)-(2.20), kong2019 (22)",
        "jia2019"
    ));
    assert!(!names_outside_citations(
        "zhong2021 §1: \"...\"",
        "zhong2021"
    ));
    assert!(names_outside_citations("if paper == jia2019", "jia2019"));
    assert!(names_outside_citations("jia2019 (VLTCO)", "jia2019"));
    assert!(names_outside_citations("jia2019-clover", "jia2019"));
}

#[test]
fn the_scanner_finds_literals_and_skips_comments() {
    let code = "let a = \"x\"; // \"y\"\n/* \"z\" */ let b = r#\"w\"#; let c = '\"'; fn f<'a>() {}\nlet d = \"e\\\"f\";\n";
    let found: Vec<(usize, String)> = lex(code).literals;
    assert_eq!(
        found,
        [
            (1, "x".to_string()),
            (2, "w".to_string()),
            (3, "e\\\"f".to_string())
        ]
    );
    let text = "fn a() { \"lib\" }\n#[cfg(test)]\nmod tests { \"test\" }\n";
    assert_eq!(lex(library_part(text)).literals, [(1, "lib".to_string())]);
}

#[test]
fn the_names_come_from_the_data() {
    let names = names(&repo_root());
    for id in ["jia2019", "kong2019-circle", "zhong2021-clover-a"] {
        assert!(
            names.inside.contains(id),
            "{id} not among {:?}",
            names.inside
        );
    }
    assert!(names.whole.contains("cmco-eta-0.2-delta-0.4"));
    assert!(
        !names.whole.contains("VLTCO"),
        "a scheme's own name is code"
    );
}

#[test]
fn library_code_names_no_paper_experiment_or_variant() {
    let root = repo_root();
    let names = names(&root);
    let files = library_files(&root, "reproduce/src/main.rs");
    let mut sites = Vec::new();
    for f in files.iter().filter(|f| !EXEMPT.iter().any(|(e, _)| e == f)) {
        let text = std::fs::read_to_string(root.join(f)).expect("a readable source file");
        for (line, lit) in lex(library_part(&text)).literals {
            let hit = names
                .inside
                .iter()
                .find(|n| names_outside_citations(&lit, n))
                .or_else(|| names.whole.iter().find(|n| **n == lit));
            if let Some(n) = hit {
                sites.push(format!("  {f}:{line}: {n:?} in {lit:?}"));
            }
        }
    }
    assert!(
        sites.is_empty(),
        "paper data written into library code (move it into experiments/ or papers/):\n{}",
        sites.join("\n")
    );
}
