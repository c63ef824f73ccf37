//! The standard task set of the control experiments: one run of each paper's scheme, declared as
//! data in `experiments/`[`TASK_SET_FILE`] (experiment and variant ids) and resolved against the
//! experiment files (robot, closed path, theta0, scheme and the paper's networks), and the way to
//! build a task's arm, path and scheme ([`with_task`]).

use crate::error::ControlError;
use catalog::experiment::{load_dir, Job, SolverChoice};
use robots::Robot;
use schemes::paths::Path;
use schemes::scheme::Scheme;
use settings::solver_spec::SolverSpec;
use simulation::run::check_job;
use simulation::run::{build_cyclic_parts, job_model, job_robot};

/// A task: an experiment and one of its variants (ids).
#[derive(Clone, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskRef {
    /// The experiment's id.
    pub experiment: catalog::ids::ExperimentId,
    /// The variant's id.
    pub variant: catalog::ids::VariantId,
}

/// Where the standard task set is declared, relative to the experiments directory (a
/// subdirectory, which the experiment loader does not read).
pub const TASK_SET_FILE: &str = "control/tasks.toml";

/// The task set file: a list of `[[task]]` tables.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct TaskSetFile {
    task: Vec<TaskRef>,
}

/// The standard task set declared in `experiments/`[`TASK_SET_FILE`], read as an input
/// (`inputs::Kind::TaskSet`: a regular file inside `experiments`, at most 1 MiB, never quoted
/// in an error): every paper's scheme once, in the file's order. A project without the file
/// has no control experiments ([`ControlError::NoTaskSet`]).
pub fn standard_task_refs(experiments: &std::path::Path) -> Result<Vec<TaskRef>, ControlError> {
    let path = experiments.join(TASK_SET_FILE);
    let shown = path.display().to_string();
    let origin = inputs::Origin::Under(experiments);
    let text = match inputs::read_text(&path, inputs::Kind::TaskSet, origin) {
        Ok(text) => text,
        Err(e) if e.is_not_found() => return Err(ControlError::NoTaskSet(shown)),
        Err(e) => return Err(e.into()),
    };
    let file: TaskSetFile =
        inputs::toml_error::from_str(&text).map_err(|source| ControlError::TaskSet {
            path: shown.clone(),
            source,
        })?;
    if file.task.is_empty() {
        return Err(ControlError::EmptyTaskSet(shown));
    }
    Ok(file.task)
}

/// A task resolved from the experiment files.
#[derive(Clone, Debug)]
pub struct Task {
    pub reference: TaskRef,
    /// The variant's first job (its robot, path, theta0, scheme).
    pub job: Job,
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

/// The tasks of `refs` from the experiment files in `dir`.
pub fn load_tasks(dir: &std::path::Path, refs: &[TaskRef]) -> Result<Vec<Task>, ControlError> {
    let files = load_dir(dir, check_job)?;
    let jobs: Vec<Job> = files.iter().flat_map(|f| f.jobs()).collect();
    refs.iter()
        .map(|r| {
            let mine: Vec<&Job> = jobs
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
    let setup = |e: catalog::error::SetupError| ControlError::Setup {
        task: task.id(),
        message: e.to_string(),
    };
    let model = job_model(job).map_err(|e| match e {
        catalog::error::SetupError::UnknownRobot(e) => {
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

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::path::PathBuf;
    use std::time::Duration;

    /// The stand-in for a secret a hostile file would hold.
    const MARKER: &str = "SECRET_MARKER_c0n7";

    /// A scratch `experiments/` (with `control/`) beside an `outside/secret`.
    fn scratch(tag: &str) -> (PathBuf, PathBuf) {
        let base = std::env::temp_dir().join(format!(
            "driftbench-control-tasks-{tag}-{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&base);
        std::fs::create_dir_all(base.join("experiments/control")).unwrap();
        std::fs::create_dir_all(base.join("outside")).unwrap();
        std::fs::write(base.join("outside/secret"), format!("{MARKER}\n")).unwrap();
        (base.join("experiments"), base)
    }

    /// The message of [`standard_task_refs`]'s refusal, called in a thread: the test fails if
    /// it has not returned within 5 s or read the file.
    fn refusal(experiments: &std::path::Path) -> String {
        let dir = experiments.to_path_buf();
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(standard_task_refs(&dir).err().map(|e| e.to_string()));
        });
        rx.recv_timeout(Duration::from_secs(5))
            .expect("the task set was read or refused within 5 s (a FIFO must not block)")
            .expect("the task set is refused")
    }

    #[test]
    fn the_committed_task_set_reads() {
        let experiments = catalog::root::from_current_dir()
            .unwrap()
            .join("experiments");
        let refs = standard_task_refs(&experiments).unwrap();
        assert!(refs.len() >= 4, "{refs:?}");
    }

    #[test]
    fn a_hostile_task_set_is_refused_without_its_content() {
        let (experiments, base) = scratch("hostile");
        let file = experiments.join(TASK_SET_FILE);
        // Missing: no control experiments.
        let e = standard_task_refs(&experiments).unwrap_err();
        assert!(matches!(e, ControlError::NoTaskSet(_)), "{e:?}");
        // A symbolic link out of the experiments directory (to a secret, to the environment).
        for target in [
            base.join("outside/secret"),
            PathBuf::from("/proc/self/environ"),
        ] {
            std::os::unix::fs::symlink(&target, &file).unwrap();
            let e = refusal(&experiments);
            assert!(e.contains("leads outside") && !e.contains(MARKER), "{e}");
            std::fs::remove_file(&file).unwrap();
        }
        // A FIFO: refused at once, not waited on.
        let made = std::process::Command::new("mkfifo")
            .arg(&file)
            .status()
            .unwrap();
        assert!(made.success());
        let e = refusal(&experiments);
        assert!(e.contains("a FIFO, not a regular file"), "{e}");
        std::fs::remove_file(&file).unwrap();
        // Over its cap of 1 MiB: refused before it is parsed.
        let mut big = "[[task]]\nexperiment = \"e\"\nvariant = \"v\"\n".to_string();
        big.push_str(&format!("# {MARKER}\n").repeat((1 << 20) / 20));
        std::fs::write(&file, &big).unwrap();
        let e = refusal(&experiments);
        assert!(
            e.contains("larger than its cap") && !e.contains(MARKER),
            "{e}"
        );
        // TOML errors give the line and column, never the file's lines (an invalid id is
        // named, as the offending value; the lines around it are not).
        for text in [
            format!("[[task]]\nexperiment = \"e\"\nvariant = \"v\"\n# {MARKER}\nnot toml\n"),
            format!("[[task]]\nexperiment = \"e\" {MARKER}\n"),
            format!("# {MARKER}\n[[task]]\nexperiment = \"e\"\nvariant = \"Not-A-Slug\"\n"),
            format!("[[task]]\nexperiment = \"e\"\n\"{MARKER}\n"),
        ] {
            std::fs::write(&file, &text).unwrap();
            let e = refusal(&experiments);
            assert!(!e.contains(MARKER) && e.contains("line "), "{text:?}: {e}");
        }
        std::fs::remove_dir_all(&base).unwrap();
    }
}
