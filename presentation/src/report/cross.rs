//! The cross experiment: every velocity-level solver on every velocity-level scheme and path.
//!
//! Three matrices, rows = solver, columns = scheme · path: the drift against the scheme's
//! reference (theta0, or kong2019's theta*0), the max position error, and the score max
//! |x − x*|. Under each, a "best" line per column computed from the numbers among the
//! completed neural runs ([`analysis::cross_best`], held by the report model): the drift
//! closest to the exact column's (drift is the scheme's property; a solver should not change
//! it), the smallest position error, the smallest score.

use super::markdown::{sci, Table, MISSING};
use analysis::cross_best::{Best, ColumnBest, MEASURES};
use records::index::{completed, failed_at, metric, Runs, EXACT};
use records::RunRow;

/// The matrices' titles, in the order of [`MEASURES`].
const TITLES: [&str; MEASURES.len()] = [
    "Drift ‖θ(T) − θ_ref‖ (rad; θ_ref = θ0, or θ*0 where the experiment declares one)",
    "Max position error (m)",
    "Score: max |x − x*| against the exact optimum (includes the start-up transient from the zero network state: on a deviated start, θ0 ≠ θ*0, every solver ties at |x*(0)|)",
    "Score: RMS |x − x*| over the run (time-weighted, so the start-up transient counts for its duration only)",
];

/// The cross section as Markdown (empty when there are no cross runs); `bests`: the best of
/// every column ([`analysis::cross_best::bests`]).
pub fn section(runs: &Runs, paper: &str, bests: &[ColumnBest]) -> String {
    let rows: Vec<&RunRow> = runs.of_paper(paper).collect();
    let mut columns: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r.experiment.as_str(), r.variant_id.as_str()))
        .collect();
    columns.dedup();
    // (id, label), the exact column first, then by label.
    let mut solvers: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r.solver_id.as_str(), r.solver.as_str()))
        .collect();
    solvers.sort_by_key(|s| (s.0 != EXACT, s.1, s.0));
    solvers.dedup_by_key(|s| s.0);
    if columns.is_empty() {
        return String::new();
    }
    let label = |(e, v): (&str, &str)| {
        let r = rows
            .iter()
            .find(|r| r.experiment == e && r.variant_id == v)
            .expect("column taken from the rows");
        format!("{} · {}", r.scheme, r.path)
    };
    let mut out = String::new();
    for (title, &(column, _)) in TITLES.iter().zip(MEASURES.iter()) {
        let mut header = vec!["solver".to_string()];
        header.extend(columns.iter().map(|c| label(*c)));
        let mut t = Table::new(header);
        for (id, shown) in &solvers {
            let mut row = vec![shown.to_string()];
            row.extend(columns.iter().map(|(e, v)| {
                match runs.find(e, v, id) {
                    None => MISSING.to_string(),
                    Some(r) if !completed(r) => failed_at(r),
                    Some(r) => metric(r, column)
                        .map(sci)
                        .unwrap_or_else(|| MISSING.to_string()),
                }
            }));
            t.push(row);
        }
        let mut best_row = vec!["**best**".to_string()];
        best_row.extend(columns.iter().map(|(e, v)| {
            best_cell(
                bests
                    .iter()
                    .find(|b| b.measure == column && b.experiment == *e && b.variant == *v)
                    .map_or(Best::Nothing, |b| b.best),
            )
        }));
        t.push(best_row);
        out.push_str(&format!("**{title}**\n\n{}\n", t.render()));
    }
    out
}

/// The best of a column ([`analysis::cross_best`]) as "solver", "tie (n, e.g. solver)" or
/// "tie (all n)".
fn best_cell(best: Best) -> String {
    match best {
        Best::Nothing => MISSING.to_string(),
        Best::Tie {
            runs, all: true, ..
        } => format!("tie (all {runs})"),
        Best::Tie { runs, first, .. } => format!("tie ({runs}, e.g. {})", first.solver),
        Best::Run(r) => r.solver.clone(),
    }
}
