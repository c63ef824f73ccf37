//! A registered QP solver as a run's solver: robio2018's Algorithm 1 at every instant of a
//! fixed-step loop (the organisation of the papers' numerical-method simulations; the
//! networks' runs are the coupled ODE of [`crate::coupled`] instead). The solver is built by
//! the registry (`solvers::registry::build`) from the run's id and settings and called through
//! the one seam, [`qp::QpSolver`]: any registered solver (the six PLPE methods, the active set,
//! Clarabel, OSQP with its feature, an outside one) can be a run's.
//!
//! With sampling gap h and t_k = min(k h, T), k = 0 .. K = ceil(T / h):
//!
//! ```text
//! QP_k = scheme(t_k, theta_k)                       the scheme's QP at the sampled state
//! U_k  = the solver's answer to QP_k, started from what it left at t_{k-1}
//!        (a PLPE method: iterated from U_{k-1} until |e(U)|_2 <= tolerance, robio2018 (21))
//! theta_{k+1} = theta_k + (t_{k+1} - t_k) U_k[..n]  the command held over the step
//! ```
//!
//! (at the acceleration level the arm state [theta; thetadot] moves the same way with
//! thetaddot = U_k[..n]). The solver starts from its reset state (the PLPE methods: U_0 = 0). So the run's drift is the scheme's drift plus
//! what the method's stopping rule and the sampling add. Every instant is observed like an
//! accepted step of an integrated run, and scored against the exact optimum x*(t_k, theta_k)
//! where the experiment's `scoring` says. A run is bounded by its iteration budget
//! ([`ITERATIONS_PER_SECOND`] per second of the path), besides each instant's `max_iterations`.

use crate::coupled::{arm_dim, arm_slices, ExactLoop};
use crate::error::RunError;
use crate::observer::{score_instant, Observer};
use nalgebra::DVector;
use qp::QpStatus;
use schemes::Scheme;
use solvers::ode::OdeStats;
use solvers::registry::BoxedQpSolver;
use solvers::ExactPathStats;
use spec::Level;
use spec::NumericalSpec;
use spec::Scoring;
use std::time::Instant;

/// The iteration budget of a numerical run per second of its path's duration (at least one
/// second's): robio2018 (21) steps summed over the instants. The heaviest numerical runs of the
/// suite are the explanation's tolerance ladder's finest rungs (M3 on the five-pointed star at
/// |e|_2 <= 1e-8 ... 1e-10 need more than 1e6 per second: a budget of 1e6 failed them), and an
/// iteration of the papers' QP sizes takes about 0.1-0.2 us: at 2e7 per second a run that would
/// need more (a tolerance it cannot reach, a method that does not converge, with an iteration cap
/// as large as `max_iterations` allows) fails with that reason within a few seconds per second
/// of its path. One instant is never allowed more than the budget, so a run makes at most twice
/// it.
pub const ITERATIONS_PER_SECOND: u64 = 20_000_000;

/// The iteration budget of a run of `duration` seconds ([`ITERATIONS_PER_SECOND`]).
pub fn iteration_budget(duration: f64) -> u64 {
    (ITERATIONS_PER_SECOND as f64 * duration.max(1.0)).ceil() as u64
}

/// A numerical run solver's iterations (robio2018 (21) steps).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IterationStats {
    /// Over the whole run.
    pub total: u64,
    /// At the instant that needed most.
    pub max: u64,
    /// The work of the whole run in products with the LVI matrix
    /// ([`qp::QpSolve::products`] summed over the instants): the machine-independent cost,
    /// in the unit of the control tables; `None` for a solver that does not count them.
    pub products: Option<u64>,
}

/// What the loop produced: where it stopped and why (none when it completed), counts in the
/// integrator's terms (steps = instants after the first), the exact solves that scored it, and
/// the method's iterations.
pub(crate) struct NumericalRun {
    pub failure: Option<(f64, RunError)>,
    pub stats: OdeStats,
    pub qp: ExactPathStats,
    pub iterations: IterationStats,
    pub score_failures: usize,
}

