//! driftbench's results layer: what a run leaves behind and how it is kept.
//!
//! - [`runs`]: the schema of `results/runs.csv` ([`runs::RunRow`], one row per run, from a
//!   simulation's [`simulation::run::RunRecord`]) and of the traces; atomic writes; reading
//!   with the schema checked.
//! - [`table`]: CSV tables whose per-joint columns follow the robot's joint count.
//! - [`dof_cost`]: the cost against the number of joints (`results/dof-cost.csv`).
//! - [`index`]: the stored runs indexed as the report and the analyses look them up.
//! - [`leaderboard`]: every velocity-level solver on the standard task set, scored as
//!   qpbenchmark scores QP solvers (`results/leaderboard.csv`).
//! - [`journal`]: the checkpoint of finished runs that an interrupted run resumes from.
//! - [`shard`]: cluster runs: which shard a run belongs to, the shard manifest, the merge checks.
//! - [`gate`]: the regression gate (fresh rows against committed ones).
//! - [`paper_values`]: the published numbers (`report/paper-values.csv`) and which run each
//!   one is compared with.

pub mod dof_cost;
pub mod gate;
pub mod index;
pub mod journal;
pub mod leaderboard;
pub mod paper_values;
pub mod runs;
pub mod shard;
pub mod table;
