//! driftbench's row schemas: what a run leaves behind, as rows. Each type serialises to a
//! writer and parses from a reader; where the rows are kept (the sealed results directory, its
//! manifest, the journal, the shards, the atomic write) is crate `store`'s, which links this
//! crate, never the other way.
//!
//! - the schema of `results/runs.csv` ([`RunRow`], one row per run, made by the engine from its
//!   record of the run; its [`Status`]); the rows' checks ([`check_run_rows`]) and their merge
//!   ([`merge_runs`]).
//! - the `failure_kind` column, what stopped a run ([`FailureKind`]).
//! - a run's trace ([`TracePoint`], `results/traces/`).
//! - [`table`]: CSV tables whose per-joint columns follow the robot's joint count.
//! - [`dof_cost`]: the cost against the number of joints (`results/dof-cost.csv`).
//! - [`index`]: the stored runs indexed as the report and the analyses look them up.
//! - the compared runs timed alone, repeated (`results/leaderboard-timing.csv`, [`Timings`]),
//!   which the leaderboard ranks by.
//! - the exact reference per recorded QP against DAQP (`results/qp-replay.csv`,
//!   [`QpReplayRow`]): the solvers' cost, a reader's comparison with a peer. The suite's
//!   measurements of itself (its build, its clock, its phases, its profiles, its speed-up over
//!   earlier revisions) are not results: crate `driftbench-benches` holds their schemas
//!   (`benches/results/`).
//! - a trajectory made elsewhere, scored, as a row ([`score_row`]; its file is read by crate
//!   `inputs`, `inputs::trajectory`).
//! - [`percentile()`]: the one percentile definition of the workspace (numpy's default).
//! - [`control`]: the control experiments' result files (`results/control*.csv`,
//!   `results/cycles*.csv`).
//! - the explanation's result files (`results/ladder.csv`, [`LadderRow`];
//!   `results/attribution.csv`, [`AttributionRow`]); [`inference`]: the setup inference's
//!   (`results/inference.csv`, `results/inference-entries.csv`).
//!
//! The public modules are the files with a vocabulary of their own (column names, readers and
//! writers by the same name); every other schema is an item at the root.
//!
//! The report reads every one of these files through this crate and the store alone: rendering
//! needs the records, not the solvers that made them. What is decided from them (claims, the
//! leaderboard, the regression gate, verdicts, fits) and the papers as data are crate
//! `analysis`'s: this crate holds the schemas, no verdict.

#![deny(missing_docs)]

mod attribution;
pub mod control;
pub mod dof_cost;
mod error;
mod failure_kind;
pub mod index;
pub mod inference;
mod ladder;
mod percentile;
mod qp_replay;
mod runs;
pub mod table;
mod timing;
mod trace;
mod trajectory;
pub use attribution::{AttributionRow, Component};
pub use error::RowsError;
pub use failure_kind::FailureKind;
pub use ladder::{LadderMethod, LadderRow};
pub use percentile::percentile;
pub use qp_replay::{QpReplayRow, FILE as QP_REPLAY_FILE, SUITE as QP_REPLAY_SUITE};
pub use runs::{
    check_names as check_run_names, check_rows as check_run_rows, merge as merge_runs, runs_csv,
    RunRow, Status,
};
pub use timing::{TimingRow, Timings, FILE as TIMING_FILE, REPETITIONS as TIMING_REPETITIONS};
pub use trace::{trace_csv, TracePoint};
pub use trajectory::{score_row, trajectory_id, TRAJECTORY_KIND};
