//! The report's header: what it is, where its numbers come from (git revision, crate
//! version, integrators and tolerances, all read from the rows), and how to regenerate it.

use super::markdown::{sci, Table};
use analysis::papers::Papers;
use analysis::sweep_summary::SweepSummary;
use records::index::Runs;
use std::collections::BTreeSet;

/// A count as an English word below ten (`four papers`), digits above.
fn count_word(n: usize) -> String {
    const WORDS: [&str; 10] = [
        "no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine",
    ];
    WORDS
        .get(n)
        .map_or_else(|| n.to_string(), |w| w.to_string())
}

/// The header as Markdown: `runs`, the runs the report holds, and `sweeps`, the summaries of
/// the large sweeps, whose runs beyond their samples are counted and their revisions named.
pub fn header(runs: &Runs, sweeps: &[SweepSummary], papers: &Papers, figures: usize) -> String {
    let published = papers.values.len();
    let mut left_out = 0;
    for s in sweeps {
        left_out += s.left_out();
    }
    let distinct = |f: fn(&records::RunRow) -> &str, of: fn(&SweepSummary) -> &BTreeSet<String>| {
        let mut v: Vec<&str> = runs.all().iter().map(f).collect();
        v.extend(sweeps.iter().flat_map(|s| of(s).iter().map(String::as_str)));
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
        runs.all().len() + left_out,
        distinct(|r| &r.git_rev, |s| &s.revisions),
        distinct(|r| &r.crate_version, |s| &s.versions),
    ));
    let mut t = Table::new(["integrator", "rtol", "atol", "runs", "solvers"]);
    // A numerical loop has no tolerances: its rows group by the loop alone.
    let tolerances = |r: &records::RunRow| match numerical_loop(r) {
        Some(_) => (f64::NAN, f64::NAN),
        None => (r.rtol, r.atol),
    };
    let mut settings: Vec<(String, f64, f64)> = runs
        .all()
        .iter()
        .map(|r| {
            let (rtol, atol) = tolerances(r);
            (method_label(r), rtol, atol)
        })
        .collect();
    settings.sort_by(|a, b| {
        a.0.cmp(&b.0)
            .then(a.1.total_cmp(&b.1))
            .then(a.2.total_cmp(&b.2))
    });
    settings
        .dedup_by(|a, b| a.0 == b.0 && a.1.total_cmp(&b.1).is_eq() && a.2.total_cmp(&b.2).is_eq());
    for (method, rtol, atol) in settings {
        let of: Vec<&records::RunRow> = runs
            .all()
            .iter()
            .filter(|r| {
                let (a, b) = tolerances(r);
                method_label(r) == method
                    && a.total_cmp(&rtol).is_eq()
                    && b.total_cmp(&atol).is_eq()
            })
            .collect();
        let mut solvers: Vec<&str> = of.iter().map(|r| r.solver.as_str()).collect();
        solvers.sort();
        solvers.dedup();
        let cell = |v: f64| {
            if v.is_nan() {
                "n/a".to_string()
            } else {
                sci(v)
            }
        };
        t.push([
            method,
            cell(rtol),
            cell(atol),
            of.len().to_string(),
            solvers.join(", "),
        ]);
    }
    if left_out > 0 {
        out.push_str(&format!("**Integrators and tolerances** (from the rows the report holds: every run but {left_out} of large sweeps, each held as the {} runs of its sample):\n\n", crate::figures::sweep::MAX_RUN_FIGURES));
    } else {
        out.push_str("**Integrators and tolerances** (from the rows):\n\n");
    }
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

/// The integrator of a row, with ode15s's MaxStep where the run sets one; for a numerical
/// method, its fixed-step loop ([`numerical_loop`]).
fn method_label(r: &records::RunRow) -> String {
    if let Some(l) = numerical_loop(r) {
        return l;
    }
    match r.max_step {
        Some(h) => format!("{} (MaxStep {h})", r.integrator),
        None => r.integrator.clone(),
    }
}

/// How a numerical method's run steps (none for any other run): a fixed-step loop of step
/// h = duration / steps, each instant's iteration stopped by the rule its solver's name states
/// (robio2018 Algorithm 1); the row's integrator tolerances do not apply to it.
pub fn numerical_loop(r: &records::RunRow) -> Option<String> {
    matches!(r.solver_kind, spec::SolverKind::Numerical(_)).then(|| {
        format!(
            "fixed-step loop, h = {} s, stopped per instant as the solver's name says",
            sci(r.fixed_step())
        )
    })
}

/// A row's tolerance `v` as a cell: "n/a" for a numerical method's loop, which has none.
pub fn tolerance_cell(r: &records::RunRow, v: f64) -> String {
    match numerical_loop(r) {
        Some(_) => "n/a".to_string(),
        None => sci(v),
    }
}
