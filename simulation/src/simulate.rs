//! The simulation proper: a robot following a path under a scheme, the scheme's QP solved at
//! every instant by the exact optimum or by a recurrent network integrated together with the
//! arm, observed at every accepted step (metrics, the score against the exact optimum, a
//! thinned trace). [`simulate`] takes trait objects (`Robot`, `Path`, `Scheme`,
//! `NeuralSolver`): the experiment files' factories ([`crate::run`]) are one way to build them,
//! a user's own types another (`examples/`).
//!
//! The coupled ODE ([`crate::coupled`]): at the velocity level the state is [theta; y_net] with
//! thetadot = x[..N]; at the acceleration level [theta; thetadot; y_net] with thetaddot =
//! x[..N]. The exact column integrates theta alone with x = x*(t, theta).

use crate::coupled::{arm_dim, arm_slices, ExactLoop, NeuralLoop};
use crate::error::RunError;
use crate::metrics::RunMetrics;
use crate::numerical::{run_numerical, IterationStats};
use crate::observer::{score_instant, Observer};
use nalgebra::DVector;
use records::TracePoint;
use robots::Robot;
use schemes::paths::Path;
use schemes::Scheme;
use spec::JobPart;
use spec::Level;
use spec::NumericalSpec;
use spec::SetupError;
use spec::{NetworkInit, Scoring};

use settings::IntegratorSettings;
use solvers::neural::NeuralSolver;
use solvers::ode::{integrate, Control, OdeError, OdeFailure, OdeStats, OdeSystem};
use solvers::ExactError;
use solvers::ExactPathStats;
use std::time::Instant;

/// What solves the scheme's QP along a run.
pub enum Solver<'a> {
    /// The exact optimum in the loop: the certified active-set solver, Clarabel when it fails
    /// and on a sample ([`solvers::ExactPath`]).
    Exact,
    /// A recurrent network integrated together with the arm, scored against the exact optimum
    /// at every accepted step. The closure builds it (called twice: the network, and a probe
    /// that reads the network's own error at accepted states).
    Network(&'a dyn Fn() -> Result<Box<dyn NeuralSolver>, SetupError>),
    /// A numerical QP method iterated at every instant of a fixed-step loop
    /// (`numerical`), scored like a network.
    Numerical(&'a NumericalSpec),
}

/// How a run is integrated and observed.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// The integrator of the coupled arm + solver ODE.
    pub integrator: IntegratorSettings,
    /// Where a network is scored against the exact optimum.
    pub scoring: Scoring,
    /// Where a network's state starts.
    pub network_init: NetworkInit,
}

/// Outcome of a run.
#[derive(Clone, Debug)]
pub enum Outcome {
    /// The run reached the path's end: its metrics.
    Completed(RunMetrics),
    /// The run stopped at t; `partial` holds the metrics up to there (peaks, errors, margins;
    /// its drift is theta(t) - theta0, not a drift over the task).
    Failed {
        /// When it stopped (s): the last accepted step, or the failing instant (0 when the run
        /// could not be built).
        t: f64,
        /// Why it stopped.
        error: RunError,
        /// The metrics up to t; `None` when no step was observed.
        partial: Option<RunMetrics>,
    },
}

/// Everything a simulation produces.
#[derive(Clone, Debug)]
pub struct Run {
    /// The scheme's name (`VLTCO`, ...).
    pub scheme_name: String,
    /// How the run ended, with its metrics.
    pub outcome: Outcome,
    /// The integrator's cost (for a numerical run: steps are the instants after the first).
    pub stats: OdeStats,
    /// Exact QP solves (in the loop for the exact column, for scoring in neural runs), with the
    /// active-set solver's fallbacks to Clarabel and the Clarabel sample.
    pub qp: ExactPathStats,
    /// Scoring instants where Clarabel failed (excluded from the score).
    pub score_failures: usize,
    /// Seconds spent observing accepted steps (metrics, trace, and the Clarabel solves that
    /// score the run or give the exact column's thetadot); part of the ODE's wall time.
    pub observe_seconds: f64,
    /// Samples for the figures: about 400, uniform in t, and the last.
    pub trace: Vec<TracePoint>,
    /// A numerical run solver's iterations; none for the exact column and the networks.
    pub iterations: Option<IterationStats>,
}