/// The run's solver for QPs of the scheme's sizes, built by the registry from the spec's id
/// and settings, its iteration cap lowered to the run's budget where it takes one (one instant
/// may use the whole budget but not more); with the cap it was given.
fn build_solver(
    spec: &NumericalSpec,
    scheme: &dyn Scheme,
    budget: u64,
) -> Result<(BoxedQpSolver, Option<u32>), RunError> {
    let setup = |e: solvers::registry::RegistryError| {
        RunError::Setup(spec::SetupError::QpSolver(e.to_string()))
    };
    let mut settings = spec.resolved().map_err(|e| setup(e.into()))?;
    let requested = settings.max_iterations;
    settings.max_iterations = requested.map(|m| m.min(u32::try_from(budget).unwrap_or(u32::MAX)));
    let solver =
        solvers::registry::build(spec.method.id(), &settings, scheme.dims()).map_err(setup)?;
    Ok((solver, requested))
}

/// Runs the loop of the module docs from `theta0` over the path's duration `t1`, scored where
/// `scoring` says.
pub(crate) fn run_numerical(
    scheme: &dyn Scheme,
    spec: &NumericalSpec,
    theta0: &[f64],
    t1: f64,
    scoring: Scoring,
    observer: &mut Observer<'_>,
) -> Result<NumericalRun, RunError> {
    let n = scheme.joints();
    let started = Instant::now();
    let level = scheme.level();
    let dims = scheme.dims();
    let budget = iteration_budget(t1);
    let (mut solver, requested) = build_solver(spec, scheme, budget)?;
    let mut qp = scheme.new_qp();
    let mut scorer = ExactLoop::new(scheme);
    let mut y = vec![0.0; arm_dim(n, level)];
    y[..n].copy_from_slice(theta0);
    let mut x = DVector::<f64>::zeros(dims.nx);
    let instants = (t1 / spec.step).ceil().max(1.0) as usize;
    let mut iterations = IterationStats::default();
    let mut failures = 0usize;
    let mut next_score_t = 0.0;
    let mut failure: Option<(f64, RunError)> = None;
    for k in 0..=instants {
        let t = (k as f64 * spec.step).min(t1);
        let (theta, thetadot) = arm_slices(n, level, &y, &y);
        scheme.build(t, theta, thetadot, &mut qp);
        match solver.solve(&qp) {
            Ok(solve) => {
                let it = u64::from(solve.iterations);
                iterations.total += it;
                iterations.max = iterations.max.max(it);
                if let Some(p) = solve.products {
                    *iterations.products.get_or_insert(0) += p;
                }
            }
            // The budget, not the solver's own cap, stopped the instant.
            Err(e)
                if e.status == QpStatus::IterationLimit
                    && requested.is_some_and(|m| u64::from(m) > budget) =>
            {
                failure = Some((t, RunError::IterationBudget { t, budget }));
                break;
            }
            Err(error) => {
                let (status, message) = (error.status, error.to_string());
                failure = Some((t, RunError::Numerical { t, status, message }));
                break;
            }
        }
        if iterations.total > budget {
            failure = Some((t, RunError::IterationBudget { t, budget }));
            break;
        }
        x.as_mut_slice().copy_from_slice(solver.x());
        let observe = Instant::now();
        let (_, thetadot) = arm_slices(n, level, &y, x.as_slice());
        if score_instant(
            observer,
            &mut scorer,
            scoring,
            &mut next_score_t,
            t1,
            (t, theta, thetadot),
            &x,
        ) == Some(false)
        {
            failures += 1;
        }
        observer.sample(t, &y, &x, level);
        observer.seconds += observe.elapsed().as_secs_f64();
        if let Some(reason) = observer.divergence(&y) {
            failure = Some((t, RunError::Diverged { t, reason }));
            break;
        }
        if k == instants {
            break;
        }
        let h = (((k + 1) as f64) * spec.step).min(t1) - t;
        hold_command(n, level, &mut y, &x, h);
    }
    let stats = OdeStats {
        steps: instants,
        rhs_evals: instants + 1,
        wall_seconds: started.elapsed().as_secs_f64(),
        ..OdeStats::default()
    };
    Ok(NumericalRun {
        failure,
        stats,
        qp: scorer.stats(),
        iterations,
        score_failures: failures,
    })
}

/// Moves the arm state `y` over a step `h` with the command `x` held (module docs): theta by
/// h x[..n] at the velocity level; at the acceleration level theta by h thetadot, then thetadot
/// by h x[..n].
fn hold_command(n: usize, level: Level, y: &mut [f64], x: &DVector<f64>, h: f64) {
    match level {
        Level::Velocity => {
            for i in 0..n {
                y[i] += h * x[i];
            }
        }
        Level::Acceleration => {
            for i in 0..n {
                y[i] += h * y[n + i];
                y[n + i] += h * x[i];
            }
        }
    }
}
