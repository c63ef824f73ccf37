//! driftbench's simulation layer, the engine: the runs of experiment files in, records out.
//!
//! A run arrives as data (`spec::RunSpec`, which crate `catalog` makes from an experiment
//! file; the engine links no file format): a robot from the registry, a path and a scheme
//! (built by crate `schemes`), and a solver: the exact optimum in the loop or one of the papers' networks (crate
//! `solvers`). [`run::run_job`] builds the run's parts, couples arm and solver into one ODE
//! ([`coupled`]), integrates it ([`simulate`]; a numerical method's fixed-step loop:
//! [`numerical`]), observes every accepted step ([`observer`] into [`metrics`]: drift, position
//! error, margins, the score against the exact optimum) and returns a
//! [`run::RunRecord`]; [`runner`] runs many in parallel. [`run::check_job`] builds a run's parts
//! without integrating: loading an experiment file takes it (the orchestrator hands it to
//! crate `catalog`), to reject what a run would reject. Why a run failed: [`error`]. A record as a row of `results/runs.csv`: [`row`];
//! the row's schema, the trace's and writing them are the `records` crate's work, presenting
//! them the `presentation` crate's. [`score_trajectory`] scores a trajectory
//! produced elsewhere on a task, with the metrics and the score of a run.
//! [`task_numbers`] computes a task's check values (its task card's).

#![deny(missing_docs)]

pub mod coupled;
pub mod error;
pub mod metrics;
pub mod numerical;
pub mod observer;
pub mod row;
pub mod run;
pub mod runner;
pub mod score_trajectory;
pub mod simulate;
pub mod task_numbers;
