//! Running one [`Job`]: build robot, path, scheme and solver, integrate, collect metrics, the
//! score against the exact optimum and a thinned trace for the figures.

use crate::coupled::{arm_dim, arm_state, ExactLoop, NeuralLoop};
use crate::error::RunError;
use crate::experiment::{Job, NetworkInit, SolverChoice};
use crate::metrics::{MetricsAccumulator, RunMetrics, Sample, ScoreSample};
use crate::robot_registry::{robot_by_name, RobotVisitor};
use nalgebra::{DVector, SVector};
use robots::{Dynamics, Robot};
use schemes::paths::{build_path, Path};
use schemes::scheme::{Level, Scheme};
use schemes::spec::build_scheme;
use solvers::exact_path::ExactPathStats;
use solvers::ode::{integrate, Control, OdeError, OdeFailure, OdeStats, OdeSystem};
use solvers::ExactError;
use std::sync::Arc;
use std::time::Instant;

/// Samples kept per run for the figures (uniform in t, plus the last).
const TRACE_POINTS: usize = 400;

/// A run stops as diverging when a joint velocity exceeds this many times its bound (the
/// papers' schemes keep every joint inside its bound; 10x is far outside anything a run that
/// recovers reaches, and MTN's blow-up passes it within a fraction of a second).
pub const DIVERGENCE_FACTOR: f64 = 10.0;
/// ... or when an entry of the integrated state (angles, velocities, network state) exceeds this.
pub const DIVERGENCE_STATE: f64 = 1e6;

/// One row of a run's trace.
#[derive(Clone, Debug, PartialEq)]
pub struct TracePoint {
    pub t: f64,
    pub theta: Vec<f64>,
    pub thetadot: Vec<f64>,
    pub thetaddot: Option<Vec<f64>>,
    pub torque: Option<Vec<f64>>,
    pub desired: [f64; 3],
    pub actual: [f64; 3],
    /// |x_nn - x*|_inf at this instant (neural runs).
    pub score_dx: Option<f64>,
    /// The network's own error norm at this instant (where it has one).
    pub network_error: Option<f64>,
}

/// Outcome of a run.
#[derive(Clone, Debug)]
pub enum Outcome {
    Completed(RunMetrics),
    /// The run stopped at t; `partial` holds the metrics up to there (peaks, errors, margins;
    /// its drift is theta(t) - theta0, not a drift over the task).
    Failed {
        t: f64,
        error: RunError,
        partial: Option<RunMetrics>,
    },
}

/// Everything a run produces.
#[derive(Clone, Debug)]
pub struct RunRecord {
    pub job: Job,
    pub scheme_name: String,
    pub outcome: Outcome,
    pub stats: OdeStats,
    /// Exact QP solves (in the loop for the exact column, for scoring in neural runs), with the
    /// active-set solver's fallbacks to Clarabel and the Clarabel sample.
    pub qp: ExactPathStats,
    /// Scoring instants where Clarabel failed (excluded from the score).
    pub score_failures: usize,
    /// Seconds spent observing accepted steps (metrics, trace, and the Clarabel solves that
    /// score the run or give the exact column's thetadot); part of the ODE's wall time.
    pub observe_seconds: f64,
    pub trace: Vec<TracePoint>,
}

/// Runs one job to completion or failure; never panics on bad numerics.
pub fn run_job(job: &Job) -> RunRecord {
    struct Run<'a>(&'a Job);
    impl RobotVisitor for Run<'_> {
        type Output = Result<RunRecord, RunError>;
        fn visit<const N: usize>(
            self,
            robot: Arc<dyn Robot<N>>,
            dynamics: Option<Arc<dyn Dynamics<N>>>,
        ) -> Self::Output {
            run_with::<N>(self.0, robot, dynamics)
        }
    }
    let result = match robot_by_name(&job.robot) {
        Some(robot) => robot.visit(Run(job)),
        None => Err(RunError::Setup {
            part: JobPart::Robot,
            message: format!("unknown robot \"{}\"", job.robot),
        }),
    };
    result.unwrap_or_else(|error| RunRecord {
        job: job.clone(),
        scheme_name: job.scheme.display_name(),
        outcome: Outcome::Failed {
            t: 0.0,
            error,
            partial: None,
        },
        stats: OdeStats::default(),
        qp: ExactPathStats::default(),
        score_failures: 0,
        observe_seconds: 0.0,
        trace: Vec::new(),
    })
}

/// Which part of a [`Job`] could not be built (see [`check_job`]).
#[derive(Clone, Debug, PartialEq)]
pub enum JobPart {
    Robot,
    Theta0,
    ThetaRef,
    Path,
    Scheme,
    Solver,
}