/// Simulates `robot` following `path` under `scheme`, its QP solved by `solver`, from joint
/// angles `theta0` (`theta_ref`: the scheme's joint reference, where the drift margins are
/// measured from), integrated and observed as `settings` say. The library's entry point: every
/// argument is a trait object, so a network, scheme, path or robot written outside the suite
/// runs exactly as the papers' do (see `examples/`). Errors only when the run cannot start (a
/// network that cannot be built, no exact optimum at t = 0 for `NetworkInit::Exact`); a run
/// that stops early is an `Ok` [`Run`] with [`Outcome::Failed`].
pub fn simulate(
    robot: &dyn Robot,
    path: &dyn Path,
    scheme: &dyn Scheme,
    solver: Solver<'_>,
    theta0: &[f64],
    theta_ref: &[f64],
    settings: &Settings,
) -> Result<Run, RunError> {
    let joints = robot.dof();
    for (part, v) in [(JobPart::Theta0, theta0), (JobPart::ThetaRef, theta_ref)] {
        if v.len() != joints || scheme.joints() != joints {
            return Err(SetupError::PoseLength {
                part,
                given: v.len(),
                joints,
            }
            .into());
        }
    }
    let mut observer = Observer::new(robot, scheme, path, theta0, theta_ref);
    let t1 = path.duration();
    let mut iterations = None;
    let (outcome, stats, qp) = match solver {
        Solver::Numerical(spec) => {
            let r = run_numerical(scheme, spec, theta0, t1, settings.scoring, &mut observer)?;
            iterations = Some(r.iterations);
            observer.score_failures = r.score_failures;
            (outcome(&observer, r.failure), r.stats, r.qp)
        }
        Solver::Exact => run_exact(scheme, theta0, t1, settings, &mut observer),
        Solver::Network(build) => run_network(scheme, build, theta0, t1, settings, &mut observer)?,
    };
    Ok(Run {
        scheme_name: scheme.name(),
        outcome,
        stats,
        qp,
        score_failures: observer.score_failures,
        observe_seconds: observer.seconds,
        trace: observer.trace,
        iterations,
    })
}

/// The exact column: theta alone integrated with x = x*(t, theta) in the loop, every accepted
/// step observed with the optimum there (solved a second time by a probe, so that the loop's
/// own solves are not disturbed); an exact-QP failure stops the run at its instant.
fn run_exact(
    scheme: &dyn Scheme,
    theta0: &[f64],
    t1: f64,
    settings: &Settings,
    observer: &mut Observer<'_>,
) -> (Outcome, OdeStats, ExactPathStats) {
    let n = scheme.joints();
    let level = scheme.level();
    let mut sys = ExactLoop::new(scheme);
    let mut y0 = vec![0.0; arm_dim(n, level)];
    y0[..n].copy_from_slice(theta0);
    let mut probe = ExactLoop::new(scheme);
    let mut exact_failure = None;
    let result = integrate(&mut sys, &y0, 0.0, t1, &settings.integrator, |t, y| {
        let started = Instant::now();
        let (theta, thetadot) = arm_slices(n, level, y, y);
        let control = match probe.optimum(t, theta, thetadot) {
            Ok((x, _)) => {
                observer.sample(t, y, x, level);
                observer
                    .divergence(y)
                    .map_or(Control::Continue, Control::Stop)
            }
            Err(e) => {
                let stop = Control::Stop(format!("exact QP at t = {t:.6}: {e}"));
                exact_failure.get_or_insert((t, e));
                stop
            }
        };
        observer.seconds += started.elapsed().as_secs_f64();
        control
    });
    let mut solves = sys.stats();
    solves.add(&probe.stats());
    finish(
        result,
        sys.failure.take().or(exact_failure),
        observer,
        solves,
    )
}

