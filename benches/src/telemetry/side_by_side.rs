//! `benches/results/side-by-side/build.csv`: the cold release build of `reproduce` at two
//! revisions on one machine, one after the other (written by
//! `benches/side_by_side/build_and_runs.sh BASELINE CANDIDATE`, which prints each build and,
//! without `--build-only`, the papers' runs' `sim_s` ratios with
//! `benches/side_by_side/compare.py`). The build ratio is computed here only ([`compare`]).
//!
//! A build's CPU time is the user plus system seconds of cargo and every process it starts; a
//! revision's, the median over its rounds (its wall time likewise). The ratio is the
//! candidate's median over the baseline's; issue 38's target is at most [`TARGET_RATIO`] of
//! [`BASELINE`]'s build. CPU seconds are the comparable figure on a shared machine: wall time
//! stretches with whatever else runs, which the load average before each build records.

use records::table::Row;
use serde::{Deserialize, Serialize};

/// The file's path inside `benches/results/`.
pub const FILE: &str = "side-by-side/build.csv";
/// The revision issue 38 measures the build against, as the script is given it.
pub const BASELINE: &str = "f5570fd";
/// Issue 38's target: the candidate's cold build at most this fraction of the baseline's.
pub const TARGET_RATIO: f64 = 0.7;

/// One cold build of one revision.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SideBySideBuildRow {
    /// The revision as the script was given it (a branch, a tag or a short commit).
    pub revision: String,
    /// Its commit (40 hex digits).
    pub commit: String,
    /// The round (1-based; the revisions take turns within a round).
    pub round: usize,
    /// Wall seconds of the build.
    pub wall_s: f64,
    /// User CPU seconds of cargo and every process it started.
    pub user_s: f64,
    /// System CPU seconds, likewise.
    pub sys_s: f64,
    /// The one-minute load average before the build.
    pub load1: f64,
}

impl Row for SideBySideBuildRow {}

impl SideBySideBuildRow {
    /// CPU seconds: user plus system.
    pub fn cpu_s(&self) -> f64 {
        self.user_s + self.sys_s
    }
}

/// One revision's builds, summarised.
#[derive(Clone, Debug, PartialEq)]
pub struct Builds {
    /// The revision as the script was given it.
    pub revision: String,
    /// Its commit, abbreviated to 12 hex digits.
    pub commit: String,
    /// Its builds.
    pub rounds: usize,
    /// Median CPU seconds.
    pub cpu_s: f64,
    /// Median wall seconds.
    pub wall_s: f64,
    /// The highest load average before any of its builds.
    pub max_load1: f64,
}

/// The baseline's and the candidate's builds and the verdict.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// [`BASELINE`]'s builds.
    pub baseline: Builds,
    /// The other revision's builds (the file's first revision that is not the baseline).
    pub candidate: Builds,
    /// Candidate over baseline, median CPU seconds.
    pub cpu_ratio: f64,
    /// Candidate over baseline, median wall seconds.
    pub wall_ratio: f64,
    /// Whether `cpu_ratio` is at most [`TARGET_RATIO`].
    pub met: bool,
}

fn builds(rows: &[SideBySideBuildRow], revision: &str) -> Option<Builds> {
    let mine: Vec<&SideBySideBuildRow> = rows.iter().filter(|r| r.revision == revision).collect();
    let first = mine.first()?;
    Some(Builds {
        revision: revision.to_string(),
        commit: first.commit.chars().take(12).collect(),
        rounds: mine.len(),
        cpu_s: super::throughput::median(mine.iter().map(|r| r.cpu_s()).collect()),
        wall_s: super::throughput::median(mine.iter().map(|r| r.wall_s).collect()),
        max_load1: mine
            .iter()
            .map(|r| r.load1)
            .fold(f64::NEG_INFINITY, f64::max),
    })
}

/// [`BASELINE`] against the file's other revision; None unless both were built.
pub fn compare(rows: &[SideBySideBuildRow]) -> Option<Comparison> {
    let baseline = builds(rows, BASELINE)?;
    let other = rows.iter().find(|r| r.revision != BASELINE)?;
    let candidate = builds(rows, &other.revision)?;
    let cpu_ratio = candidate.cpu_s / baseline.cpu_s;
    Some(Comparison {
        cpu_ratio,
        wall_ratio: candidate.wall_s / baseline.wall_s,
        met: cpu_ratio <= TARGET_RATIO,
        baseline,
        candidate,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(
        revision: &str,
        round: usize,
        wall_s: f64,
        user_s: f64,
        load1: f64,
    ) -> SideBySideBuildRow {
        SideBySideBuildRow {
            revision: revision.to_string(),
            commit: format!("{revision}0123456789abcdef"),
            round,
            wall_s,
            user_s,
            sys_s: 10.0,
            load1,
        }
    }

    #[test]
    fn the_ratio_is_of_the_medians_of_cpu_seconds_and_judged_against_the_target() {
        // Baseline CPU 410 and 430 (median 420), candidate 290 and 300 (median 295): 0.702,
        // just short of 0.7.
        let rows = vec![
            row(BASELINE, 1, 200.0, 400.0, 1.0),
            row("cand", 1, 150.0, 280.0, 3.0),
            row(BASELINE, 2, 220.0, 420.0, 2.0),
            row("cand", 2, 170.0, 290.0, 0.5),
        ];
        let c = compare(&rows).unwrap();
        assert_eq!((c.baseline.cpu_s, c.candidate.cpu_s), (420.0, 295.0));
        assert_eq!((c.baseline.wall_s, c.candidate.wall_s), (210.0, 160.0));
        assert!((c.cpu_ratio - 295.0 / 420.0).abs() < 1e-12 && !c.met);
        assert_eq!((c.candidate.rounds, c.candidate.max_load1), (2, 3.0));
        assert_eq!(c.candidate.commit, "cand01234567");
        let faster = vec![
            row(BASELINE, 1, 200.0, 400.0, 1.0),
            row("cand", 1, 150.0, 270.0, 1.0),
        ];
        assert!(compare(&faster).unwrap().met);
    }

    #[test]
    fn without_both_revisions_there_is_no_comparison() {
        assert_eq!(compare(&[row(BASELINE, 1, 1.0, 1.0, 0.0)]), None);
        assert_eq!(compare(&[row("cand", 1, 1.0, 1.0, 0.0)]), None);
    }
}
