//! What the drift attribution and the tolerance ladder of a paper's runs say
//! (`results/attribution.csv`, `results/ladder.csv`, written by crate `explain`): which runs were
//! explained, the terms of their sums and the share of the drift each carries, and how the
//! papers' norms compare with ours integrated at MATLAB's default tolerances (ode15s, RelTol
//! 1e-3, AbsTol 1e-6) instead of the stated 1e-6 / 1e-8. A run is named by its ids
//! ([`RunIds`]: experiment, variant, solver).

use crate::papers::{Mapping, Papers};
use records::{AttributionRow, Component};
use records::{LadderMethod, LadderRow};
use settings::Method;

/// A run's ids: (experiment, variant, solver).
pub type RunIds<'a> = (&'a str, &'a str, &'a str);

/// The ids of an attribution row's run.
fn ids_of(r: &AttributionRow) -> RunIds<'_> {
    (
        r.experiment.as_str(),
        r.variant_id.as_str(),
        r.solver_id.as_str(),
    )
}

/// The ids of a ladder row's run.
pub fn ladder_ids(r: &LadderRow) -> RunIds<'_> {
    (
        r.experiment.as_str(),
        r.variant_id.as_str(),
        r.solver_id.as_str(),
    )
}

/// The runs the attribution rows of `paper` explain, in file order.
pub fn runs_of<'a>(rows: &'a [AttributionRow], paper: &str) -> Vec<RunIds<'a>> {
    let mut out: Vec<RunIds> = Vec::new();
    for r in rows.iter().filter(|r| r.paper == paper) {
        let k = ids_of(r);
        if !out.contains(&k) {
            out.push(k);
        }
    }
    out
}

/// The row of component `name` of run `key`.
pub fn component<'a>(
    rows: &'a [AttributionRow],
    key: RunIds,
    name: Component,
) -> Option<&'a AttributionRow> {
    rows.iter()
        .find(|r| ids_of(r) == key && r.component == name)
}

/// The terms of the sums the attribution rows of `keys` use, in column order: the scheme,
/// then a network's lag and integration error and/or a numerical method's sampling gap and
/// stopping rule.
pub fn sum_components(rows: &[AttributionRow], keys: &[RunIds]) -> Vec<Component> {
    let mut out: Vec<Component> = rows
        .iter()
        .filter(|r| keys.contains(&ids_of(r)))
        .map(|r| r.component)
        .filter(|c| *c != Component::Run && !c.is_switch())
        .collect();
    out.sort();
    out.dedup();
    out
}

/// The switch effects ("of which") the attribution rows of `paper` hold, in column order.
pub fn switches(rows: &[AttributionRow], paper: &str) -> Vec<Component> {
    let mut out: Vec<Component> = rows
        .iter()
        .filter(|r| r.paper == paper && r.component.is_switch())
        .map(|r| r.component)
        .collect();
    out.sort();
    out.dedup();
    out
}

/// The component that holds the converged solver's error of run `key`: the second term of
/// its sum (a network's lag, or a numerical method's sampling gap).
pub fn converged_component(rows: &[AttributionRow], key: RunIds) -> Component {
    [Component::NetworkLag, Component::SamplingGap]
        .into_iter()
        .find(|c| component(rows, key, *c).is_some())
        .unwrap_or(Component::NetworkLag)
}

/// The shares of the drift (|d_component| / |d_run|) that each term of the sums carries over
/// the explained runs `keys`, in [`sum_components`]' order.
pub fn shares(rows: &[AttributionRow], keys: &[RunIds]) -> Vec<(Component, Vec<f64>)> {
    sum_components(rows, keys)
        .into_iter()
        .map(|c| {
            let v = keys
                .iter()
                .filter_map(|k| component(rows, *k, c).and_then(|r| r.share))
                .collect();
            (c, v)
        })
        .collect()
}