/// A network integrated together with the arm (the coupled ODE of [`crate::NeuralLoop`]), its
/// state started at zero or at x*(0) ([`NetworkInit`]), scored against the exact optimum where
/// `settings.scoring` says and its own error read at those states by a second instance of the
/// network. Errors when the network cannot be built or x*(0) cannot be solved.
fn run_network(
    scheme: &dyn Scheme,
    build: &dyn Fn() -> Result<Box<dyn NeuralSolver>, SetupError>,
    theta0: &[f64],
    t1: f64,
    settings: &Settings,
    observer: &mut Observer<'_>,
) -> Result<(Outcome, OdeStats, ExactPathStats), RunError> {
    let n = scheme.joints();
    let level = scheme.level();
    let network = build()?;
    let mut sys = NeuralLoop::new(scheme, network);
    let k = sys.net_offset();
    let mut y0 = vec![0.0; sys.dim()];
    y0[..n].copy_from_slice(theta0);
    let mut scorer = ExactLoop::new(scheme);
    if settings.network_init == NetworkInit::Exact {
        // x*(0) at the arm's initial state (at the velocity level thetadot is the
        // command itself, which the QP does not depend on).
        let thetadot0 = match level {
            Level::Velocity => vec![0.0; n],
            Level::Acceleration => y0[n..2 * n].to_vec(),
        };
        let (x0, _) = scorer
            .optimum(0.0, theta0, &thetadot0)
            .map_err(|error| RunError::ExactQp { t: 0.0, error })?;
        y0[k..k + x0.len()].copy_from_slice(x0.as_slice());
    }
    // A second instance of the network, to read its own error at accepted states.
    let mut probe = build()?;
    let mut failures = 0usize;
    let mut next_score_t = 0.0;
    // The network's estimate at the accepted step (allocated once).
    let mut x_nn = DVector::zeros(scheme.dims().nx);
    let result = integrate(&mut sys, &y0, 0.0, t1, &settings.integrator, |t, y| {
        let started = Instant::now();
        x_nn.copy_from_slice(&y[k..k + x_nn.len()]);
        let (theta, thetadot) = arm_slices(n, level, y, &y[k..]);
        let scored = score_instant(
            observer,
            &mut scorer,
            settings.scoring,
            &mut next_score_t,
            t1,
            (t, theta, thetadot),
            &x_nn,
        );
        match scored {
            None => {
                observer.sample(t, y, &x_nn, level);
                observer.seconds += started.elapsed().as_secs_f64();
                return observer
                    .divergence(y)
                    .map_or(Control::Continue, Control::Stop);
            }
            Some(false) => failures += 1,
            Some(true) => {}
        }
        // scorer.qp holds the QP at this state even when Clarabel failed on it.
        if let Some(e) = probe.error_norm(&scorer.qp, &y[k..]) {
            observer.network_error(t, e);
        }
        observer.sample(t, y, &x_nn, level);
        observer.seconds += started.elapsed().as_secs_f64();
        observer
            .divergence(y)
            .map_or(Control::Continue, Control::Stop)
    });
    let mut r = finish(result, None, observer, scorer.stats());
    r.1.rhs_evals += sys.jacobian_rhs_evals;
    observer.score_failures = failures;
    Ok(r)
}

/// The outcome of an integrated run from the integrator's result: completed, or failed at the
/// last accepted step with the reason (an exact-QP failure names its own instant; the observer
/// stops a run only for divergence or an exact-QP failure).
fn finish(
    result: Result<(Vec<f64>, OdeStats), OdeFailure>,
    exact_failure: Option<(f64, ExactError)>,
    observer: &Observer<'_>,
    qp: ExactPathStats,
) -> (Outcome, OdeStats, ExactPathStats) {
    match result {
        Ok((_, stats)) => (outcome(observer, None), stats, qp),
        Err(OdeFailure { error, stats }) => {
            let t = observer.last_t;
            let error = match (exact_failure, error) {
                (Some((t, error)), _) => RunError::ExactQp { t, error },
                (None, OdeError::Stopped { t, reason }) => RunError::Diverged { t, reason },
                (None, e) => RunError::Integration(e),
            };
            (outcome(observer, Some((t, error))), stats, qp)
        }
    }
}

/// A run's outcome from what the observer saw: completed without a `failure`, else failed at
/// its instant with the metrics up to there (when any step was observed).
fn outcome(observer: &Observer<'_>, failure: Option<(f64, RunError)>) -> Outcome {
    match failure {
        None => Outcome::Completed(observer.metrics.finish(0.0)),
        Some((t, error)) => Outcome::Failed {
            t,
            error,
            partial: observer.has_samples().then(|| observer.metrics.finish(0.0)),
        },
    }
}
