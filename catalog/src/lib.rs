//! driftbench's catalog: what runs exist and what they are called, as data.
//!
//! An experiment file ([`experiment`]) describes runs (`spec::RunSpec`): a robot from the
//! registry (`robots::registry`), a path and a scheme (crate `spec`), a solver
//! (`spec::SolverChoice`: the exact optimum in the loop, a registered QP solver,
//! `spec::numerical`, or a network as `settings::solver_spec` writes it; its kind is a
//! `spec::SolverKind`), an integrator (`settings::integrator`) and where the run
//! is scored (`spec::Scoring`). A variant may stand for many through a
//! `sweep` table ([`sweep`], expanded at the TOML level). Every run is identified by ids, not
//! labels (`spec::run_key`, `spec::ids`), and every id or label that becomes a file name obeys
//! `spec::naming`. The
//! errors of all of it are in [`error`]. [`root`] finds
//! the project (the directory of `experiments/`, `results/` and `report/`) and the code
//! revision runs are stamped with; [`task_set`] reads the control experiments' standard task
//! set (`experiments/control/tasks.toml`, into `spec::TaskSet`); [`robot_files`] registers a paper's own robot files
//! (`papers/<paper>/robots/*.toml`) with the robot registry. The solvers' own settings (network specifications,
//! integrator settings) are crate `settings`', below this crate and the solvers alike: this
//! crate reads them from files, it does not define them.
//!
//! Nothing here builds or runs a solver: the engine (crate `simulation`) builds the runs. A
//! file is read and validated here as data; the orchestrator then checks every run of it with
//! the engine's setup and places a failure at the field at fault
//! ([`experiment::DeclaredRun`]), before anything runs.
//! Crates that only read or present results depend on this crate, not on the engine.

#![deny(missing_docs)]

pub mod error;
pub mod experiment;
mod fields;
pub mod robot_files;
pub mod root;
pub mod sweep;
pub mod task_set;
