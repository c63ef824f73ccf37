//! Scoring a trajectory produced anywhere (MATLAB, Octave, Python, a real arm) on a task of the
//! suite, with the same metrics as a run and the same score against the exact optimum.
//!
//! A [`Trajectory`] (records' type, as read from a file) is samples (t_k, theta_k) with 0 = t_0 < t_1 < ... < t_m = T (the task's
//! duration) and theta_0 = the task's theta0, optionally with the joint velocities thetadot_k
//! (the command x[..n] the trajectory's solver gave). Without them thetadot_k is taken by the
//! second-order finite difference of theta on the (possibly non-uniform) grid: with
//! h_1 = t_k - t_{k-1}, h_2 = t_{k+1} - t_k,
//!
//! ```text
//! thetadot_k = (h_1^2 theta_{k+1} - h_2^2 theta_{k-1} + (h_2^2 - h_1^2) theta_k) / (h_1 h_2 (h_1 + h_2)),
//! ```
//!
//! and the one-sided second-order formula at both ends.
//!
//! Every sample goes through the run's own observer (`simulate`): drift theta(T) - theta0,
//! position error |r*(t) - f(theta)| against the task's path, joint and velocity margins,
//! peaks, sigma_min(J). Every sample is also scored as a network's accepted step is: the task's
//! QP is built at (t_k, theta_k), its exact optimum x* solved, and the trajectory's command
//! x = [thetadot_k; x*[n..]] (its auxiliary entries, which a trajectory does not carry, taken
//! from x*) compared with it: |x[..n] - x*[..n]|_inf, the relative objective gap
//! (f(x) - f(x*)) / max(1, |f(x*)|) and the constraint violation of x.
//!
//! Only velocity-level schemes are scored (there x = thetadot and the QP depends on (t, theta)
//! alone); at the acceleration level the command would be a second difference of the samples.

use crate::coupled::ExactLoop;
use crate::metrics::ScoreSample;
use crate::observer::Observer;
use crate::run::{build_parts, RunRecord};
use crate::simulate::{Outcome, Run};
use inputs::trajectory::Trajectory;
use nalgebra::DVector;
use robots::Model;
use spec::Level;
use spec::RunSpec;
use spec::SetupError;

use solvers::ode::OdeStats;
use std::time::Instant;

/// Relative tolerance on the first and last instants (t_0 = 0, t_m = T) in units of T.
pub const TIME_TOLERANCE: f64 = 1e-9;

/// Tolerance on |theta_0 - theta0|_inf (rad): a trajectory started elsewhere drifts from
/// another pose, and its drift would not be the task's.
pub const START_TOLERANCE: f64 = 1e-6;

/// Why a trajectory cannot be scored on a task.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TrajectoryError {
    /// Fewer than 3 samples (or a column with fewer rows than `t`): the number.
    #[error("a trajectory needs at least 3 samples, got {0}")]
    TooShort(usize),
    /// A sample of theta or thetadot has not one entry per joint.
    #[error("sample {row}: {what} has {given} entries, the task's robot has {joints} joints")]
    Width {
        /// The sample's index (from 0).
        row: usize,
        /// The column: `theta` or `thetadot`.
        what: &'static str,
        /// The entries given.
        given: usize,
        /// The task robot's joint count.
        joints: usize,
    },
    /// The sample times do not increase strictly.
    #[error("sample {row}: t = {t} does not follow t = {previous} (t must increase strictly)")]
    NotIncreasing {
        /// The sample's index (from 0).
        row: usize,
        /// Its time (s).
        t: f64,
        /// The previous sample's time (s).
        previous: f64,
    },
    /// A joint angle or velocity of a sample is NaN or infinite.
    #[error("sample {row}: a value is not finite")]
    NotFinite {
        /// The sample's index (from 0).
        row: usize,
    },
    /// The first sample is not at t = 0 (to `TIME_TOLERANCE` T): its time (s).
    #[error("the trajectory starts at t = {0}, the task at t = 0")]
    Start(f64),
    /// The last sample is not at the task's duration (to `TIME_TOLERANCE` T).
    #[error("the trajectory ends at t = {t}, the task at its duration T = {duration} s")]
    End {
        /// The last sample's time (s).
        t: f64,
        /// The task's duration T (s).
        duration: f64,
    },
    /// The first sample's angles differ from the task's theta0 by more than
    /// `START_TOLERANCE`.
    #[error(
        "theta at t = 0 differs from the task's theta0 by {diff:.3e} rad at joint {joint} (tolerance {START_TOLERANCE:e})"
    )]
    StartPose {
        /// The first joint that differs, numbered from 1.
        joint: usize,
        /// |theta_0 - theta0| at that joint (rad).
        diff: f64,
    },
    /// The task's scheme is acceleration-level: its name.
    #[error("scoring a trajectory needs a velocity-level scheme (x = thetadot); {0} is acceleration-level")]
    AccelerationLevel(String),
    /// The samples are finite, but a metric of them is not (it overflowed).
    #[error("its {metric} is not finite (the samples overflow it); the trajectory is not scored")]
    MetricNotFinite {
        /// The metric, by its `runs.csv` name (e.g. `drift_norm`).
        metric: &'static str,
    },
    /// The task's parts (robot, path, scheme) cannot be built.
    #[error(transparent)]
    Setup(#[from] SetupError),
}

