//! What the report's Performance page says about the solvers' cost and the runs' times,
//! computed here so that the page only formats it: ratios of medians, per-step quotients,
//! fits and the verdicts against their targets, each a typed summary of one results file.
//!
//! - [`instant`]: per instant at the Jaco2's size (`results/dof-cost.csv`): each quantity's
//!   median over the network RHS and the KKT floor, and the exact solve against its target;
//! - [`replay`]: the exact reference per tick against DAQP (`results/qp-replay.csv`);
//! - [`whole_runs`]: the reproduction's runs per step by solver kind (`results/runs.csv`), and
//!   the whole runs against the papers' MATLAB times;
//! - [`dof`]: the cost against the number of joints: the fits' extent, the whole runs per N,
//!   the growth past the registry's sizes.
//!
//! The suite's measurements of itself (its build and clock, its phases, its sampling profiles,
//! its speed-up over earlier revisions) are judged by crate `driftbench-benches`
//! (`benches/REPORT.md`), not here.

pub mod dof;
pub mod instant;
pub mod replay;
pub mod whole_runs;
