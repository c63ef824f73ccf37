//! The many-cycles runs in continuous time, as the papers simulate: the exact column (the QP's
//! optimum in the loop, [`simulation::simulate`] with the experiment's exact integrator,
//! Dormand-Prince 5(4) at RelTol 1e-11) over the task's path repeated K times.
//!
//! The drift after cycle c is read from the run's trace at t = c T, interpolated linearly
//! between the two accepted steps around it. The papers' paths rest at every c T (zero speed),
//! so the interpolation error there is second order in the step and negligible.

use crate::task::{Task, TaskVisitor};
use nalgebra::SVector;
use robots::Robot;
use schemes::paths::Path;
use schemes::scheme::Scheme;
use simulation::experiment::NetworkInit;
use simulation::simulate::{simulate, Outcome, Scoring, Settings, Solver, TracePoint};

/// The drifts and per-cycle changes of a continuous run, and how it ended.
#[derive(Clone, Debug, PartialEq)]
pub struct ContinuousCycles {
    /// `ok`, or the failure with its instant.
    pub status: String,
    pub drift: Vec<f64>,
    pub change: Vec<f64>,
}

/// theta at `t` from the trace (linear between the accepted steps around it); `None` past its
/// end.
fn theta_at(trace: &[TracePoint], t: f64) -> Option<Vec<f64>> {
    let i = trace.iter().position(|p| p.t >= t)?;
    let b = &trace[i];
    if i == 0 || b.t == t {
        return Some(b.theta.clone());
    }
    let a = &trace[i - 1];
    let w = (t - a.t) / (b.t - a.t);
    Some(
        a.theta
            .iter()
            .zip(&b.theta)
            .map(|(x, y)| x + w * (y - x))
            .collect(),
    )
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Runs the exact column of `task` over the path repeated (a [`TaskVisitor`]; use with
/// [`crate::task::with_task`] and the same number of cycles).
pub struct ExactCycles<'a> {
    pub task: &'a Task,
    pub cycles: usize,
}

impl TaskVisitor for ExactCycles<'_> {
    type Output = ContinuousCycles;
    fn visit<const N: usize>(
        self,
        robot: &dyn Robot<N>,
        path: &dyn Path,
        scheme: &dyn Scheme<N>,
        theta0: &SVector<f64, N>,
        period: f64,
    ) -> Self::Output {
        let job = &self.task.job;
        let theta_ref = SVector::<f64, N>::from_column_slice(&job.theta_ref);
        let settings = Settings {
            integrator: job.integrator,
            scoring: Scoring::Off,
            network_init: NetworkInit::Zero,
        };
        let run = simulate(
            robot,
            path,
            scheme,
            Solver::Exact,
            theta0,
            &theta_ref,
            &settings,
        );
        let (status, trace) = match run {
            Ok(r) => {
                let status = match &r.outcome {
                    Outcome::Completed(_) => "ok".to_string(),
                    Outcome::Failed { t, error, .. } => format!("failed at t = {t}: {error}"),
                };
                (status, r.trace)
            }
            Err(e) => (format!("failed: {e}"), Vec::new()),
        };
        let mut out = ContinuousCycles {
            status,
            drift: Vec::new(),
            change: Vec::new(),
        };
        let mut previous = theta0.as_slice().to_vec();
        for c in 1..=self.cycles {
            let Some(theta) = theta_at(&trace, c as f64 * period) else {
                break;
            };
            out.drift.push(distance(&theta, theta0.as_slice()));
            out.change.push(distance(&theta, &previous));
            previous = theta;
        }
        out
    }
}
