//! The newcomer's clock: the last run's phases (`benches/results/phases.csv`) in all, and per revision
//! a fresh clone's steps together (`benches/results/clock.csv`).

use crate::telemetry::clock::ClockRow;
use reproduce::phases::PhaseRow;

/// The wall time of the phases that ran (s), in all.
pub fn phases_seconds(phases: &[PhaseRow]) -> f64 {
    phases.iter().filter_map(|r| r.seconds).sum()
}

/// One revision's clone timed: its steps together.
#[derive(Clone, Debug, PartialEq)]
pub struct CommitClock<'a> {
    pub commit: &'a str,
    /// The revision as given to the script (its first step's).
    pub revision: &'a str,
    /// The steps' wall times summed (s).
    pub seconds: f64,
    /// The steps' ids, in file order.
    pub steps: Vec<&'static str>,
    /// Some step exited with a non-zero code.
    pub failed: bool,
}

/// Per commit, in file order.
pub fn by_commit(clock: &[ClockRow]) -> Vec<CommitClock<'_>> {
    records::table::distinct(clock, |r| &r.commit)
        .into_iter()
        .map(|commit| {
            let steps: Vec<&ClockRow> = clock.iter().filter(|r| r.commit == commit).collect();
            CommitClock {
                commit,
                revision: &steps[0].revision,
                seconds: steps.iter().map(|r| r.seconds).sum::<f64>(),
                steps: steps.iter().map(|r| r.step.id()).collect(),
                failed: steps.iter().any(|r| r.exit_code != 0),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_commit_sums_its_steps() {
        let csv = "revision,commit,step,seconds,exit_code,machine,cores,date\n\
                   HEAD,c1,build,300,0,CPU,2,d\n\
                   HEAD,c1,reproduce,150,0,CPU,2,d\n\
                   old,c0,test,60,101,CPU,2,d\n";
        let clock: Vec<ClockRow> = records::table::from_reader(csv.as_bytes()).unwrap();
        let commits = by_commit(&clock);
        assert_eq!(commits.len(), 2);
        assert_eq!(
            (commits[0].commit, commits[0].revision, commits[0].seconds),
            ("c1", "HEAD", 450.0)
        );
        assert_eq!(commits[0].steps, ["build", "reproduce"]);
        assert!(!commits[0].failed && commits[1].failed);
        let phases_csv =
            "phase,status,seconds,share_pct,items,note,selection,whole,machine,cores,git_rev\n\
                          setup,ran,1.0,25.0,,,s,false,CPU,2,abc\n\
                          runs,ran,3.0,75.0,12,,s,false,CPU,2,abc\n\
                          explain,skipped,,,,,s,false,CPU,2,abc\n";
        let phases: Vec<PhaseRow> = records::table::from_reader(phases_csv.as_bytes()).unwrap();
        assert_eq!(phases_seconds(&phases), 4.0);
    }
}