impl JobPart {
    /// The experiment-file field the part comes from.
    pub fn field(&self) -> &'static str {
        match self {
            JobPart::Robot => "robot",
            JobPart::Theta0 => "theta0",
            JobPart::ThetaRef => "theta_ref",
            JobPart::Path => "path",
            JobPart::Scheme => "scheme",
            JobPart::Solver => "solvers",
        }
    }
}

/// Builds everything a run builds before integrating (robot, path from f(theta_ref), scheme,
/// and the network for the scheme's QP sizes) without integrating anything, so that an
/// experiment file is rejected at load for exactly what would make its run fail at t = 0.
/// The error names the part (and so the file's field) and the builder's own message.
pub fn check_job(job: &Job) -> Result<(), (JobPart, String)> {
    fn with<const N: usize>(
        job: &Job,
        robot: Arc<dyn Robot<N>>,
        dynamics: Option<Arc<dyn Dynamics<N>>>,
    ) -> Result<(), (JobPart, String)> {
        for (part, v) in [
            (JobPart::Theta0, &job.theta0),
            (JobPart::ThetaRef, &job.theta_ref),
        ] {
            if v.len() != N {
                return Err((
                    part,
                    format!("has {} entries, the robot has {N} joints", v.len()),
                ));
            }
            if v.iter().any(|x| !x.is_finite()) {
                return Err((part, "entries must be finite".to_string()));
            }
        }
        let (_, scheme) = build_parts::<N>(job, robot, dynamics)?;
        if let SolverChoice::Neural(spec) = &job.solver {
            solvers::neural::build_solver(spec, scheme.dims()).map_err(|e| {
                (
                    JobPart::Solver,
                    format!("{}: {e} (scheme {})", spec.display_name(), scheme.name()),
                )
            })?;
        }
        Ok(())
    }
    struct Check<'a>(&'a Job);
    impl RobotVisitor for Check<'_> {
        type Output = Result<(), (JobPart, String)>;
        fn visit<const N: usize>(
            self,
            robot: Arc<dyn Robot<N>>,
            dynamics: Option<Arc<dyn Dynamics<N>>>,
        ) -> Self::Output {
            with::<N>(self.0, robot, dynamics)
        }
    }
    match robot_by_name(&job.robot) {
        Some(robot) => robot.visit(Check(job)),
        None => Err((JobPart::Robot, format!("unknown robot \"{}\"", job.robot))),
    }
}

/// The path (starting at f(theta_ref)) and the scheme of a run.
#[allow(clippy::type_complexity)]
fn build_parts<const N: usize>(
    job: &Job,
    robot: Arc<dyn Robot<N>>,
    dynamics: Option<Arc<dyn Dynamics<N>>>,
) -> Result<(Arc<dyn Path>, Box<dyn Scheme<N>>), (JobPart, String)> {
    let theta_ref = SVector::<f64, N>::from_column_slice(&job.theta_ref);
    let start = robot.position(&theta_ref);
    let path: Arc<dyn Path> =
        Arc::from(build_path(&job.path, start).map_err(|e| (JobPart::Path, e.to_string()))?);
    let scheme = build_scheme::<N>(
        &job.scheme,
        robot.clone(),
        dynamics,
        path.clone(),
        theta_ref,
    )
    .map_err(|e| {
        let mut message = e.to_string();
        if let schemes::spec::SchemeError::MissingDynamics { .. } = e {
            message.push_str(&format!(
                " (robot \"{}\" is kinematic only; robots with dynamics: {})",
                job.robot,
                crate::robot_registry::robots_with_dynamics().join(", ")
            ));
        }
        (JobPart::Scheme, message)
    })?;
    Ok((path, scheme))
}

