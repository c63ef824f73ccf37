//! Drift attribution: what each ingredient of a run adds to its drift and position error.
//!
//! # Mathematics
//!
//! For a run of a paper's solver let d_run be its drift theta(T) - theta(0) (per joint) at the
//! run's own integrator setting, d_net the same network integrated to convergence (the finest
//! completed rung of its [tolerance ladder](super::ladder)) and d_exact the exact column (Clarabel in
//! the loop) integrated to convergence (the finest Dormand-Prince rung). The telescoping sum
//!
//! ```text
//!   d_run = d_exact + (d_net - d_exact) + (d_run - d_net)
//!         = scheme  + network lag        + integration error
//! ```
//!
//! holds exactly, per joint. Ingredients that are switched rather than converged are measured
//! by one controlled re-run each, everything else held: the injected perturbation
//! (zhang2018's Delta_s, Delta_D; the group's code) as d_run - d_run(no perturbation); a path
//! that does not close (the group's butterfly as printed) as d_run - d_run(closed path); our
//! own regularisation of kong2019's sign-power as d_run - d_run(smoothing / 100) (switch runs
//! are capped at the ladder's step limit: the finer smoothing is stiffer still). These switch
//! effects overlap the three terms above (they are part of the scheme or of the network): they
//! are "of which" columns, not further summands. For the position error the same runs give
//! max_t |r* - f(theta)| of each; a switch row holds the difference of the two maxima.
//!
//! A numerical run (a method of robio2018 at every instant of a fixed-step loop of step h,
//! stopped at |e(U)|_2 <= tol) has no network and no integrator tolerance. With d*(h) the
//! finest completed rung of its ladder (the same loop and h, stopped at 1e-10):
//!
//! ```text
//!   d_run = d_exact + (d*(h) - d_exact) + (d_run - d*(h))
//!         = scheme  + sampling gap       + stopping rule
//! ```
//!
//! The sampling gap is what holding each instant's command over h adds (the loop's forward
//! Euler step), the stopping rule what ending each instant's iteration at tol adds.

use records::RunRow;
use records::{AttributionRow, Component};
use records::{LadderMethod, LadderRow};
use settings::SolverSpec;
use spec::RunSpec;
use spec::Scoring;
use spec::SolverChoice;

/// The largest RelTol whose rung may serve as a converged reference.
pub const CONVERGED_RTOL: f64 = 1e-8;

/// A controlled re-run that switches one ingredient off.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Switch {
    /// The injected perturbation removed.
    NoPerturbation,
    /// The path closed (the butterfly with its closing correction).
    ClosedPath,
    /// kong2019's sign-power linear zone delta divided by 100.
    FinerSmoothing,
}

impl Switch {
    /// The attribution component this switch measures.
    pub fn component(self) -> Component {
        match self {
            Switch::NoPerturbation => Component::InjectedPerturbation,
            Switch::ClosedPath => Component::PathNonClosure,
            Switch::FinerSmoothing => Component::SignPowerSmoothing,
        }
    }

    /// `job` with this ingredient switched off, or `None` when the run does not have it.
    pub fn apply(self, job: &RunSpec) -> Option<RunSpec> {
        let SolverChoice::Neural(spec) = &job.solver else {
            return None;
        };
        let mut out = RunSpec {
            scoring: Scoring::Off,
            ..job.clone()
        };
        out.integrator.max_steps = out
            .integrator
            .max_steps
            .min(super::ladder::LADDER_MAX_STEPS);
        match self {
            Switch::NoPerturbation => {
                let spec = without_perturbation(spec)?;
                out.solver = SolverChoice::Neural(spec);
            }
            Switch::ClosedPath => {
                if job.path.name != "butterfly-as-printed" {
                    return None;
                }
                out.path.name = "butterfly".to_string();
            }
            Switch::FinerSmoothing => {
                let SolverSpec::FiniteTime {
                    beta,
                    alpha,
                    smoothing,
                } = *spec
                else {
                    return None;
                };
                out.solver = SolverChoice::Neural(SolverSpec::FiniteTime {
                    beta,
                    alpha,
                    smoothing: smoothing / 100.0,
                });
            }
        }
        Some(out)
    }
}

/// Every switch, in report order.
pub const SWITCHES: [Switch; 3] = [
    Switch::NoPerturbation,
    Switch::ClosedPath,
    Switch::FinerSmoothing,
];

