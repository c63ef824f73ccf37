//! The tolerance ladder: one run re-integrated at a sequence of tolerances and methods, to tell
//! which published digits could be integration noise.
//!
//! # Mathematics
//!
//! Let d(rtol) be the drift theta(T) - theta(0) of a run integrated with relative tolerance rtol
//! (absolute tolerance atol = rtol / 100, the ratio of the papers' RelTol 1e-6 / AbsTol 1e-8).
//! For a method of order p whose local error control works, the global error behaves like
//! C rtol^(p / (p + 1)), so d(rtol) converges as rtol -> 0. We take the finest rung that
//! completed as the converged value d* and report for every rung the relative change
//! |d(rtol) - d*| / |d*| (2-norm over the joints) and the digits it shares with d*,
//! -log10 of that change. A published digit at or beyond the digits shared at the paper's own
//! setting (ode15s, RelTol 1e-6, AbsTol 1e-8) could be integration noise.
//!
//! Rungs: BDF/NDF (ode15s's method) at MATLAB's defaults (RelTol 1e-3, AbsTol 1e-6) and at
//! RelTol 1e-3 ... 1e-10; a second method at the same RelTols (Dormand-Prince 5(4), ode45's
//! method; ESDIRK3(4) for the finite-time network); the run's own setting. A run with the
//! group's `MaxStep` keeps it on every rung. The exact column (Clarabel in the loop) is laddered
//! with its experiment's exact method (Dormand-Prince, or BDF where the scheme is stiff), down
//! to RelTol 1e-12. Explicit rungs
//! on the stiff networks (gamma = 1e7) cannot finish: rungs are capped at
//! [`LADDER_MAX_STEPS`] (explicit: [`LADDER_MAX_EXPLICIT_STEPS`]) accepted steps and an
//! unfinished rung is reported as such, not dropped.
//!
//! A numerical run (robio2018's methods in a fixed-step loop, `simulation::numerical`) has no
//! integrator tolerance: its error control is the stopping rule |e(U)|_2 <= tolerance at every
//! instant. Its rungs are the same loop, at the run's own step h, stopped at
//! [`NUMERICAL_TOLERANCES`] (1e-3 ... 1e-10); the finest completed one is d*(h), the drift of
//! the sampled scheme with the QP solved to 1e-10. Its rows carry the method
//! [`LadderMethod::FixedStep`], the stopping tolerance in `rtol`, `atol` = 0 and h in `max_step`.

use records::RunRow;
use records::{LadderMethod, LadderRow};
use settings::SolverSpec;
use settings::{IntegratorSettings, Method};
use spec::RunSpec;
use spec::Scoring;
use spec::SolverChoice;

/// Accepted steps after which an implicit ladder rung is abandoned (every implicit run of the
/// papers' experiments needs a few thousand; the finite-time network needed ~650,000 BDF steps
/// at RelTol 1e-6 until its coupled Jacobian took the chain rule through the QP data).
pub const LADDER_MAX_STEPS: usize = 100_000;
/// The same for explicit rungs: an explicit method on a network with gain 1e7 would need ~10^8
/// steps; 20,000 tell that it cannot finish.
pub const LADDER_MAX_EXPLICIT_STEPS: usize = 20_000;

/// RelTol of the BDF rungs (and of the second method's) of a neural run.
const NEURAL_RTOLS: [f64; 8] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
/// RelTol of the rungs of the exact column (its run is at 1e-11; 1e-12 is the reference).
const EXACT_RTOLS: [f64; 7] = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];
/// Stopping tolerances |e(U)|_2 <= tol of the rungs of a numerical run (robio2018 prints 1e-3).
pub const NUMERICAL_TOLERANCES: [f64; 8] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];

/// One rung: method and tolerances.
fn rung(method: Method, rtol: f64, atol: f64, max_step: Option<f64>) -> IntegratorSettings {
    IntegratorSettings {
        method,
        rtol,
        atol,
        max_steps: if method == Method::Dopri5 || method == Method::Tsit45 {
            LADDER_MAX_EXPLICIT_STEPS
        } else {
            LADDER_MAX_STEPS
        },
        max_step,
        ..IntegratorSettings::default()
    }
}

/// The integrator rungs of `job`'s ladder (none for a numerical run: see [`jobs`]). A neural run: BDF at MATLAB's defaults and at every RelTol,
/// then a second method at every RelTol (ESDIRK3(4) for the finite-time network, stiff in the
/// sign-power's band, where an explicit method cannot finish; Dormand-Prince otherwise), then
/// its own setting (with the group's MaxStep where it has one). The exact column: its
/// experiment's exact method (Dormand-Prince; BDF for kong2019, whose finite-time scheme is
/// stiff itself).
pub fn rungs(job: &RunSpec) -> Vec<IntegratorSettings> {
    let max_step = job.integrator.max_step;
    let mut out = Vec::new();
    match &job.solver {
        // A numerical run has no integrator tolerance: its rungs vary the stopping rule (jobs).
        SolverChoice::Numerical(_) => return out,
        SolverChoice::Exact => {
            out.extend(
                EXACT_RTOLS
                    .iter()
                    .map(|&r| rung(job.integrator.method, r, r / 100.0, None)),
            );
        }
        SolverChoice::Neural(spec) => {
            let finite_time = matches!(spec, SolverSpec::FiniteTime { .. });
            let second = if finite_time {
                Method::Esdirk34
            } else {
                Method::Dopri5
            };
            out.push(rung(Method::Bdf, 1e-3, 1e-6, max_step));
            for method in [Method::Bdf, second] {
                out.extend(
                    NEURAL_RTOLS
                        .iter()
                        .map(|&r| rung(method, r, r / 100.0, max_step)),
                );
            }
            // The run's own setting keeps its own step limit: it is the run of results/runs.csv.
            let own = job.integrator;
            if let Some(same) = out.iter_mut().find(|r| {
                (r.method, r.rtol, r.atol, r.max_step)
                    == (own.method, own.rtol, own.atol, own.max_step)
            }) {
                *same = own;
            } else {
                out.push(own);
            }
        }
    }
    out
}

