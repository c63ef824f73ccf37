//! The many-cycles runs in continuous time, as the papers simulate: the exact column (the QP's
//! optimum in the loop, [`simulation::simulate()`] with the experiment's exact integrator,
//! Dormand-Prince 5(4) at RelTol 1e-11) over the task's path repeated K times.
//!
//! The K cycles are K runs of one cycle each, every run started where the previous ended (its
//! last accepted state, at t = T exactly), with the same scheme and path (the scheme's
//! reference pose stays the experiment's): at the velocity level, where the arm's state is
//! theta alone, that is exactly the K-cycle motion; at the acceleration level each cycle
//! starts from rest, dropping the arm's residual speed at c T (the path itself rests there).
//! The drift after cycle c is |theta(c T) - theta_0|.
//!
//! With [`Rounding::OneUlp`] (the rounding-noise probe; a continuous run has no ticks) the first
//! cycle starts from theta_0 with each joint angle moved by one ulp (module `rounding`), and the
//! drift is still measured from the task's theta_0.

use crate::rounding::Rounding;
use crate::task::{Task, TaskArm};
use records::control::ControlStatus;
use simulation::{simulate, Outcome, Settings, Solver};
use spec::NetworkInit;
use spec::Scoring;

/// The drifts and per-cycle changes of a continuous run, and how it ended.
#[derive(Clone, Debug, PartialEq)]
pub struct ContinuousCycles {
    /// Why the runs stopped before the last cycle, with the instant (none: every cycle ran).
    pub failure: Option<String>,
    pub drift: Vec<f64>,
    pub change: Vec<f64>,
}

impl ContinuousCycles {
    /// The trend row's status and failure: failed when a cycle did not complete.
    pub fn end(&self) -> (ControlStatus, Option<String>) {
        let status = match self.failure {
            Some(_) => ControlStatus::Failed,
            None => ControlStatus::Ok,
        };
        (status, self.failure.clone())
    }
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Runs the exact column of `task` for `cycles` cycles ([`ExactCycles::run_on`] a task's arm
/// from [`crate::task::with_task`] with one cycle: the runs are chained here).
pub struct ExactCycles<'a> {
    pub task: &'a Task,
    pub cycles: usize,
    /// theta_0 as the task gives it, or moved by one ulp (module docs).
    pub rounding: Rounding,
}

impl ExactCycles<'_> {
    /// The cycles on `arm`.
    pub fn run_on(self, arm: &TaskArm<'_>) -> ContinuousCycles {
        let (robot, path, scheme, theta0) = (arm.robot, arm.path, arm.scheme, arm.theta0);
        let job = &self.task.job;
        let theta_ref = &job.theta_ref;
        let settings = Settings {
            integrator: job.integrator,
            scoring: Scoring::Off,
            network_init: NetworkInit::Zero,
        };
        let mut out = ContinuousCycles {
            failure: None,
            drift: Vec::new(),
            change: Vec::new(),
        };
        let mut start = theta0.to_vec();
        if let Some(mut moves) = self.rounding.moves() {
            moves.apply(&mut start);
        }
        for _ in 0..self.cycles {
            let run = simulate(
                robot,
                path,
                scheme,
                Solver::Exact,
                &start,
                theta_ref,
                &settings,
            );
            let end = match run {
                Ok(r) => match (&r.outcome, r.trace.last()) {
                    (Outcome::Completed(_), Some(last)) => last.theta.clone(),
                    (Outcome::Failed { t, error, .. }, _) => {
                        out.failure = Some(format!("failed at t = {t}: {error}"));
                        break;
                    }
                    (Outcome::Completed(_), None) => {
                        out.failure = Some("failed: no trace".to_string());
                        break;
                    }
                },
                Err(e) => {
                    out.failure = Some(format!("failed: {e}"));
                    break;
                }
            };
            out.drift.push(distance(&end, theta0));
            out.change.push(distance(&end, &start));
            start = end;
        }
        out
    }
}
