//! driftbench's results layer: what a run leaves behind and how it is kept.
//!
//! - [`runs`]: the schema of `results/runs.csv` ([`runs::RunRow`], one row per run, made by the
//!   engine from its record of the run); atomic writes; reading with the schema checked.
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
//! - [`owned_dir`]: a directory the program owns; the only way a name read from a file becomes
//!   a path under it (plain names, no symbolic link leaving it).
//! - [`integrity`]: the manifest of what the program wrote (line count, size, SHA-256 per file).
//! - [`tracked_dir`]: an owned directory with its manifest: writes recorded, edits found,
//!   deletions only of files the program provably wrote.
//! - [`results_dir`]: `results/` as one type: lock, layout, traces, pruning.
//! - [`journal`]: the checkpoint of finished runs that an interrupted run resumes from;
//!   [`kill_point`]: the test hook that kills the process after any durable step.
//! - [`shard`]: cluster runs: which shard a run belongs to, the shard directory's binding and
//!   manifest, the merge checks; [`fnv`]: the stable hash they use.
//! - [`sorted`]: rows in key order, streamed: a `runs.csv` read row by row, sources merged
//!   k-way, the latest row of each key kept (a shard's fold and a merge, in flat memory).
//! - [`migrate`]: results written before run ids (labels as identities), brought up to date once.
//! - [`trajectory`]: a trajectory made elsewhere, scored, as a row (its file is read by crate
//!   `inputs`, `inputs::trajectory`).
//! - [`percentile`]: the one percentile definition of the workspace (numpy's default).
//! - [`control`]: the control experiments' result files (`results/control*.csv`,
//!   `results/cycles*.csv`).
//! - [`ladder`], [`attribution`]: the explanation's result files (`results/ladder.csv`,
//!   `results/attribution.csv`); [`inference`]: the setup inference's (`results/inference.csv`,
//!   `results/inference-entries.csv`).
//!
//! The report reads every one of these files through this crate alone: rendering needs the
//! records, not the solvers that made them. What is decided from them (claims, the leaderboard,
//! the regression gate, verdicts, fits) and the papers as data are crate `analysis`'s: this
//! crate holds the schemas and the store, no verdict.

#![deny(missing_docs)]

pub mod attribution;
pub mod control;
pub mod dof_cost;
pub mod error;
pub mod failure_kind;
pub mod fnv;
pub mod index;
pub mod inference;
pub mod integrity;
pub mod journal;
pub mod kill_point;
pub mod ladder;
pub mod migrate;
pub mod owned_dir;
pub mod percentile;
pub mod qp_replay;
pub mod results_dir;
pub mod runs;
pub mod shard;
pub mod sorted;
pub mod table;
pub mod timing;
pub mod trace;
pub mod tracked_dir;
pub mod trajectory;
