//! The papers as the report shows them: every text that `papers/` gives (titles, citations, assumed setups,
//! claims, a published table's name, experiments, columns and notes, the sweep checks'
//! headings and paragraphs) put through [`super::markdown::text`], once, before any section is
//! rendered, so that no section can show an input's Markdown or HTML. The paper id is escaped
//! too (the folder's name; load refuses any that is not a slug, which escaping leaves as it
//! is). Texts that are matched with each other (a paper id everywhere it is given, a value's
//! experiment and column with a mapping's and a sweep column's, a value's table with a sweep
//! check's) are escaped alike and still match; run keys, selections and metric names are not
//! shown as written text and stay as they are.

use super::markdown::text;
use analysis::papers::Papers;

/// `papers` with every text escaped (module docs).
pub fn papers(papers: &Papers) -> Papers {
    let mut p = papers.clone();
    for paper in &mut p.papers {
        paper.id = text(&paper.id);
        paper.title = text(&paper.title);
        paper.citation = paper.citation.as_deref().map(text);
        paper.assumed_setup = paper.assumed_setup.as_deref().map(text);
        for claim in &mut paper.claims {
            claim.short = text(&claim.short);
            claim.text = text(&claim.text);
        }
    }
    for v in &mut p.values {
        for field in [
            &mut v.paper,
            &mut v.table,
            &mut v.experiment,
            &mut v.column,
            &mut v.note,
        ] {
            *field = text(field);
        }
        v.inconsistent = v.inconsistent.as_deref().map(text);
    }
    for m in &mut p.mappings {
        m.paper = text(&m.paper);
        m.published_experiment = text(&m.published_experiment);
        m.published_column = text(&m.published_column);
    }
    for check in &mut p.sweep_checks {
        check.paper = text(&check.paper);
        check.heading = text(&check.heading);
        check.text = text(&check.text);
        check.table = text(&check.table);
        for c in &mut check.columns {
            c.published_experiment = text(&c.published_experiment);
        }
    }
    p
}
