//! The simulation proper: a robot following a path under a scheme, the scheme's QP solved at
//! every instant by the exact optimum or by a recurrent network integrated together with the
//! arm, observed at every accepted step (metrics, the score against the exact optimum, a
//! thinned trace). [`simulate`] takes trait objects (`Robot<N>`, `Path`, `Scheme<N>`,
//! `NeuralSolver`): the experiment files' factories ([`crate::run`]) are one way to build them,
//! a user's own types another (`examples/`).
//!
//! The coupled ODE ([`crate::coupled`]): at the velocity level the state is [theta; y_net] with
//! thetadot = x[..N]; at the acceleration level [theta; thetadot; y_net] with thetaddot =
//! x[..N]. The exact column integrates theta alone with x = x*(t, theta).

use crate::coupled::{arm_dim, arm_state, ExactLoop, NeuralLoop};
use crate::error::RunError;
use crate::metrics::{MetricsAccumulator, RunMetrics, Sample, ScoreSample};
use catalog::error::SetupError;
use catalog::experiment::{NetworkInit, Scoring};
use catalog::numerical_spec::NumericalSpec;
use nalgebra::{DVector, SVector};
use records::trace::TracePoint;
use robots::Robot;
use schemes::paths::Path;
use schemes::scheme::{Level, Scheme};
use schemes::slice_scheme::Fixed;
use settings::integrator::IntegratorSettings;
use solvers::exact_path::ExactPathStats;
use solvers::neural::NeuralSolver;
use solvers::ode::{integrate, Control, OdeError, OdeFailure, OdeStats, OdeSystem};
use solvers::ExactError;
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
    /// ([`crate::numerical`]), scored like a network.
    Numerical(&'a NumericalSpec),
}

/// A numerical run solver's iterations (robio2018 (21) steps).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IterationStats {
    /// Over the whole run.
    pub total: u64,
    /// At the instant that needed most.
    pub max: u64,
    /// The work of the whole run in products with the LVI matrix
    /// (`solvers::lvi_numerical::LviMethod::products` summed over the instants): the
    /// machine-independent cost, in the unit of the control tables.
    pub products: u64,
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

/// Samples kept per run for the figures (uniform in t, plus the last).
const TRACE_POINTS: usize = 400;