/// The smallest and the largest of `shares` (none when empty).
pub fn share_range(shares: &[f64]) -> Option<(f64, f64)> {
    let lo = shares.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = shares.iter().copied().fold(0.0, f64::max);
    (!shares.is_empty()).then_some((lo, hi))
}

/// Whether (method, rtol, atol) is MATLAB's default: ode15s (BDF) at RelTol 1e-3, AbsTol 1e-6.
pub fn is_matlab_setting(method: LadderMethod, rtol: f64, atol: f64) -> bool {
    method == LadderMethod::Integrator(Method::Bdf) && rtol == 1e-3 && atol == 1e-6
}

/// The rung at MATLAB's default tolerances ([`is_matlab_setting`]).
pub fn is_matlab_default(r: &LadderRow) -> bool {
    is_matlab_setting(r.method, r.rtol, r.atol)
}

/// Run `key`'s rung at MATLAB's default tolerances, completed or not.
pub fn matlab_rung<'a>(ladder: &'a [LadderRow], key: RunIds) -> Option<&'a LadderRow> {
    ladder
        .iter()
        .find(|r| ladder_ids(r) == key && is_matlab_default(r))
}

/// The mapping whose run is `key`.
fn mapping_of<'a>(papers: &'a Papers, key: RunIds) -> Option<&'a Mapping> {
    papers.mappings.iter().find(|m| {
        (
            m.run.experiment.as_str(),
            m.run.variant.as_str(),
            m.run.solver.as_str(),
        ) == key
    })
}

/// The paper's drift norm for run `key`, and whether it is derived from the printed joints.
pub fn published_norm(papers: &Papers, key: RunIds) -> Option<(f64, bool)> {
    mapping_of(papers, key).and_then(|m| papers.published(m, "drift_norm"))
}

/// The runs integrated at MATLAB's default tolerances against the same runs as run (at the
/// stated tolerances), over the published columns with both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MatlabTolerances {
    /// Columns compared.
    pub compared: usize,
    /// Of them, those where the paper's norm is nearer (in ratio, |ln(paper / ours)|) ours at
    /// MATLAB's defaults than ours as run.
    pub nearer_matlab: usize,
    /// The drift at MATLAB's defaults over the drift as run: smallest and largest.
    pub lo: f64,
    pub hi: f64,
}

/// [`MatlabTolerances`] over the explained runs `keys`; none when no column has both drifts.
pub fn matlab_tolerances(
    attribution: &[AttributionRow],
    ladder: &[LadderRow],
    papers: &Papers,
    keys: &[RunIds],
) -> Option<MatlabTolerances> {
    let mut nearer_matlab = 0;
    let mut compared = 0;
    let mut ratios = Vec::new();
    for key in keys {
        let Some((published, _)) = published_norm(papers, *key) else {
            continue;
        };
        let run = component(attribution, *key, Component::Run).and_then(|r| r.drift_norm);
        let matlab = ladder
            .iter()
            .find(|r| ladder_ids(r) == *key && is_matlab_default(r) && r.completed())
            .and_then(|r| r.drift_norm);
        if let (Some(run), Some(matlab)) = (run, matlab) {
            compared += 1;
            ratios.push(matlab / run);
            if (published / matlab).ln().abs() < (published / run).ln().abs() {
                nearer_matlab += 1;
            }
        }
    }
    (compared > 0).then(|| MatlabTolerances {
        compared,
        nearer_matlab,
        lo: ratios.iter().copied().fold(f64::INFINITY, f64::min),
        hi: ratios.iter().copied().fold(0.0, f64::max),
    })
}

/// Several published solver columns on one scheme (an experiment's variant): how far apart the
/// paper's drift norms are, and ours (largest / smallest).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolverSpread<'a> {
    pub experiment: &'a str,
    /// The variant's label (its id where no attribution row names it).
    pub variant: &'a str,
    /// Columns (solvers) with both norms.
    pub columns: usize,
    pub theirs: f64,
    pub ours: f64,
}

