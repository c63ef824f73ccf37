//! `results/qp-replay.csv`: the exact reference per tick against DAQP, on the same QPs.
//!
//! `benches/qp_replay/replay.sh` records, through the Python package, the QPs a network is
//! handed along a run (one per distinct instant, the first 2000 of each task, `benches/qp_replay/replay.sh`), then replays
//! the same sequence to the suite's active set (`benches/src/bin/qp_replay.rs`, timed in Rust)
//! and to DAQP (installed from PyPI in the script's own environment, timed by DAQP's own C
//! timers). Warm means each solve starts from the previous QP's answer (the suite's working
//! set; DAQP's workspace updated in place), cold from nothing (the suite with an empty working
//! set; DAQP set up afresh). One [`QpReplayRow`] per task, solver and start.

use crate::table::Row;
use serde::{Deserialize, Serialize};

/// The file name inside `results/`.
pub const FILE: &str = "qp-replay.csv";
/// [`QpReplayRow::solver`] of the suite's active set (the other rows are DAQP's).
pub const SUITE: &str = "active-set";

/// One row of `results/qp-replay.csv` (module docs).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct QpReplayRow {
    /// The task the QPs were recorded on (`<experiment> / <variant>`).
    pub task: String,
    /// The QP's sizes: variables, equalities, general inequalities, finite bounds.
    pub nx: usize,
    /// Equality rows.
    pub n_eq: usize,
    /// General inequality rows.
    pub n_in: usize,
    /// Finite variable bounds.
    pub n_bounds: usize,
    /// QPs replayed, and how many times the whole sequence was.
    pub qps: usize,
    /// Times the whole sequence was replayed.
    pub repeats: usize,
    /// [`SUITE`] or `daqp <version>`.
    pub solver: String,
    /// `warm` or `cold`.
    pub start: String,
    /// Microseconds per solve: the mean over the QPs of each QP's median over the repeats,
    /// and the 95th percentile of those medians.
    pub mean_us: f64,
    /// 95th percentile over the QPs of each QP's median time (us).
    pub p95_us: f64,
    /// The largest |x - x_other|_inf against the other solver's answers on the same QPs.
    pub max_dx_vs_other: f64,
    /// The code revision of the suite's solver (as `runs.csv`'s `git_rev`).
    pub git_rev: String,
}

impl Row for QpReplayRow {}