/// Checks the samples of `trajectory` against a task of `joints` joints, duration `duration`
/// and start `theta0` (module docs).
pub fn check(
    trajectory: &Trajectory,
    joints: usize,
    duration: f64,
    theta0: &[f64],
) -> Result<(), TrajectoryError> {
    let m = trajectory.t.len();
    if m < 3 {
        return Err(TrajectoryError::TooShort(m));
    }
    let mut columns: Vec<(&'static str, &Vec<Vec<f64>>)> = vec![("theta", &trajectory.theta)];
    if let Some(v) = &trajectory.thetadot {
        columns.push(("thetadot", v));
    }
    for (what, rows) in columns {
        if rows.len() != m {
            return Err(TrajectoryError::TooShort(rows.len().min(m)));
        }
        for (row, v) in rows.iter().enumerate() {
            if v.len() != joints {
                return Err(TrajectoryError::Width {
                    row,
                    what,
                    given: v.len(),
                    joints,
                });
            }
            if v.iter().any(|x| !x.is_finite()) {
                return Err(TrajectoryError::NotFinite { row });
            }
        }
    }
    for (row, w) in trajectory.t.windows(2).enumerate() {
        if !w[1].is_finite() || w[1] <= w[0] {
            return Err(TrajectoryError::NotIncreasing {
                row: row + 1,
                t: w[1],
                previous: w[0],
            });
        }
    }
    if !trajectory.t[0].is_finite() || trajectory.t[0].abs() > TIME_TOLERANCE * duration {
        return Err(TrajectoryError::Start(trajectory.t[0]));
    }
    let end = trajectory.t[m - 1];
    if (end - duration).abs() > TIME_TOLERANCE * duration {
        return Err(TrajectoryError::End { t: end, duration });
    }
    for (i, (a, b)) in trajectory.theta[0].iter().zip(theta0).enumerate() {
        let diff = (a - b).abs();
        if diff > START_TOLERANCE {
            return Err(TrajectoryError::StartPose { joint: i + 1, diff });
        }
    }
    Ok(())
}

/// thetadot at every sample of `trajectory`: the given one, else the finite difference of the
/// module docs.
pub fn velocities(trajectory: &Trajectory) -> Vec<Vec<f64>> {
    if let Some(v) = &trajectory.thetadot {
        return v.clone();
    }
    let (t, y) = (&trajectory.t, &trajectory.theta);
    let m = t.len();
    let n = y[0].len();
    // Weights of y[a], y[b], y[c] in the derivative at t[at] of the parabola through them.
    let parabola = |a: usize, b: usize, c: usize, at: usize| -> Vec<f64> {
        let (ta, tb, tc, x) = (t[a], t[b], t[c], t[at]);
        let wa = ((x - tb) + (x - tc)) / ((ta - tb) * (ta - tc));
        let wb = ((x - ta) + (x - tc)) / ((tb - ta) * (tb - tc));
        let wc = ((x - ta) + (x - tb)) / ((tc - ta) * (tc - tb));
        (0..n)
            .map(|i| wa * y[a][i] + wb * y[b][i] + wc * y[c][i])
            .collect()
    };
    (0..m)
        .map(|k| match k {
            0 => parabola(0, 1, 2, 0),
            k if k == m - 1 => parabola(m - 3, m - 2, m - 1, m - 1),
            k => parabola(k - 1, k, k + 1, k),
        })
        .collect()
}

/// Scores `trajectory` on the task of `job` (its robot, path, scheme, theta0 and theta_ref;
/// its solver and integrator play no part). The record's run has the metrics and the score of
/// the module docs; its `stats.steps` is the number of samples.
pub fn score_trajectory(
    job: &RunSpec,
    trajectory: &Trajectory,
) -> Result<RunRecord, TrajectoryError> {
    let run = score_with(job, trajectory, crate::run::job_model(job)?)?;
    Ok(RunRecord {
        job: job.clone(),
        run,
    })
}

fn score_with(
    job: &RunSpec,
    trajectory: &Trajectory,
    model: Model,
) -> Result<Run, TrajectoryError> {
    let started = Instant::now();
    let n = model.dof();
    check(trajectory, n, job.path.duration, &job.theta0)?;
    let robot = crate::run::job_robot(job, model.robot, model.dynamics.is_some())?;
    let (path, scheme) = build_parts(job, robot.clone(), model.dynamics)?;
    if scheme.level() != Level::Velocity {
        return Err(TrajectoryError::AccelerationLevel(scheme.name()));
    }
    let mut observer = Observer::new(
        robot.as_ref(),
        scheme.as_ref(),
        path.as_ref(),
        &job.theta0,
        &job.theta_ref,
    );
    let mut scorer = ExactLoop::new(scheme.as_ref());
    let mut failures = 0usize;
    let thetadots = velocities(trajectory);
    let nx = scheme.dims().nx;
    for ((&t, theta), thetadot) in trajectory.t.iter().zip(&trajectory.theta).zip(&thetadots) {
        let command = DVector::from_column_slice(thetadot);
        let mut x = DVector::zeros(nx);
        match scorer.optimum(t, theta, thetadot) {
            Ok((x_star, qp)) => {
                x.copy_from(x_star);
                x.rows_mut(0, n).copy_from(&command);
                let f_star = qp.objective(x_star);
                observer.score(
                    t,
                    &ScoreSample {
                        dx: (&command - x_star.rows(0, n)).amax(),
                        objective_gap: (qp.objective(&x) - f_star) / f_star.abs().max(1.0),
                        violation: qp.constraint_violation(&x),
                    },
                );
            }
            Err(_) => {
                failures += 1;
                x.rows_mut(0, n).copy_from(&command);
            }
        }
        observer.sample(t, theta, &x, Level::Velocity);
    }
    let seconds = started.elapsed().as_secs_f64();
    let metrics = observer.metrics.finish(0.0);
    if let Some(metric) = metrics.non_finite() {
        return Err(TrajectoryError::MetricNotFinite { metric });
    }
    Ok(Run {
        scheme_name: scheme.name(),
        outcome: Outcome::Completed(metrics),
        stats: OdeStats {
            steps: trajectory.t.len(),
            wall_seconds: seconds,
            ..OdeStats::default()
        },
        qp: scorer.stats(),
        score_failures: failures,
        observe_seconds: seconds,
        trace: observer.trace,
        iterations: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quadratic(m: usize) -> Trajectory {
        // theta(t) = (t^2, 3 - t) on a non-uniform grid of [0, 2].
        let t: Vec<f64> = (0..m)
            .map(|k| 2.0 * (k as f64 / (m - 1) as f64).powi(2))
            .collect();
        Trajectory {
            theta: t.iter().map(|&s| vec![s * s, 3.0 - s]).collect(),
            t,
            thetadot: None,
        }
    }

    #[test]
    fn finite_differences_are_exact_on_parabolas() {
        let tr = quadratic(7);
        for (t, v) in tr.t.iter().zip(velocities(&tr)) {
            assert!(
                (v[0] - 2.0 * t).abs() < 1e-12 && (v[1] + 1.0).abs() < 1e-12,
                "{t}: {v:?}"
            );
        }
    }

    #[test]
    fn samples_are_checked_against_the_task() {
        let tr = quadratic(5);
        assert_eq!(check(&tr, 2, 2.0, &[0.0, 3.0]), Ok(()));
        assert_eq!(
            check(&tr, 3, 2.0, &[0.0, 3.0, 0.0]),
            Err(TrajectoryError::Width {
                row: 0,
                what: "theta",
                given: 2,
                joints: 3
            })
        );
        assert_eq!(
            check(&tr, 2, 3.0, &[0.0, 3.0]),
            Err(TrajectoryError::End {
                t: 2.0,
                duration: 3.0
            })
        );
        assert!(matches!(
            check(&tr, 2, 2.0, &[0.0, 2.0]),
            Err(TrajectoryError::StartPose { joint: 2, .. })
        ));
        let mut back = tr.clone();
        back.t[2] = back.t[1];
        assert!(matches!(
            check(&back, 2, 2.0, &[0.0, 3.0]),
            Err(TrajectoryError::NotIncreasing { row: 2, .. })
        ));
        assert_eq!(
            check(&quadratic(2), 2, 2.0, &[0.0, 3.0]),
            Err(TrajectoryError::TooShort(2))
        );
    }
}
