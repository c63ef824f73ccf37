//! driftbench's catalog: what runs exist and what they are called, as data.
//!
//! An experiment file ([`PaperFile`], its [`Experiment`]s and their [`Variant`]s) describes
//! runs (`spec::RunSpec`): a robot from the registry (`robots::registry`), a path and a scheme
//! (crate `spec`), a solver (`spec::SolverChoice`: the exact optimum in the loop, a registered
//! QP solver, `spec::numerical`, or a network as `settings::solver_spec` writes it; its kind is
//! a `spec::SolverKind`), an integrator (`settings::integrator`) and where the run is scored
//! (`spec::Scoring`). A variant may stand for many through a `sweep` table (the sweep grammar,
//! module `sweep`: a sweep is kept as its plan, [`Variants`], and a variant made by index
//! with [`PaperFile::variant`]; which of a sweep's runs keep traces: [`KeptTraces`]; whether the
//! files describe a run key, decided from the names without making every run: [`RunLookup`]). Every run is identified by ids, not labels (`spec::run_key`, `spec::ids`),
//! and every id or label that becomes a file name obeys `spec::naming`. The errors of all of it
//! are re-exported here ([`ExperimentFileError`] wraps the rest). [`find_root`] finds the
//! project (the directory of `experiments/`, `results/` and `report/`); [`load_task_set`] reads
//! the control experiments' standard task set (`experiments/control/tasks.toml`, into
//! `spec::TaskSet`); [`register_paper_robots`] registers a paper's own robot files
//! (`papers/<paper>/robots/*.toml`) with the robot registry. The solvers' own settings (network
//! specifications, integrator settings) are crate `settings`', below this crate and the solvers
//! alike: this crate reads them from files, it does not define them.
//!
//! Nothing here builds or runs a solver: the engine (crate `simulation`) builds the runs. A
//! file is read and validated here as data; the orchestrator then checks every run of it with
//! the engine's setup and places a failure at the field at fault ([`DeclaredRun`]), before
//! anything runs. Crates that only read or present results depend on this crate, not on the
//! engine.
//!
//! Every module is private; what other crates use is re-exported below.

#![deny(missing_docs)]

mod error;
mod experiment;
mod fields;
mod lookup;
mod robot_files;
mod root;
mod sweep;
mod task_set;

pub use error::{
    ExperimentError, ExperimentFileError, FieldAt, FieldError, KeyPathError, RangeError,
    SweepError, SweepKeyError, TaskSetError, TomlError,
};
pub use experiment::{
    default_exact_integrator, load_dir, BaseSpec, DeclaredRun, ExpectedFailure, Experiment,
    PaperFile, Variant, Variants,
};
pub use lookup::{Found, RunLookup};
pub use robot_files::{register_paper_robots, register_path, RobotPathError};
pub use root::{find_root, root_from_current_dir, RootNotFound};
pub use sweep::{KeptTraces, Traces, CHECKED_WHOLE, MAX_EXPANSION, NAMES_COMPARED};
pub use task_set::{load_task_set, TASK_SET_FILE};
