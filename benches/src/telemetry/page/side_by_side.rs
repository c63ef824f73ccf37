//! The cold build side by side with issue 38's baseline (`benches/results/side-by-side/build.csv`;
//! [`crate::telemetry::side_by_side`] computes, this module formats).

use crate::telemetry::side_by_side::{Comparison, BASELINE, FILE, TARGET_RATIO};
use presentation::report::markdown::Table;

/// The `### The cold build against f5570fd` subsection.
pub fn section(comparison: Option<&Comparison>) -> String {
    let mut out = format!("### The cold build against {BASELINE}\n\n");
    let Some(c) = comparison else {
        out.push_str(&format!(
            "`benches/results/{FILE}` is absent or lacks a revision: \
             `benches/side_by_side/build_and_runs.sh --build-only {BASELINE} CANDIDATE` \
             measures it.\n\n"
        ));
        return out;
    };
    out.push_str(&format!(
        "`benches/side_by_side/build_and_runs.sh` built `reproduce` cold (`cargo build \
         --release -p reproduce` into an empty target directory, in a fresh clone) at `{}` and \
         at `{}` (`{}`), one after the other on the same machine. CPU seconds (user and system, \
         of cargo and every process it starts) are the comparable figure: the wall time \
         stretches with whatever else runs, and the load average before each build is kept \
         beside it. `benches/results/side-by-side/README.md` says under what load it was \
         measured.\n\n",
        c.baseline.revision, c.candidate.commit, c.candidate.revision
    ));
    let mut t = Table::new([
        "revision",
        "builds",
        "CPU (s), median",
        "wall (s), median",
        "highest load before a build",
    ]);
    for b in [&c.baseline, &c.candidate] {
        t.push([
            format!("`{}`", b.commit),
            b.rounds.to_string(),
            format!("{:.0}", b.cpu_s),
            format!("{:.0}", b.wall_s),
            format!("{:.2}", b.max_load1),
        ]);
    }
    out.push_str(&t.render());
    out.push_str(&format!(
        "\n`{}` builds in {:.3} of `{}`'s CPU time (wall time {:.3}): issue 38's target of at \
         most {TARGET_RATIO} is {}.\n\n",
        c.candidate.commit,
        c.cpu_ratio,
        c.baseline.commit,
        c.wall_ratio,
        if c.met { "met" } else { "not met" }
    ));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::telemetry::side_by_side::{compare, SideBySideBuildRow};

    #[test]
    fn the_section_shows_both_builds_and_the_verdict() {
        let row = |revision: &str, wall_s: f64, user_s: f64, load1: f64| SideBySideBuildRow {
            revision: revision.to_string(),
            commit: format!("{revision}aaaaaaaaaaaaaaaa"),
            round: 1,
            wall_s,
            user_s,
            sys_s: 20.0,
            load1,
        };
        // 420 CPU s against 280: 0.667, within 0.7.
        let rows = [
            row(BASELINE, 900.0, 400.0, 16.4),
            row("h-build", 600.0, 260.0, 15.0),
        ];
        let md = section(compare(&rows).as_ref());
        assert!(
            md.contains("| `f5570fdaaaaa` | 1 | 420 | 900 | 16.40 |")
                && md.contains("| `h-buildaaaaa` | 1 | 280 | 600 | 15.00 |")
                && md.contains("`h-buildaaaaa` builds in 0.667 of `f5570fdaaaaa`'s CPU time (wall time 0.667): issue 38's target of at most 0.7 is met."),
            "{md}"
        );
    }
}
