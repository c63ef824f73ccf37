//! A published table (one `(paper, table)` of `papers/<paper>/values.csv`) set beside ours: its
//! mapped columns, the quantities compared, and the ratio of ours to the paper's, laid out as
//! rows ([`side_by_side`]). The report renders it (`presentation::report::tables`).

use crate::misprints::{is_contradicted, Contradiction};
use crate::papers::{Mapping, Papers};
use crate::published_metrics::our_metric;
use records::index::{metric, Runs, EXACT};
use records::RunRow;

/// The published tables of `paper`, in the order the CSV lists them (`text` last).
pub fn published_tables(paper: &str, papers: &Papers) -> Vec<String> {
    let mut tables: Vec<String> = Vec::new();
    for v in papers.values.iter().filter(|v| v.paper == paper) {
        if !tables.contains(&v.table) {
            tables.push(v.table.clone());
        }
    }
    tables.sort_by_key(|t| t == "text");
    tables
}

/// The mapped columns of one published table, in the CSV's order.
fn columns_of<'a>(paper: &str, table: &str, papers: &'a Papers) -> Vec<&'a Mapping> {
    let mut cols: Vec<&Mapping> = Vec::new();
    let measured = papers
        .values
        .iter()
        .filter(|v| v.paper == paper && v.table == table && our_metric(&v.metric).is_some());
    for m in measured.filter_map(|v| papers.mapping_of(v)) {
        if !cols.contains(&m) {
            cols.push(m);
        }
    }
    cols
}

/// Whether run `r` starts off theta*0: its drift against theta*0 differs from its drift
/// (beyond rounding, 1e-12 relative).
fn starts_off_reference(r: &RunRow) -> bool {
    match (r.drift_norm, r.drift_ref_norm) {
        (Some(a), Some(b)) => (a - b).abs() > 1e-12 * a.abs().max(1.0),
        _ => false,
    }
}

/// The quantities (our column names) of one published table: what the paper prints and we
/// measure, plus the drift norm (derived when the paper prints only joints) and the drift
/// against theta*0 when some `shown` run starts off it.
fn quantities_of(
    paper: &str,
    table: &str,
    papers: &Papers,
    shown: &[&RunRow],
) -> Vec<&'static str> {
    let mut q: Vec<&'static str> = Vec::new();
    for m in papers
        .values
        .iter()
        .filter(|v| v.paper == paper && v.table == table && papers.mapping_of(v).is_some())
        .filter_map(|v| our_metric(&v.metric))
    {
        if !q.contains(&m) {
            q.push(m);
        }
    }
    if q.iter().any(|m| m.starts_with("drift_")) && !q.contains(&"drift_norm") {
        let at = q
            .iter()
            .rposition(|m| m.starts_with("drift_"))
            .map_or(q.len(), |i| i + 1);
        q.insert(at, "drift_norm");
    }
    if shown.iter().any(|r| starts_off_reference(r)) {
        let at = q
            .iter()
            .position(|m| *m == "drift_norm")
            .map_or(q.len(), |i| i + 1);
        q.insert(at, "drift_ref_norm");
    }
    q
}

/// One published table set beside ours ([`side_by_side`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SideBySide<'a> {
    /// The table (`T2`, or `text`).
    pub table: String,
    /// Its mapped columns, in the CSV's order.
    pub columns: Vec<&'a Mapping>,
    /// Whether every column maps onto one variant without companions (headers then name the
    /// solver alone).
    pub one_variant: bool,
    /// The quantities (our column names), in the table's column order (what the paper prints and we measure, plus the derived norms).
    pub quantities: Vec<&'static str>,
    /// The rows, top to bottom.
    pub rows: Vec<Row<'a>>,
}

/// A row of a side-by-side table: the paper's numbers of one column, or one of ours.
#[derive(Clone, Debug, PartialEq)]
pub enum Row<'a> {
    /// The paper's numbers of a published column.
    Paper(&'a Mapping),
    /// A run of ours (none: not run), headed `header`.
    Run {
        header: String,
        run: Option<&'a RunRow>,
    },
    /// Ours over the paper's, per quantity (none where the paper prints 0 or nothing; none without a run), of the run
    /// of the paper's solver; `contradicted`: the published column contradicts itself in this
    /// table ([`crate::misprints`]), so the ratios rest on a contradicted number.
    Ratio {
        ratios: Option<Vec<Option<f64>>>,
        contradicted: bool,
    },
}

/// A run's label in a header: the run's own when it exists, the id otherwise (`solver`: its
/// solver's label, else its variant's).
fn run_label(r: Option<&RunRow>, id: &str, solver: bool) -> String {
    r.map_or(id.to_string(), |r| {
        if solver {
            r.solver.clone()
        } else {
            r.variant.clone()
        }
    })
}