/// A run stops as diverging when a joint velocity exceeds this many times its bound (the
/// papers' schemes keep every joint inside its bound; 10x is far outside anything a run that
/// recovers reaches, and MTN's blow-up passes it within a fraction of a second).
pub const DIVERGENCE_FACTOR: f64 = 10.0;
/// ... or when an entry of the integrated state (angles, velocities, network state) exceeds this.
pub const DIVERGENCE_STATE: f64 = 1e6;

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
pub fn simulate<const N: usize>(
    robot: &dyn Robot<N>,
    path: &dyn Path,
    scheme: &dyn Scheme<N>,
    solver: Solver<'_>,
    theta0: &SVector<f64, N>,
    theta_ref: &SVector<f64, N>,
    settings: &Settings,
) -> Result<Run, RunError> {
    let theta0 = *theta0;
    let fixed = Fixed(scheme);
    let mut observer = Observer::new(robot, scheme, path, theta0, *theta_ref);
    let t1 = path.duration();
    let level = scheme.level();
    let mut iterations = None;
    let (outcome, stats, qp) = match solver {
        Solver::Numerical(spec) => {
            let r =
                crate::numerical::run_numerical(scheme, spec, &theta0, t1, settings, &mut observer);
            iterations = Some(r.iterations);
            observer.score_failures = r.score_failures;
            (r.outcome, r.stats, r.qp)
        }
        Solver::Exact => {
            let mut sys = ExactLoop::new(&fixed);
            let mut y0 = vec![0.0; arm_dim(N, level)];
            y0[..N].copy_from_slice(theta0.as_slice());
            let mut probe = ExactLoop::new(&fixed);
            let mut exact_failure = None;
            let result = integrate(&mut sys, &y0, 0.0, t1, &settings.integrator, |t, y| {
                let started = Instant::now();
                let (theta, thetadot) = arm_state::<N>(level, y, y);
                let control = match probe.optimum(t, theta.as_slice(), thetadot.as_slice()) {
                    Ok(x) => {
                        observer.sample(t, y, &x, level);
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
                &observer,
                solves,
            )
        }
        Solver::Network(build) => {
            let network = build()?;
            let mut sys = NeuralLoop::new(&fixed, network);
            let k = sys.net_offset();
            let mut y0 = vec![0.0; sys.dim()];
            y0[..N].copy_from_slice(theta0.as_slice());
            let mut scorer = ExactLoop::new(&fixed);
            if settings.network_init == NetworkInit::Exact {
                // x*(0) at the arm's initial state (at the velocity level thetadot is the
                // command itself, which the QP does not depend on).
                let thetadot0: SVector<f64, N> = match level {
                    Level::Velocity => SVector::zeros(),
                    Level::Acceleration => SVector::from_column_slice(&y0[N..2 * N]),
                };
                let x0 = scorer
                    .optimum(0.0, theta0.as_slice(), thetadot0.as_slice())
                    .map_err(|error| RunError::ExactQp { t: 0.0, error })?;
                y0[k..k + x0.len()].copy_from_slice(x0.as_slice());
            }
            // A second instance of the network, to read its own error at accepted states.
            let mut probe = build()?;
            let mut failures = 0usize;
            let mut next_score_t = 0.0;
            let result = integrate(&mut sys, &y0, 0.0, t1, &settings.integrator, |t, y| {
                let started = Instant::now();
                let x_nn = DVector::from_column_slice(&y[k..k + scheme.dims().nx]);
                let (theta, thetadot) = arm_state::<N>(level, y, &y[k..]);
                let scored = score_instant(
                    &mut observer,
                    &mut scorer,
                    settings.scoring,
                    &mut next_score_t,
                    t1,
                    (t, &theta, &thetadot),
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
            let mut r = finish(result, None, &observer, scorer.stats());
            r.1.rhs_evals += sys.jacobian_rhs_evals;
            observer.score_failures = failures;
            r
        }
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

/// Scores the command `x` at the state `(t, theta, thetadot)` against the exact optimum there,
/// when `scoring` says the instant is due (`next_score_t` keeps the grid of
/// [`Scoring::MaxInstants`]): `None` when not due, `Some(false)` when the exact solver failed
/// (the instant is left out of the score), `Some(true)` when scored.
pub(crate) fn score_instant<const N: usize>(
    observer: &mut Observer<'_, N>,
    scorer: &mut ExactLoop<'_>,
    scoring: Scoring,
    next_score_t: &mut f64,
    t1: f64,
    (t, theta, thetadot): (f64, &SVector<f64, N>, &SVector<f64, N>),
    x: &DVector<f64>,
) -> Option<bool> {
    let due = match scoring {
        Scoring::EveryStep => true,
        Scoring::Off => false,
        Scoring::MaxInstants(n) => {
            let due = t >= *next_score_t || t >= t1 * (1.0 - 1e-12);
            if due {
                *next_score_t = t + t1 / n.max(1) as f64;
            }
            due
        }
    };
    if !due {
        return None;
    }
    let Ok(x_star) = scorer.optimum(t, theta.as_slice(), thetadot.as_slice()) else {
        return Some(false);
    };
    let qp = &scorer.qp;
    let f_star = qp.objective(&x_star);
    let dx = (x.rows(0, N) - x_star.rows(0, N)).amax();
    observer.score(
        t,
        &ScoreSample {
            dx,
            objective_gap: (qp.objective(x) - f_star) / f_star.abs().max(1.0),
            violation: qp.constraint_violation(x),
        },
    );
    Some(true)
}

fn finish<const N: usize>(
    result: Result<(Vec<f64>, OdeStats), OdeFailure>,
    exact_failure: Option<(f64, ExactError)>,
    observer: &Observer<'_, N>,
    qp: ExactPathStats,
) -> (Outcome, OdeStats, ExactPathStats) {
    match result {
        Ok((_, stats)) => (Outcome::Completed(observer.metrics.finish(0.0)), stats, qp),
        Err(OdeFailure { error, stats }) => {
            // The last accepted step; an exact-QP failure names its own instant. The observer
            // stops a run only for divergence or an exact-QP failure.
            let t = observer.last_t;
            let error = match (exact_failure, error) {
                (Some((t, error)), _) => RunError::ExactQp { t, error },
                (None, OdeError::Stopped { t, reason }) => RunError::Diverged { t, reason },
                (None, e) => RunError::Integration(e),
            };
            let partial = observer.has_samples().then(|| observer.metrics.finish(0.0));
            (Outcome::Failed { t, error, partial }, stats, qp)
        }
    }
}

/// Turns accepted steps into metrics and a thinned trace (also the samples of a trajectory
/// scored by [`crate::score_trajectory`]).
pub(crate) struct Observer<'a, const N: usize> {
    robot: &'a dyn Robot<N>,
    scheme: &'a dyn Scheme<N>,
    path: &'a dyn Path,
    pub(crate) metrics: MetricsAccumulator<N>,
    pub(crate) trace: Vec<TracePoint>,
    next_trace_t: f64,
    last_t: f64,
    /// Joint velocities at the last accepted step (for [`Self::divergence`]).
    last_thetadot: SVector<f64, N>,
    last_dx: Option<f64>,
    last_network_error: Option<f64>,
    pub(crate) score_failures: usize,
    /// Wall time spent in the observer (see [`RunRecord::observe_seconds`]).
    pub(crate) seconds: f64,
}

impl<'a, const N: usize> Observer<'a, N> {
    pub(crate) fn new(
        robot: &'a dyn Robot<N>,
        scheme: &'a dyn Scheme<N>,
        path: &'a dyn Path,
        theta0: SVector<f64, N>,
        theta_ref: SVector<f64, N>,
    ) -> Self {
        Self {
            robot,
            scheme,
            path,
            metrics: MetricsAccumulator::new(robot.limits(), theta0, theta_ref),
            trace: Vec::with_capacity(TRACE_POINTS + 2),
            next_trace_t: 0.0,
            last_t: 0.0,
            last_thetadot: SVector::zeros(),
            last_dx: None,
            last_network_error: None,
            score_failures: 0,
            seconds: 0.0,
        }
    }

    pub(crate) fn has_samples(&self) -> bool {
        !self.trace.is_empty()
    }

    pub(crate) fn score(&mut self, t: f64, s: &ScoreSample) {
        self.metrics.push_score(t, s);
        self.last_dx = Some(s.dx);
    }

    fn network_error(&mut self, t: f64, e: f64) {
        self.metrics.push_network_error(t, e);
        self.last_network_error = Some(e);
    }

    /// Why the run is diverging at the state just sampled, if it is: a joint velocity beyond
    /// [`DIVERGENCE_FACTOR`] times its bound, or a state entry beyond [`DIVERGENCE_STATE`]. The
    /// run stops there with that reason instead of integrating a blow-up to the step limit.
    pub(crate) fn divergence(&self, y: &[f64]) -> Option<String> {
        let limits = self.robot.limits();
        for i in 0..N {
            let v = self.last_thetadot[i];
            let bound = limits.thetadot_max[i].max(-limits.thetadot_min[i]);
            if bound.is_finite() && v.abs() > DIVERGENCE_FACTOR * bound {
                return Some(format!(
                    "diverging: |thetadot_{}| = {:.3e} rad/s exceeds {DIVERGENCE_FACTOR} x its bound {bound} rad/s",
                    i + 1,
                    v.abs()
                ));
            }
        }
        let peak = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        (peak > DIVERGENCE_STATE || !peak.is_finite()).then(|| {
            format!("diverging: a state entry reached {peak:.3e} (limit {DIVERGENCE_STATE:e})")
        })
    }

    /// Records the accepted state y at t with joint command x (x[..n] = thetadot or thetaddot).
    pub(crate) fn sample(&mut self, t: f64, y: &[f64], x: &DVector<f64>, level: Level) {
        let (theta, thetadot) = arm_state::<N>(level, y, x.as_slice());
        let thetaddot = (level == Level::Acceleration)
            .then(|| SVector::<f64, N>::from_column_slice(&x.as_slice()[..N]));
        let torque = thetaddot.and_then(|a| self.scheme.torque(&theta, &thetadot, &a));
        let desired = self.path.at(t).r;
        let actual = self.robot.position(&theta);
        let s = Sample {
            t,
            theta,
            thetadot,
            thetaddot,
            torque,
            desired,
            actual,
            jacobian: self.robot.jacobian(&theta),
        };
        self.metrics.push(&s);
        self.last_thetadot = thetadot;
        let duration = self.path.duration();
        let is_end = t >= duration * (1.0 - 1e-12);
        if t >= self.next_trace_t || is_end {
            self.trace.push(TracePoint {
                t,
                theta: theta.iter().copied().collect(),
                thetadot: thetadot.iter().copied().collect(),
                thetaddot: thetaddot.map(|a| a.iter().copied().collect()),
                torque: torque.map(|a| a.iter().copied().collect()),
                desired: [desired.x, desired.y, desired.z],
                actual: [actual.x, actual.y, actual.z],
                score_dx: self.last_dx,
                network_error: self.last_network_error,
            });
            self.next_trace_t = t + duration / TRACE_POINTS as f64;
        }
        self.last_t = t;
    }
}
