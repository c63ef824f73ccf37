//! driftbench's simulation layer: experiment files in, runs out.
//!
//! An experiment file ([`experiment`]) describes runs ([`experiment::Job`]): a robot from the
//! registry ([`robot_registry`]), a path and a scheme (crate `schemes`), and a solver: the exact
//! optimum in the loop or one of the papers' networks (crate `solvers`). [`run::run_job`] couples
//! arm and solver into one ODE ([`coupled`]), integrates it, observes every accepted step
//! ([`metrics`]: drift, position error, margins, the score against the exact optimum) and
//! returns a [`run::RunRecord`]; [`runner`] runs many in parallel. Writing the records is the
//! `records` crate's work, presenting them the `presentation` crate's. [`root`] finds the
//! project (experiments/, results/, report/) and the code revision runs are stamped with.
//! [`score_trajectory`] scores a trajectory produced elsewhere on a task, with the metrics and
//! the score of a run. [`task_numbers`] computes a task's check values (its task card's).

pub mod coupled;
pub mod error;
pub mod experiment;
pub mod metrics;
pub mod naming;
pub mod robot_registry;
pub mod root;
pub mod run;
pub mod run_key;
pub mod runner;
pub mod score_trajectory;
pub mod simulate;
pub mod sweep;
pub mod task_numbers;
