//! Metrics accumulated along a run, one accepted integrator step at a time.
//!
//! - drift: theta(T) - theta0 per joint and its 2-norm (also against the reference theta*0
//!   where a paper distinguishes it, kong2019);
//! - end-effector position error e(t) = |r*(t) - f(theta(t))|_2: max, RMS (time-weighted by the
//!   trapezoidal rule over the accepted steps) and final value;
//! - joint-angle and joint-velocity limit margins: min over joints and time of the distance to
//!   each finite limit (negative = violated);
//! - peaks of |thetadot|_inf, |thetaddot|_inf and |tau|_inf (acceleration level);
//! - sigma_min of the 3 x n position Jacobian along the run (distance from singularity);
//! - the score of a neural solver against the exact QP optimum at the same (t, state): max and
//!   RMS (time-weighted, trapezoidal) |x_nn - x*|_inf over the joint command, max relative
//!   objective gap (f(x_nn) - f(x*)) / max(1, |f(x*)|), max constraint violation of x_nn;
//! - the network's own error norm (|Q y - u| for the zeroing networks, kong2019's J_E; the
//!   projection residual for LVI-PDNN and S-LVI-PDNN): final value and largest value after
//!   t = 1 s (kong2019's "settles within ~1 s").

use nalgebra::{DVector, Matrix3, Matrix3xX, Vector3};
use robots::JointLimits;

/// One sample of the arm's motion at an accepted step (joint vectors borrowed from the
/// observer's buffers, one entry per joint).
#[derive(Clone, Copy, Debug)]
pub struct Sample<'a> {
    /// Time (s).
    pub t: f64,
    /// Joint angles theta (rad).
    pub theta: &'a [f64],
    /// Joint velocities thetadot (rad/s): the command at the velocity level, the state at the
    /// acceleration level.
    pub thetadot: &'a [f64],
    /// Joint acceleration (acceleration level only).
    pub thetaddot: Option<&'a [f64]>,
    /// Joint torque tau (N m), for schemes with a dynamics model.
    pub torque: Option<&'a [f64]>,
    /// Desired task-point position r*(t) (m).
    pub desired: Vector3<f64>,
    /// Actual task-point position f(theta) (m).
    pub actual: Vector3<f64>,
    /// Position Jacobian J(theta).
    pub jacobian: &'a Matrix3xX<f64>,
}

/// The largest magnitude of `v`.
fn amax(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m: f64, x| m.max(x.abs()))
}

/// Comparison of a neural solver's output with the exact optimum at one instant.
#[derive(Clone, Copy, Debug)]
pub struct ScoreSample {
    /// |x_nn - x*|_inf over the joint command x[..n].
    pub dx: f64,
    /// (f(x_nn) - f(x*)) / max(1, |f(x*)|).
    pub objective_gap: f64,
    /// Largest constraint violation of x_nn.
    pub violation: f64,
}

/// Score of a neural run against Clarabel along its own trajectory.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Score {
    /// Score samples: instants compared with the exact optimum.
    pub samples: usize,
    /// Largest |x_nn - x*|_inf over the joint command (rad/s at the velocity level, rad/s^2 at the
    /// acceleration level).
    pub max_dx: f64,
    /// RMS of dx over the run, time-weighted (trapezoid of dx^2 in t, divided by the span).
    pub rms_dx: f64,
    /// The same over t >= [`SETTLE_TIME`] only, after the start-up transient of a network
    /// started from zero (dx^2 interpolated linearly at the settling instant); `None` when no
    /// score sample lies at or after it.
    pub rms_dx_after_settle: Option<f64>,
    /// Largest relative objective gap (f(x_nn) - f(x*)) / max(1, |f(x*)|).
    pub max_objective_gap: f64,
    /// Largest constraint violation of x_nn.
    pub max_violation: f64,
}

/// The network's own error norm along a run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NetworkError {
    /// The error norm at the last accepted step.
    pub final_value: f64,
    /// Largest value at t >= [`SETTLE_TIME`] (0 if the run ended before).
    pub max_after_settle: f64,
}

/// The settling time (s): kong2019's for its network error ("settles within ~1 s"), also the
/// start of the settled score ([`Score::rms_dx_after_settle`]).
pub const SETTLE_TIME: f64 = 1.0;

