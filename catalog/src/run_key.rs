//! A run's identity: [`RunKey`] = (experiment id, variant id, solver id).
//!
//! Every id is a slug ([`schemes::slug`]): the experiment's `id` and the variant's `id` as the
//! experiment file declares them (a variant without one gets `slug(label)` once, when the file is
//! read), and the solver's id derived from its specification (`exact`, or
//! [`settings::solver_spec::SolverSpec::id`]). The key names the run everywhere it is stored or
//! looked up: results rows, the journal, shard assignment (a hash of [`RunKey`]'s text),
//! baselines, trace and figure file names, the published-value mappings and claims of
//! `papers/`. Labels (`variant`, `solver` in results) are for display only: renaming one moves
//! no result.

use crate::naming::{
    check_name, NameError, MAX_EXPERIMENT_ID, MAX_SOLVER_LABEL, MAX_VARIANT_LABEL,
};
use std::fmt;

/// The solver id of the exact column (the exact optimum x*(t) in the loop).
pub const EXACT_ID: &str = "exact";

/// experiment / variant / solver, as ids.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct RunKey {
    pub experiment: String,
    pub variant: String,
    pub solver: String,
}

impl RunKey {
    pub fn new(
        experiment: impl Into<String>,
        variant: impl Into<String>,
        solver: impl Into<String>,
    ) -> Self {
        RunKey {
            experiment: experiment.into(),
            variant: variant.into(),
            solver: solver.into(),
        }
    }

    /// Reads `"<experiment> / <variant> / <solver>"` (spaces around `/` optional).
    pub fn parse(text: &str) -> Option<RunKey> {
        let (task, solver) = text.rsplit_once('/')?;
        let solver = solver.trim();
        let task = TaskKey::parse(task)?;
        (!solver.is_empty()).then(|| task.run(solver))
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

    /// Checks that the three ids can name files under results/ and report/ (no `/`, `\` or
    /// `..`, not empty, within the length limits).
    pub fn check(&self) -> Result<(), NameError> {
        check_name(&self.experiment, MAX_EXPERIMENT_ID)?;
        check_name(&self.variant, MAX_VARIANT_LABEL)?;
        check_name(&self.solver, MAX_SOLVER_LABEL)
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
    pub experiment: String,
    pub variant: String,
}

impl TaskKey {
    /// Reads `"<experiment> / <variant>"` (spaces around `/` optional).
    pub fn parse(text: &str) -> Option<TaskKey> {
        let (e, v) = text.split_once('/')?;
        let (e, v) = (e.trim(), v.trim());
        (!e.is_empty() && !v.is_empty() && !v.contains('/')).then(|| TaskKey {
            experiment: e.into(),
            variant: v.into(),
        })
    }

    /// The run of `solver` on this task.
    pub fn run(&self, solver: &str) -> RunKey {
        RunKey::new(&self.experiment, &self.variant, solver)
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
        let k = RunKey::new("jia2019-clover", "vltco", EXACT_ID);
        assert_eq!(k.to_string(), "jia2019-clover / vltco / exact");
        assert_eq!(k.stem(), "vltco__exact");
        assert_eq!(TaskKey::parse("jia2019-clover / vltco"), Some(k.task()));
        assert_eq!(TaskKey::parse("jia2019-clover/vltco"), Some(k.task()));
        assert_eq!(TaskKey::parse("jia2019-clover"), None);
        assert_eq!(TaskKey::parse("a / b / c"), None);
        assert!(k.check().is_ok());
        assert!(RunKey::new("e", "../v", "s").check().is_err());
        assert_eq!(k.task().run("lvi-pdnn").solver, "lvi-pdnn");
        assert_eq!(
            RunKey::parse("jia2019-clover / vltco / exact"),
            Some(k.clone())
        );
        assert_eq!(RunKey::parse("jia2019-clover / vltco"), None);
        assert_eq!(RunKey::parse("a / b / c / d"), None);
        assert_eq!(RunKey::parse("a / b / "), None);
    }
}
