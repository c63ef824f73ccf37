//! driftbench's row schemas: what a run leaves behind, as rows. Each type serialises to a
//! writer and parses from a reader; where the rows are kept (the sealed results directory, its
//! manifest, the journal, the shards, the atomic write) is crate `store`'s, which links this
//! crate, never the other way.
//!
//! - [`runs`]: the schema of `results/runs.csv` ([`runs::RunRow`], one row per run, made by the
//!   engine from its record of the run); the rows' checks and their merge.
//! - [`failure_kind`]: the `failure_kind` column, what stopped a run.
//! - [`trace`]: a run's trace ([`trace::TracePoint`], `results/traces/`).
//! - [`table`]: CSV tables whose per-joint columns follow the robot's joint count.
//! - [`dof_cost`]: the cost against the number of joints (`results/dof-cost.csv`).
//! - [`index`]: the stored runs indexed as the report and the analyses look them up.
//! - [`timing`]: the compared runs timed alone, repeated (`results/leaderboard-timing.csv`),
//!   which the leaderboard ranks by.
//! - [`qp_replay`]: the exact reference per recorded QP against DAQP (`results/qp-replay.csv`):
//!   the solvers' cost, a reader's comparison with a peer. The suite's measurements of itself
//!   (its build, its clock, its phases, its profiles, its speed-up over earlier revisions) are
//!   not results: crate `driftbench-benches` holds their schemas (`benches/results/`).
//! - [`trajectory`]: a trajectory made elsewhere, scored, as a row (its file is read by crate
//!   `inputs`, `inputs::trajectory`).
//! - [`percentile`]: the one percentile definition of the workspace (numpy's default).
//! - [`control`]: the control experiments' result files (`results/control*.csv`,
//!   `results/cycles*.csv`).
//! - [`ladder`], [`attribution`]: the explanation's result files (`results/ladder.csv`,
//!   `results/attribution.csv`); [`inference`]: the setup inference's (`results/inference.csv`,
//!   `results/inference-entries.csv`).
//!
//! The report reads every one of these files through this crate and the store alone: rendering
//! needs the records, not the solvers that made them. What is decided from them (claims, the
//! leaderboard, the regression gate, verdicts, fits) and the papers as data are crate
//! `analysis`'s: this crate holds the schemas, no verdict.

#![deny(missing_docs)]

pub mod attribution;
pub mod control;
pub mod dof_cost;
pub mod error;
pub mod failure_kind;
pub mod index;
pub mod inference;
pub mod ladder;
pub mod percentile;
pub mod qp_replay;
pub mod runs;
pub mod table;
pub mod timing;
pub mod trace;
pub mod trajectory;