/// Final metrics of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct RunMetrics {
    /// Joint drift theta(T) - theta0 (rad), one per joint.
    pub drift: Vec<f64>,
    /// |theta(T) - theta0|_2 (rad).
    pub drift_norm: f64,
    /// |theta(T) - theta_ref|_2 (rad): the drift from the scheme's reference (kong2019's theta*0).
    pub drift_ref_norm: f64,
    /// Largest end-effector position error |r*(t) - f(theta(t))|_2 (m).
    pub max_position_error: f64,
    /// RMS of the position error over the run (m), time-weighted by the trapezoidal rule.
    pub rms_position_error: f64,
    /// Position error at the last accepted step (m).
    pub final_position_error: f64,
    /// Smallest distance of a joint angle to a finite limit over joints and time (rad; negative:
    /// violated; +inf when no limit is finite).
    pub theta_margin: f64,
    /// Smallest distance of a joint velocity to a finite limit over joints and time (rad/s;
    /// negative: violated; +inf when no limit is finite).
    pub thetadot_margin: f64,
    /// Largest |thetadot|_inf over the run (rad/s).
    pub peak_thetadot: f64,
    /// Largest |thetaddot|_inf over the run (rad/s^2); acceleration level only.
    pub peak_thetaddot: Option<f64>,
    /// Largest |tau|_inf over the run (N m); schemes with a dynamics model only.
    pub peak_torque: Option<f64>,
    /// Smallest singular value of the position Jacobian over the run (m/rad): the distance from
    /// a singularity.
    pub min_sigma_j: f64,
    /// The score against the exact optimum; `None` when no instant was scored (the exact column,
    /// scoring off).
    pub score: Option<Score>,
    /// The network's own error norm; `None` for solvers that report none.
    pub network_error: Option<NetworkError>,
}

impl RunMetrics {
    /// The first of the metrics a run is judged by (drift, drift norms, position errors, peak
    /// joint velocity, and the score against the exact optimum where there is one) that is not
    /// finite, by its `runs.csv` name: finite samples can still overflow them (samples of 1e300
    /// give an infinite drift norm; velocities of 1e300 an infinite RMS |x - x*|).
    pub fn non_finite(&self) -> Option<&'static str> {
        if self.drift.iter().any(|d| !d.is_finite()) {
            return Some("drift");
        }
        [
            ("drift_norm", self.drift_norm),
            ("drift_ref_norm", self.drift_ref_norm),
            ("max_pos_err", self.max_position_error),
            ("rms_pos_err", self.rms_position_error),
            ("final_pos_err", self.final_position_error),
            ("peak_thetadot", self.peak_thetadot),
        ]
        .into_iter()
        .chain(self.score.iter().flat_map(|s| {
            [
                ("score_max_dx", s.max_dx),
                ("score_rms_dx", s.rms_dx),
                (
                    "score_rms_dx_after_1s",
                    s.rms_dx_after_settle.unwrap_or(0.0),
                ),
                ("score_max_obj_gap", s.max_objective_gap),
                ("score_max_violation", s.max_violation),
            ]
        }))
        .find(|(_, v)| !v.is_finite())
        .map(|(name, _)| name)
    }
}

/// Streaming accumulator of [`RunMetrics`].
pub struct MetricsAccumulator {
    limits: JointLimits,
    theta0: DVector<f64>,
    theta_ref: DVector<f64>,
    /// The time of the last sample, if any.
    last_t: Option<f64>,
    /// theta at the last sample.
    last_theta: DVector<f64>,
    /// Whether the samples carry thetaddot, and tau.
    has_thetaddot: bool,
    has_torque: bool,
    last_error: f64,
    error_sq_integral: f64,
    max_error: f64,
    theta_margin: f64,
    thetadot_margin: f64,
    peak_thetadot: f64,
    peak_thetaddot: f64,
    peak_torque: f64,
    min_sigma: f64,
    score: Score,
    /// (t, dx) of the last score sample and the trapezoidal integral of dx^2.
    last_score: Option<(f64, f64)>,
    dx_sq_integral: f64,
    /// The integral of dx^2 over t >= SETTLE_TIME, and dx at the first sample there when it is
    /// the only one (a span of zero).
    settled_sq_integral: f64,
    settled_first: Option<f64>,
    network_error: Option<NetworkError>,
}

