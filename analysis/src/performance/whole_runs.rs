//! Whole runs: the reproduction's own runs per step by solver kind (`results/runs.csv`), and the
//! runs against the papers' MATLAB compute times, each timed alone where it was
//! ([`records::Timings`]), with the smallest speed-ups against the targets.

use crate::papers::Papers;
use records::dof_cost::Summary;
use records::index::{completed, Runs};
use records::RunRow;
use records::{TimingRow, Timings};
use std::collections::BTreeMap;

/// The targets: every zhong2021 simulation this many times faster than the paper's
/// MATLAB time ...
pub const TARGET_SIMULATION_SPEEDUP: f64 = 300.0;
/// ... and every whole run (scoring included) this many times.
pub const TARGET_TOTAL_SPEEDUP: f64 = 150.0;

/// The completed runs of one solver kind, per step: the whole run's wall time per accepted
/// step, the simulation's per RHS evaluation (both us), and the RHS evaluations a run takes;
/// medians and 95th percentiles over the runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KindCost<'a> {
    pub kind: &'a str,
    pub runs: usize,
    pub wall_per_step_us: Option<Summary>,
    pub sim_per_rhs_us: Option<Summary>,
    pub rhs_evals: Option<Summary>,
}

/// [`KindCost`] of every solver kind with a completed run that took a step and an evaluation,
/// by kind id.
pub fn by_solver_kind(runs: &Runs) -> Vec<KindCost<'_>> {
    let mut kinds: BTreeMap<&str, Vec<&RunRow>> = BTreeMap::new();
    for r in runs.all() {
        if completed(r) && r.steps > 0 && r.rhs_evals > 0 {
            kinds.entry(r.solver_kind.id()).or_default().push(r);
        }
    }
    kinds
        .into_iter()
        .map(|(kind, rows)| {
            let per_step: Vec<f64> = rows
                .iter()
                .map(|r| r.wall_s * 1e6 / r.steps as f64)
                .collect();
            let per_rhs: Vec<f64> = rows
                .iter()
                .map(|r| r.sim_s * 1e6 / r.rhs_evals as f64)
                .collect();
            let evals: Vec<f64> = rows.iter().map(|r| r.rhs_evals as f64).collect();
            KindCost {
                kind,
                runs: rows.len(),
                wall_per_step_us: Summary::of(&per_step),
                sim_per_rhs_us: Summary::of(&per_rhs),
                rhs_evals: Summary::of(&evals),
            }
        })
        .collect()
}

/// One published compute time beside our run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MatlabLine<'a> {
    pub experiment: &'a str,
    /// The solver's id.
    pub solver: &'a str,
    /// The paper's MATLAB time (s).
    pub paper_s: f64,
    /// Ours (s): the simulation and the whole run, the medians of the run timed alone, else the
    /// parallel reproduction's; none without a completed run.
    pub ours: Option<(f64, f64)>,
    /// The run timed alone, where it was.
    pub timing: Option<&'a TimingRow>,
    /// The paper's time over our simulation's.
    pub paper_over_simulation: Option<f64>,
    /// The paper's time over our whole run's.
    pub paper_over_total: Option<f64>,
}

/// The smallest speed-ups over the runs shown, and whether each meets its target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmallestSpeedups {
    pub simulation: f64,
    pub total: f64,
    /// `simulation` >= [`TARGET_SIMULATION_SPEEDUP`].
    pub simulation_met: bool,
    /// `total` >= [`TARGET_TOTAL_SPEEDUP`].
    pub total_met: bool,
}

/// Every published compute time beside our runs.
#[derive(Clone, Debug, PartialEq)]
pub struct MatlabComparison<'a> {
    /// Per timed experiment (in the published values' order) and solver.
    pub lines: Vec<MatlabLine<'a>>,
    /// Runs timed alone.
    pub alone: usize,
    /// Runs with a time of ours.
    pub shown: usize,
    /// None without a run of ours.
    pub smallest: Option<SmallestSpeedups>,
}

/// [`MatlabComparison`] of the papers' compute times with `runs`, timed alone by `timings`.
pub fn matlab_comparison<'a>(
    runs: &'a Runs,
    timings: &'a Timings,
    papers: &'a Papers,
) -> MatlabComparison<'a> {
    let (mut min_sim, mut min_total) = (f64::INFINITY, f64::INFINITY);
    let (mut alone, mut shown) = (0, 0);
    let mut lines = Vec::new();
    // The runs the timing pass times alone (`Papers::timed_runs`), one per published time.
    for timed in papers.timed_runs(runs) {
        let (experiment, solver, paper_s) = (timed.experiment, timed.solver, timed.published_s);
        let run = timed.run.filter(|r| completed(r));
        let timing = run.and_then(|r| timings.get(&r.key()));
        let ours = match (run, timing) {
            (_, Some(t)) => Some((t.sim_s_median, t.wall_s_median)),
            (Some(r), None) => Some((r.sim_s, r.wall_s)),
            (None, None) => None,
        };
        if let Some((s, w)) = ours {
            min_sim = min_sim.min(paper_s / s);
            min_total = min_total.min(paper_s / w);
            shown += 1;
        }
        alone += usize::from(timing.is_some());
        lines.push(MatlabLine {
            experiment,
            solver,
            paper_s,
            ours,
            timing,
            paper_over_simulation: ours.map(|(s, _)| paper_s / s),
            paper_over_total: ours.map(|(_, w)| paper_s / w),
        });
    }
    let smallest = (min_sim.is_finite() && min_total.is_finite()).then_some(SmallestSpeedups {
        simulation: min_sim,
        total: min_total,
        simulation_met: min_sim >= TARGET_SIMULATION_SPEEDUP,
        total_met: min_total >= TARGET_TOTAL_SPEEDUP,
    });
    MatlabComparison {
        lines,
        alone,
        shown,
        smallest,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_are_priced_per_step_by_kind() {
        let mut a = RunRow::blank(
            &spec::RunKey::from_ids("e", "v", "s").unwrap(),
            spec::SolverKind::Exact,
        );
        (a.steps, a.rhs_evals, a.wall_s, a.sim_s) = (100, 400, 0.01, 0.004);
        let mut b = a.clone();
        (b.steps, b.wall_s) = (50, 0.01);
        let runs = Runs::new(vec![a, b]);
        let costs = by_solver_kind(&runs);
        assert_eq!(costs.len(), 1);
        assert_eq!(costs[0].runs, 2);
        // 100 us and 200 us a step: the median between them.
        let step = costs[0].wall_per_step_us.unwrap();
        assert_eq!(step.median_us, 150.0);
        assert_eq!(
            costs[0].sim_per_rhs_us.unwrap().median_us,
            0.004 * 1e6 / 400.0
        );
        assert_eq!(costs[0].rhs_evals.unwrap().median_us, 400.0);
    }

    #[test]
    fn without_published_times_nothing_is_compared() {
        let (runs, timings, papers) =
            (Runs::new(Vec::new()), Timings::default(), Papers::default());
        let c = matlab_comparison(&runs, &timings, &papers);
        assert!(c.lines.is_empty() && c.smallest.is_none());
        assert_eq!((c.alone, c.shown), (0, 0));
    }
}
