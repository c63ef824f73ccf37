//! driftbench's runs as data: what the experiment files say and the engine builds from.
//!
//! - a scheme and its parameters by the papers' names ([`SchemeSpec`], its [`Level`]), its
//!   checks, and the list of terms each preset expands to;
//! - a composed scheme's terms ([`ComposedSpec`], [`TermSpec`]);
//! - a desired path by name, duration, size and pose ([`PathSpec`]), the path names with their
//!   default sizes and durations ([`PATH_NAMES`]), and the checks of its fields ([`PathError`]);
//! - the three readings of the repetitive-motion term's linear coefficient ([`RmpReading`]);
//! - a run's description ([`RunSpec`]: its solver, scoring, network start and limits
//!   overrides), and the part of a run that could not be built ([`SetupError`]);
//! - a registered QP solver run at every instant of a fixed-step loop, with its settings
//!   ([`NumericalSpec`]); the kind of solver behind a results row ([`SolverKind`]);
//! - a robot's tool offset and base as data, and why one does not fit ([`MountSpec`],
//!   [`MountError`]);
//! - validated ids (paper, experiment, variant, solver: the module [`ids`], the one public
//!   module, a vocabulary of its own), a run's and a task's identity made of them ([`RunKey`],
//!   [`TaskKey`]), and the rules for ids and labels that name files ([`check_name`], [`slug`]);
//! - the control experiments' standard task set ([`TaskSet`]: its tasks and their [`Budget`])
//!   and their main control period ([`MAIN_H`]).
//!
//! Crate `catalog` reads experiment files (and the task set) into these types; the engine (crate `schemes`, then
//! `simulation`) builds its runtime objects from them. The crate links no engine and no file
//! format, only crate `settings` (the solvers' settings as data, a leaf like this one), so that
//! the experiment files' reader and the results' schemas can state a run without compiling
//! kinematics.

#![deny(missing_docs)]

pub mod ids;
mod mount;
mod naming;
mod numerical;
mod path;
mod rmp;
mod run;
mod run_key;
mod scheme;
mod solver_kind;
mod task_set;
mod terms;

pub use mount::{MountError, MountSpec, MAX_OFFSET};
pub use naming::{
    check_name, has_markup, slug, NameError, MAX_EXPERIMENT_ID, MAX_SOLVER_LABEL, MAX_VARIANT_LABEL,
};
pub use numerical::{NumericalSpec, NumericalSpecError};
pub use path::{
    default_duration, default_scale, phase_supported, scale_provenance, PathError, PathSample,
    PathSpec, MAX_DURATION, MIN_DURATION, PATH_NAMES,
};
pub use rmp::RmpReading;
pub use run::{
    JobPart, LimitsError, LimitsSpec, NetworkInit, RunSpec, Scoring, SetupError, SolverChoice,
    EXACT_ID,
};
pub use run_key::{KeyError, RunKey, TaskKey};
pub use scheme::{hl_jdf_name, vltco_name, Level, RepetitiveForm, SchemeError, SchemeSpec};
pub use solver_kind::SolverKind;
pub use task_set::{Budget, TaskRef, TaskSet, MAIN_H};
pub use terms::{tracking_axes, BoundPlacement, ComposedSpec, Penalty, Task, TermSpec};