/// The published `table` of `paper` beside our `runs` (none when nothing maps): per published
/// column, the paper's row then, per variant (the mapped one and its companions, each run
/// once), the exact run (once per variant; a companion without an exact run shows none), the
/// run of the paper's solver and the ratio. `contradicted`: the paper's contradicted columns
/// ([`crate::misprints::contradictions`]).
pub fn side_by_side<'a>(
    paper: &str,
    table: &str,
    papers: &'a Papers,
    runs: &'a Runs,
    contradicted: &[Contradiction],
) -> Option<SideBySide<'a>> {
    let columns = columns_of(paper, table, papers);
    let first = columns.first()?;
    let one_variant = columns
        .iter()
        .all(|c| c.run.variant == first.run.variant && c.companions.is_empty());
    let name = |solver: &str, variant: &str| {
        if one_variant {
            solver.to_string()
        } else {
            format!("{solver}, {variant}")
        }
    };
    // The layout first: the ratio rows keep their run and mapping until the quantities are
    // known.
    let mut layout: Vec<Row> = Vec::new();
    let mut pending: Vec<Option<(&RunRow, &Mapping)>> = Vec::new();
    let mut exact_shown: Vec<(&str, &str)> = Vec::new();
    for &m in &columns {
        layout.push(Row::Paper(m));
        pending.push(None);
        let e = m.run.experiment.as_str();
        let mut shown_runs: Vec<&spec::RunKey> = Vec::new();
        for shown_run in std::iter::once(&m.run).chain(m.companions.iter()) {
            if shown_runs.contains(&shown_run) {
                continue;
            }
            shown_runs.push(shown_run);
            let variant = &shown_run.variant;
            let exact = runs.find(e, variant, EXACT);
            let without_exact = shown_run != &m.run && exact.is_none();
            if !without_exact && !exact_shown.contains(&(e, variant)) {
                exact_shown.push((e, variant));
                let header = name("exact", &run_label(exact, variant, false));
                layout.push(Row::Run { header, run: exact });
                pending.push(None);
            }
            let run = runs.find(e, variant, &shown_run.solver);
            let header = name(
                &run_label(run, &shown_run.solver, true),
                &run_label(run.or(exact), variant, false),
            );
            layout.push(Row::Run { header, run });
            pending.push(None);
            layout.push(Row::Ratio {
                ratios: None,
                contradicted: is_contradicted(
                    contradicted,
                    Some(table),
                    &m.published_experiment,
                    &m.published_column,
                ),
            });
            pending.push(run.map(|r| (r, m)));
        }
    }
    let shown: Vec<&RunRow> = layout
        .iter()
        .filter_map(|row| match row {
            Row::Run { run, .. } => *run,
            _ => None,
        })
        .collect();
    let quantities = quantities_of(paper, table, papers, &shown);
    let rows = layout
        .into_iter()
        .zip(pending)
        .map(|(row, of)| match (row, of) {
            (Row::Ratio { contradicted, .. }, Some((r, m))) => Row::Ratio {
                ratios: Some(
                    quantities
                        .iter()
                        .map(|q| ratio_to_paper(r, m, q, papers))
                        .collect(),
                ),
                contradicted,
            },
            (row, _) => row,
        })
        .collect();
    Some(SideBySide {
        table: table.to_string(),
        columns,
        one_variant,
        quantities,
        rows,
    })
}

/// Our run `r`'s `metric` over the paper's in `mapping`'s column; none where either is missing
/// or the paper prints 0 (robio2018's theta_6), which has no ratio.
fn ratio_to_paper(
    r: &RunRow,
    mapping: &Mapping,
    metric_name: &str,
    papers: &Papers,
) -> Option<f64> {
    metric(r, metric_name)
        .zip(papers.published(mapping, metric_name))
        .filter(|(_, (p, _))| *p != 0.0)
        .map(|(o, (p, _))| o / p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use spec::SolverKind;

    #[test]
    fn a_run_off_theta_star_adds_the_reference_drift() {
        let mut r = RunRow::blank(
            &spec::RunKey::from_ids("e", "v", "s").unwrap(),
            SolverKind::Exact,
        );
        r.drift_norm = Some(0.5);
        r.drift_ref_norm = Some(0.5 + 1e-13);
        assert!(!starts_off_reference(&r));
        r.drift_ref_norm = Some(0.25);
        assert!(starts_off_reference(&r));
        let papers = Papers::default();
        assert_eq!(quantities_of("p", "T1", &papers, &[&r]), ["drift_ref_norm"]);
        assert!(published_tables("p", &papers).is_empty());
    }

    /// A paper whose table T1 prints `drift_norm` = 0.5 and `drift_6` = 0 for column `c`,
    /// mapped onto run e / v / s.
    fn printed() -> (Papers, Mapping) {
        let mapping = Mapping {
            paper: "p".into(),
            published_experiment: "E".into(),
            published_column: "c".into(),
            run: spec::RunKey::parse("e / v / s").unwrap(),
            companions: Vec::new(),
        };
        let value = |metric: &str, value: f64| crate::papers::PaperValue {
            paper: "p".into(),
            table: "T1".into(),
            experiment: "E".into(),
            column: "c".into(),
            metric: metric.into(),
            value,
            note: String::new(),
            inconsistent: None,
        };
        let papers = Papers {
            values: vec![value("drift_norm", 0.5), value("drift_6", 0.0)],
            mappings: vec![mapping.clone()],
            ..Papers::default()
        };
        (papers, mapping)
    }

    #[test]
    fn ours_is_set_over_the_papers_number_unless_it_prints_zero() {
        let (papers, mapping) = printed();
        let mut r = RunRow::blank(
            &spec::RunKey::from_ids("e", "v", "s").unwrap(),
            SolverKind::Exact,
        );
        r.drift_norm = Some(0.25);
        r.drift = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.1];
        assert_eq!(
            ratio_to_paper(&r, &mapping, "drift_norm", &papers),
            Some(0.5)
        );
        assert_eq!(ratio_to_paper(&r, &mapping, "drift_6", &papers), None);
        assert_eq!(ratio_to_paper(&r, &mapping, "max_pos_err", &papers), None);
        assert_eq!(columns_of("p", "T1", &papers), [&mapping]);
        assert_eq!(published_tables("p", &papers), ["T1"]);
        assert_eq!(
            quantities_of("p", "T1", &papers, &[&r]),
            ["drift_norm", "drift_6"]
        );
    }
}
