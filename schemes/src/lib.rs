//! Desired paths and the papers' redundancy-resolution schemes, each turning (t, robot state)
//! into one QP (`qp::Qp`, crate `qp`, which the solvers take). A scheme is a list of terms
//! (objective terms, equality rows, inequality rows, bounds; the table is in the terms' module,
//! `schemes/src/terms/mod.rs`) composed into the one scheme type; the papers' schemes
//! (jia2019's VLTCO family, zhong2021's CMCO, zhang2018's HL-JDF, kong2019's two, robio2018's
//! RMP) are presets that expand to term lists (their specifications are data, crate `spec`;
//! [`build_scheme`] makes the scheme of one). Every scheme takes the joint count as a run-time
//! value: joint vectors are slices, and a scheme allocates its scratch space when it is built,
//! not per QP ([`Scheme`]).
//!
//! Public: the [`Scheme`] trait with its default dQP/dt ([`central_difference`],
//! [`default_step`]), the builders ([`build_scheme`], [`build_composed`]), the merged joint
//! bounds ([`merged_bound`], [`piecewise_bound`]), the tracking term's rotation helpers
//! ([`orientation_error`], [`rotation_exp`], [`rotation_log`]), and the module [`paths`] (the
//! desired paths, a sub-API of their own: [`paths::Path`], [`paths::build_path`]).

#![deny(missing_docs)]

mod build;
mod composed;
mod joint_limits;
pub mod paths;
mod scheme;
mod terms;
pub use build::{build_composed, build_scheme};
pub use joint_limits::{merged_bound, piecewise_bound};
pub use scheme::{central_difference, default_step, Scheme};
pub use terms::tracking::{orientation_error, rotation_exp, rotation_log};
