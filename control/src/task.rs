//! The tasks of the control experiments: the standard task set (`spec::TaskSet`: one
//! run of each paper's scheme by experiment and variant ids, and the budget of their runs, which
//! the orchestrator reads from `experiments/control/tasks.toml` with `catalog::load_task_set`)
//! resolved against the experiment files' runs (robot, closed path, theta0, scheme and the
//! paper's networks, [`load_tasks`]), and the way to build a task's arm, path and scheme
//! ([`with_task`]). This crate reads no file.

use crate::error::ControlError;
use robots::Robot;
use schemes::paths::Path;
use schemes::Scheme;
use settings::SolverSpec;
use simulation::{build_cyclic_parts, job_model, job_robot};
use spec::RunSpec;
use spec::SolverChoice;
use spec::TaskRef;

/// A task resolved from the experiment files.
#[derive(Clone, Debug)]
pub struct Task {
    pub reference: TaskRef,
    /// The variant's first job (its robot, path, theta0, scheme).
    pub job: RunSpec,
    /// The networks the paper runs on it.
    pub networks: Vec<SolverSpec>,
}

impl Task {
    /// `experiment / variant` (ids).
    pub fn id(&self) -> String {
        format!("{} / {}", self.reference.experiment, self.reference.variant)
    }

    /// The scheme's name (`VLTCO`, `CMCO`, ...).
    pub fn scheme(&self) -> String {
        self.job.scheme.display_name()
    }

    /// The paper id.
    pub fn paper(&self) -> &str {
        &self.job.paper
    }
}

/// The tasks of `refs` among `jobs` (every run of the experiment files, which the
/// orchestrator loads): a task's first run and its networks.
pub fn load_tasks(jobs: &[RunSpec], refs: &[TaskRef]) -> Result<Vec<Task>, ControlError> {
    refs.iter()
        .map(|r| {
            let mine: Vec<&RunSpec> = jobs
                .iter()
                .filter(|j| j.experiment == r.experiment && j.variant_id == r.variant)
                .collect();
            let first = mine.first().ok_or_else(|| {
                ControlError::UnknownTask(format!("{} / {}", r.experiment, r.variant))
            })?;
            let networks = mine
                .iter()
                .filter_map(|j| match &j.solver {
                    SolverChoice::Neural(s) => Some(s.clone()),
                    // The numerical methods run at every tick anyway (control::method).
                    SolverChoice::Exact | SolverChoice::Numerical(_) => None,
                })
                .collect();
            Ok(Task {
                reference: r.clone(),
                job: (*first).clone(),
                networks,
            })
        })
        .collect()
}

/// A task's arm, its path repeated `cycles` times ([`with_task`]), its scheme on that path, its
/// initial joint angles, and one cycle's duration `period`.
pub struct TaskArm<'a> {
    /// The task's robot (with the task's limits).
    pub robot: &'a dyn Robot,
    /// The task's path, repeated.
    pub path: &'a dyn Path,
    /// The task's scheme on the repeated path.
    pub scheme: &'a dyn Scheme,
    /// theta0, one entry per joint.
    pub theta0: &'a [f64],
    /// One cycle's duration (s).
    pub period: f64,
}

/// Builds `task`'s arm, its path repeated `cycles` times and its scheme on it, and runs `f` on
/// them.
pub fn with_task<R>(
    task: &Task,
    cycles: usize,
    f: impl FnOnce(&TaskArm<'_>) -> R,
) -> Result<R, ControlError> {
    let job = &task.job;
    let setup = |e: spec::SetupError| ControlError::Setup {
        task: task.id(),
        message: e.to_string(),
    };
    let model = job_model(job).map_err(|e| match e {
        spec::SetupError::UnknownRobot(e) => {
            ControlError::UnknownTask(format!("robot {}: {e}", job.robot))
        }
        e => setup(e),
    })?;
    let robot = job_robot(job, model.robot, model.dynamics.is_some()).map_err(setup)?;
    let (path, scheme) =
        build_cyclic_parts(job, robot.clone(), model.dynamics, cycles).map_err(setup)?;
    let period = path.duration() / cycles.max(1) as f64;
    Ok(f(&TaskArm {
        robot: robot.as_ref(),
        path: path.as_ref(),
        scheme: scheme.as_ref(),
        theta0: &job.theta0,
        period,
    }))
}
