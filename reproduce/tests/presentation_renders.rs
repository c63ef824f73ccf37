//! The report's pages only render (issue #28, "presentation computes nothing"): what they show
//! is computed in crate `analysis` (ratios of medians, sums of times, per-step quotients, fits,
//! verdicts against targets) as typed summaries, which `presentation::report` formats.
//!
//! Searched: the library part of every file of `presentation/src/report/` but `markdown.rs`
//! (the number formats: a fraction as a percentage, seconds as minutes, a ratio to the best),
//! as code without comments and literals ([`common::lex`]), for arithmetic on numbers: a
//! division, a float literal (a factor, a unit or a threshold), and the calls that aggregate or
//! transform numbers ([`FORBIDDEN`]). The figures (`presentation/src/figures/`) are not
//! searched: placing a drawing on its canvas is their rendering.

use crate::common::{lex, library_part, repo_root};

/// Calls that aggregate or transform numbers.
const FORBIDDEN: [&str; 15] = [
    ".sum",
    ".product(",
    "f64::min",
    "f64::max",
    ".abs(",
    ".sqrt(",
    ".ln(",
    ".log10(",
    ".log2(",
    ".exp(",
    ".powi(",
    ".powf(",
    "percentile",
    "Summary::of",
    "fit_power_law",
];

/// The float literals of one line of code (`2.0`, `1e-3`, `5f64`; not a tuple index `x.0`,
/// a range `1..n` or a digit inside a name).
fn float_literals(line: &str) -> Vec<String> {
    let c: Vec<char> = line.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let starts = c[i].is_ascii_digit()
            && (i == 0 || !(c[i - 1].is_alphanumeric() || c[i - 1] == '_' || c[i - 1] == '.'));
        if !starts {
            i += 1;
            continue;
        }
        let start = i;
        while i < c.len() && (c[i].is_ascii_digit() || c[i] == '_') {
            i += 1;
        }
        let mut float = false;
        if c.get(i) == Some(&'.') && c.get(i + 1).is_some_and(|d| d.is_ascii_digit()) {
            float = true;
            i += 1;
            while i < c.len() && c[i].is_ascii_digit() {
                i += 1;
            }
        }
        if matches!(c.get(i), Some('e' | 'E')) {
            let digits = if matches!(c.get(i + 1), Some('+' | '-')) {
                i + 2
            } else {
                i + 1
            };
            if c.get(digits).is_some_and(|d| d.is_ascii_digit()) {
                float = true;
                i = digits;
                while i < c.len() && c[i].is_ascii_digit() {
                    i += 1;
                }
            }
        }
        let rest: String = c[i..].iter().take(3).collect();
        if rest == "f64" || rest == "f32" {
            float = true;
            i += 3;
        }
        if float {
            out.push(c[start..i].iter().collect());
        }
    }
    out
}

/// The arithmetic of `code` (lexed library code), as `line: what`.
fn arithmetic(code: &str) -> Vec<String> {
    let mut found = Vec::new();
    for (n, line) in code.lines().enumerate() {
        let mut what: Vec<String> = FORBIDDEN
            .iter()
            .filter(|p| line.contains(*p))
            .map(|p| p.to_string())
            .collect();
        if line.contains('/') {
            what.push("a division".to_string());
        }
        what.extend(float_literals(line));
        if !what.is_empty() {
            found.push(format!(
                "{}: {} in `{}`",
                n + 1,
                what.join(", "),
                line.trim()
            ));
        }
    }
    found
}

#[test]
fn the_scanner_finds_arithmetic_outside_comments_and_literals() {
    let code = lex("let r = a / b; // x / y\nlet s = format!(\"{:.1} %\", v);\nlet t = (1..n, x.0, u64::MAX);\nlet k = 100.0 * f;\nlet m = v.iter().sum::<f64>() + 1e-3 + 2f64;\n").code;
    let found = arithmetic(&code);
    assert_eq!(found.len(), 3, "{found:?}");
    assert!(found[0].starts_with("1: a division"), "{found:?}");
    assert!(found[1].starts_with("4: 100.0"), "{found:?}");
    assert!(found[2].starts_with("5: .sum, 1e-3, 2f64"), "{found:?}");
}

#[test]
fn the_report_pages_compute_nothing() {
    let root = repo_root();
    let dir = root.join("presentation/src/report");
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .expect("presentation/src/report/")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|f| f.ends_with(".rs") && f != "markdown.rs")
        .collect();
    files.sort();
    assert!(
        files.iter().any(|f| f == "performance.rs"),
        "the report's sources were not found under {}",
        dir.display()
    );
    let mut sites = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(dir.join(f)).expect("a readable source file");
        for site in arithmetic(&lex(library_part(&text)).code) {
            sites.push(format!("  presentation/src/report/{f}:{site}"));
        }
    }
    assert!(
        sites.is_empty(),
        "arithmetic in the report's pages (compute it in crate analysis, as a typed summary the \
         page formats; a unit of display belongs in markdown.rs):\n{}",
        sites.join("\n")
    );
}