/// The solver without its injected perturbation, `None` when it has none.
fn without_perturbation(spec: &SolverSpec) -> Option<SolverSpec> {
    let mut s = spec.clone();
    match &mut s {
        SolverSpec::FpCdnn { perturbation, .. }
        | SolverSpec::VpCdnn { perturbation, .. }
        | SolverSpec::GroupZnn { perturbation, .. } => perturbation.take().map(|_| ()),
        _ => None,
    }?;
    Some(s)
}

/// The controlled re-runs of one target besides its ladders: (switch, job).
pub fn switch_jobs(job: &RunSpec) -> Vec<(Switch, RunSpec)> {
    SWITCHES
        .iter()
        .filter_map(|&s| s.apply(job).map(|j| (s, j)))
        .collect()
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The attribution rows of one run from its ladder, its exact column's ladder and its switch
/// runs. A numerical method's ladder ([`LadderMethod::FixedStep`] rungs) gives the sum scheme + sampling
/// gap + stopping rule, a network's scheme + network lag + integration error.
pub fn attribution_rows(
    neural: &[LadderRow],
    exact: &[LadderRow],
    switches: &[(Switch, RunRow)],
) -> Vec<AttributionRow> {
    let Some(run) = neural.iter().find(|r| r.as_run) else {
        return Vec::new();
    };
    let numerical = run.method == LadderMethod::FixedStep;
    let [_, lag, error] = if numerical {
        Component::NUMERICAL_SUM
    } else {
        Component::NETWORK_SUM
    };
    let converged_what = if numerical {
        "method at its finest stopping tolerance"
    } else {
        "converged network"
    };
    let drifts = |r: &LadderRow| r.completed().then(|| r.drift.clone());
    let d_run = drifts(run);
    // A reference counts as converged only from RelTol CONVERGED_RTOL on (the finite-time
    // network's ladder stops at 1e-4: it has none).
    let converged = |r: &&LadderRow| r.reference && r.rtol <= CONVERGED_RTOL;
    let net_ref = neural.iter().find(converged);
    let exact_ref = exact.iter().find(converged);
    let d_net = net_ref.and_then(drifts);
    let d_exact = exact_ref.and_then(drifts);
    let run_norm = d_run.as_deref().map(norm);
    let row = |component: Component, d: Option<Vec<f64>>, err: Option<f64>, note: &str| {
        let n = d.as_deref().map(norm);
        AttributionRow {
            paper: run.paper.clone(),
            experiment: run.experiment.clone(),
            variant_id: run.variant_id.clone(),
            solver_id: run.solver_id.clone(),
            variant: run.variant.clone(),
            solver: run.solver.clone(),
            component,
            drift: d.clone().unwrap_or_default(),
            drift_norm: n,
            share: n.zip(run_norm).map(|(a, b)| a / b),
            max_pos_err: err,
            note: if d.is_some() {
                String::new()
            } else {
                note.to_string()
            },
        }
    };
    let diff = |a: &Option<Vec<f64>>, b: &Option<Vec<f64>>| -> Option<Vec<f64>> {
        let (a, b) = (a.as_ref()?, b.as_ref()?);
        Some(a.iter().zip(b).map(|(x, y)| x - y).collect())
    };
    let unfinished = |r: Option<&LadderRow>, what: &str| match r {
        None => format!("no {what} rung completed at RelTol <= {CONVERGED_RTOL:e}"),
        Some(r) => format!("{what}: {}", r.failure),
    };
    let mut rows = vec![
        row(Component::Run, d_run.clone(), run.max_pos_err, &run.failure),
        row(
            Component::Scheme,
            d_exact.clone(),
            exact_ref.and_then(|r| r.max_pos_err),
            &unfinished(exact_ref, "exact"),
        ),
        row(
            lag,
            diff(&d_net, &d_exact),
            net_ref.and_then(|r| r.max_pos_err),
            &unfinished(net_ref, converged_what),
        ),
        row(
            error,
            diff(&d_run, &d_net),
            None,
            &unfinished(net_ref, converged_what),
        ),
    ];
    for (s, r) in switches {
        let d_off = r.completed().then(|| r.drift.clone());
        let err = run.max_pos_err.zip(r.max_pos_err).map(|(a, b)| a - b);
        let note = if d_run.is_none() {
            format!("the run itself failed: {}", run.failure)
        } else {
            format!("run without it: {}", r.failure)
        };
        rows.push(row(s.component(), diff(&d_run, &d_off), err, &note));
    }
    rows
}

/// The exact counterpart of `job` (same variant, Clarabel in the loop), whose ladder gives the
/// converged scheme drift.
pub fn exact_counterpart(job: &RunSpec) -> RunSpec {
    RunSpec {
        solver: SolverChoice::Exact,
        scoring: Scoring::Off,
        ..job.clone()
    }
}
