//! Why a paper's drifts are what they are, read from the explanation layer's rows
//! (`results/attribution.csv`, `results/ladder.csv`; [`crate::drift_attribution`]), once per
//! render: the runs of the paper's solver that were explained, the terms of their sums
//! (d_run = d_exact + the lag + the integration error for a network, d_exact + the sampling
//! gap + the stopping rule for a numerical method, joint by joint) and the share
//! |component| / |d_run| each carries over those runs, the solvers' spreads on one scheme,
//! what MATLAB's default tolerances (ode15s, RelTol 1e-3, AbsTol 1e-6) would change, and the
//! tolerance ladder's rungs and cells. The report's "why" sections format it.

use super::Explained;
use crate::drift_attribution::{
    component, converged_component, is_matlab_setting, ladder_ids, matlab_rung, matlab_tolerances,
    published_norm, runs_of, share_range, shares, solver_spreads, sum_components, switches,
    MatlabTolerances, RunIds, SolverSpread,
};
use crate::papers::Papers;
use records::{AttributionRow, Component};
use records::{LadderMethod, LadderRow};

/// One paper's "why": its drift attribution and its tolerance ladder, each absent where the
/// paper has no row of it.
#[derive(Clone, Debug)]
pub struct Why<'a> {
    /// The paper id (or the group's, `crate::paper_rules::GROUP`).
    pub paper: &'a str,
    /// The attribution of its explained runs (none without one).
    pub attribution: Option<Attribution<'a>>,
    /// Its tolerance ladder (none without a rung).
    pub ladder: Option<Ladder<'a>>,
}

/// The attribution of a paper's explained runs.
#[derive(Clone, Debug)]
pub struct Attribution<'a> {
    /// The terms of the sums, in column order ([`sum_components`]).
    pub terms: Vec<Component>,
    /// The "of which" switches of the paper's runs ([`switches`]).
    pub switches: Vec<Component>,
    /// Every explained run, in file order.
    pub runs: Vec<AttributedRun<'a>>,
    /// Each term of the sums with the smallest and largest share it carries over the runs
    /// (none where no run has a share of it).
    pub shares: Vec<(Component, Option<(f64, f64)>)>,
    /// How far apart several solvers of one scheme are, the paper's and ours.
    pub spreads: Vec<SolverSpread<'a>>,
    /// The runs at MATLAB's default tolerances against the same runs as run.
    pub matlab: Option<MatlabTolerances>,
}

/// One explained run: its rows and the paper's norm.
#[derive(Clone, Debug)]
pub struct AttributedRun<'a> {
    /// Its ids.
    pub key: RunIds<'a>,
    /// The paper's drift norm, and whether it is derived from the printed joints.
    pub published_norm: Option<(f64, bool)>,
    /// The row of the run as run ([`Component::Run`]).
    pub run: Option<&'a AttributionRow>,
    /// Its rung at MATLAB's default tolerances, completed or not.
    pub matlab_rung: Option<&'a LadderRow>,
    /// Its row of each column: the sums' terms, then the switches.
    pub columns: Vec<Option<&'a AttributionRow>>,
    /// The row of the exact column, converged ([`Component::Scheme`]).
    pub scheme: Option<&'a AttributionRow>,
    /// The row of the converged solver (network or numerical method).
    pub converged: Option<&'a AttributionRow>,
}

/// The tolerance ladder of a paper's runs.
#[derive(Clone, Debug)]
pub struct Ladder<'a> {
    /// The rungs, sorted by method id, then from the loosest tolerances to the tightest.
    pub rungs: Vec<Rung>,
    /// Every run of the ladder, in file order, with its row at each rung.
    pub runs: Vec<LadderRun<'a>>,
    /// Whether a numerical method's fixed-step rungs are among them.
    pub fixed_step: bool,
}

