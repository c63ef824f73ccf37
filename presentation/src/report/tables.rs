//! The papers' tables side by side with ours, and the suite's own table of every run.
//!
//! A published table (one `(paper, table)` of `papers/<paper>/values.csv`) becomes one Markdown table:
//! columns are the quantities (joint drifts, drift norm, and whatever else the paper prints),
//! and for each published column there are rows for the paper's number, our exact run, our
//! run of the paper's solver, and the ratio ours/paper — then the same for each companion
//! variant (each run once). The exact column separates what the scheme does from what the solver adds. Which
//! columns and quantities a table has, and the ratios, are [`analysis::published_table`]'s.

use super::markdown::metric_cell;
use super::markdown::{sci, sci_opt, Table, MISSING};
use analysis::misprints::{contradictions, is_contradicted, Contradiction};
use analysis::papers::{Mapping, Papers};
use analysis::published_table::{columns_of, quantities_of, ratio_to_paper};
use records::index::{metric, status_text, Runs, EXACT};
use records::runs::RunRow;

/// A quantity's row label.
pub fn quantity_label(metric: &str) -> String {
    match metric {
        "drift_norm" => "‖θ(T) − θ(0)‖".to_string(),
        "drift_ref_norm" => "‖θ(T) − θ*0‖".to_string(),
        "wall_s" | "sim_s" => "compute time (s)".to_string(),
        "max_pos_err" => "max position error (m)".to_string(),
        "final_pos_err" => "final position error (m)".to_string(),
        m => match m.strip_prefix("drift_") {
            Some(i) => format!("θ{i}(T) − θ{i}(0)"),
            None => m.to_string(),
        },
    }
}

/// One column of ours: a run, and the published column its ratio is taken against.
struct OursColumn<'a> {
    header: String,
    run: Option<&'a RunRow>,
    ratio_of: Option<&'a Mapping>,
}

/// A column of the side-by-side table: the paper's number, or one of ours.
enum Col<'a> {
    Paper(&'a Mapping),
    Ours(OursColumn<'a>),
}

/// A run's label in a header: the run's own when it exists, the id otherwise (`solver`: its
/// solver's label, else its variant's).
fn label(r: Option<&RunRow>, id: &str, solver: bool) -> String {
    r.map_or(id.to_string(), |r| {
        if solver {
            r.solver.clone()
        } else {
            r.variant.clone()
        }
    })
}

/// The column layout of a published table's `columns` side by side with ours: per published
/// column, the paper's number then, per variant (the mapped one and its companions), the exact
/// run (once per variant), the paper's solver and the ratio. `one_variant`: headers name the
/// solver alone.
fn layout<'a>(columns: &[&'a Mapping], runs: &'a Runs, one_variant: bool) -> Vec<Col<'a>> {
    let name = |solver: &str, variant: &str| {
        if one_variant {
            solver.to_string()
        } else {
            format!("{solver}, {variant}")
        }
    };
    let mut cols: Vec<Col> = Vec::new();
    let mut exact_shown: Vec<(&str, &str)> = Vec::new();
    for &m in columns {
        cols.push(Col::Paper(m));
        let e = m.run.experiment.as_str();
        let mut shown_runs: Vec<&catalog::run_key::RunKey> = Vec::new();
        for shown_run in std::iter::once(&m.run).chain(m.companions.iter()) {
            if shown_runs.contains(&shown_run) {
                continue;
            }
            shown_runs.push(shown_run);
            let variant = &shown_run.variant;
            let exact = runs.find(e, variant, EXACT);
            let shown_label = label(exact, variant, false);
            // A companion variant without an exact column (`exact = false`) shows none.
            let without_exact = shown_run != &m.run && exact.is_none();
            if !without_exact && !exact_shown.contains(&(e, variant)) {
                exact_shown.push((e, variant));
                cols.push(Col::Ours(OursColumn {
                    header: name("exact", &shown_label),
                    run: exact,
                    ratio_of: None,
                }));
            }
            let run = runs.find(e, variant, &shown_run.solver);
            cols.push(Col::Ours(OursColumn {
                header: name(
                    &label(run, &shown_run.solver, true),
                    &label(run.or(exact), variant, false),
                ),
                run,
                ratio_of: None,
            }));
            cols.push(Col::Ours(OursColumn {
                header: "ratio ours / paper".to_string(),
                run,
                ratio_of: Some(m),
            }));
        }
    }
    cols
}

/// What the table's cells flagged, for its footnotes.
#[derive(Default)]
struct Marks {
    /// A norm not printed by the paper (derived from its joints).
    derived: bool,
    /// A printed number the paper's own contradict.
    inconsistent: bool,
    /// A ratio taken from a column whose printed numbers contradict each other.
    rests_on_contradiction: bool,
}

/// The cell of column `c` of published `table` for quantity `q` (`contradicted`: the paper's
/// contradicted columns).
fn cell(
    c: &Col,
    (table, q): (&str, &str),
    papers: &Papers,
    contradicted: &[Contradiction],
    marks: &mut Marks,
) -> String {
    match c {
        Col::Paper(m) => {
            let printed = match papers.published(m, q) {
                Some((v, d)) => {
                    marks.derived |= d;
                    format!("{}{}", sci(v), if d { "*" } else { "" })
                }
                None => MISSING.to_string(),
            };
            match papers.inconsistent(m, q) {
                Some((v, _)) => {
                    marks.inconsistent = true;
                    format!("{printed} (printed {}†)", sci(v))
                }
                None => printed,
            }
        }
        Col::Ours(OursColumn { run: None, .. }) => "no run".to_string(),
        Col::Ours(OursColumn {
            run: Some(r),
            ratio_of: None,
            ..
        }) => metric_cell(r, q),
        Col::Ours(OursColumn {
            run: Some(r),
            ratio_of: Some(m),
            ..
        }) => match ratio_to_paper(r, m, q, papers) {
            Some(v)
                if is_contradicted(
                    contradicted,
                    Some(table),
                    &m.published_experiment,
                    &m.published_column,
                ) =>
            {
                marks.rests_on_contradiction = true;
                format!("{}‡", sci(v))
            }
            v => sci_opt(v),
        },
    }
}

