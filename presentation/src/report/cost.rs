//! Cost: integrator, tolerances, steps, evaluations, QP solves and wall time per run, and
//! zhong2021's compute-time comparison with the paper's MATLAB times, as ratios.
//!
//! Absolute times are not comparable across machines and languages, ratios within one
//! machine are: S-LVI-PDNN's time over the mean time of the VP-RNN-PF variants is what
//! zhong2021 claims (about 2x on the clover, 7x on "dai").

use super::markdown::{sci, sci_opt, Table, MISSING};
use analysis::cost_ratio::TimeRow;
use analysis::papers::Papers;
use analysis::sweep_summary::SweepSummary;
use records::index::{completed, Runs};

/// One cost table per paper: every run's integrator, tolerances and effort (of a large sweep
/// of `sweeps`, its sample: [`super::tables::shown`]).
pub fn cost_table(runs: &Runs, sweeps: &[SweepSummary], paper: &str) -> String {
    let mut t = Table::new([
        "experiment",
        "variant",
        "solver",
        "integrator",
        "rtol",
        "atol",
        "steps (rejected)",
        "RHS evals",
        "Jacobians",
        "QP solves",
        "wall (s)",
        "simulation (s)",
    ]);
    let (rows, left_out) = super::tables::shown(
        runs.of_paper(paper),
        sweeps.iter().filter(|s| s.paper == paper),
        SweepSummary::left_out,
    );
    for r in rows {
        // Runs that failed before their first step have no statistics.
        let lost = !completed(r) && r.steps == 0;
        let count = |n: usize| {
            if lost {
                "not recorded".to_string()
            } else {
                n.to_string()
            }
        };
        t.push([
            r.experiment.to_string(),
            r.variant.clone(),
            r.solver.clone(),
            super::header::numerical_loop(r).unwrap_or_else(|| r.integrator.clone()),
            super::header::tolerance_cell(r, r.rtol),
            super::header::tolerance_cell(r, r.atol),
            if lost {
                count(0)
            } else {
                format!("{} ({})", r.steps, r.rejected)
            },
            count(r.rhs_evals),
            count(r.jac_evals),
            r.qp_solves.to_string(),
            if lost { count(0) } else { sci(r.wall_s) },
            if lost { count(0) } else { sci(r.sim_s) },
        ]);
    }
    t.render() + &super::tables::left_out_note(left_out)
}

/// The label of solver id `solver` in `experiment` (its first run's), or the id.
pub(crate) fn solver_label(runs: &Runs, experiment: &str, solver: &str) -> String {
    runs.of_experiment(experiment)
        .find(|r| r.solver_id == solver)
        .map_or_else(|| solver.to_string(), |r| r.solver.clone())
}

/// The papers that publish compute times (in file order), for the headings.
pub(crate) fn timed_papers(papers: &Papers) -> String {
    papers.timed_papers().join(", ")
}

/// The published compute times: per experiment and solver, the paper's MATLAB seconds and
/// ours, each also divided by the mean of the VP-RNN-PF variants (`times`,
/// [`analysis::cost_ratio::matlab_times`]).
pub fn matlab_comparison(runs: &Runs, times: &[TimeRow]) -> String {
    let mut t = Table::new([
        "experiment",
        "solver",
        "paper (MATLAB, s)",
        "paper ÷ VP-RNN-PF mean",
        "ours (s)",
        "ours ÷ VP-RNN-PF mean",
    ]);
    for row in times {
        t.push([
            row.experiment.clone(),
            solver_label(runs, &row.experiment, &row.solver),
            sci(row.paper_s),
            sci_opt(row.paper_ratio),
            row.ours_s.map(sci).unwrap_or_else(|| MISSING.to_string()),
            sci_opt(row.ours_ratio),
        ]);
    }
    t.render()
}
