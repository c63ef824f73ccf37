//! A run's identity: [`RunKey`] = (experiment id, variant id, solver id).
//!
//! Every id is a validated slug ([`crate::ids`]): the experiment's `id` and the variant's `id` as the
//! experiment file declares them (a variant without one gets `slug(label)` once, when the file is
//! read), and the solver's id derived from its specification (`exact`, or
//! [`settings::SolverSpec::id`]). The key names the run everywhere it is stored or
//! looked up: results rows, the journal, shard assignment (a hash of [`RunKey`]'s text),
//! baselines, trace and figure file names, the published-value mappings and claims of
//! `papers/`. Labels (`variant`, `solver` in results) are for display only: renaming one moves
//! no result.

use crate::ids::{ExperimentId, IdError, SolverId, VariantId};
use std::fmt;

/// Why a text is not a run or task key.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum KeyError {
    /// Not of the form `<experiment> / <variant> / <solver>` (or `<experiment> / <variant>`).
    #[error("{} is not of the form `{form}`", settings::shown(text))]
    Shape {
        /// The text given.
        text: String,
        /// The form expected.
        form: &'static str,
    },
    /// A part that is not a valid id.
    #[error(transparent)]
    Id(#[from] IdError),
}

const RUN_FORM: &str = "<experiment> / <variant> / <solver>";
const TASK_FORM: &str = "<experiment> / <variant>";

/// experiment / variant / solver, as ids.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct RunKey {
    /// The experiment's id.
    pub experiment: ExperimentId,
    /// The variant's id.
    pub variant: VariantId,
    /// The solver's id.
    pub solver: SolverId,
}

impl RunKey {
    /// The key of three ids.
    pub fn new(experiment: ExperimentId, variant: VariantId, solver: SolverId) -> Self {
        RunKey {
            experiment,
            variant,
            solver,
        }
    }

    /// The key of three texts, each checked as its kind of id.
    pub fn from_ids(experiment: &str, variant: &str, solver: &str) -> Result<Self, IdError> {
        Ok(RunKey {
            experiment: ExperimentId::new(experiment)?,
            variant: VariantId::new(variant)?,
            solver: SolverId::new(solver)?,
        })
    }

    /// Reads `"<experiment> / <variant> / <solver>"` (spaces around `/` optional): three parts,
    /// each a valid id.
    pub fn parse(text: &str) -> Result<RunKey, KeyError> {
        let shape = || KeyError::Shape {
            text: text.to_string(),
            form: RUN_FORM,
        };
        let (task, solver) = text.rsplit_once('/').ok_or_else(shape)?;
        let task = match TaskKey::parse(task) {
            Err(KeyError::Shape { .. }) => return Err(shape()),
            other => other?,
        };
        Ok(task.run(SolverId::new(solver.trim())?))
    }

    /// The task the run belongs to (what every solver of a variant shares).
    pub fn task(&self) -> TaskKey {
        TaskKey {
            experiment: self.experiment.clone(),
            variant: self.variant.clone(),
        }
    }

    /// `<variant>__<solver>`: the run's file stem inside its experiment's directory, shared by
    /// the traces and the figures.
    pub fn stem(&self) -> String {
        format!("{}__{}", self.variant, self.solver)
    }
}

impl fmt::Display for RunKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} / {} / {}",
            self.experiment, self.variant, self.solver
        )
    }
}

/// experiment / variant, as ids: a task (the robot, path, theta0 and scheme a variant fixes).
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TaskKey {
    /// The experiment's id.
    pub experiment: ExperimentId,
    /// The variant's id.
    pub variant: VariantId,
}

impl TaskKey {
    /// The key of two texts, each checked as its kind of id.
    pub fn from_ids(experiment: &str, variant: &str) -> Result<Self, IdError> {
        Ok(TaskKey {
            experiment: ExperimentId::new(experiment)?,
            variant: VariantId::new(variant)?,
        })
    }

    /// Reads `"<experiment> / <variant>"` (spaces around `/` optional): two parts, each a valid
    /// id.
    pub fn parse(text: &str) -> Result<TaskKey, KeyError> {
        let shape = || KeyError::Shape {
            text: text.to_string(),
            form: TASK_FORM,
        };
        let (e, v) = text.split_once('/').ok_or_else(shape)?;
        if v.contains('/') {
            return Err(shape());
        }
        Ok(TaskKey::from_ids(e.trim(), v.trim())?)
    }

    /// The run of `solver` on this task.
    pub fn run(&self, solver: SolverId) -> RunKey {
        RunKey::new(self.experiment.clone(), self.variant.clone(), solver)
    }
}

impl fmt::Display for TaskKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} / {}", self.experiment, self.variant)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_print_parse_and_name_files() {
        let k = RunKey::from_ids("jia2019-clover", "vltco", crate::run::EXACT_ID).unwrap();
        assert_eq!(k.to_string(), "jia2019-clover / vltco / exact");
        assert_eq!(k.stem(), "vltco__exact");
        assert_eq!(TaskKey::parse("jia2019-clover / vltco"), Ok(k.task()));
        assert_eq!(TaskKey::parse("jia2019-clover/vltco"), Ok(k.task()));
        assert!(matches!(
            TaskKey::parse("jia2019-clover"),
            Err(KeyError::Shape { .. })
        ));
        assert!(matches!(
            TaskKey::parse("a / b / c"),
            Err(KeyError::Shape { .. })
        ));
        assert!(RunKey::from_ids("e", "../v", "s").is_err());
        assert!(
            matches!(RunKey::parse("e / V / s"), Err(KeyError::Id(_))),
            "ids are slugs"
        );
        let lvi = SolverId::new("lvi-pdnn").unwrap();
        assert_eq!(k.task().run(lvi).solver, "lvi-pdnn");
        assert_eq!(
            RunKey::parse("jia2019-clover / vltco / exact"),
            Ok(k.clone())
        );
        for bad in ["jia2019-clover / vltco", "a / b / c / d"] {
            assert!(
                matches!(RunKey::parse(bad), Err(KeyError::Shape { .. })),
                "{bad}"
            );
        }
        assert!(matches!(RunKey::parse("a / b / "), Err(KeyError::Id(_))));
    }
}
