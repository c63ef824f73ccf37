//! The report formats the report model and decides nothing while it writes a page: no module
//! of `presentation/src/report/` calls or imports a function of analysis's verdict modules
//! (the `pub fn`s of those modules' sources, read here); it takes their types and constants
//! and the model (`analysis::report_model`), built once per render. A module's tests (from
//! `#[cfg(test)]` on, the end of a file by this crate's convention) render nothing of the
//! report: they may prepare a page's inputs as the results' writers do (the fits of
//! `results/dof-cost.csv`, `analysis::fits::fit_rows`).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The analysis modules that decide or compute what a page shows (their `pub fn`s are the
/// verdict functions).
const VERDICT_MODULES: [&str; 16] = [
    "claim_verdict",
    "control_claim",
    "control_track",
    "cost_ratio",
    "cross_best",
    "drift_attribution",
    "fits",
    "inference_verdict",
    "leaderboard",
    "leaderboard_reading",
    "misprints",
    "paper_verdict",
    "performance",
    "published_table",
    "sweep_comparison",
    "sweep_summary",
];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The `.rs` files under `dir`, recursively.
fn sources(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            out.extend(sources(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out.sort();
    out
}

/// `text` without its comments (lines from `//` on) and without its tests (from the line
/// `#[cfg(test)]` on).
fn code(text: &str) -> String {
    text.lines()
        .take_while(|l| l.trim() != "#[cfg(test)]")
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The names of the `pub fn`s of analysis module `module` (a file or a directory).
fn verdict_functions(module: &str) -> BTreeSet<String> {
    let src = root().join("analysis/src");
    let files = if src.join(module).is_dir() {
        sources(&src.join(module))
    } else {
        vec![src.join(format!("{module}.rs"))]
    };
    let mut names = BTreeSet::new();
    for file in files {
        for rest in code(&read(&file)).split("pub fn ").skip(1) {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            names.insert(name);
        }
    }
    names
}

/// The identifiers of `span`.
fn identifiers(span: &str) -> Vec<&str> {
    span.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|s| !s.is_empty())
        .collect()
}

/// What `code` takes from analysis module `module` that is a function of `functions` (or the
/// module itself, imported whole or under another name): one line per finding.
fn uses(code: &str, module: &str, functions: &BTreeSet<String>) -> Vec<String> {
    let path = format!("analysis::{module}");
    let mut found = Vec::new();
    for (at, _) in code.match_indices(&path) {
        let after = &code[at + path.len()..];
        // A longer module name (`leaderboard_reading` after `leaderboard`) is another module.
        if after.starts_with(|c: char| c.is_alphanumeric() || c == '_') {
            continue;
        }
        // The path up to the end of its statement or call.
        let end = after.find([';', '(']).unwrap_or(after.len());
        let span = &after[..end];
        if span.trim_start().starts_with("as ") || span.contains("self") {
            found.push(format!("imports `{path}` whole: {}", span.trim()));
            continue;
        }
        for name in identifiers(span) {
            if functions.contains(name) {
                found.push(format!("takes `{path}::{name}`"));
            }
        }
    }
    found
}

#[test]
fn the_report_calls_no_verdict_function() {
    let report = root().join("presentation/src/report");
    let files = sources(&report);
    assert!(files.len() > 10, "presentation/src/report: too few modules");
    let mut offences = Vec::new();
    for module in VERDICT_MODULES {
        let functions = verdict_functions(module);
        assert!(!functions.is_empty(), "analysis::{module}: no pub fn found");
        for file in &files {
            let name = file.file_name().and_then(|n| n.to_str()).unwrap_or("");
            let found = uses(&code(&read(file)), module, &functions);
            offences.extend(found.into_iter().map(|f| format!("{name}: {f}")));
        }
    }
    assert!(
        offences.is_empty(),
        "report modules decide while they format (move it into analysis::report_model):\n{}",
        offences.join("\n")
    );
}

#[test]
fn the_detector_finds_a_call_an_import_and_an_alias() {
    let functions: BTreeSet<String> = ["decide".to_string()].into();
    let m = "paper_verdict";
    assert_eq!(
        uses(
            "let d = analysis::paper_verdict::decide(p, c, r, q);",
            m,
            &functions
        )
        .len(),
        1
    );
    assert_eq!(
        uses(
            "use analysis::paper_verdict::{decide, Level};",
            m,
            &functions
        )
        .len(),
        1
    );
    assert_eq!(
        uses("use analysis::paper_verdict as v;", m, &functions).len(),
        1
    );
    assert!(uses(
        "use analysis::paper_verdict::{Level, SOLVER_MATTERS};",
        m,
        &functions
    )
    .is_empty());
    assert!(uses("use analysis::paper_verdict_x::decide;", m, &functions).is_empty());
    // A call in a module's tests is not the page's; one before them is.
    let with_tests =
        "fn page() {}\n#[cfg(test)]\nmod tests {\n    analysis::paper_verdict::decide(p);\n}";
    assert!(uses(&code(with_tests), m, &functions).is_empty());
    let before = "fn page() { analysis::paper_verdict::decide(p); }\n#[cfg(test)]\nmod tests {}";
    assert_eq!(uses(&code(before), m, &functions).len(), 1);
    assert!(verdict_functions("paper_verdict").contains("decide"));
}
