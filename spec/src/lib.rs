//! driftbench's runs as data: what the experiment files say and the engine builds from.
//!
//! - [`scheme`]: a scheme and its parameters by the papers' names ([`scheme::SchemeSpec`]),
//!   its checks, and the list of terms each preset expands to;
//! - [`terms`]: a composed scheme's terms ([`terms::ComposedSpec`], [`terms::TermSpec`]);
//! - [`path`]: a desired path by name, duration, size and pose ([`path::PathSpec`]), the path
//!   names with their default sizes and durations, and the checks of its fields;
//! - [`rmp`]: the three readings of the repetitive-motion term's linear coefficient;
//! - [`run`]: a run's solver, scoring, network start and limits overrides, and the part of a
//!   run that could not be built;
//! - [`numerical`]: a registered QP solver run at every instant of a fixed-step loop, with its
//!   settings; [`solver_kind`]: the kind of solver behind a results row;
//! - [`mount`]: a robot's tool offset and base as data, and why one does not fit;
//! - [`ids`]: validated ids (paper, experiment, variant, solver), [`run_key`]: a run's and a
//!   task's identity made of them, and [`naming`]: the rules for ids and labels that name
//!   files;
//! - [`task_set`]: the control experiments' standard task set (its tasks and their budget) and
//!   their main control period.
//!
//! Crate `catalog` reads experiment files (and the task set) into these types; the engine (crate `schemes`, then
//! `simulation`) builds its runtime objects from them. The crate links no engine and no file
//! format, only crate `settings` (the solvers' settings as data, a leaf like this one), so that
//! the experiment files' reader and the results' schemas can state a run without compiling
//! kinematics.

#![deny(missing_docs)]

pub mod ids;
pub mod mount;
pub mod naming;
pub mod numerical;
pub mod path;
pub mod rmp;
pub mod run;
pub mod run_key;
pub mod scheme;
pub mod solver_kind;
pub mod task_set;
pub mod terms;