impl MetricsAccumulator {
    /// An empty accumulator for an arm with `limits`, drifts measured from `theta0` and
    /// `theta_ref` (one entry per joint each).
    pub fn new(limits: JointLimits, theta0: &[f64], theta_ref: &[f64]) -> Self {
        let n = theta0.len();
        Self {
            limits,
            theta0: DVector::from_column_slice(theta0),
            theta_ref: DVector::from_column_slice(theta_ref),
            last_t: None,
            last_theta: DVector::zeros(n),
            has_thetaddot: false,
            has_torque: false,
            last_error: 0.0,
            error_sq_integral: 0.0,
            max_error: 0.0,
            theta_margin: f64::INFINITY,
            thetadot_margin: f64::INFINITY,
            peak_thetadot: 0.0,
            peak_thetaddot: 0.0,
            peak_torque: 0.0,
            min_sigma: f64::INFINITY,
            score: Score::default(),
            last_score: None,
            dx_sq_integral: 0.0,
            settled_sq_integral: 0.0,
            settled_first: None,
            network_error: None,
        }
    }

    /// Adds an accepted step.
    pub fn push(&mut self, s: &Sample<'_>) {
        let e = (s.desired - s.actual).norm();
        if let Some(prev_t) = self.last_t {
            let dt = s.t - prev_t;
            self.error_sq_integral += 0.5 * dt * (e * e + self.last_error * self.last_error);
        }
        self.max_error = self.max_error.max(e);
        let l = &self.limits;
        for i in 0..s.theta.len() {
            self.theta_margin =
                self.theta_margin
                    .min(margin(s.theta[i], l.theta_min[i], l.theta_max[i]));
            self.thetadot_margin = self.thetadot_margin.min(margin(
                s.thetadot[i],
                l.thetadot_min[i],
                l.thetadot_max[i],
            ));
        }
        self.peak_thetadot = self.peak_thetadot.max(amax(s.thetadot));
        if let Some(a) = s.thetaddot {
            self.peak_thetaddot = self.peak_thetaddot.max(amax(a));
        }
        if let Some(tau) = s.torque {
            self.peak_torque = self.peak_torque.max(amax(tau));
        }
        let m = jjt(s.jacobian);
        if !exceeds(&m, self.min_sigma) {
            self.min_sigma = self.min_sigma.min(least_singular_value(&m));
        }
        self.last_error = e;
        self.last_t = Some(s.t);
        self.last_theta.copy_from_slice(s.theta);
        self.has_thetaddot = s.thetaddot.is_some();
        self.has_torque = s.torque.is_some();
    }

    /// Adds a comparison with the exact optimum at time t.
    pub fn push_score(&mut self, t: f64, c: &ScoreSample) {
        let sc = &mut self.score;
        sc.samples += 1;
        sc.max_dx = sc.max_dx.max(c.dx);
        sc.max_objective_gap = sc.max_objective_gap.max(c.objective_gap);
        sc.max_violation = sc.max_violation.max(c.violation);
        if let Some((t0, dx0)) = self.last_score {
            let (e0, e1) = (dx0 * dx0, c.dx * c.dx);
            self.dx_sq_integral += 0.5 * (t - t0) * (e0 + e1);
            if t > SETTLE_TIME && t > t0 {
                // The part of the segment at or after the settling instant, dx^2 linear in t.
                let s = t0.max(SETTLE_TIME);
                let es = e0 + (e1 - e0) * (s - t0) / (t - t0);
                self.settled_sq_integral += 0.5 * (t - s) * (es + e1);
            }
        }
        if t >= SETTLE_TIME && self.settled_first.is_none() {
            self.settled_first = Some(c.dx);
        }
        self.last_score = Some((t, c.dx));
    }

    /// Adds the network's own error norm at time t.
    pub fn push_network_error(&mut self, t: f64, e: f64) {
        let n = self.network_error.get_or_insert_with(NetworkError::default);
        n.final_value = e;
        if t >= SETTLE_TIME {
            n.max_after_settle = n.max_after_settle.max(e);
        }
    }

