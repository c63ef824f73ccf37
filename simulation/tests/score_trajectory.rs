//! A trajectory scored from its samples agrees with the run that produced it: the run's own
//! trace (theta, thetadot at ~400 instants), scored as an external trajectory, has the run's
//! drift exactly and its error and score to the resolution of the thinned samples.

use inputs::trajectory::Trajectory;
use simulation::run_job;
use simulation::{score_trajectory, TrajectoryError};
use simulation::{Outcome, Run};
use spec::RunSpec;
use spec::SolverChoice;

fn job(experiment: &str, variant: &str, neural: bool) -> RunSpec {
    let root = catalog::root_from_current_dir().unwrap();
    catalog::load_dir(&root.join("experiments"))
        .unwrap()
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .find(|j| {
            j.experiment == experiment
                && j.variant == variant
                && matches!(j.solver, SolverChoice::Neural(_)) == neural
        })
        .expect("the job is in the experiment files")
}

fn trace_of(run: &Run, with_velocities: bool) -> Trajectory {
    Trajectory {
        t: run.trace.iter().map(|p| p.t).collect(),
        theta: run.trace.iter().map(|p| p.theta.clone()).collect(),
        thetadot: with_velocities.then(|| run.trace.iter().map(|p| p.thetadot.clone()).collect()),
    }
}

fn metrics(run: &Run) -> &simulation::RunMetrics {
    match &run.outcome {
        Outcome::Completed(m) => m,
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_znn_runs_own_trace_scores_as_the_run() {
    let job = job("kong2019-circle", "ZNN (eq. 22)", true);
    let run = run_job(&job).run;
    let m = metrics(&run);
    let scored = score_trajectory(&job, &trace_of(&run, true)).unwrap();
    let s = metrics(&scored.run);
    assert_eq!(s.drift, m.drift);
    assert!((s.max_position_error - m.max_position_error).abs() <= 0.05 * m.max_position_error);
    let (run_score, trace_score) = (m.score.unwrap(), s.score.unwrap());
    assert_eq!(trace_score.samples, run.trace.len());
    // The start transient (the network starts at 0, x*(0) != 0) is the max in both.
    assert!((trace_score.max_dx - run_score.max_dx).abs() <= 1e-6 * run_score.max_dx);
    assert!(
        (trace_score.rms_dx / run_score.rms_dx - 1.0).abs() < 0.2,
        "{trace_score:?} vs {run_score:?}"
    );
}

#[test]
fn the_exact_columns_trace_is_at_the_optimum_even_from_differenced_velocities() {
    let job = job("kong2019-circle", "ZNN (eq. 22)", false);
    let run = run_job(&job).run;
    let given = score_trajectory(&job, &trace_of(&run, true)).unwrap();
    let differenced = score_trajectory(&job, &trace_of(&run, false)).unwrap();
    let given = metrics(&given.run).score.unwrap();
    let differenced = metrics(&differenced.run).score.unwrap();
    // The exact column's thetadot is x*: zero distance up to the solver's tolerance.
    assert!(given.max_dx < 1e-6, "{given:?}");
    // Second-order differences of ~400 samples of a 9 s circle: close, not exact.
    assert!(
        differenced.rms_dx < 1e-2 && differenced.rms_dx > given.rms_dx,
        "{differenced:?}"
    );
    assert!(given.max_violation < 1e-6, "{given:?}");
}

#[test]
fn a_trajectory_of_another_task_is_refused() {
    let job = job("kong2019-circle", "ZNN (eq. 22)", false);
    let run = run_job(&job).run;
    let mut short = trace_of(&run, true);
    short.t.pop();
    short.theta.pop();
    short.thetadot.as_mut().unwrap().pop();
    assert!(matches!(
        score_trajectory(&job, &short),
        Err(TrajectoryError::End { .. })
    ));
}

/// Finite samples whose metrics overflow (theta = 1e300 after the start: the drift norm is
/// infinite) are refused naming the metric, never scored as ok.
#[test]
fn samples_whose_metrics_overflow_are_refused() {
    let job = job("kong2019-circle", "ZNN (eq. 22)", false);
    let run = run_job(&job).run;
    let mut huge = trace_of(&run, true);
    let last = huge.t.len() - 1;
    for k in 1..=last {
        huge.theta[k][0] = 1e300;
        huge.theta[k][1] = -1e300;
    }
    let e = score_trajectory(&job, &huge).unwrap_err();
    assert!(matches!(e, TrajectoryError::MetricNotFinite { .. }), "{e}");
    assert!(e.to_string().contains("not finite"), "{e}");
}