/// [`SolverSpread`] of each scheme of the explained runs `keys` with at least two columns.
pub fn solver_spreads<'a>(
    attribution: &'a [AttributionRow],
    papers: &Papers,
    keys: &[RunIds<'a>],
) -> Vec<SolverSpread<'a>> {
    let mut schemes: Vec<(&str, &str)> = keys.iter().map(|k| (k.0, k.1)).collect();
    schemes.dedup();
    let spread = |v: &[f64]| {
        v.iter().copied().fold(0.0, f64::max) / v.iter().copied().fold(f64::INFINITY, f64::min)
    };
    let mut out = Vec::new();
    for (experiment, variant) in schemes {
        let norms: Vec<(f64, f64)> = papers
            .mappings
            .iter()
            .filter(|m| m.run.experiment == experiment && m.run.variant == variant)
            .filter_map(|m| {
                let theirs = papers.published(m, "drift_norm")?.0;
                let k = &m.run;
                let ours = component(
                    attribution,
                    (&k.experiment, &k.variant, &k.solver),
                    Component::Run,
                )?
                .drift_norm?;
                Some((theirs, ours))
            })
            .collect();
        if norms.len() < 2 {
            continue;
        }
        let theirs: Vec<f64> = norms.iter().map(|n| n.0).collect();
        let ours: Vec<f64> = norms.iter().map(|n| n.1).collect();
        out.push(SolverSpread {
            experiment,
            variant: attribution
                .iter()
                .find(|r| r.experiment == experiment && r.variant_id == variant)
                .map_or(variant, |r| r.variant.as_str()),
            columns: norms.len(),
            theirs: spread(&theirs),
            ours: spread(&ours),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(solver: &str, component: Component, share: Option<f64>) -> AttributionRow {
        AttributionRow {
            paper: "p".into(),
            experiment: spec::ids::ExperimentId::new("e").unwrap(),
            variant_id: spec::ids::VariantId::new("v").unwrap(),
            solver_id: spec::ids::SolverId::new(solver.to_lowercase()).unwrap(),
            variant: "V".into(),
            solver: solver.into(),
            component,
            drift: Vec::new(),
            drift_norm: Some(1.0),
            share,
            max_pos_err: None,
            note: String::new(),
        }
    }

    #[test]
    fn shares_are_gathered_per_term_over_the_runs() {
        let rows = [
            row("a", Component::Run, None),
            row("a", Component::Scheme, Some(0.9)),
            row("a", Component::NetworkLag, Some(0.1)),
            row("b", Component::Run, None),
            row("b", Component::Scheme, Some(0.5)),
            row("b", Component::SamplingGap, Some(0.4)),
            row("b", Component::InjectedPerturbation, Some(0.2)),
        ];
        let keys = runs_of(&rows, "p");
        assert_eq!(keys, [("e", "v", "a"), ("e", "v", "b")]);
        assert_eq!(
            shares(&rows, &keys),
            [
                (Component::Scheme, vec![0.9, 0.5]),
                (Component::NetworkLag, vec![0.1]),
                (Component::SamplingGap, vec![0.4]),
            ]
        );
        assert_eq!(switches(&rows, "p"), [Component::InjectedPerturbation]);
        assert_eq!(converged_component(&rows, keys[1]), Component::SamplingGap);
        assert_eq!(share_range(&[0.9, 0.5]), Some((0.5, 0.9)));
        assert_eq!(share_range(&[]), None);
        // No published norm: nothing to set against MATLAB's tolerances or between solvers.
        let papers = Papers::default();
        assert!(matlab_tolerances(&rows, &[], &papers, &keys).is_none());
        assert!(solver_spreads(&rows, &papers, &keys).is_empty());
        assert!(is_matlab_setting(
            LadderMethod::Integrator(Method::Bdf),
            1e-3,
            1e-6
        ));
    }
}
