//! The newcomer's clock against its targets (`benches/results/clock.csv`, [`crate::telemetry::clock`]).
//!
//! Issue 29 sets, measured side by side with the baseline revision [`BASELINE`] in one session
//! on an otherwise idle machine:
//!
//! | step | target |
//! |---|---|
//! | cold `cargo build --release -p reproduce` | at most half of the baseline's |
//! | the whole reproduction | at most half of the baseline's |
//! | clean-clone `cargo test --workspace --release` | at most 5 minutes |
//! | `pip install ./python` | at most 6 minutes |
//!
//! [`targets`] compares the newest measured revision (the last row's that is not the baseline)
//! with them: per step, both times, the limit in seconds, and whether it is met. The decision is
//! here; benches/REPORT.md only shows it.

use crate::telemetry::clock::{ClockRow, Step};

/// The revision the clock's relative targets are measured against, as `clock.sh` is given it.
pub const BASELINE: &str = "cc915b9";

/// A target's bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bound {
    /// At most this fraction of the baseline's time.
    OfBaseline(f64),
    /// At most this many seconds.
    Seconds(f64),
}

/// The targets, per step (module docs).
pub const TARGETS: [(Step, Bound); 4] = [
    (Step::Build, Bound::OfBaseline(0.5)),
    (Step::Reproduce, Bound::OfBaseline(0.5)),
    (Step::Test, Bound::Seconds(300.0)),
    (Step::Wheel, Bound::Seconds(360.0)),
];

/// One step against its target.
#[derive(Clone, Debug, PartialEq)]
pub struct TargetRow {
    /// The step.
    pub step: Step,
    /// Its bound.
    pub bound: Bound,
    /// The baseline's time (s), where measured.
    pub baseline_s: Option<f64>,
    /// The measured revision's time (s), where measured.
    pub measured_s: Option<f64>,
    /// The limit in seconds (for a relative bound, only with the baseline's time).
    pub limit_s: Option<f64>,
    /// measured / baseline, where both are there.
    pub ratio: Option<f64>,
    /// Whether the measured time is within the limit (`None`: not measured, or no limit); a
    /// step that failed (non-zero exit code) does not meet its target.
    pub met: Option<bool>,
}

/// The measured revision's commit: the last row's (in file order) that is not the baseline.
pub fn measured_commit(clock: &[ClockRow]) -> Option<&str> {
    clock
        .iter()
        .rev()
        .find(|r| r.revision != BASELINE)
        .map(|r| r.commit.as_str())
}

/// Every target of [`TARGETS`] against `clock` (module docs).
pub fn targets(clock: &[ClockRow]) -> Vec<TargetRow> {
    let measured = measured_commit(clock);
    let time = |step: Step, of: &dyn Fn(&ClockRow) -> bool| {
        clock
            .iter()
            .rev()
            .find(|r| r.step == step && of(r))
            .map(|r| (r.seconds, r.exit_code == 0))
    };
    TARGETS
        .iter()
        .map(|&(step, bound)| {
            let baseline = time(step, &|r| r.revision == BASELINE);
            let now = time(step, &|r| Some(r.commit.as_str()) == measured);
            let limit_s = match bound {
                Bound::OfBaseline(f) => baseline.map(|(s, _)| f * s),
                Bound::Seconds(s) => Some(s),
            };
            let met = match (now, limit_s) {
                (Some((s, ok)), Some(limit)) => Some(ok && s <= limit),
                _ => None,
            };
            TargetRow {
                step,
                bound,
                baseline_s: baseline.map(|b| b.0),
                measured_s: now.map(|n| n.0),
                limit_s,
                ratio: now.zip(baseline).map(|(n, b)| n.0 / b.0),
                met,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(revision: &str, commit: &str, step: Step, seconds: f64, exit_code: i32) -> ClockRow {
        ClockRow {
            revision: revision.into(),
            commit: commit.into(),
            step,
            seconds,
            exit_code,
            machine: "cpu".into(),
            cores: 2,
            date: "2026-12-04T00:00:00Z".into(),
        }
    }

    #[test]
    fn relative_and_absolute_targets_are_decided_against_the_newest_revision() {
        let clock = [
            row(BASELINE, "cc915b978835", Step::Build, 264.0, 0),
            row(BASELINE, "cc915b978835", Step::Reproduce, 100.0, 0),
            row("old", "aaaa", Step::Build, 10.0, 0),
            row("HEAD", "bbbb", Step::Build, 132.0, 0),
            row("HEAD", "bbbb", Step::Reproduce, 51.0, 0),
            row("HEAD", "bbbb", Step::Test, 299.0, 1),
        ];
        assert_eq!(measured_commit(&clock), Some("bbbb"));
        let t = targets(&clock);
        let of = |s: Step| t.iter().find(|r| r.step == s).unwrap();
        let build = of(Step::Build);
        assert_eq!((build.limit_s, build.met), (Some(132.0), Some(true)));
        assert_eq!(build.ratio, Some(0.5));
        assert_eq!(of(Step::Reproduce).met, Some(false));
        assert_eq!(
            of(Step::Test).met,
            Some(false),
            "a failed step misses its target"
        );
        let wheel = of(Step::Wheel);
        assert_eq!((wheel.measured_s, wheel.met), (None, None));
        assert_eq!(wheel.limit_s, Some(360.0));
    }

    #[test]
    fn without_the_baseline_a_relative_target_has_no_limit() {
        let t = targets(&[row("HEAD", "bbbb", Step::Build, 100.0, 0)]);
        assert_eq!((t[0].limit_s, t[0].met, t[0].ratio), (None, None, None));
    }
}
