//! The report given hostile texts in `papers/` (which come from other people): a title with
//! line breaks, a heading and a table row in it, a `javascript:` link and raw HTML in the
//! citation, claims and published values, a paper id that would be a link. The committed
//! inputs are loaded, their texts replaced in memory (past the load-time checks that refuse
//! most of them), and the rendered Markdown is checked for its structure: the report's own
//! headings only, every table row as wide as its header, no link to `javascript:`, no raw tag.

use analysis::sweep_summary::Held;
use presentation::report::{pages, Inputs};

/// Every page of the report, one after the other.
fn whole(inputs: &Inputs) -> String {
    pages(inputs).iter().map(|p| p.markdown.as_str()).collect()
}

const SCRIPT: &str = "<script>alert(1)</script>";

fn hostile() -> (Inputs, String) {
    let root = catalog::root_from_current_dir().unwrap();
    let held = Held::read(&root.join("results/runs.csv"), &|_| true).unwrap();
    let clean = Inputs::load(&root, &root.join("papers"), held).expect("committed inputs load");
    let before = whole(&clean);
    let mut inputs = clean;
    let papers = &mut inputs.papers;
    let p = &mut papers.papers[0];
    p.title = format!("T\n## Summary\n| a | b |\n|---|---|\n{SCRIPT}");
    p.citation = Some("[click](javascript:alert(1)) <a href=\"javascript:x\">x</a>".into());
    let c = &mut p.claims[0];
    c.short = "<img src=x onerror=alert(1)>".into();
    c.text = "x | y\n### Injected".into();
    for v in papers.values.iter_mut().take(3) {
        v.note = format!("{SCRIPT} | ![i](javascript:1) `code`");
        v.column = format!("{} | </td>", v.column);
    }
    let last = papers.papers.len() - 1;
    papers.papers[last].id = "a](javascript:alert(1))".into();
    (inputs, before)
}

/// The `|` of a table line that separate cells (not escaped ones).
fn cell_separators(line: &str) -> usize {
    let mut n = 0;
    let mut chars = line.chars();
    while let Some(c) = chars.next() {
        match c {
            '\\' => {
                chars.next();
            }
            '|' => n += 1,
            _ => {}
        }
    }
    n
}

/// The lines that start a Markdown heading.
fn headings(md: &str) -> Vec<&str> {
    md.lines().filter(|l| l.starts_with('#')).collect()
}

#[test]
fn hostile_paper_texts_show_as_text_and_keep_the_structure() {
    let (inputs, before) = hostile();
    let md = whole(&inputs);
    // The clean report's headings, and the renamed paper's section (its id escaped).
    let clean = headings(&before);
    let hostile = headings(&md);
    assert_eq!(
        hostile.iter().filter(|l| **l == "## Summary").count(),
        1,
        "one Summary"
    );
    for h in &hostile {
        assert!(
            clean.contains(h) || h.contains("a\\](javascript:alert(1))"),
            "an injected heading: {h}"
        );
    }
    assert!(hostile.contains(&"# a\\](javascript:alert(1))"));
    for raw in ["<script", "</script", "<img", "<a href", "</td"] {
        assert!(!md.contains(raw), "raw {raw:?} in the report");
    }
    assert_eq!(
        md.match_indices("](javascript:")
            .filter(|(i, _)| !md[..*i].ends_with('\\'))
            .count(),
        0,
        "a javascript: link"
    );
    // Every table row is as wide as its header.
    let mut header: Option<usize> = None;
    for line in md.lines() {
        if !line.starts_with('|') {
            header = None;
            continue;
        }
        let n = cell_separators(line);
        match header {
            None => header = Some(n),
            Some(h) => assert_eq!(n, h, "a table row of another width: {line}"),
        }
    }
    // The texts are there, escaped.
    assert!(
        md.contains("*T \\#\\# Summary | a | b | |---|---| &lt;script&gt;"),
        "the title"
    );
    assert!(md.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
    assert!(md.contains("\\[click\\](javascript:alert(1)) &lt;a href="));
    assert!(md.contains("&lt;img src=x onerror=alert(1)&gt;"));
}