    /// Metrics of the run so far (its last sample is theta(T)).
    pub fn finish(&self, start_time: f64) -> RunMetrics {
        let last_t = self.last_t.expect("a run has at least its initial sample");
        let drift = &self.last_theta - &self.theta0;
        let duration = last_t - start_time;
        let score = (self.score.samples > 0).then(|| {
            let rms_dx = match self.last_score {
                Some((t_last, _)) if t_last > start_time => {
                    (self.dx_sq_integral / (t_last - start_time)).sqrt()
                }
                _ => self.score.max_dx,
            };
            let rms_dx_after_settle = match (self.last_score, self.settled_first) {
                (Some((t_last, _)), Some(_)) if t_last > SETTLE_TIME => {
                    Some((self.settled_sq_integral / (t_last - SETTLE_TIME)).sqrt())
                }
                (_, first) => first,
            };
            Score {
                rms_dx,
                rms_dx_after_settle,
                ..self.score
            }
        });
        RunMetrics {
            drift: drift.iter().copied().collect(),
            drift_norm: drift.norm(),
            drift_ref_norm: (&self.last_theta - &self.theta_ref).norm(),
            max_position_error: self.max_error,
            rms_position_error: if duration > 0.0 {
                (self.error_sq_integral / duration).sqrt()
            } else {
                self.last_error
            },
            final_position_error: self.last_error,
            theta_margin: self.theta_margin,
            thetadot_margin: self.thetadot_margin,
            peak_thetadot: self.peak_thetadot,
            peak_thetaddot: self.has_thetaddot.then_some(self.peak_thetaddot),
            peak_torque: self.has_torque.then_some(self.peak_torque),
            min_sigma_j: self.min_sigma,
            score,
            network_error: self.network_error,
        }
    }
}

/// sigma_min(J), the smallest singular value of a 3 x n Jacobian J: sqrt of the least
/// eigenvalue l1 of M = J J' ([`jjt`]; 0 where rounding makes it negative).
///
/// M is symmetric positive semidefinite with eigenvalues l1 <= l2 <= l3; its characteristic
/// polynomial is p(l) = l^3 - tr l^2 + c2 l - det with tr = tr M, c2 = l1 l2 + l1 l3 + l2 l3
/// (the sum of M's principal 2 x 2 minors) and det = det M. Since c2 >= l2 l3,
/// l1 = det / (l2 l3) >= det / c2, and Newton's method on p starts there: on [0, l1] p is
/// negative, increasing (p' vanishes first between l1 and l2) and concave (p'' = 6 l - 2 tr < 0
/// for l < tr / 3, and l1 <= tr / 3), so every tangent lies above p, every iterate stays at or
/// below l1 and grows towards it, quadratically; the iteration stops when an iterate no longer
/// grows (rounding has reached l1). The rounding of p (a few eps tr^3, from det) moves the root
/// by that over p'(l1) = (l2 - l1)(l3 - l1): where p'(l1) is below tr^2 / 100 (l1 close to l2,
/// or M near rank 1), or an entry is not finite, l1 is taken from M's eigenvalue decomposition
/// instead. Either way l1 is within about 100 eps tr of the decomposition's (a test compares
/// them on 3,000 Jacobians, near-singular and with l1 = l2 among them), not bit for bit.
fn least_singular_value(m: &Matrix3<f64>) -> f64 {
    let minor = |a: usize, b: usize| m[(a, a)] * m[(b, b)] - m[(a, b)] * m[(b, a)];
    let tr = m[(0, 0)] + m[(1, 1)] + m[(2, 2)];
    let c2 = minor(0, 1) + minor(0, 2) + minor(1, 2);
    let det = m[(0, 0)] * (m[(1, 1)] * m[(2, 2)] - m[(1, 2)] * m[(2, 1)])
        - m[(0, 1)] * (m[(1, 0)] * m[(2, 2)] - m[(1, 2)] * m[(2, 0)])
        + m[(0, 2)] * (m[(1, 0)] * m[(2, 1)] - m[(1, 1)] * m[(2, 0)]);
    // p'(l1) = (l2 - l1)(l3 - l1) <= l2 l3 <= c2: where c2 is at most tr^2 / 100 Newton's answer
    // would be refused below anyway, and det / c2 may be rounding over rounding there (M of
    // rank one or nearly), no lower bound at all; so the decomposition answers at once.
    let bounded = c2 > 1e-2 * tr * tr;
    if !bounded {
        return m.symmetric_eigenvalues().min().max(0.0).sqrt();
    }
    let mut l = (det / c2).max(0.0);
    let mut slope = f64::NAN;
    // Quadratic convergence from the bound: a handful of steps; the bound is a guard.
    for _ in 0..100 {
        let p = ((l - tr) * l + c2) * l - det;
        slope = (3.0 * l - 2.0 * tr) * l + c2;
        let next = l - p / slope;
        if slope > 0.0 && next > l {
            l = next;
        } else {
            break;
        }
    }
    let l1 = if slope > 1e-2 * tr * tr {
        l
    } else {
        m.symmetric_eigenvalues().min()
    };
    l1.max(0.0).sqrt()
}