/// A rung of the ladder.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rung {
    pub method: LadderMethod,
    pub rtol: f64,
    pub atol: f64,
    /// MATLAB's default setting ([`is_matlab_setting`]).
    pub matlab: bool,
}

/// A run of the ladder.
#[derive(Clone, Debug)]
pub struct LadderRun<'a> {
    /// Its ids.
    pub key: RunIds<'a>,
    /// Its first row (its labels).
    pub first: &'a LadderRow,
    /// Its row at each rung (same order as [`Ladder::rungs`]).
    pub cells: Vec<Option<&'a LadderRow>>,
}

impl<'a> Why<'a> {
    /// The "why" of `paper` from the rows of `explained`, against the published norms of
    /// `papers`.
    pub(super) fn build(paper: &'a str, explained: Explained<'a>, papers: &Papers) -> Self {
        Why {
            paper,
            attribution: Attribution::build(paper, explained, papers),
            ladder: Ladder::build(paper, explained.ladder),
        }
    }
}

impl<'a> Attribution<'a> {
    fn build(paper: &str, explained: Explained<'a>, papers: &Papers) -> Option<Self> {
        let (attribution, ladder) = (explained.attribution, explained.ladder);
        let keys = runs_of(attribution, paper);
        if keys.is_empty() {
            return None;
        }
        let terms = sum_components(attribution, &keys);
        let switches = switches(attribution, paper);
        let columns: Vec<Component> = terms.iter().chain(&switches).copied().collect();
        let runs = keys
            .iter()
            .map(|&key| AttributedRun {
                key,
                published_norm: published_norm(papers, key),
                run: component(attribution, key, Component::Run),
                matlab_rung: matlab_rung(ladder, key),
                columns: columns
                    .iter()
                    .map(|c| component(attribution, key, *c))
                    .collect(),
                scheme: component(attribution, key, Component::Scheme),
                converged: component(attribution, key, converged_component(attribution, key)),
            })
            .collect();
        Some(Attribution {
            shares: shares(attribution, &keys)
                .into_iter()
                .map(|(c, v)| (c, share_range(&v)))
                .collect(),
            spreads: solver_spreads(attribution, papers, &keys),
            matlab: matlab_tolerances(attribution, ladder, papers, &keys),
            terms,
            switches,
            runs,
        })
    }
}

impl<'a> Ladder<'a> {
    fn build(paper: &str, ladder: &'a [LadderRow]) -> Option<Self> {
        let rows: Vec<&LadderRow> = ladder.iter().filter(|r| r.paper == paper).collect();
        if rows.is_empty() {
            return None;
        }
        let mut rungs: Vec<(LadderMethod, f64, f64)> = Vec::new();
        for r in &rows {
            let k = (r.method, r.rtol, r.atol);
            if !rungs.contains(&k) {
                rungs.push(k);
            }
        }
        rungs.sort_by(|a, b| {
            a.0.id()
                .cmp(b.0.id())
                .then(b.1.total_cmp(&a.1))
                .then(b.2.total_cmp(&a.2))
        });
        let mut runs: Vec<LadderRun> = Vec::new();
        for &r in &rows {
            let key = ladder_ids(r);
            if runs.iter().any(|run| run.key == key) {
                continue;
            }
            let cells = rungs
                .iter()
                .map(|(m, rt, at)| {
                    rows.iter()
                        .find(|r| {
                            ladder_ids(r) == key && r.method == *m && r.rtol == *rt && r.atol == *at
                        })
                        .copied()
                })
                .collect();
            runs.push(LadderRun {
                key,
                first: r,
                cells,
            });
        }
        Some(Ladder {
            fixed_step: rows.iter().any(|r| r.method == LadderMethod::FixedStep),
            rungs: rungs
                .into_iter()
                .map(|(method, rtol, atol)| Rung {
                    method,
                    rtol,
                    atol,
                    matlab: is_matlab_setting(method, rtol, atol),
                })
                .collect(),
            runs,
        })
    }
}