/// The jobs of `job`'s ladder (scoring off: only drift and position error are read): its
/// `rungs`, or for a numerical run the same loop stopped at each of
/// [`NUMERICAL_TOLERANCES`] (the run's own tolerance kept where it is not among them; a QP
/// solver that takes no tolerance has the one rung, its own run).
pub fn jobs(job: &RunSpec) -> Vec<RunSpec> {
    let base = RunSpec {
        scoring: Scoring::Off,
        ..job.clone()
    };
    if let SolverChoice::Numerical(spec) = &job.solver {
        let Some(own) = spec.tolerance_in_effect() else {
            return vec![base];
        };
        let mut tolerances = NUMERICAL_TOLERANCES.to_vec();
        if !tolerances.contains(&own) {
            tolerances.push(own);
        }
        return tolerances
            .into_iter()
            .map(|tolerance| RunSpec {
                solver: SolverChoice::Numerical(spec::NumericalSpec {
                    tolerance: Some(tolerance),
                    ..*spec
                }),
                ..base.clone()
            })
            .collect();
    }
    rungs(job)
        .into_iter()
        .map(|integrator| RunSpec {
            integrator,
            ..base.clone()
        })
        .collect()
}

/// What a rung is, as its ladder row states it: (method, rtol, atol, max_step). For a
/// numerical run: ([`LadderMethod::FixedStep`], stopping tolerance (0 for a QP solver that
/// takes none), 0, Some(h)).
fn setting(job: &RunSpec) -> (LadderMethod, f64, f64, Option<f64>) {
    match &job.solver {
        SolverChoice::Numerical(spec) => (
            LadderMethod::FixedStep,
            spec.tolerance_in_effect().unwrap_or(0.0),
            0.0,
            Some(spec.step),
        ),
        _ => {
            let s = job.integrator;
            (
                LadderMethod::Integrator(s.method),
                s.rtol,
                s.atol,
                s.max_step,
            )
        }
    }
}

/// Relative 2-norm distance |a - b| / |b| of two drift vectors.
pub fn rel_distance(a: &[f64], b: &[f64]) -> f64 {
    let num: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    let den: f64 = b.iter().map(|y| y * y).sum();
    (num / den.max(f64::MIN_POSITIVE)).sqrt()
}

/// The converged reference among one run's rungs: the completed rung with the smallest
/// tolerance (RelTol, or a numerical run's stopping tolerance; ties: BDF before ESDIRK3(4)
/// before Dormand-Prince, then the smaller AbsTol), as an index into `rows` (`rows[i]` is the
/// run of `rungs[i]`).
pub fn reference(rungs: &[RunSpec], rows: &[RunRow]) -> Option<usize> {
    let preferred = |m: LadderMethod| match m {
        LadderMethod::Integrator(Method::Bdf) => 0,
        LadderMethod::Integrator(Method::Esdirk34) => 1,
        LadderMethod::Integrator(Method::Dopri5) => 2,
        _ => 3,
    };
    let settings: Vec<_> = rungs.iter().map(setting).collect();
    rows.iter()
        .enumerate()
        .filter(|(_, r)| r.completed())
        .min_by(|(a, _), (b, _)| {
            let (a, b) = (&settings[*a], &settings[*b]);
            a.1.total_cmp(&b.1)
                .then(preferred(a.0).cmp(&preferred(b.0)))
                .then(a.2.total_cmp(&b.2))
        })
        .map(|(i, _)| i)
}

/// The ladder rows of one run from its rungs' results (`rows[i]` is the run of `rungs[i]`,
/// one of [`jobs`]`(base)`). The rows carry `base`'s key and labels: a numerical rung's own
/// solver id names its tolerance.
pub fn ladder_rows(base: &RunSpec, rungs: &[RunSpec], rows: &[RunRow]) -> Vec<LadderRow> {
    let reference = reference(rungs, rows);
    let d_star = reference.map(|i| &rows[i].drift);
    let own = setting(base);
    rungs
        .iter()
        .zip(rows)
        .enumerate()
        .map(|(i, (job, r))| {
            let rel_change = d_star
                .as_ref()
                .filter(|_| r.completed())
                .map(|d| rel_distance(&r.drift, d));
            let (method, rtol, atol, max_step) = setting(job);
            let as_run = (method, rtol, atol, max_step) == own;
            LadderRow {
                paper: r.paper.clone(),
                experiment: r.experiment.clone(),
                variant_id: r.variant_id.clone(),
                solver_id: base.key().solver,
                variant: r.variant.clone(),
                solver: base.solver.label(),
                method,
                rtol,
                atol,
                max_step,
                as_run,
                status: r.status,
                failure: r.failure.clone(),
                drift: r.drift.clone(),
                drift_norm: r.drift_norm,
                max_pos_err: r.max_pos_err,
                rel_change: rel_change.filter(|_| Some(i) != reference),
                stable_digits: rel_change
                    .filter(|_| Some(i) != reference)
                    .map(|c| -c.max(1e-16).log10()),
                reference: Some(i) == reference,
                steps: r.steps,
                rejected: r.rejected,
                rhs_evals: r.rhs_evals,
                wall_s: r.wall_s,
            }
        })
        .collect()
}