fn run_with<const N: usize>(
    job: &Job,
    robot: Arc<dyn Robot<N>>,
    dynamics: Option<Arc<dyn Dynamics<N>>>,
) -> Result<RunRecord, RunError> {
    let theta0 = SVector::<f64, N>::from_column_slice(&job.theta0);
    let theta_ref = SVector::<f64, N>::from_column_slice(&job.theta_ref);
    let (path, scheme) = build_parts::<N>(job, robot.clone(), dynamics)
        .map_err(|(part, message)| RunError::Setup { part, message })?;
    let mut observer = Observer::new(
        robot.as_ref(),
        scheme.as_ref(),
        path.as_ref(),
        theta0,
        theta_ref,
    );
    let t1 = path.duration();
    let level = scheme.level();
    let (outcome, stats, qp) = match &job.solver {
        SolverChoice::Exact => {
            let mut sys = ExactLoop::new(scheme.as_ref());
            let mut y0 = vec![0.0; arm_dim::<N>(level)];
            y0[..N].copy_from_slice(theta0.as_slice());
            let mut probe = ExactLoop::new(scheme.as_ref());
            let mut exact_failure = None;
            let result = integrate(&mut sys, &y0, 0.0, t1, &job.integrator, |t, y| {
                let started = Instant::now();
                let (theta, thetadot) = arm_state::<N>(level, y, y);
                let control = match probe.optimum(t, &theta, &thetadot) {
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
        SolverChoice::Neural(spec) => {
            let network = solvers::neural::build_solver(spec, scheme.dims()).map_err(|e| {
                RunError::Setup {
                    part: JobPart::Solver,
                    message: e.to_string(),
                }
            })?;
            let mut sys = NeuralLoop::new(scheme.as_ref(), network);
            let k = sys.net_offset();
            let mut y0 = vec![0.0; sys.dim()];
            y0[..N].copy_from_slice(theta0.as_slice());
            let mut scorer = ExactLoop::new(scheme.as_ref());
            if job.network_init == NetworkInit::Exact {
                // x*(0) at the arm's initial state (at the velocity level thetadot is the
                // command itself, which the QP does not depend on).
                let thetadot0 = match level {
                    Level::Velocity => SVector::zeros(),
                    Level::Acceleration => SVector::from_column_slice(&y0[N..2 * N]),
                };
                let x0 = scorer
                    .optimum(0.0, &theta0, &thetadot0)
                    .map_err(|error| RunError::ExactQp { t: 0.0, error })?;
                y0[k..k + x0.len()].copy_from_slice(x0.as_slice());
            }
            // A second instance of the network, to read its own error at accepted states.
            let mut probe = solvers::neural::build_solver(spec, scheme.dims()).map_err(|e| {
                RunError::Setup {
                    part: JobPart::Solver,
                    message: e.to_string(),
                }
            })?;
            let mut failures = 0usize;
            let result = integrate(&mut sys, &y0, 0.0, t1, &job.integrator, |t, y| {
                let started = Instant::now();
                let x_nn = DVector::from_column_slice(&y[k..k + scheme.dims().nx]);
                let (theta, thetadot) = arm_state::<N>(level, y, &y[k..]);
                if !job.score {
                    observer.sample(t, y, &x_nn, level);
                    observer.seconds += started.elapsed().as_secs_f64();
                    return observer
                        .divergence(y)
                        .map_or(Control::Continue, Control::Stop);
                }
                match scorer.optimum(t, &theta, &thetadot) {
                    Ok(x_star) => {
                        let qp = &scorer.qp;
                        let f_star = qp.objective(&x_star);
                        let dx = (x_nn.rows(0, N) - x_star.rows(0, N)).amax();
                        observer.score(
                            t,
                            &ScoreSample {
                                dx,
                                objective_gap: (qp.objective(&x_nn) - f_star)
                                    / f_star.abs().max(1.0),
                                violation: qp.constraint_violation(&x_nn),
                            },
                        );
                    }
                    Err(_) => failures += 1,
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
    Ok(RunRecord {
        job: job.clone(),
        scheme_name: scheme.name(),
        outcome,
        stats,
        qp,
        score_failures: observer.score_failures,
        observe_seconds: observer.seconds,
        trace: observer.trace,
    })
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

/// Turns accepted steps into metrics and a thinned trace.
struct Observer<'a, const N: usize> {
    robot: &'a dyn Robot<N>,
    scheme: &'a dyn Scheme<N>,
    path: &'a dyn Path,
    metrics: MetricsAccumulator<N>,
    trace: Vec<TracePoint>,
    next_trace_t: f64,
    last_t: f64,
    /// Joint velocities at the last accepted step (for [`Self::divergence`]).
    last_thetadot: SVector<f64, N>,
    last_dx: Option<f64>,
    last_network_error: Option<f64>,
    score_failures: usize,
    /// Wall time spent in the observer (see [`RunRecord::observe_seconds`]).
    seconds: f64,
}

impl<'a, const N: usize> Observer<'a, N> {
    fn new(
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

    fn has_samples(&self) -> bool {
        !self.trace.is_empty()
    }

    fn score(&mut self, t: f64, s: &ScoreSample) {
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
    fn divergence(&self, y: &[f64]) -> Option<String> {
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
    fn sample(&mut self, t: f64, y: &[f64], x: &DVector<f64>, level: Level) {
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
