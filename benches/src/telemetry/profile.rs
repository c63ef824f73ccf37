//! `benches/results/profile.csv`: where one paper's reproduction spends its time, by sampling profile
//! (written by `benches/profile/paper.sh PAPER`, which runs perf over the release binary and
//! sorts each sample with `benches/profile/classify.py`; the row's `paper` says which).
//!
//! One [`ProfileRow`] per (part, category): the part of the program (the neural runs'
//! `simulation`, the `exact column`'s right-hand side, the `observer` of accepted steps,
//! `other`), the category inside it, whether it is part of the simulation's floor (the RHS,
//! Jacobian and LU work the run's counts require), and its samples. A share of the simulation
//! is the category's samples over all the simulation's samples; the floor ratio of the
//! simulation is all its samples over its floor's ([`floor_ratio`]).

use records::table::Row;
use serde::{Deserialize, Serialize};

/// The file name inside `benches/results/`.
pub const FILE: &str = "profile.csv";
/// [`ProfileRow::part`] of the neural runs' integration.
pub const SIMULATION: &str = "simulation";
/// [`ProfileRow::part`] of the exact column's right-hand side: its QP solves.
pub const EXACT_COLUMN: &str = "exact column";
/// [`ProfileRow::category`] of the right-hand side (the network and the QP assembly).
pub const RHS: &str = "RHS (network and QP assembly)";

/// One row of `benches/results/profile.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProfileRow {
    /// `simulation`, `exact column`, `observer` or `other`.
    pub part: String,
    /// What the samples were doing (`RHS (network and QP assembly)`, `LU factorisation`, ...).
    pub category: String,
    /// `yes` when the category is part of the floor.
    pub floor: String,
    /// Samples taken in the category.
    pub samples: usize,
    /// Samples over all the process's samples.
    pub share_of_process: f64,
    /// Samples over the simulation's (simulation rows only).
    pub share_of_simulation: Option<f64>,
    /// Samples / frequency / passes: CPU milliseconds per pass of the paper's runs.
    pub ms_per_pass: f64,
    /// The paper whose runs were profiled (`reproduce --paper <paper>`).
    pub paper: String,
    /// Passes of the paper's runs the profile covered.
    pub passes: usize,
    /// The sampling frequency (Hz).
    pub frequency_hz: f64,
    /// The code revision profiled (as `runs.csv`'s `git_rev`).
    pub git_rev: String,
}

impl Row for ProfileRow {}

impl ProfileRow {
    /// Whether the category is part of the simulation's floor (`floor` is `yes`).
    pub fn in_floor(&self) -> bool {
        self.floor == "yes"
    }
}

/// The rows of one paper's profile, in file order.
pub fn of_paper(rows: &[ProfileRow], paper: &str) -> Vec<ProfileRow> {
    rows.iter().filter(|r| r.paper == paper).cloned().collect()
}

/// The simulation's samples over its floor's (None without simulation or floor samples).
pub fn floor_ratio(rows: &[ProfileRow]) -> Option<f64> {
    let simulation = rows.iter().filter(|r| r.part == SIMULATION);
    let (all, floor) = simulation.fold((0usize, 0usize), |(all, floor), r| {
        (
            all + r.samples,
            floor + if r.in_floor() { r.samples } else { 0 },
        )
    });
    (floor > 0).then(|| all as f64 / floor as f64)
}

/// The integration's samples (the simulation's and the exact column's: what a run's `sim_s`
/// times) over its floor's (the simulation's floor, and the whole exact column, every sample of
/// which is a right-hand side, i.e. a QP solve); None without floor samples.
pub fn integration_floor_ratio(rows: &[ProfileRow]) -> Option<f64> {
    let (all, floor) =
        rows.iter()
            .fold((0usize, 0usize), |(all, floor), r| match r.part.as_str() {
                SIMULATION if r.in_floor() => (all + r.samples, floor + r.samples),
                SIMULATION => (all + r.samples, floor),
                EXACT_COLUMN => (all + r.samples, floor + r.samples),
                _ => (all, floor),
            });
    (floor > 0).then(|| all as f64 / floor as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(part: &str, floor: bool, samples: usize) -> ProfileRow {
        ProfileRow {
            part: part.into(),
            category: "c".into(),
            floor: if floor { "yes" } else { "no" }.into(),
            samples,
            share_of_process: 0.0,
            share_of_simulation: None,
            ms_per_pass: 0.0,
            paper: "p".into(),
            passes: 1,
            frequency_hz: 1.0,
            git_rev: "r".into(),
        }
    }

    #[test]
    fn the_floor_ratio_counts_the_simulation_only() {
        let rows = [
            row(SIMULATION, true, 60),
            row(SIMULATION, false, 20),
            row("observer", false, 500),
        ];
        assert_eq!(floor_ratio(&rows), Some(80.0 / 60.0));
        assert_eq!(floor_ratio(&rows[1..]), None);
    }

    #[test]
    fn the_integration_floor_ratio_counts_the_exact_column_as_floor() {
        let rows = [
            row(SIMULATION, true, 60),
            row(SIMULATION, false, 20),
            row(EXACT_COLUMN, false, 100),
            row("observer", false, 500),
        ];
        assert_eq!(integration_floor_ratio(&rows), Some(180.0 / 160.0));
        assert_eq!(integration_floor_ratio(&rows[3..]), None);
    }
}
