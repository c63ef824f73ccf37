//! Cost: integrator, tolerances, steps, evaluations, QP solves and wall time per run, and
//! zhong2021's compute-time comparison with the paper's MATLAB times, as ratios.
//!
//! Absolute times are not comparable across machines and languages, ratios within one
//! machine are: S-LVI-PDNN's time over the mean time of the VP-RNN-PF variants is what
//! zhong2021 claims (about 2x on the clover, 7x on "dai").

use super::markdown::{sci, sci_opt, Table, MISSING};
use catalog::network_kind::NetworkKind;
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

/// The network kind of solver id `solver` in `experiment` (its first run's `solver_kind`).
fn kind_of(runs: &Runs, experiment: &str, solver: &str) -> Option<NetworkKind> {
    runs.of_experiment(experiment)
        .find(|r| r.solver_id == solver)
        .and_then(|r| r.solver_kind.parse().ok())
}

/// The label of solver id `solver` in `experiment` (its first run's), or the id.
pub(crate) fn solver_label(runs: &Runs, experiment: &str, solver: &str) -> String {
    runs.of_experiment(experiment)
        .find(|r| r.solver_id == solver)
        .map_or_else(|| solver.to_string(), |r| r.solver.clone())
}

/// zhong2021's efficiency measure among (network kind, quantity) pairs: S-LVI-PDNN's quantity
/// over the mean of the VP-RNN-PF variants'.
fn s_over_vp_mean(of: &[(Option<NetworkKind>, f64)]) -> Option<f64> {
    let s = of
        .iter()
        .find(|(k, _)| *k == Some(NetworkKind::SLviPdnn))
        .map(|(_, x)| *x)?;
    vp_mean(of).map(|vp| s / vp)
}

/// The mean quantity of the VP-RNN-PF variants among (network kind, quantity) pairs.
fn vp_mean(of: &[(Option<NetworkKind>, f64)]) -> Option<f64> {
    let vp: Vec<f64> = of
        .iter()
        .filter(|(k, _)| *k == Some(NetworkKind::VpRnnPf))
        .map(|(_, x)| *x)
        .collect();
    (!vp.is_empty()).then(|| vp.iter().sum::<f64>() / vp.len() as f64)
}

/// S-LVI-PDNN's right-hand-side evaluations over the mean of the VP-RNN-PF variants' in one
/// experiment: the deterministic measure of relative cost (the same on every machine and under
/// any load), which the compute-time claim is decided by.
pub fn evaluation_ratio(runs: &Runs, experiment: &str) -> Option<f64> {
    let evals: Vec<(Option<NetworkKind>, f64)> = runs
        .of_experiment(experiment)
        .filter(|r| completed(r))
        .map(|r| (r.solver_kind.parse().ok(), r.rhs_evals as f64))
        .collect();
    s_over_vp_mean(&evals)
}

/// [`Slowdown`] of one zhong2021 experiment.
pub fn slowdown(runs: &Runs, papers: &Papers, experiment: &str) -> Slowdown {
    let ours: Vec<(Option<NetworkKind>, f64)> = runs
        .of_experiment(experiment)
        .filter(|r| completed(r))
        .map(|r| (r.solver_kind.parse().ok(), r.sim_s))
        .collect();
    let paper: Vec<(Option<NetworkKind>, f64)> = papers
        .times_of(experiment)
        .map(|(solver, t)| (kind_of(runs, experiment, solver), t))
        .collect();
    Slowdown {
        ours: s_over_vp_mean(&ours),
        paper: s_over_vp_mean(&paper),
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
        let kinds = |of: &[(&str, f64)]| -> Vec<(Option<NetworkKind>, f64)> {
            of.iter()
                .map(|(s, x)| (kind_of(runs, exp, s), *x))
                .collect()
        };
        let (paper_vp, ours_vp) = (vp_mean(&kinds(&paper)), vp_mean(&kinds(&ours)));
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
