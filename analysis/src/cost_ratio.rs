//! zhong2021's compute-time comparison, as ratios within one machine: S-LVI-PDNN's quantity
//! (compute time, or right-hand-side evaluations) over the mean of the VP-RNN-PF variants', ours
//! and the paper's (its MATLAB seconds). Absolute times are not comparable across machines and
//! languages; ratios within one machine are, and the evaluation counts are the same on every
//! machine (the claim is decided by them: [`evaluation_ratio`]).

use crate::papers::Papers;
use records::index::{completed, Runs};
use settings::NetworkKind;

/// S-LVI-PDNN's compute time over the mean VP-RNN-PF compute time, ours and the paper's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slowdown {
    /// Ours, in simulation seconds (varies with the machine).
    pub ours: Option<f64>,
    /// The paper's, in its MATLAB seconds.
    pub paper: Option<f64>,
}

/// The network kind of solver id `solver` in `experiment` (its first run's `solver_kind`).
fn kind_of(runs: &Runs, experiment: &str, solver: &str) -> Option<NetworkKind> {
    runs.of_experiment(experiment)
        .find(|r| r.solver_id == solver)
        .and_then(|r| r.solver_kind.network())
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
        .map(|r| (r.solver_kind.network(), r.rhs_evals as f64))
        .collect();
    s_over_vp_mean(&evals)
}

/// [`Slowdown`] of one zhong2021 experiment.
pub fn slowdown(runs: &Runs, papers: &Papers, experiment: &str) -> Slowdown {
    let ours: Vec<(Option<NetworkKind>, f64)> = runs
        .of_experiment(experiment)
        .filter(|r| completed(r))
        .map(|r| (r.solver_kind.network(), r.sim_s))
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

/// One published compute time beside ours ([`matlab_times`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TimeRow {
    /// The experiment id.
    pub experiment: String,
    /// The solver id.
    pub solver: String,
    /// The paper's MATLAB seconds, and over the mean of the paper's VP-RNN-PF variants.
    pub paper_s: f64,
    pub paper_ratio: Option<f64>,
    /// Our simulation seconds, and over the mean of our VP-RNN-PF variants.
    pub ours_s: Option<f64>,
    pub ours_ratio: Option<f64>,
}

/// Every published compute time with ours beside it, each also over the mean of the VP-RNN-PF
/// variants of its side, by experiment in file order.
pub fn matlab_times(runs: &Runs, papers: &Papers) -> Vec<TimeRow> {
    let mut out = Vec::new();
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
            out.push(TimeRow {
                experiment: exp.to_string(),
                solver: solver.to_string(),
                paper_s: *p,
                paper_ratio: paper_vp.map(|m| p / m),
                ours_s: o,
                ours_ratio: o.zip(ours_vp).map(|(o, m)| o / m),
            });
        }
    }
    out
}
