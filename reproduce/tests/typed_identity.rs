//! Identity is typed in library code: statuses, kinds, methods, families, quantities and
//! verdicts are enums, runs are keyed by ids, and a label (display text) is never compared to
//! decide what something is. This test reads the `src/` of every workspace member (test modules
//! after `#[cfg(test)]` and `//` comments left out) and refuses the spellings of a label or
//! string-status comparison listed in [`FORBIDDEN`].
//!
//! Not refused: comparing an id with an id (`r.solver_id == id`), and the grammars of names
//! that are parsed, not compared as labels, in [`ALLOWED`] with their reasons.

use crate::common;

use common::{library_files, repo_root};

/// (spelling, why it is refused).
const FORBIDDEN: &[(&str, &str)] = &[
    (
        "status == \"",
        "a status is an enum (RunRow, ControlRow, TrendRow, phases)",
    ),
    ("status != \"", "a status is an enum"),
    ("== \"ok\"", "a status is an enum"),
    ("!= \"ok\"", "a status is an enum"),
    (
        "kind == \"",
        "a kind is an enum (SolverKind, NetworkKind, RowKind)",
    ),
    ("kind != \"", "a kind is an enum"),
    (
        "method == \"",
        "a method is an enum (integrator Method, LadderMethod)",
    ),
    ("family == \"", "a controller family is an enum (Family)"),
    ("quantity == \"", "a cost quantity is an enum (Quantity)"),
    ("verdict == \"", "a verdict is an enum (Verdict)"),
    (
        "component == \"",
        "an attribution component is an enum (Component)",
    ),
    ("class == \"", "a trend class is an enum (TrendClass)"),
    ("from_label", "nothing is read back from its label"),
    (
        "split(\"__\")",
        "file names are made from ids, never split back",
    ),
    (
        "split_once(\" / \")",
        "a task's label is never split back into ids",
    ),
    ("_id.starts_with(", "an id prefix is not a kind"),
    ("solver.starts_with(", "a label prefix is not a kind"),
    ("label.starts_with(", "a label prefix is not a kind"),
];

/// Spellings of [`LABEL_CALLS`] beside `==` or `!=` on one line are label comparisons.
const LABEL_CALLS: &[&str] = &["label()", "display_name()"];

/// (file, spelling) pairs that are not label comparisons, each with its reason.
const ALLOWED: &[(&str, &str, &str)] = &[];

/// The library code of `text`: up to its `#[cfg(test)]`, each line without its `//` comment.
fn code_lines(text: &str) -> Vec<(usize, String)> {
    let code = text.split("#[cfg(test)]").next().unwrap_or("");
    code.lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.split("//").next().unwrap_or("").to_string()))
        .collect()
}

/// The (line, spelling) of every refused spelling in `text`.
fn refused(text: &str) -> Vec<(usize, &'static str)> {
    let mut hits = Vec::new();
    for (n, line) in code_lines(text) {
        for (spelling, _) in FORBIDDEN {
            if line.contains(spelling) {
                hits.push((n, *spelling));
            }
        }
        let compares = line.contains("==") || line.contains("!=");
        for call in LABEL_CALLS {
            if compares && line.contains(call) {
                hits.push((n, *call));
            }
        }
    }
    hits
}

#[test]
fn the_finder_sees_label_and_string_status_comparisons() {
    let text = "fn a(r: &R) -> bool { r.status == \"ok\" }\n\
                // r.status == \"ok\" in a comment\n\
                fn b(m: &M, r: &R) -> bool { r.method == m.label() }\n\
                fn c(r: &R) -> bool { r.solver_id == \"exact\" }\n\
                fn d(r: &R) -> bool { r.solver_id.starts_with(\"vp\") }\n\
                #[cfg(test)]\n\
                mod tests { fn e(r: &R) -> bool { r.status == \"ok\" } }\n";
    assert_eq!(
        refused(text),
        [
            (1, "status == \""),
            (1, "== \"ok\""),
            (3, "label()"),
            (5, "_id.starts_with(")
        ]
    );
}

#[test]
fn library_code_compares_no_labels_or_string_statuses() {
    let root = repo_root();
    let files = library_files(&root, "records/src/runs.rs");
    let sites: Vec<String> = files
        .iter()
        .flat_map(|f| {
            let text = std::fs::read_to_string(root.join(f)).expect("a readable source file");
            refused(&text)
                .into_iter()
                .filter(|(_, spelling)| {
                    !ALLOWED
                        .iter()
                        .any(|(file, s, _)| file == f && s == spelling)
                })
                .map(|(line, spelling)| {
                    let why = FORBIDDEN
                        .iter()
                        .find(|(s, _)| *s == spelling)
                        .map_or("a label is display only", |(_, why)| why);
                    format!("  {f}:{line}: `{spelling}`: {why}")
                })
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(
        sites.is_empty(),
        "{} label or string-status comparisons in library code; compare ids or enums:\n{}",
        sites.len(),
        sites.join("\n")
    );
}
