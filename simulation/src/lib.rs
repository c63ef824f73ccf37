//! driftbench's simulation layer, the engine: the runs of experiment files in, records out.
//!
//! A run arrives as data (`spec::RunSpec`, which crate `catalog` makes from an experiment
//! file; the engine links no file format): a robot from the registry, a path and a scheme
//! (built by crate `schemes`), and a solver: the exact optimum in the loop or one of the papers'
//! networks (crate `solvers`). [`run_job`] builds the run's parts, couples arm and solver into
//! one ODE ([`NeuralLoop`]), integrates it ([`simulate()`]; a numerical method runs a
//! fixed-step loop instead), observes every accepted step into [`RunMetrics`] (drift, position
//! error, margins, the [`Score`] against the exact optimum) and returns a [`RunRecord`];
//! [`run_jobs`] runs many in parallel. [`check_job`] builds a run's parts without integrating:
//! the orchestrator checks every run of a loaded experiment file with it, before anything runs,
//! to reject what a run would reject. Why a run failed: [`RunError`]. A record as a row of
//! `results/runs.csv`: [`run_row`]; the row's schema, the trace's and writing them are the
//! `records` crate's work, presenting them the `presentation` crate's. [`score_trajectory()`]
//! scores a trajectory produced elsewhere on a task, with the metrics and the score of a run.
//! [`task_numbers()`] computes a task's check values (its task card's). The modules are
//! private; these items are the crate's surface.

#![deny(missing_docs)]

mod coupled;
mod error;
mod metrics;
mod numerical;
mod observer;
mod row;
mod run;
mod runner;
mod score_trajectory;
mod simulate;
mod task_numbers;
pub use coupled::NeuralLoop;
pub use error::RunError;
pub use metrics::{RunMetrics, Score, SETTLE_TIME};
pub use row::run_row;
pub use run::{
    build_cyclic_parts, build_network, check_job, job_model, job_mount, job_robot, qp_shape,
    run_job, run_job_with_network, NetworkBuilder, RunRecord,
};
pub use runner::{map_costliest_first, run_jobs, run_jobs_into, run_jobs_with};
pub use score_trajectory::{score_trajectory, TrajectoryError};
pub use simulate::{simulate, Outcome, Run, Settings, Solver};
pub use task_numbers::{task_numbers, TaskNumbers};
