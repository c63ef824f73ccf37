//! `benches/results/clock.csv`: a newcomer's clock from clone to report, per code revision (written by
//! `benches/clock/clock.sh`, read by benches/REPORT.md, "The newcomer's clock").
//!
//! For each revision the script clones the repository afresh into a temporary directory, with
//! a target directory of its own, and times with the wall clock each [`Step`]: the cold release
//! build of `reproduce`, the whole reproduction, the workspace's tests (their build
//! included) and the Python package's install from nothing. One [`ClockRow`] per revision and step; a step that failed keeps its time and its
//! exit code.

use records::table::Row;
use serde::{Deserialize, Serialize};

/// The file name inside `benches/results/`.
pub const FILE: &str = "clock.csv";

/// What `benches/clock/clock.sh` times.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Step {
    /// `cargo build --release -p reproduce` in the fresh clone (cold: an empty target directory).
    Build,
    /// `cargo run --release -p reproduce`: the whole reproduction, after the build.
    Reproduce,
    /// `cargo test --workspace --release`, the test build included.
    Test,
    /// `pip install ./python` in a fresh virtual environment with a target directory of its
    /// own: the Python package built from nothing.
    Wheel,
}

impl Step {
    /// The id in `benches/results/clock.csv` (and the script's `--only`).
    pub fn id(self) -> &'static str {
        match self {
            Step::Build => "build",
            Step::Reproduce => "reproduce",
            Step::Test => "test",
            Step::Wheel => "wheel",
        }
    }

    /// The command the step times.
    pub fn command(self) -> &'static str {
        match self {
            Step::Build => "cargo build --release -p reproduce",
            Step::Reproduce => "cargo run --release -p reproduce",
            Step::Test => "cargo test --workspace --release",
            Step::Wheel => "pip install ./python",
        }
    }
}

/// One row of `benches/results/clock.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ClockRow {
    /// The revision as given to the script (`cc915b9`, `HEAD`).
    pub revision: String,
    /// The commit it resolved to (12 hex digits).
    pub commit: String,
    /// The step timed.
    pub step: Step,
    /// Wall time (s).
    pub seconds: f64,
    /// The step's exit code (0: it succeeded).
    pub exit_code: i32,
    /// CPU model (`/proc/cpuinfo`) and logical cores (`nproc`).
    pub machine: String,
    /// Logical cores (`nproc`).
    pub cores: usize,
    /// When the step started (UTC, ISO 8601).
    pub date: String,
}

impl Row for ClockRow {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_row_as_the_script_writes_it() {
        // The script quotes the revision and the machine (either may hold a comma or a quote).
        let csv = "revision,commit,step,seconds,exit_code,machine,cores,date\n\
                   \"HEAD\",0123456789ab,reproduce,130.250,0,\"Test CPU, 2 GHz\",2,2026-12-03T13:00:00Z\n";
        let rows: Vec<ClockRow> = records::table::from_reader(csv.as_bytes()).unwrap();
        assert_eq!(rows[0].step, Step::Reproduce);
        assert_eq!(rows[0].machine, "Test CPU, 2 GHz");
        assert_eq!(rows[0].step.id(), "reproduce");
        let bad = csv.replace(",reproduce,", ",bench,");
        assert!(records::table::from_reader::<ClockRow, _>(bad.as_bytes()).is_err());
    }
}
