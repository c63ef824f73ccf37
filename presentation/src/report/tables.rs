//! The papers' tables side by side with ours, and the suite's own table of every run.
//!
//! A published table (one `(paper, table)` of `papers/<paper>/values.csv`) becomes one Markdown table:
//! columns are the quantities (joint drifts, drift norm, and whatever else the paper prints),
//! and for each published column there are rows for the paper's number, our exact run, our
//! run of the paper's solver, and the ratio ours/paper — then the same for each companion
//! variant (each run once). The exact column separates what the scheme does from what the solver adds. Which
//! columns, rows and quantities a table has, and the ratios, are
//! [`analysis::published_table`]'s (held by the report model).

use super::markdown::metric_cell;
use super::markdown::{sci, sci_opt, Table, MISSING};
use crate::figures::sweep::MAX_RUN_FIGURES;
use analysis::papers::{Mapping, Papers};
use analysis::published_table::{Row, SideBySide};
use analysis::sweep_summary::SweepSummary;
use records::index::{metric, status_text, Runs, EXACT};
use records::RunRow;

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

/// The cells of `row` for the quantities `quantities`.
fn cells(row: &Row, quantities: &[&str], papers: &Papers, marks: &mut Marks) -> Vec<String> {
    match row {
        Row::Paper(m) => quantities
            .iter()
            .map(|q| {
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
            })
            .collect(),
        Row::Run { run: None, .. } | Row::Ratio { ratios: None, .. } => {
            vec!["no run".to_string(); quantities.len()]
        }
        Row::Run { run: Some(r), .. } => quantities.iter().map(|q| metric_cell(r, q)).collect(),
        Row::Ratio {
            ratios: Some(ratios),
            contradicted,
        } => ratios
            .iter()
            .map(|v| match v {
                Some(v) if *contradicted => {
                    marks.rests_on_contradiction = true;
                    format!("{}‡", sci(*v))
                }
                v => sci_opt(*v),
            })
            .collect(),
    }
}

/// One published table side by side with ours ([`analysis::published_table::side_by_side`]),
/// as Markdown.
pub fn side_by_side(table: &SideBySide, papers: &Papers, runs: &Runs) -> String {
    let mut header = vec!["run".to_string()];
    header.extend(table.quantities.iter().map(|q| quantity_label(q)));
    let mut t = Table::new(header);
    let mut marks = Marks::default();
    for row in &table.rows {
        let mut cells_of = vec![match row {
            Row::Paper(m) => format!("**paper: {}**", m.published_column),
            Row::Run { header, .. } => header.clone(),
            Row::Ratio { .. } => "ratio ours / paper".to_string(),
        }];
        cells_of.extend(cells(row, &table.quantities, papers, &mut marks));
        t.push(cells_of);
    }
    let mut out = caption(&table.table, &table.columns, runs, table.one_variant);
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
            shown.map_or(k.variant.as_str(), |r| r.variant.as_str())
        ));
    }
    out.push_str(". One row per number (the paper's, our runs, and the ratio of our run of the paper's solver to the paper's), one column per quantity.\n\n");
    out
}

/// The rows a per-run table shows, in their order: `rows`, runs the report holds (every run
/// of an experiment of at most [`MAX_RUN_FIGURES`] runs, and of a larger one, a large sweep,
/// its sample: its failures, its extremes, runs evenly spaced; `analysis::sweep_summary`), so
/// that a table has at most that many rows per experiment whatever the sweep's size; and how
/// many runs it leaves out: of each large sweep of `sweeps` (those in the table's scope),
/// `left_out` of it (its runs beyond its sample, or its runs of the kind the table shows).
pub fn shown<'a, 's>(
    rows: impl Iterator<Item = &'a RunRow>,
    sweeps: impl Iterator<Item = &'s SweepSummary>,
    left_out: fn(&SweepSummary) -> usize,
) -> (Vec<&'a RunRow>, usize) {
    let mut count = 0;
    for s in sweeps {
        count += left_out(s);
    }
    (rows.collect(), count)
}

/// The line below a per-run table that left `left_out` runs out ([`shown`]); none when it
/// left none out.
pub fn left_out_note(left_out: usize) -> String {
    if left_out == 0 {
        return String::new();
    }
    format!(
        "\n{left_out} more run(s) of large sweeps are not in this table: an experiment of more than {MAX_RUN_FIGURES} runs shows the {MAX_RUN_FIGURES} its figures draw (its failures, its extremes, runs evenly spaced); its sweep section has its extremes and failures, and `results/runs.csv` every run.\n"
    )
}

/// The suite's table of the runs of one experiment (`shown`: a large sweep's sample, the
/// others of `sweeps` counted as left out): status, drift, position error, peaks and
/// joint-limit margins (columns that no run measures are left out).
pub fn runs_table(runs: &Runs, sweeps: &[SweepSummary], experiment: &str) -> String {
    let (rows, left_out) = shown(
        runs.of_experiment(experiment),
        sweeps.iter().filter(|s| s.experiment == experiment),
        SweepSummary::left_out,
    );
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
    t.without_empty_columns().render() + &left_out_note(left_out)
}