/// M = J J' of a 3 x n Jacobian with the roundings of nalgebra's `j * j.transpose()` (entry
/// (r, c) is J_r0 J_c0, then J_rk J_ck + the sum so far for k = 1, 2, ...), without the
/// transpose's allocation; the skip bound ([`exceeds`]) and sigma_min read the same M.
fn jjt(j: &Matrix3xX<f64>) -> Matrix3<f64> {
    let mut m = Matrix3::zeros();
    for (k, column) in j.as_slice().chunks_exact(3).enumerate() {
        for r in 0..3 {
            for c in 0..3 {
                let p = column[r] * column[c];
                m[(r, c)] = if k == 0 { p } else { p + m[(r, c)] };
            }
        }
    }
    m
}

/// Whether sigma_min(J) certainly exceeds `sigma` (so the running minimum stays `sigma`
/// without an eigenvalue decomposition): whether M - s I is positive definite, M = J J'
/// ([`jjt`]; symmetric, eigenvalues l1 <= l2 <= l3) and s = 1.01 sigma^2 + 1e-10 tr M, read
/// from the signs of the pivots d1, d2, d3 of its factorisation L D L' (Sylvester's law of
/// inertia: as many eigenvalues of M - s I are negative as pivots are, so three positive
/// pivots mean l1 > s). Rounded, the factorisation is exact for M - s I + E with |E| a few eps
/// tr M (Cholesky's backward error), so the pivots are required to exceed 1e-12 tr M and then
/// l1 > s - 1e-14 tr M; the margin of 1 % and 1e-10 tr M lies far above that and above the
/// error of the eigenvalue sigma_min computes (about 100 eps tr M), so skipping never changes
/// the minimum. False for an infinite `sigma` (the first sample) and for NaN. (Summed from 0
/// instead, as before M was shared with sigma_min, an entry of M could differ only in the sign
/// of an exact zero, which moves no pivot: the same answer.)
fn exceeds(m: &Matrix3<f64>, sigma: f64) -> bool {
    let tr = m[(0, 0)] + m[(1, 1)] + m[(2, 2)];
    let s = 1.01 * sigma * sigma + 1e-10 * tr;
    let floor = 1e-12 * tr;
    // Each pivot is tested after all are formed: a pivot at or below the floor (or NaN) makes
    // the later ones meaningless (infinite or NaN), but never a panic, and the answer false.
    let d1 = m[(0, 0)] - s;
    let (l1, l2) = (m[(1, 0)] / d1, m[(2, 0)] / d1);
    let d2 = m[(1, 1)] - s - l1 * m[(1, 0)];
    let x = m[(2, 1)] - l2 * m[(1, 0)];
    let d3 = m[(2, 2)] - s - l2 * m[(2, 0)] - x * x / d2;
    d1 > floor && d2 > floor && d3 > floor
}

