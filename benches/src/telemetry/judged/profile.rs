//! What a paper's sampling profile says (`benches/results/profile.csv`, [`crate::telemetry::profile`]): how its
//! process splits into parts, what the papers' MATLAB times are against its simulation's CPU
//! time, and whether the right-hand side is the larger part of the simulation.

use crate::telemetry::profile::{ProfileRow, RHS, SIMULATION};
use analysis::papers::Papers;

/// Each part's share of the process (the shares of its categories summed), in file order.
pub fn part_shares(rows: &[ProfileRow]) -> Vec<(&str, f64)> {
    let mut parts: Vec<(&str, f64)> = Vec::new();
    for r in rows {
        match parts.iter_mut().find(|(p, _)| *p == r.part) {
            Some((_, share)) => *share += r.share_of_process,
            None => parts.push((&r.part, r.share_of_process)),
        }
    }
    parts
}

/// The papers' published MATLAB times together against the simulation's CPU time per pass of
/// one profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MatlabOverSimulation {
    /// The runs the papers time.
    pub runs: usize,
    /// Their MATLAB times summed (s).
    pub matlab_s: f64,
    /// The simulation's CPU time per pass (s).
    pub simulation_s: f64,
    /// `matlab_s` / `simulation_s`.
    pub ratio: f64,
}

/// [`MatlabOverSimulation`] of `profile`, where both times are positive.
pub fn matlab_over_simulation(
    profile: &[ProfileRow],
    papers: &Papers,
) -> Option<MatlabOverSimulation> {
    let simulation_s: f64 = profile
        .iter()
        .filter(|r| r.part == SIMULATION)
        .map(|r| r.ms_per_pass / 1e3)
        .sum();
    let matlab_s: f64 = papers.timed_values().map(|(v, _)| v.value).sum();
    (simulation_s > 0.0 && matlab_s > 0.0).then(|| MatlabOverSimulation {
        runs: papers.timed_values().count(),
        matlab_s,
        simulation_s,
        ratio: matlab_s / simulation_s,
    })
}

/// Whether the simulation's largest category (by samples) is the right-hand side.
pub fn rhs_dominates(profile: &[ProfileRow]) -> bool {
    profile
        .iter()
        .filter(|r| r.part == SIMULATION)
        .max_by(|a, b| a.samples.cmp(&b.samples))
        .is_some_and(|r| r.category == RHS)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn profile() -> Vec<ProfileRow> {
        let csv = "part,category,floor,samples,share_of_process,share_of_simulation,\
                   ms_per_pass,paper,passes,frequency_hz,git_rev\n\
                   simulation,RHS (network and QP assembly),yes,60,0.5,0.75,30.0,demo,2,1000,abc\n\
                   simulation,BDF method,no,20,0.25,0.25,10.0,demo,2,1000,abc\n\
                   observer,metrics,no,40,0.25,,20.0,demo,2,1000,abc\n";
        records::table::from_reader(csv.as_bytes()).unwrap()
    }

    #[test]
    fn parts_sum_their_categories() {
        assert_eq!(
            part_shares(&profile()),
            [("simulation", 0.75), ("observer", 0.25)]
        );
        assert!(rhs_dominates(&profile()));
        // No paper times its runs: nothing to set against the simulation.
        assert!(matlab_over_simulation(&profile(), &Papers::default()).is_none());
    }
}
