//! Cost: integrator, tolerances, steps, evaluations, QP solves and wall time per run, and
//! zhong2021's compute-time comparison with the paper's MATLAB times, as ratios.
//!
//! Absolute times are not comparable across machines and languages, ratios within one
//! machine are: S-LVI-PDNN's time over the mean time of the VP-RNN-PF variants is what
//! zhong2021 claims (about 2x on the clover, 7x on "dai").

use super::markdown::{sci, sci_opt, Table, MISSING};
use records::index::{completed, Runs};
use records::papers::Papers;

/// One cost table per paper: every run's integrator, tolerances and effort.
pub fn cost_table(runs: &Runs, paper: &str) -> String {
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
    for r in runs.of_paper(paper) {
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
            r.experiment.clone(),
            r.variant.clone(),
            r.solver.clone(),
            r.integrator.clone(),
            sci(r.rtol),
            sci(r.atol),
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
    t.render()
}

/// S-LVI-PDNN's compute time over the mean VP-RNN-PF compute time, ours and the paper's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slowdown {
    pub ours: Option<f64>,
    pub paper: Option<f64>,
}

/// The mean of the VP-RNN-PF variants' times among (solver label, seconds) pairs.
/// Solver ids of zhong2021's efficiency claim: S-LVI-PDNN against the VP-RNN-PF variants.
const S_LVI_PDNN: &str = "s-lvi-pdnn";
const VP_RNN_PF: &str = "vp-rnn-pf";

/// The label of solver id `solver` in `experiment` (its first run's), or the id.
pub(crate) fn solver_label(runs: &Runs, experiment: &str, solver: &str) -> String {
    runs.of_experiment(experiment)
        .find(|r| r.solver_id == solver)
        .map_or_else(|| solver.to_string(), |r| r.solver.clone())
}

fn vp_mean(times: &[(&str, f64)]) -> Option<f64> {
    let vp: Vec<f64> = times
        .iter()
        .filter(|(s, _)| s.starts_with(VP_RNN_PF))
        .map(|(_, t)| *t)
        .collect();
    (!vp.is_empty()).then(|| vp.iter().sum::<f64>() / vp.len() as f64)
}

/// S-LVI-PDNN's right-hand-side evaluations over the mean of the VP-RNN-PF variants' in one
/// experiment: the deterministic measure of relative cost (the same on every machine and under
/// any load), which the compute-time claim is decided by.
pub fn evaluation_ratio(runs: &Runs, experiment: &str) -> Option<f64> {
    let evals: Vec<(&str, f64)> = runs
        .of_experiment(experiment)
        .filter(|r| completed(r))
        .map(|r| (r.solver_id.as_str(), r.rhs_evals as f64))
        .collect();
    let s = evals
        .iter()
        .find(|(s, _)| *s == S_LVI_PDNN)
        .map(|(_, e)| *e)?;
    vp_mean(&evals).map(|vp| s / vp)
}

/// [`Slowdown`] of one zhong2021 experiment.
pub fn slowdown(runs: &Runs, papers: &Papers, experiment: &str) -> Slowdown {
    let ratio = |times: &[(&str, f64)]| {
        let s = times
            .iter()
            .find(|(s, _)| *s == S_LVI_PDNN)
            .map(|(_, t)| *t)?;
        vp_mean(times).map(|vp| s / vp)
    };
    let ours: Vec<(&str, f64)> = runs
        .of_experiment(experiment)
        .filter(|r| completed(r))
        .map(|r| (r.solver_id.as_str(), r.sim_s))
        .collect();
    let paper: Vec<(&str, f64)> = papers.times_of(experiment).collect();
    Slowdown {
        ours: ratio(&ours),
        paper: ratio(&paper),
    }
}

/// The papers that publish compute times (in file order), for the headings.
pub(crate) fn timed_papers(papers: &Papers) -> String {
    papers.timed_papers().join(", ")
}

/// The published compute times: per experiment and solver, the paper's MATLAB seconds and
/// ours, each also divided by the mean of the VP-RNN-PF variants.
pub fn matlab_comparison(runs: &Runs, papers: &Papers) -> String {
    let mut t = Table::new([
        "experiment",
        "solver",
        "paper (MATLAB, s)",
        "paper ÷ VP-RNN-PF mean",
        "ours (s)",
        "ours ÷ VP-RNN-PF mean",
    ]);
    for exp in papers.timed_experiments() {
        let paper: Vec<(&str, f64)> = papers.times_of(exp).collect();
        let ours: Vec<(&str, f64)> = runs
            .of_experiment(exp)
            .filter(|r| paper.iter().any(|(s, _)| *s == r.solver_id))
            .map(|r| (r.solver_id.as_str(), r.sim_s))
            .collect();
        let (paper_vp, ours_vp) = (vp_mean(&paper), vp_mean(&ours));
        for (solver, p) in &paper {
            let o = ours.iter().find(|(s, _)| s == solver).map(|(_, t)| *t);
            t.push([
                exp.to_string(),
                solver_label(runs, exp, solver),
                sci(*p),
                sci_opt(paper_vp.map(|m| p / m)),
                o.map(sci).unwrap_or_else(|| MISSING.to_string()),
                sci_opt(o.zip(ours_vp).map(|(o, m)| o / m)),
            ]);
        }
    }
    t.render()
}
