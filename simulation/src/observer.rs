//! The observer of a run: every accepted step (or sampled instant) of the arm becomes metrics
//! ([`crate::metrics`]) and a thinned trace, the run is stopped when it diverges, and the
//! command is scored against the exact optimum where the experiment's scoring says
//! (`score_instant`). Shared by the integrated runs ([`crate::simulate`]), the fixed-step
//! loop of the numerical methods ([`crate::numerical`]) and a trajectory scored from a file
//! ([`crate::score_trajectory`]).

use crate::coupled::{arm_slices, ExactLoop};
use crate::metrics::{MetricsAccumulator, Sample, ScoreSample};
use nalgebra::{DVector, Matrix3xX};
use records::TracePoint;
use robots::Robot;
use schemes::paths::Path;
use schemes::Scheme;
use spec::Level;
use spec::Scoring;

/// Samples kept per run for the figures (uniform in t, plus the last).
const TRACE_POINTS: usize = 400;

/// A run stops as diverging when a joint velocity exceeds this many times its bound (the
/// papers' schemes keep every joint inside its bound; 10x is far outside anything a run that
/// recovers reaches, and MTN's blow-up passes it within a fraction of a second).
pub const DIVERGENCE_FACTOR: f64 = 10.0;
/// ... or when an entry of the integrated state (angles, velocities, network state) exceeds this.
pub const DIVERGENCE_STATE: f64 = 1e6;

/// Scores the command `x` at the state `(t, theta, thetadot)` against the exact optimum there,
/// when `scoring` says the instant is due (`next_score_t` keeps the grid of
/// [`Scoring::MaxInstants`]): `None` when not due, `Some(false)` when the exact solver failed
/// (the instant is left out of the score), `Some(true)` when scored.
pub(crate) fn score_instant(
    observer: &mut Observer<'_>,
    scorer: &mut ExactLoop<'_>,
    scoring: Scoring,
    next_score_t: &mut f64,
    t1: f64,
    (t, theta, thetadot): (f64, &[f64], &[f64]),
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
    let Ok((x_star, qp)) = scorer.optimum(t, theta, thetadot) else {
        return Some(false);
    };
    let f_star = qp.objective(x_star);
    // |x - x*|_inf over the joint command without a vector of differences, folded as
    // nalgebra's `amax` folds (from the first entry, m >= v ? m : v, so a NaN is kept as
    // nalgebra keeps it).
    let mut diffs = x
        .iter()
        .zip(x_star.iter())
        .take(theta.len())
        .map(|(a, b)| (a - b).abs());
    let first = diffs.next().unwrap_or(0.0);
    let dx = diffs.fold(first, |m, v| if m >= v { m } else { v });
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

/// Turns accepted steps into metrics and a thinned trace (also the samples of a trajectory
/// scored by [`crate::score_trajectory()`]).
pub(crate) struct Observer<'a> {
    robot: &'a dyn Robot,
    scheme: &'a dyn Scheme,
    path: &'a dyn Path,
    pub(crate) metrics: MetricsAccumulator,
    pub(crate) trace: Vec<TracePoint>,
    next_trace_t: f64,
    pub(crate) last_t: f64,
    /// Joint velocities at the last accepted step (for [`Self::divergence`]).
    last_thetadot: Vec<f64>,
    /// The arm's state, command, torque and Jacobian at the step being sampled (allocated once).
    theta: Vec<f64>,
    thetaddot: Vec<f64>,
    torque: Vec<f64>,
    jacobian: Matrix3xX<f64>,
    last_dx: Option<f64>,
    last_network_error: Option<f64>,
    pub(crate) score_failures: usize,
    /// Wall time spent in the observer (see [`crate::RunRecord::observe_seconds`]).
    pub(crate) seconds: f64,
}

impl<'a> Observer<'a> {
    pub(crate) fn new(
        robot: &'a dyn Robot,
        scheme: &'a dyn Scheme,
        path: &'a dyn Path,
        theta0: &[f64],
        theta_ref: &[f64],
    ) -> Self {
        let n = robot.dof();
        Self {
            robot,
            scheme,
            path,
            metrics: MetricsAccumulator::new(robot.limits().clone(), theta0, theta_ref),
            trace: Vec::with_capacity(TRACE_POINTS + 2),
            next_trace_t: 0.0,
            last_t: 0.0,
            last_thetadot: vec![0.0; n],
            theta: vec![0.0; n],
            thetaddot: vec![0.0; n],
            torque: vec![0.0; n],
            jacobian: Matrix3xX::zeros(n),
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

    pub(crate) fn network_error(&mut self, t: f64, e: f64) {
        self.metrics.push_network_error(t, e);
        self.last_network_error = Some(e);
    }

    /// Why the run is diverging at the state just sampled, if it is: a joint velocity beyond
    /// [`DIVERGENCE_FACTOR`] times its bound, or a state entry beyond [`DIVERGENCE_STATE`]. The
    /// run stops there with that reason instead of integrating a blow-up to the step limit.
    pub(crate) fn divergence(&self, y: &[f64]) -> Option<String> {
        let limits = self.robot.limits();
        for (i, &v) in self.last_thetadot.iter().enumerate() {
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
        let n = self.theta.len();
        let (theta, thetadot) = arm_slices(n, level, y, x.as_slice());
        self.theta.copy_from_slice(theta);
        self.last_thetadot.copy_from_slice(thetadot);
        let (theta, thetadot) = (&self.theta[..], &self.last_thetadot[..]);
        let thetaddot = (level == Level::Acceleration).then(|| {
            self.thetaddot.copy_from_slice(&x.as_slice()[..n]);
            &self.thetaddot[..]
        });
        let torque = match thetaddot {
            Some(a) if self.scheme.torque(theta, thetadot, a, &mut self.torque) => {
                Some(&self.torque[..])
            }
            _ => None,
        };
        let desired = self.path.at(t).r;
        let actual = self.robot.position(theta);
        self.robot.jacobian(theta, self.jacobian.as_mut_slice());
        let s = Sample {
            t,
            theta,
            thetadot,
            thetaddot,
            torque,
            desired,
            actual,
            jacobian: &self.jacobian,
        };
        self.metrics.push(&s);
        let duration = self.path.duration();
        let is_end = t >= duration * (1.0 - 1e-12);
        if t >= self.next_trace_t || is_end {
            self.trace.push(TracePoint {
                t,
                theta: theta.to_vec(),
                thetadot: thetadot.to_vec(),
                thetaddot: thetaddot.map(<[f64]>::to_vec),
                torque: torque.map(<[f64]>::to_vec),
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
