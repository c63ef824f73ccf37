//! The report's header: what it is, where its numbers come from (git revision, crate
//! version, integrators and tolerances, all read from the rows), and how to regenerate it.

use super::markdown::{sci, Table};
use analysis::papers::Papers;
use records::index::Runs;

/// A count as an English word below ten (`four papers`), digits above.
fn count_word(n: usize) -> String {
    const WORDS: [&str; 10] = [
        "no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine",
    ];
    WORDS
        .get(n)
        .map_or_else(|| n.to_string(), |w| w.to_string())
}

/// The header as Markdown.
pub fn header(runs: &Runs, papers: &Papers, figures: usize) -> String {
    let published = papers.values.len();
    let distinct = |f: fn(&records::runs::RunRow) -> &str| {
        let mut v: Vec<&str> = runs.all().iter().map(f).collect();
        v.sort();
        v.dedup();
        v.iter()
            .map(|s| format!("`{s}`"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut out = String::from("# driftbench — reproduction report\n\n");
    let ids: Vec<&str> = papers.papers.iter().map(|p| p.id.as_str()).collect();
    out.push_str(&format!(
        "A reproduction of {} paper{} on drift-free (repetitive) redundancy resolution: {}. For each paper: a verdict, its tables side by side with ours, and its claims checked \
against the measured numbers; then every neural run scored against the exact optimum of the same QP, the \
computational cost, a cross experiment (every solver on every scheme and path), and the deviations from the papers.\n\n",
        count_word(ids.len()),
        if ids.len() == 1 { "" } else { "s" },
        ids.join(", ")
    ));
    out.push_str(&format!(
        "**Provenance.** Generated from `results/runs.csv` ({} runs), `papers/*/values.csv` ({published} published numbers), \
and {figures} figures in `report/figures/`. Runs produced at git revision {} by reproduce {}.\n\n",
        runs.all().len(),
        distinct(|r| &r.git_rev),
        distinct(|r| &r.crate_version),
    ));
    let mut t = Table::new(["integrator", "rtol", "atol", "runs", "solvers"]);
    let mut settings: Vec<(String, f64, f64)> = runs
        .all()
        .iter()
        .map(|r| (method_label(r), r.rtol, r.atol))
        .collect();
    settings.sort_by(|a, b| {
        a.0.cmp(&b.0)
            .then(a.1.total_cmp(&b.1))
            .then(a.2.total_cmp(&b.2))
    });
    settings.dedup();
    for (method, rtol, atol) in settings {
        let of: Vec<&records::runs::RunRow> = runs
            .all()
            .iter()
            .filter(|r| method_label(r) == method && r.rtol == rtol && r.atol == atol)
            .collect();
        let mut solvers: Vec<&str> = of.iter().map(|r| r.solver.as_str()).collect();
        solvers.sort();
        solvers.dedup();
        t.push([
            method,
            sci(rtol),
            sci(atol),
            of.len().to_string(),
            solvers.join(", "),
        ]);
    }
    out.push_str("**Integrators and tolerances** (from the rows):\n\n");
    out.push_str(&t.render());
    out.push_str(
        "\n**Regenerate.** `cargo run --release -p reproduce` re-runs every experiment and rewrites `results/` and this \
report; the report alone is re-rendered from the stored results, without re-running anything, by \
`cargo run --release -p reproduce -- report`. Identical inputs give a byte-identical report. This page is the front page: each paper and each topic has its own page (Contents, below).\n\n\
**Reading it.** Numbers have three significant digits. \"exact\" is the same scheme with Clarabel's exact QP solution \
in the loop: it separates what the scheme does from what the neural solver adds. Ratios are ours / paper. Drift is \
θ(T) − θ(0) in rad; position errors in m; times in s.\n\n",
    );
    out
}

/// The integrator of a row, with ode15s's MaxStep where the run sets one.
fn method_label(r: &records::runs::RunRow) -> String {
    match r.max_step {
        Some(h) => format!("{} (MaxStep {h})", r.integrator),
        None => r.integrator.clone(),
    }
}
