//! The standard task set of the control experiments: one run of each paper's scheme, declared as
//! data in `experiments/`[`TASK_SET_FILE`] (experiment and variant ids, and the [`Budget`] of
//! their runs: the period sweep, the cycles, the claim's check runs) and resolved against the
//! experiment files (robot, closed path, theta0, scheme and the paper's networks), and the way to
//! build a task's arm, path and scheme ([`with_task`]).

use crate::error::ControlError;
use robots::Robot;
use schemes::paths::Path;
use schemes::Scheme;
use settings::SolverSpec;
use simulation::{build_cyclic_parts, job_model, job_robot};
use spec::RunSpec;
use spec::SolverChoice;

/// A task: an experiment and one of its variants (ids).
#[derive(Clone, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskRef {
    /// The experiment's id.
    pub experiment: spec::ids::ExperimentId,
    /// The variant's id.
    pub variant: spec::ids::VariantId,
}

/// Where the standard task set is declared, relative to the experiments directory (a
/// subdirectory, which the experiment loader does not read).
pub const TASK_SET_FILE: &str = "control/tasks.toml";

/// The task set file: a list of `[[task]]` tables and the `[budget]` of their runs.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct TaskSetFile {
    task: Vec<TaskRef>,
    budget: BudgetFile,
}

/// The `[budget]` table of the task set file, in the file's units.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct BudgetFile {
    /// The periods of the sweep besides the main one (ms).
    sweep_ms: Vec<f64>,
    /// Cycles of the many-cycles runs.
    cycles: usize,
    /// Ticks of a network's check run for the efficiency claim.
    check_ticks: usize,
    /// A check run's Euler steps per tick, as a multiple of the steps the network needs.
    check_steps_factor: u64,
}

/// How much the control experiments run.
#[derive(Clone, Debug, PartialEq)]
pub struct Budget {
    /// The control period every method runs at (s); [`records::control::MAIN_H`], the period
    /// of the report's verdicts, for the standard task set.
    pub h: f64,
    /// The other periods of the sweep (s): networks and the active set only.
    pub sweep: Vec<f64>,
    /// Cycles of the many-cycles runs.
    pub cycles: usize,
    /// Ticks of a network's check run for the efficiency claim.
    pub check_ticks: usize,
    /// A check run's Euler steps per tick over the steps the network needs
    /// ([`records::control::steps_needed`]).
    pub check_steps_factor: u64,
}

impl BudgetFile {
    /// The budget at the main period [`records::control::MAIN_H`], each field checked: the
    /// error names the file (`shown`), the field and its valid values.
    fn budget(self, shown: &str) -> Result<Budget, ControlError> {
        let invalid = |field: &'static str, valid: &'static str| ControlError::Budget {
            path: shown.to_string(),
            field,
            valid,
        };
        if self.sweep_ms.iter().any(|&p| !(p.is_finite() && p > 0.0)) {
            return Err(invalid("sweep_ms", "a list of finite periods > 0 (ms)"));
        }
        if self.cycles == 0 {
            return Err(invalid("cycles", "an integer >= 1"));
        }
        if self.check_ticks == 0 {
            return Err(invalid("check_ticks", "an integer >= 1"));
        }
        if self.check_steps_factor == 0 {
            return Err(invalid("check_steps_factor", "an integer >= 1"));
        }
        Ok(Budget {
            h: records::control::MAIN_H,
            sweep: self.sweep_ms.iter().map(|p| p * 1e-3).collect(),
            cycles: self.cycles,
            check_ticks: self.check_ticks,
            check_steps_factor: self.check_steps_factor,
        })
    }
}

/// The standard task set: its tasks, in the file's order, and their budget.
#[derive(Clone, Debug, PartialEq)]
pub struct TaskSet {
    /// Every paper's scheme once.
    pub tasks: Vec<TaskRef>,
    /// How much is run on them.
    pub budget: Budget,
}