/// Distance of v inside [lo, hi] (negative when outside); infinite limits never bind.
fn margin(v: f64, lo: f64, hi: f64) -> f64 {
    (v - lo).min(hi - v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sigma_min(j: &Matrix3xX<f64>) -> f64 {
        least_singular_value(&jjt(j))
    }

    fn limits() -> JointLimits {
        JointLimits {
            theta_min: DVector::from_column_slice(&[-1.0, f64::NEG_INFINITY]),
            theta_max: DVector::from_column_slice(&[1.0, f64::INFINITY]),
            thetadot_min: DVector::from_column_slice(&[-2.0, -2.0]),
            thetadot_max: DVector::from_column_slice(&[2.0, 2.0]),
        }
    }

    /// A sample at t with angles theta and position error err, pushed into `m`.
    fn push(m: &mut MetricsAccumulator, t: f64, theta: [f64; 2], err: f64) {
        let jacobian = Matrix3xX::from_row_slice(&[1.0, 0.0, 0.0, 2.0, 0.0, 0.0]);
        m.push(&Sample {
            t,
            theta: &theta,
            thetadot: &[0.5, -1.5],
            thetaddot: None,
            torque: None,
            desired: Vector3::new(err, 0.0, 0.0),
            actual: Vector3::zeros(),
            jacobian: &jacobian,
        });
    }

    #[test]
    fn score_rms_is_time_weighted_and_network_error_settles() {
        let mut m = MetricsAccumulator::new(limits(), &[0.0; 2], &[0.0; 2]);
        push(&mut m, 0.0, [0.0, 0.0], 0.0);
        let score = |dx: f64| ScoreSample {
            dx,
            objective_gap: 0.0,
            violation: 0.0,
        };
        // dx = 1 on [0, 0.001] sampled densely, then 0 until t = 10: RMS ~ sqrt(0.001 / 10).
        for k in 0..=10 {
            m.push_score(k as f64 * 1e-4, &score(1.0));
        }
        m.push_score(0.0011, &score(0.0));
        m.push_score(10.0, &score(0.0));
        m.push_network_error(0.5, 3.0);
        m.push_network_error(1.5, 2e-4);
        m.push_network_error(9.0, 1e-6);
        push(&mut m, 10.0, [0.0, 0.0], 0.0);
        let r = m.finish(0.0);
        let s = r.score.unwrap();
        assert_eq!(s.samples, 13);
        assert_eq!(s.max_dx, 1.0);
        assert!(
            (s.rms_dx - (0.00105f64 / 10.0).sqrt()).abs() < 1e-6,
            "time-weighted, not per sample: {}",
            s.rms_dx
        );
        // Nothing after the transient: the settled RMS is zero.
        assert_eq!(s.rms_dx_after_settle, Some(0.0));
        let e = r.network_error.unwrap();
        assert_eq!((e.final_value, e.max_after_settle), (1e-6, 2e-4));
    }

    /// Finite but huge velocities (1e300 rad/s against an optimum of order 1) overflow the
    /// score's RMS while every other metric stays finite: the run is not "ok".
    #[test]
    fn an_overflowing_score_is_a_non_finite_metric() {
        let mut m = MetricsAccumulator::new(limits(), &[0.0; 2], &[0.0; 2]);
        push(&mut m, 0.0, [0.0, 0.0], 0.0);
        let huge = ScoreSample {
            dx: 1e300,
            objective_gap: 0.0,
            violation: 0.0,
        };
        m.push_score(0.0, &huge);
        m.push_score(1.0, &huge);
        push(&mut m, 1.0, [0.0, 0.0], 0.0);
        let r = m.finish(0.0);
        assert_eq!(r.score.as_ref().map(|s| s.max_dx), Some(1e300));
        assert_eq!(r.non_finite(), Some("score_rms_dx"));
        let mut fine = MetricsAccumulator::new(limits(), &[0.0; 2], &[0.0; 2]);
        push(&mut fine, 0.0, [0.0, 0.0], 0.0);
        fine.push_score(0.0, &ScoreSample { dx: 1.0, ..huge });
        assert_eq!(fine.finish(0.0).non_finite(), None);
    }

    #[test]
    fn the_settled_rms_counts_from_the_settling_time_only() {
        let score = |dx: f64| ScoreSample {
            dx,
            objective_gap: 0.0,
            violation: 0.0,
        };
        let run = |samples: &[(f64, f64)]| {
            let mut m = MetricsAccumulator::new(limits(), &[0.0; 2], &[0.0; 2]);
            push(&mut m, 0.0, [0.0, 0.0], 0.0);
            for &(t, dx) in samples {
                m.push_score(t, &score(dx));
            }
            push(&mut m, samples.last().unwrap().0, [0.0, 0.0], 0.0);
            m.finish(0.0).score.unwrap()
        };
        // A transient of 1 rad/s until t = 0.5, then 1e-4 rad/s: the whole-run RMS sees the
        // transient, the settled one only the 1e-4.
        let s = run(&[
            (0.0, 1.0),
            (0.5, 1.0),
            (0.5, 1e-4),
            (3.0, 1e-4),
            (5.0, 1e-4),
        ]);
        assert!(s.rms_dx > 0.3, "{}", s.rms_dx);
        assert!((s.rms_dx_after_settle.unwrap() - 1e-4).abs() < 1e-15);
        // A segment across t = 1: dx^2 from 0 at t = 0 to 4 at t = 2 (linear), so on [1, 2]
        // dx^2 runs from 2 to 4 and its mean is 3.
        let s = run(&[(0.0, 0.0), (2.0, 2.0)]);
        assert!((s.rms_dx_after_settle.unwrap() - 3f64.sqrt()).abs() < 1e-12);
        // Only one sample at the settling time: its dx; none at or after it: no value.
        assert_eq!(
            run(&[(0.0, 5.0), (1.0, 0.25)]).rms_dx_after_settle,
            Some(0.25)
        );
        assert_eq!(run(&[(0.0, 5.0), (0.9, 0.25)]).rms_dx_after_settle, None);
    }

    #[test]
    fn sigma_min_of_a_known_jacobian() {
        let j = Matrix3xX::from_row_slice(&[
            0.0, 3.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0,
        ]);
        assert!((sigma_min(&j) - 0.5).abs() < 1e-12);
        let rotated = nalgebra::Rotation3::from_euler_angles(0.3, -0.2, 1.1).matrix() * j;
        assert!((sigma_min(&rotated) - 0.5).abs() < 1e-12);
    }

    /// Newton's l1 agrees with the eigenvalue decomposition's to about 100 eps tr M: random,
    /// nearly singular, and with two equal singular values (where Newton is refused).
    #[test]
    fn sigma_min_agrees_with_the_eigenvalue_decomposition() {
        let mut state = 11u64;
        let mut next = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for case in 0..3000 {
            let mut j = Matrix3xX::from_fn(5, |_, _| next());
            if case % 3 == 1 {
                // Nearly singular: the third row close to a combination of the first two.
                let row = j.row(0) * 0.7 - j.row(1) * 0.2 + j.row(2) * (1e-4 * next());
                j.set_row(2, &row);
            }
            if case % 3 == 2 {
                // Two equal singular values: l1 = l2.
                let q = nalgebra::Rotation3::from_euler_angles(next(), next(), next());
                let d = Matrix3::from_diagonal(&Vector3::new(0.3, 0.3, 1.0));
                let qd = q.matrix() * d;
                j = Matrix3xX::from_fn(5, |r, c| if c < 3 { qd[(r, c)] } else { 0.0 });
            }
            let m = jjt(&j);
            let eigen = m.symmetric_eigenvalues().min().max(0.0);
            let ours = least_singular_value(&m).powi(2);
            assert!(
                (ours - eigen).abs() <= 1e-13 * m.trace(),
                "case {case}: l1 {ours} by Newton, {eigen} by the decomposition"
            );
        }
        // Rank one, and rank one with rounding in c2 and det (a lower bound of rounding over
        // rounding): the decomposition's answer, about 0, never a large value.
        for j in [
            Matrix3xX::from_fn(5, |r, c| [0.3, -0.7, 1.1][r] * (c as f64 - 1.7)),
            Matrix3xX::from_fn(5, |r, c| [0.1, 0.2, 0.3][r] * (0.1 * c as f64 + 0.3)),
        ] {
            let m = jjt(&j);
            let eigen = m.symmetric_eigenvalues().min().max(0.0).sqrt();
            assert_eq!(least_singular_value(&m).to_bits(), eigen.to_bits());
            assert!(eigen < 1e-7 * m.trace().sqrt(), "{eigen}");
        }
        // Not finite: the decomposition's answer, not a loop.
        let mut m = Matrix3::identity();
        m[(1, 1)] = f64::NAN;
        let decomposition = m.symmetric_eigenvalues().min().max(0.0).sqrt();
        assert_eq!(least_singular_value(&m).to_bits(), decomposition.to_bits());
    }

    /// J J' carries the bits of nalgebra's `j * j.transpose()` (zeros of either sign and NaN
    /// among the entries, 0 to 9 columns).
    #[test]
    fn jjt_rounds_as_the_nalgebra_product() {
        let mut state = 11u64;
        let mut next = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1);
            match state >> 60 {
                0 => 0.0,
                1 => -0.0,
                2 if state.is_multiple_of(7) => f64::NAN,
                _ => (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5,
            }
        };
        for n in 0..10 {
            for _ in 0..200 {
                let j = Matrix3xX::from_fn(n, |_, _| next());
                let reference: Matrix3<f64> = &j * j.transpose();
                let bits = |m: &Matrix3<f64>| m.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&jjt(&j)), bits(&reference), "{j}");
            }
        }
    }

    #[test]
    fn the_skip_bound_is_a_lower_bound_of_sigma_min() {
        // sigma = (3, 2, 0.5), M = diag(9, 4, 0.25): M - s I is positive definite for
        // s = 1.01 sigma^2 + 1e-10 tr M < 0.25, so sigma_min exceeds 0.497 certainly; 0.4976
        // (1.01 x 0.4976^2 = 0.25008) is not certain.
        let j = Matrix3xX::from_row_slice(&[
            0.0, 3.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0,
        ]);
        let m = jjt(&j);
        assert!(exceeds(&m, 0.497) && !exceeds(&m, 0.4976) && !exceeds(&m, f64::INFINITY));
        // Over many Jacobians: whenever the bound says sigma_min(J) exceeds s, it does.
        let mut state = 7u64;
        let mut next = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut skipped = 0;
        for _ in 0..2000 {
            let j = Matrix3xX::from_fn(5, |_, _| next());
            let exact = sigma_min(&j);
            for s in [0.5 * exact, 0.9 * exact, 0.999 * exact, exact, 1.1 * exact] {
                if exceeds(&jjt(&j), s) {
                    skipped += 1;
                    assert!(
                        exact > s,
                        "sigma_min {exact} <= {s} though the bound skipped it"
                    );
                }
            }
        }
        // Sharp up to its margin: 0.5 and 0.9 sigma_min are certain in almost every case.
        assert!(
            skipped > 3900,
            "the bound skipped only {skipped} of 10000 cases"
        );
        // Two equal smallest singular values (the Katana's are close) do not weaken it.
        let twin = Matrix3xX::from_row_slice(&[
            2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0,
        ]);
        assert!(exceeds(&jjt(&twin), 0.99) && !exceeds(&jjt(&twin), 0.996));
        let nan = Matrix3xX::from_element(5, f64::NAN);
        assert!(!exceeds(&jjt(&nan), 0.1));
    }

    #[test]
    fn drift_margins_and_rms_of_a_constant_error() {
        let mut m = MetricsAccumulator::new(limits(), &[0.0, 0.0], &[0.1, 0.0]);
        push(&mut m, 0.0, [0.0, 0.0], 0.3);
        push(&mut m, 1.0, [0.9, 5.0], 0.3);
        push(&mut m, 3.0, [0.3, 4.0], 0.3);
        let r = m.finish(0.0);
        assert_eq!(r.drift, vec![0.3, 4.0]);
        assert!((r.drift_norm - (0.09f64 + 16.0).sqrt()).abs() < 1e-15);
        assert!((r.drift_ref_norm - (0.04f64 + 16.0).sqrt()).abs() < 1e-15);
        assert!((r.rms_position_error - 0.3).abs() < 1e-15);
        assert!(
            (r.theta_margin - 0.1).abs() < 1e-15,
            "closest approach is 1 - 0.9"
        );
        assert!((r.thetadot_margin - 0.5).abs() < 1e-15);
        assert_eq!(r.peak_thetadot, 1.5);
        assert!(
            r.min_sigma_j.abs() < 1e-12,
            "a 3 x 2 Jacobian has rank 2: sigma_min(J J') = 0"
        );
        assert!(r.score.is_none() && r.peak_torque.is_none() && r.network_error.is_none());
    }
}
