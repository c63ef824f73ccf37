//! `benches/results/build-profile.csv`: where a cold `cargo build --release -p reproduce` spends its
//! time, unit by unit (written by `benches/clock/build_profile.sh` from cargo's own
//! `--timings` report, read by benches/REPORT.md, "Where the build's time goes").
//!
//! One [`BuildUnitRow`] per compilation unit: a crate's library or binary, a build script's
//! compilation or its run. Times are seconds from the build's start, as cargo measured them.
//! `unblocked_by` is the unit whose end (or, under pipelining, whose metadata) let this one
//! start: the last of its dependencies to be ready. Following it back from the unit that ends
//! last gives the build's critical path, the chain no number of cores can shorten
//! ([`crate::telemetry::judged::build`]). Every row repeats the build's wall time, the commit and
//! the machine, so the file describes one build.

use records::table::Row;
use serde::{Deserialize, Serialize};

/// The file name inside `benches/results/`.
pub const FILE: &str = "build-profile.csv";

/// What a compilation unit builds (cargo's `target` of the unit).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum UnitKind {
    /// A library (proc-macro crates included).
    Lib,
    /// A binary.
    Bin,
    /// A build script compiled.
    BuildScript,
    /// A build script run (OSQP's C sources compiled by CMake, for example).
    BuildScriptRun,
    /// A test target.
    Test,
}

impl UnitKind {
    /// The id in `benches/results/build-profile.csv`.
    pub fn id(self) -> &'static str {
        match self {
            UnitKind::Lib => "lib",
            UnitKind::Bin => "bin",
            UnitKind::BuildScript => "build-script",
            UnitKind::BuildScriptRun => "build-script-run",
            UnitKind::Test => "test",
        }
    }
}

/// One row of `benches/results/build-profile.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BuildUnitRow {
    /// The unit's index in cargo's report (what `unblocked_by` refers to).
    pub unit: usize,
    /// The crate's name.
    pub crate_name: String,
    /// The crate's version.
    pub version: String,
    /// What the unit builds.
    pub kind: UnitKind,
    /// Whether the crate is one of this workspace's.
    pub workspace: bool,
    /// When the unit started (s from the build's start).
    pub start_s: f64,
    /// How long it took (s of wall time; one unit mostly keeps one core busy).
    pub duration_s: f64,
    /// The unit whose end let this one start (empty: it could start at once).
    pub unblocked_by: Option<usize>,
    /// The commit built (12 hex digits).
    pub commit: String,
    /// CPU model (`/proc/cpuinfo`).
    pub machine: String,
    /// Logical cores (`nproc`): cargo's parallel jobs.
    pub cores: usize,
    /// When the build started (UTC, ISO 8601).
    pub date: String,
    /// The whole build's wall time (s), as the script timed it.
    pub build_wall_s: f64,
}

impl Row for BuildUnitRow {}

impl BuildUnitRow {
    /// When the unit ended (s from the build's start).
    pub fn end_s(&self) -> f64 {
        self.start_s + self.duration_s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_as_the_script_writes_them() {
        let csv = "unit,crate_name,version,kind,workspace,start_s,duration_s,unblocked_by,commit,machine,cores,date,build_wall_s\n\
                   0,itoa,1.0.19,lib,false,0.10,0.25,,abc,\"CPU, x\",2,d,1.0\n\
                   1,osqp-sys,0.6.3,build-script-run,false,0.36,0.14,0,abc,\"CPU, x\",2,d,1.0\n";
        let rows: Vec<BuildUnitRow> = records::table::from_reader(csv.as_bytes()).unwrap();
        assert_eq!(rows[0].unblocked_by, None);
        assert_eq!(rows[1].unblocked_by, Some(0));
        assert_eq!(rows[1].kind, UnitKind::BuildScriptRun);
        assert_eq!(rows[1].kind.id(), "build-script-run");
        assert_eq!(rows[0].machine, "CPU, x");
        assert!((rows[1].end_s() - 0.5).abs() < 1e-12);
        // A kind cargo's report never has, and a flag that is not a boolean, are refused.
        for (good, bad) in [
            (",lib,false,", ",library,false,"),
            (",lib,false,", ",lib,maybe,"),
        ] {
            let broken = csv.replace(good, bad);
            assert!(records::table::from_reader::<BuildUnitRow, _>(broken.as_bytes()).is_err());
        }
    }
}
