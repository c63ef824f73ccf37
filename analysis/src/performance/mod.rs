//! What the report's Performance page says about the measurements, computed here so that the
//! page only formats it: ratios of medians, sums of times, per-step quotients, fits and the
//! verdicts against the targets of the issue, each a typed summary of one results file.
//!
//! - [`instant`]: per instant at the Jaco2's size (`results/dof-cost.csv`): each quantity's
//!   median over the network RHS and the KKT floor, and the exact solve against its target;
//! - [`replay`]: the exact reference per tick against DAQP (`results/qp-replay.csv`);
//! - [`whole_runs`]: the reproduction's runs per step by solver kind (`results/runs.csv`), and
//!   the whole runs against the papers' MATLAB times;
//! - [`dof`]: the cost against the number of joints: the fits' extent, the whole runs per N,
//!   the growth past the registry's sizes;
//! - [`profile`]: what a paper's sampling profile says (`results/profile.csv`);
//! - [`speedup`]: every paper's runs against an earlier revision (`results/speedup.csv`);
//! - [`clock`]: the newcomer's clock (`results/phases.csv`, `results/clock.csv`);
//! - [`explain_phase`]: where the reproduction's explain phase spends its time
//!   (`results/ladder.csv`'s rung times against `results/phases.csv`);
//! - [`build`]: where a cold build spends its time (`results/build-profile.csv`): its CPU
//!   bound, its critical path, its costliest units.

pub mod build;
pub mod clock;
pub mod dof;
pub mod explain_phase;
pub mod instant;
pub mod profile;
pub mod replay;
pub mod speedup;
pub mod whole_runs;