/// The standard task set declared in `experiments/`[`TASK_SET_FILE`], read as an input
/// (`inputs::Kind::TaskSet`: a regular file inside `experiments`, at most 1 MiB, never quoted
/// in an error): every paper's scheme once, in the file's order, and the budget of their runs.
/// A project without the file has no control experiments ([`ControlError::NoTaskSet`]).
pub fn standard_task_set(experiments: &std::path::Path) -> Result<TaskSet, ControlError> {
    let path = experiments.join(TASK_SET_FILE);
    let shown = path.display().to_string();
    let origin = inputs::Origin::Under(experiments);
    let text = match inputs::read_text(&path, inputs::Kind::TaskSet, origin) {
        Ok(text) => text,
        Err(e) if e.is_not_found() => return Err(ControlError::NoTaskSet(shown)),
        Err(e) => return Err(e.into()),
    };
    let file: TaskSetFile = inputs::parse_toml(&text).map_err(|source| ControlError::TaskSet {
        path: shown.clone(),
        source,
    })?;
    if file.task.is_empty() {
        return Err(ControlError::EmptyTaskSet(shown));
    }
    Ok(TaskSet {
        tasks: file.task,
        budget: file.budget.budget(&shown)?,
    })
}

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

    /// The message of [`standard_task_set`]'s refusal, called in a thread: the test fails if
    /// it has not returned within 5 s or read the file.
    fn refusal(experiments: &std::path::Path) -> String {
        let dir = experiments.to_path_buf();
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(standard_task_set(&dir).err().map(|e| e.to_string()));
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
        let set = standard_task_set(&experiments).unwrap();
        assert!(set.tasks.len() >= 4, "{set:?}");
        assert_eq!(set.budget.h, records::control::MAIN_H);
    }

    #[test]
    fn a_budget_out_of_range_is_named_with_its_valid_values() {
        let (experiments, base) = scratch("budget");
        let file = experiments.join(TASK_SET_FILE);
        let task = "[[task]]\nexperiment = \"e\"\nvariant = \"v\"\n";
        let budget = |sweep: &str, cycles: u32, ticks: u32, factor: u32| {
            format!(
                "{task}[budget]\nsweep_ms = [{sweep}]\ncycles = {cycles}\n\
                 check_ticks = {ticks}\ncheck_steps_factor = {factor}\n"
            )
        };
        std::fs::write(&file, budget("0.5, 2.0", 3, 5, 2)).unwrap();
        let set = standard_task_set(&experiments).unwrap();
        assert_eq!(set.budget.sweep, vec![0.5e-3, 2e-3]);
        assert_eq!((set.budget.cycles, set.budget.check_ticks), (3, 5));
        assert_eq!(set.budget.check_steps_factor, 2);
        for (text, field) in [
            (budget("0.5, -1.0", 3, 5, 2), "sweep_ms"),
            (budget("0.5", 0, 5, 2), "cycles"),
            (budget("0.5", 3, 0, 2), "check_ticks"),
            (budget("0.5", 3, 5, 0), "check_steps_factor"),
        ] {
            std::fs::write(&file, &text).unwrap();
            let e = standard_task_set(&experiments).unwrap_err();
            assert!(
                matches!(&e, ControlError::Budget { field: f, .. } if *f == field),
                "{e:?}"
            );
            assert!(
                e.to_string().contains(&format!("[budget] {field} must be")),
                "{e}"
            );
        }
        // A task set without its budget is refused too.
        std::fs::write(&file, task).unwrap();
        let e = standard_task_set(&experiments).unwrap_err();
        assert!(e.to_string().contains("budget"), "{e}");
        std::fs::remove_dir_all(&base).unwrap();
    }

    #[test]
    fn a_hostile_task_set_is_refused_without_its_content() {
        let (experiments, base) = scratch("hostile");
        let file = experiments.join(TASK_SET_FILE);
        // Missing: no control experiments.
        let e = standard_task_set(&experiments).unwrap_err();
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