/// One published table side by side with ours, as Markdown (empty when nothing maps).
pub fn side_by_side(paper: &str, table: &str, papers: &Papers, runs: &Runs) -> String {
    let columns = columns_of(paper, table, papers);
    if columns.is_empty() {
        return String::new();
    }
    let one_variant = columns
        .iter()
        .all(|c| c.run.variant == columns[0].run.variant && c.companions.is_empty());
    let cols = layout(&columns, runs, one_variant);
    let shown: Vec<&RunRow> = cols
        .iter()
        .filter_map(|c| if let Col::Ours(o) = c { o.run } else { None })
        .collect();
    let quantities = quantities_of(paper, table, papers, &shown);
    let mut header = vec!["run".to_string()];
    header.extend(quantities.iter().map(|q| quantity_label(q)));
    let mut t = Table::new(header);
    let mut marks = Marks::default();
    let contradicted = contradictions(paper, papers);
    for c in &cols {
        let mut row = vec![match c {
            Col::Paper(m) => format!("**paper: {}**", m.published_column),
            Col::Ours(o) => o.header.clone(),
        }];
        row.extend(
            quantities
                .iter()
                .map(|q| cell(c, (table, q), papers, &contradicted, &mut marks)),
        );
        t.push(row);
    }
    let mut out = caption(table, &columns, runs, one_variant);
    out.push_str(&t.render());
    if marks.derived {
        out.push_str("\n\\* not printed by the paper: the norm of its per-joint entries.\n");
    }
    if marks.inconsistent {
        out.push_str(
            "\n† printed, but contradicted by the paper's own numbers (a norm below one of its \
             entries, a negative norm, or a number given twice; the warnings are listed under \
             the paper): no ratio is taken from it.\n",
        );
    }
    if marks.rests_on_contradiction {
        out.push_str(
            "\n‡ the paper's column contradicts itself (its printed norm is not the norm of its \
             printed entries; see \"Printed numbers that contradict each other\"): the ratio \
             rests on a contradicted number and the verdict does not count it.\n",
        );
    }
    out
}

/// The caption above a side-by-side table: the table, our experiments, the variant (when one)
/// and what the ratio is.
fn caption(table: &str, columns: &[&Mapping], runs: &Runs, one_variant: bool) -> String {
    let ids: Vec<&str> =
        columns
            .iter()
            .map(|c| c.run.experiment.as_str())
            .fold(Vec::new(), |mut v, e| {
                if !v.contains(&e) {
                    v.push(e);
                }
                v
            });
    let caption = if table == "text" {
        "Numbers quoted in the text".to_string()
    } else {
        format!("Table {}", table.trim_start_matches('T'))
    };
    let mut out = format!(
        "**{caption}** — our experiment{} {}",
        if ids.len() > 1 { "s" } else { "" },
        ids.iter()
            .map(|e| format!("`{e}`"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    if one_variant {
        let k = &columns[0].run;
        let shown = runs.find(&k.experiment, &k.variant, EXACT);
        out.push_str(&format!(
            ", variant \"{}\"",
            label(shown, &k.variant, false)
        ));
    }
    out.push_str(". One row per number (the paper's, our runs, and the ratio of our run of the paper's solver to the paper's), one column per quantity.\n\n");
    out
}

/// The suite's table of every run of one experiment: status, drift, position error, peaks
/// and joint-limit margins (columns that no run measures are left out).
pub fn runs_table(runs: &Runs, experiment: &str) -> String {
    let rows: Vec<&RunRow> = runs.of_experiment(experiment).collect();
    let off_reference = rows.iter().any(|r| r.drift_norm != r.drift_ref_norm);
    let mut quantities = vec!["drift_norm"];
    if off_reference {
        quantities.push("drift_ref_norm");
    }
    quantities.extend([
        "max_pos_err",
        "final_pos_err",
        "peak_thetadot",
        "peak_thetaddot",
        "peak_torque",
        "theta_margin",
        "thetadot_margin",
    ]);
    let label = |q: &str| match q {
        "peak_thetadot" => "peak |θ̇|".to_string(),
        "peak_thetaddot" => "peak |θ̈|".to_string(),
        "peak_torque" => "peak |τ|".to_string(),
        "theta_margin" => "min θ margin".to_string(),
        "thetadot_margin" => "min θ̇ margin".to_string(),
        q => quantity_label(q),
    };
    let mut header = vec!["variant".to_string(), "solver".to_string()];
    header.extend(quantities.iter().map(|q| label(q)));
    header.push("status".to_string());
    let mut t = Table::new(header);
    for r in rows {
        let mut row = vec![r.variant.clone(), r.solver.clone()];
        row.extend(quantities.iter().map(|q| sci_opt(metric(r, q))));
        row.push(status_text(r));
        t.push(row);
    }
    t.without_empty_columns().render()
}
