//! The control experiments' standard task set, read from `experiments/`[`TASK_SET_FILE`]: one
//! run of each paper's scheme (experiment and variant ids) and the budget of their runs (the
//! period sweep, the cycles, the claim's check runs), into `spec::TaskSet`. The
//! engine (crate `control`) takes the set as data and reads no file; the orchestrator reads it
//! here, through the input reader (crate `inputs`).

use crate::error::TaskSetError;
use spec::{Budget, TaskRef, TaskSet, MAIN_H};
use std::path::Path;

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

impl BudgetFile {
    /// The budget at the main period [`MAIN_H`], each field checked: the error names the file
    /// (`shown`), the field and its valid values.
    fn budget(self, shown: &str) -> Result<Budget, TaskSetError> {
        let invalid = |field: &'static str, valid: &'static str| TaskSetError::Budget {
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
            h: MAIN_H,
            sweep: self.sweep_ms.iter().map(|p| p * 1e-3).collect(),
            cycles: self.cycles,
            check_ticks: self.check_ticks,
            check_steps_factor: self.check_steps_factor,
        })
    }
}

/// The standard task set declared in `experiments/`[`TASK_SET_FILE`], read as an input
/// (`inputs::Kind::TaskSet`: a regular file inside `experiments`, at most 1 MiB, never quoted
/// in an error): every paper's scheme once, in the file's order, and the budget of their runs.
/// A project without the file has no control experiments ([`TaskSetError::Missing`]).
pub fn load_task_set(experiments: &Path) -> Result<TaskSet, TaskSetError> {
    let path = experiments.join(TASK_SET_FILE);
    let shown = path.display().to_string();
    let origin = inputs::Origin::Under(experiments);
    let text = match inputs::read_text(&path, inputs::Kind::TaskSet, origin) {
        Ok(text) => text,
        Err(e) if e.is_not_found() => return Err(TaskSetError::Missing(shown)),
        Err(e) => return Err(e.into()),
    };
    let file: TaskSetFile = inputs::parse_toml(&text).map_err(|source| TaskSetError::Toml {
        path: shown.clone(),
        source,
    })?;
    if file.task.is_empty() {
        return Err(TaskSetError::Empty(shown));
    }
    Ok(TaskSet {
        tasks: file.task,
        budget: file.budget.budget(&shown)?,
    })
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use inputs::HOSTILE_MARKER;
    use std::path::PathBuf;

    /// A scratch `experiments/` (with `control/`) and the directory that holds it (removed
    /// when dropped).
    fn scratch(tag: &str) -> (PathBuf, inputs::Scratch) {
        let base = inputs::Scratch::dir(&format!("control-tasks-{tag}"));
        std::fs::create_dir_all(base.join("experiments/control")).unwrap();
        (base.join("experiments"), base)
    }

    #[test]
    fn the_committed_task_set_reads() {
        let experiments = crate::root_from_current_dir().unwrap().join("experiments");
        let set = load_task_set(&experiments).unwrap();
        assert!(set.tasks.len() >= 4, "{set:?}");
        assert_eq!(set.budget.h, MAIN_H);
    }

    #[test]
    fn a_budget_out_of_range_is_named_with_its_valid_values() {
        let (experiments, _base) = scratch("budget");
        let file = experiments.join(TASK_SET_FILE);
        let task = "[[task]]\nexperiment = \"e\"\nvariant = \"v\"\n";
        let budget = |sweep: &str, cycles: u32, ticks: u32, factor: u32| {
            format!(
                "{task}[budget]\nsweep_ms = [{sweep}]\ncycles = {cycles}\n\
                 check_ticks = {ticks}\ncheck_steps_factor = {factor}\n"
            )
        };
        std::fs::write(&file, budget("0.5, 2.0", 3, 5, 2)).unwrap();
        let set = load_task_set(&experiments).unwrap();
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
            let e = load_task_set(&experiments).unwrap_err();
            assert!(
                matches!(&e, TaskSetError::Budget { field: f, .. } if *f == field),
                "{e:?}"
            );
            assert!(
                e.to_string().contains(&format!("[budget] {field} must be")),
                "{e}"
            );
        }
        // A task set without its budget is refused too.
        std::fs::write(&file, task).unwrap();
        let e = load_task_set(&experiments).unwrap_err();
        assert!(e.to_string().contains("budget"), "{e}");
    }

    #[test]
    fn a_hostile_task_set_is_refused_without_its_content() {
        let (experiments, _base) = scratch("hostile");
        // Missing: no control experiments.
        let e = load_task_set(&experiments).unwrap_err();
        assert!(matches!(e, TaskSetError::Missing(_)), "{e:?}");
        let dir = experiments.clone();
        inputs::assert_refuses_hostile_files(
            &experiments.join(TASK_SET_FILE),
            inputs::Kind::TaskSet,
            "[[task]]\nexperiment = \"e\"\nvariant = \"v\"\n[budget]\nsweep_ms = [0.5]\n\
             cycles = 3\ncheck_ticks = 5\ncheck_steps_factor = 2\n",
            // An invalid id is named, as the offending value; the lines around it are not.
            &[format!(
                "# {HOSTILE_MARKER}\n[[task]]\nexperiment = \"e\"\nvariant = \"Not-A-Slug\"\n"
            )],
            move || load_task_set(&dir).err().map(|e| e.to_string()),
        );
    }
}
