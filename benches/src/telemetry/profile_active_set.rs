//! `benches/results/profile-active-set.csv`: where the hot-started active-set solve of the 7-variable QP
//! spends its time, by sampling profile (written by `benches/profile/active_set.sh`, which runs
//! perf over the criterion bench `jia2019/exact-active-set/hot` and sorts each sample by the
//! function it was in with `benches/profile/active_set.py`; that script's module doc lists the
//! categories).
//!
//! One [`HotSolveRow`] per category, with its share of the solve's samples (the bench harness
//! left out), so the shares add up to one.

use records::table::Row;
use serde::{Deserialize, Serialize};

/// The file name inside `benches/results/`.
pub const FILE: &str = "profile-active-set.csv";
/// [`HotSolveRow::category`] of the certification (the KKT residuals of every answer).
pub const CERTIFICATION: &str = "certification (KKT residuals)";

/// One row of `benches/results/profile-active-set.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HotSolveRow {
    /// What the samples were doing (`KKT factorisation and solves (...)`, [`CERTIFICATION`],
    /// `QP validation`, ...).
    pub category: String,
    /// Samples over the solve's samples.
    pub share: f64,
    /// The criterion bench profiled (group/function).
    pub bench: String,
    /// Seconds of criterion's profiling loop the samples were taken over.
    pub seconds: f64,
    /// The sampling frequency (Hz).
    pub frequency_hz: f64,
    /// The code revision profiled (as `runs.csv`'s `git_rev`).
    pub git_rev: String,
}

impl Row for HotSolveRow {}

/// The certification's share of the solve (None if the profile has no such row).
pub fn certification_share(rows: &[HotSolveRow]) -> Option<f64> {
    rows.iter()
        .find(|r| r.category == CERTIFICATION)
        .map(|r| r.share)
}
