//! What the report's Performance page shows that is computed from the measurements, once per
//! render ([`crate::performance`], [`crate::fits`]): per scheme of `results/dof-cost.csv`, each
//! quantity's median per instant over the network RHS and the KKT floor, the exact solve
//! against its target and where faer's dense LU overtakes nalgebra's; the replay against
//! DAQP (`results/qp-replay.csv`) and its target; the reproduction's runs per step by solver
//! kind (`results/runs.csv`); the fits' extents, the whole runs per N and the growth past the
//! registry's sizes; and the whole runs against the papers' MATLAB times. The page formats it.

use crate::fits::{crossover, Crossover};
use crate::papers::Papers;
use crate::performance::dof::{
    fit_extents, large_n_fits, largest_n, largest_registry_n, runs_at_n, schemes, FitExtent,
    LargeNFit, RunsAtN,
};
use crate::performance::instant::{exact_over_rhs, per_instant, ExactOverRhs, InstantCost};
use crate::performance::replay::{lines, target, ReplayLine, ReplayTarget};
use crate::performance::whole_runs::{
    by_solver_kind, matlab_comparison, KindCost, MatlabComparison,
};
use records::dof_cost::{DofCostRow, Quantity};
use records::index::Runs;
use records::QpReplayRow;
use records::Timings;

/// The measurements the Performance page reads besides the runs (absent files: empty).
#[derive(Clone, Copy, Debug, Default)]
pub struct Measured<'a> {
    /// `results/dof-cost.csv`.
    pub dof: &'a [DofCostRow],
    /// `results/qp-replay.csv`.
    pub qp_replay: &'a [QpReplayRow],
}

/// The Performance page's computed content (module docs).
#[derive(Clone, Debug)]
pub struct Performance<'a> {
    /// Every scheme of the DOF measurement, in file order, with its costs.
    pub schemes: Vec<SchemeCost<'a>>,
    /// The replay against DAQP, a line per row.
    pub replay: Vec<ReplayLine<'a>>,
    /// The replay's target, decided (none without the suite's and DAQP's rows).
    pub replay_target: Option<ReplayTarget>,
    /// The reproduction's completed runs per step, by solver kind.
    pub by_solver_kind: Vec<KindCost<'a>>,
    /// The largest N measured (0 without a measurement).
    pub largest_n: usize,
    /// Every fit row with the measurements it was fitted to.
    pub fit_extents: Vec<FitExtent<'a>>,
    /// The whole runs of the DOF measurement, per scheme and N.
    pub runs_at_n: Vec<RunsAtN<'a>>,
    /// The growth exponents of the whole runs past the registry's sizes.
    pub large_n_fits: Vec<LargeNFit<'a>>,
    /// The largest joint count of the two-scheme sweep.
    pub largest_registry_n: usize,
    /// The whole runs against the papers' MATLAB times.
    pub matlab: MatlabComparison<'a>,
}

/// One scheme's costs in the DOF measurement.
#[derive(Clone, Debug)]
pub struct SchemeCost<'a> {
    /// The scheme (its paper id).
    pub scheme: &'a str,
    /// Each quantity per instant at the Jaco2's size, with its ratios.
    pub per_instant: Vec<InstantCost<'a>>,
    /// The hot-started active set over one network RHS evaluation, against its target.
    pub exact_over_rhs: Option<ExactOverRhs<'a>>,
    /// Where faer's LU overtakes nalgebra's, per dense LU quantity (the network Jacobian's LU,
    /// then the KKT floor) that has both backends measured.
    pub crossovers: Vec<(Quantity, Crossover)>,
}

impl<'a> Performance<'a> {
    /// The page's content from `measured`, the stored `runs` timed alone in `timings`, and
    /// the papers' compute times in `papers` (what [`super::ReportModel::build`] builds).
    pub fn build(
        measured: Measured<'a>,
        runs: &'a Runs,
        timings: &'a Timings,
        papers: &'a Papers,
    ) -> Self {
        let dof = measured.dof;
        Performance {
            schemes: schemes(dof)
                .into_iter()
                .map(|scheme| SchemeCost {
                    scheme,
                    per_instant: per_instant(dof, scheme),
                    exact_over_rhs: exact_over_rhs(dof, scheme),
                    crossovers: [Quantity::NetworkLu, Quantity::KktFloor]
                        .into_iter()
                        .filter_map(|q| crossover(dof, scheme, q).map(|c| (q, c)))
                        .collect(),
                })
                .collect(),
            replay: lines(measured.qp_replay),
            replay_target: target(measured.qp_replay),
            by_solver_kind: by_solver_kind(runs),
            largest_n: largest_n(dof),
            fit_extents: fit_extents(dof),
            runs_at_n: runs_at_n(dof),
            large_n_fits: large_n_fits(dof),
            largest_registry_n: largest_registry_n(),
            matlab: matlab_comparison(runs, timings, papers),
        }
    }
}
