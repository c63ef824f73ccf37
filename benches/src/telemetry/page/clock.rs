//! The newcomer's clock on benches/REPORT.md: how long a newcomer waits from clone to report,
//! and where that time goes.
//!
//! - the phases of the last `reproduce run` (`benches/results/phases.csv`, [`reproduce::phases`]);
//! - where its explain phase spends its time: the tolerance ladders' rungs as
//!   `results/ladder.csv` timed them ([`crate::telemetry::judged::explain_phase`]);
//! - per revision, a fresh clone's cold build, whole reproduction, tests and wheel
//!   (`benches/results/clock.csv` by `benches/clock/clock.sh`, [`crate::telemetry::clock`]) against the targets
//!   ([`crate::telemetry::judged::targets`]);
//! - where a cold build spends its time: its CPU bound, critical path and costliest units
//!   (`benches/results/build-profile.csv` by `benches/clock/build_profile.sh`,
//!   [`crate::telemetry::judged::build`]).
//!
//! What is computed from the files is [`crate::telemetry::judged`]'s; this module formats, and escapes
//! every text it reads.

use crate::telemetry::build_profile::BuildUnitRow;
use crate::telemetry::clock::{ClockRow, Step};
use crate::telemetry::judged::clock::{by_commit, phases_seconds};
use crate::telemetry::judged::targets::{targets, BASELINE};
use crate::telemetry::judged::{build, explain_phase};
use presentation::report::markdown::{minutes, percent, text, Table, MISSING};
use records::LadderRow;
use records::Status;
use reproduce::phases::{PhaseRow, PhaseStatus};

/// The files the newcomer's clock reads, each empty where absent.
#[derive(Clone, Copy, Debug)]
pub struct Clock<'a> {
    /// `benches/results/phases.csv`.
    pub phases: &'a [PhaseRow],
    /// `results/ladder.csv`.
    pub ladder: &'a [LadderRow],
    /// `benches/results/clock.csv`.
    pub clock: &'a [ClockRow],
    /// `benches/results/build-profile.csv`.
    pub build: &'a [BuildUnitRow],
}

/// Groups of rungs with at least this share of the rungs' time get a row of their own.
const MAJOR_SHARE: f64 = 0.01;

/// `### The newcomer's clock`: the phases of the last `reproduce run`, per revision a fresh
/// clone's steps, the targets, then where the explain phase and a cold build spend their time
/// (module docs); each absent file says how to produce it.
pub fn section(c: &Clock) -> String {
    let mut out = String::from("### The newcomer's clock\n\n");
    out.push_str(&phase_table(c.phases));
    out.push_str(&clock_table(c.clock));
    out.push_str(&clock_targets_table(c.clock));
    out.push_str(&explain_cost(c.ladder, c.phases, c.clock));
    out.push_str(&build_profile(c.build, c.clock));
    out
}

/// The limit of a step's target in seconds, where the clock gives one.
fn limit_s(clock: &[ClockRow], step: Step) -> Option<f64> {
    targets(clock)
        .into_iter()
        .find(|t| t.step == step)
        .and_then(|t| t.limit_s)
}

/// `#### Where the reproduction's time goes`: the explain phase's rungs grouped, against the
/// phase and the reproduction's target.
fn explain_cost(ladder: &[LadderRow], phases: &[PhaseRow], clock: &[ClockRow]) -> String {
    let Some(cost) = explain_phase::summarise(ladder, phases) else {
        return String::new();
    };
    let mut out = format!(
        "#### Where the reproduction's time goes\n\nThe explain phase's tolerance ladders \
         re-run each explained run at a sequence of tolerances, one rung per core at a time, and `results/{}` keeps each rung's wall time \
         (`wall_s`): {} rungs took {:.1} core-seconds in all",
        store::results_dir::LADDER,
        cost.rungs,
        cost.rung_core_s,
    );
    match (cost.phase_s, cost.cores, cost.phase_core_s()) {
        (Some(s), Some(cores), Some(core_s)) => out.push_str(&format!(
            ", of the {core_s:.1} the last run's explain phase had ({s:.1} s on {cores} cores; \
             the rest went to the attribution's switch runs and to rungs waiting for a core). A \
             group's floor is the phase time it needs at least on these cores, however its \
             rungs are shared out.\n\n"
        )),
        _ => out.push_str(
            " (`benches/results/phases.csv` has no explain phase to set them against).\n\n",
        ),
    }
    let mut t = Table::new([
        "paper",
        "method",
        "rungs that",
        "rungs",
        "core-seconds",
        "share",
        "floor (s)",
    ]);
    let (major, minor) = cost.split(MAJOR_SHARE);
    for g in major {
        t.push([
            text(g.paper),
            g.method.id().to_string(),
            match g.status {
                Status::Ok => "completed".to_string(),
                Status::Failed => "stopped early".to_string(),
            },
            g.rungs.to_string(),
            format!("{:.1}", g.core_s),
            percent(g.share, 1),
            g.floor_s
                .map_or_else(|| MISSING.to_string(), |f| format!("{f:.1}")),
        ]);
    }
    out.push_str(&t.render());
    if minor.groups > 0 {
        out.push_str(&format!(
            "\nThe groups under {} of the rungs' time, together: groups {}, rungs {}, \
             core-seconds {:.1}.\n",
            percent(MAJOR_SHARE, 0),
            minor.groups,
            minor.rungs,
            minor.core_s
        ));
    }
    out.push_str("\nA rung stopped early ran until its step cap or its divergence bound.\n");
    let limit = limit_s(clock, Step::Reproduce);
    if let (Some(limit), Some(exceed), Some(floor)) = (
        limit,
        limit.and_then(|l| cost.rungs_exceed(l)),
        cost.floor_s(cost.rung_core_s),
    ) {
        out.push_str(&format!(
            "\nThe reproduction's target is at most {limit:.1} s (half of {BASELINE}'s). The \
             rungs alone need at least {floor:.1} s on these cores: {}.\n",
            if exceed {
                "the target cannot be met while the ladders compute what they do"
            } else {
                "within the target"
            },
        ));
    }
    out.push('\n');
    out
}

/// `#### Where the build's time goes`: a cold build's bounds, critical path and costliest
/// units, against the build's target.
fn build_profile(rows: &[BuildUnitRow], clock: &[ClockRow]) -> String {
    let Some(p) = build::summarise(rows) else {
        return format!(
            "`benches/results/{}` is absent: `benches/clock/build_profile.sh` builds a fresh clone cold \
             with `cargo build --release -p reproduce --timings` and keeps cargo's unit table \
             (about 3 minutes of an otherwise idle machine).\n\n",
            crate::telemetry::build_profile::FILE
        );
    };
    let mut out = format!(
        "#### Where the build's time goes\n\nA cold `cargo build --release -p reproduce \
         --timings` of `{}` on {} ({} cores), unit by unit (`benches/results/{}`, by \
         `benches/clock/build_profile.sh` from cargo's own timings): {:.1} s of wall time. Its \
         {} units took {:.1} s of one core each ({:.1} s of them the workspace's own crates, in \
         bold below), so on {} cores no schedule of this work, each unit taking what it took here, ends before {:.1} s (the CPU bound). Its \
         critical path, traced back from the last unit through the dependency whose end let \
         each unit start, is {:.1} s of work that no number of cores shortens (the gaps \
         between its units, waiting for a free core, not counted):\n\n",
        text(p.commit),
        text(p.machine),
        p.cores,
        crate::telemetry::build_profile::FILE,
        p.wall_s,
        rows.len(),
        p.unit_s,
        p.workspace_unit_s,
        p.cores,
        p.cpu_bound_s,
        p.critical_s,
    );
    let mut path = Table::new(["crate", "kind", "starts (s)", "takes (s)"]);
    for u in &p.critical_path {
        path.push([
            unit_name(u),
            u.kind.id().to_string(),
            format!("{:.1}", u.start_s),
            format!("{:.1}", u.duration_s),
        ]);
    }
    out.push_str(&path.render());
    out.push_str("\nThe costliest units:\n\n");
    let mut top = Table::new(["crate", "kind", "takes (s)", "share of the CPU time"]);
    for u in &p.costliest {
        top.push([
            unit_name(u),
            u.kind.id().to_string(),
            format!("{:.1}", u.duration_s),
            percent(p.share(u), 1),
        ]);
    }
    out.push_str(&top.render());
    if let Some(limit) = limit_s(clock, Step::Build) {
        out.push_str(&format!(
            "\nThe build's target is at most {limit:.1} s (half of {BASELINE}'s): {}.\n",
            if p.bounds_exceed(limit) {
                "the bounds above exceed it, so no schedule of this work on these cores meets \
                 it; only less work can"
            } else {
                "the bounds above are within it"
            }
        ));
    }
    out.push('\n');
    out
}

/// A unit's crate and version, in bold when the crate is the workspace's.
fn unit_name(u: &BuildUnitRow) -> String {
    let name = format!("{} {}", text(&u.crate_name), text(&u.version));
    if u.workspace {
        format!("**{name}**")
    } else {
        name
    }
}

/// The clock's targets (`crate::telemetry::judged::targets`), once a revision besides the baseline has
/// been measured.
fn clock_targets_table(clock: &[ClockRow]) -> String {
    use crate::telemetry::judged::targets::{measured_commit, Bound};
    let Some(commit) = measured_commit(clock) else {
        return String::new();
    };
    let mut t = Table::new([
        "step".to_string(),
        "target".to_string(),
        format!("{BASELINE} (min)"),
        format!("`{}` (min)", text(commit)),
        "ratio".to_string(),
        "limit (min)".to_string(),
        "met".to_string(),
    ]);
    let minutes =
        |s: Option<f64>| s.map_or_else(|| MISSING.to_string(), |s| format!("{:.1}", s / 60.0));
    for r in targets(clock) {
        t.push([
            r.step.id().to_string(),
            match r.bound {
                Bound::OfBaseline(f) => format!("at most {f} x {BASELINE}'s"),
                Bound::Seconds(s) => format!("at most {:.0} min", s / 60.0),
            },
            minutes(r.baseline_s),
            minutes(r.measured_s),
            r.ratio
                .map_or_else(|| MISSING.to_string(), |x| format!("{x:.2}")),
            minutes(r.limit_s),
            match r.met {
                Some(true) => "yes".to_string(),
                Some(false) => "**no**".to_string(),
                None => MISSING.to_string(),
            },
        ]);
    }
    format!(
        "The targets (issue 29), the newest measured revision against {BASELINE}:\n\n{}\n",
        t.render()
    )
}

/// The phases of the last run, with whether it was a whole reproduction.
fn phase_table(phases: &[PhaseRow]) -> String {
    let Some(first) = phases.first() else {
        return format!(
            "`benches/results/{}` is absent: `cargo run --release -p reproduce -- run --phases \
             benches/results/phases.csv` writes it at its end (the wall time of each phase of \
             the run; a whole reproduction gives every phase).\n\n",
            reproduce::phases::FILE
        );
    };
    let total = phases_seconds(phases);
    let skipped: Vec<String> = phases
        .iter()
        .filter(|r| r.status == PhaseStatus::Skipped)
        .map(|r| format!("{} ({})", r.phase.id(), text(&r.note)))
        .collect();
    let scope = if reproduce::phases::complete(phases) {
        "a whole reproduction (every run, every phase)".to_string()
    } else {
        let mut scope = format!(
            "**a partial run**, not a whole reproduction: selection {}",
            text(&first.selection)
        );
        if !skipped.is_empty() {
            scope.push_str(&format!("; skipped: {}", skipped.join(", ")));
        }
        scope
    };
    let mut t = Table::new(["phase", "seconds", "share", "items", "note"]);
    for r in phases {
        t.push([
            r.phase.id().to_string(),
            r.seconds
                .map_or_else(|| "skipped".to_string(), |s| format!("{s:.1}")),
            r.share_pct
                .map_or_else(|| MISSING.to_string(), |p| format!("{p:.1} %")),
            r.items.map_or_else(
                || MISSING.to_string(),
                |n| format!("{n} {}", r.phase.items_are()),
            ),
            text(&r.note),
        ]);
    }
    format!(
        "Where the wall time of a `reproduce run` went (`benches/results/{}`, written at its \
         end by `--phases`): {scope}. Measured on {} ({} logical cores \
         available) at revision `{}`, {:.1} s in all. Each phase runs from the end of the one before: \
         *setup* reads the experiment files, checks everything before a run starts and opens \
         `results/`; *runs* is the selected runs in parallel with `runs.csv` and the traces \
         written; *explain*, the explanation layer; *control*, the control experiments; \
         *timing*, the compared runs again one at a time; *figures*; *report*, its pages, task \
         cards and the leaderboard table.\n\n{}\n",
        reproduce::phases::FILE,
        text(&first.machine),
        first.cores,
        text(&first.git_rev),
        total,
        t.render()
    )
}

/// Per revision, a fresh clone's steps as `benches/clock/clock.sh` timed them.
fn clock_table(clock: &[ClockRow]) -> String {
    if clock.is_empty() {
        return format!(
            "`benches/results/{}` is absent: `benches/clock/clock.sh` measures, for each revision given \
             (default `cc915b9 HEAD`), a fresh clone's cold `{}`, the whole reproduction (`{}`) \
             and `{}`, on an otherwise idle machine (about half an hour of the whole machine per \
             revision; `docs/guide/clock.md`).\n\n",
            crate::telemetry::clock::FILE,
            crate::telemetry::clock::Step::Build.command(),
            crate::telemetry::clock::Step::Reproduce.command(),
            crate::telemetry::clock::Step::Test.command(),
        );
    }
    let mut t = Table::new([
        "revision",
        "commit",
        "step",
        "minutes",
        "exit code",
        "machine",
        "date (UTC)",
    ]);
    for r in clock {
        t.push([
            text(&r.revision),
            format!("`{}`", text(&r.commit)),
            format!("{} (`{}`)", r.step.id(), r.step.command()),
            minutes(r.seconds),
            r.exit_code.to_string(),
            format!("{} ({} cores)", text(&r.machine), r.cores),
            text(&r.date),
        ]);
    }
    let mut totals = String::new();
    for c in by_commit(clock) {
        totals.push_str(&format!(
            "- `{}` ({}): {} min for {}{}.\n",
            text(c.commit),
            text(c.revision),
            minutes(c.seconds),
            c.steps.join(" + "),
            if c.failed { ", a step failing" } else { "" }
        ));
    }
    format!(
        "From clone to report, per revision (`benches/results/{}`): measured by \
         `benches/clock/clock.sh`, which clones each revision afresh (`git clone --no-local`) \
         into a temporary directory with its own, empty target directory and times each step by \
         the wall clock; the reproduction runs after the build, so its time excludes it, and the \
         tests' time includes their build. Cargo's registry cache may be shared with the user's \
         (so downloads are not timed; `--fresh-cargo-home` times them). The script needs an \
         otherwise idle machine, which it cannot check: the date and machine of each step are in \
         its row.\n\n{}\n{totals}\n",
        crate::telemetry::clock::FILE,
        t.render()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_newcomers_clock_renders_from_synthetic_csvs() {
        // A partial run: explain skipped, runs 3 s of 4 s; text with Markdown in it.
        let phases_csv = "phase,status,seconds,share_pct,items,note,selection,whole,machine,cores,git_rev\n\
                          setup,ran,1.0,25.0,,,--paper demo,false,CPU <b>*x*</b>,2,abc\n\
                          runs,ran,3.0,75.0,12,2 of them resumed from the journal,--paper demo,false,CPU <b>*x*</b>,2,abc\n\
                          explain,skipped,,,,--skip-explain,--paper demo,false,CPU <b>*x*</b>,2,abc\n";
        let phases: Vec<PhaseRow> = records::table::from_reader(phases_csv.as_bytes()).unwrap();
        let clock_csv = "revision,commit,step,seconds,exit_code,machine,cores,date\n\
                         HEAD,0123456789ab,build,300,0,Test CPU,2,2026-12-03T13:00:00Z\n\
                         HEAD,0123456789ab,reproduce,150,0,Test CPU,2,2026-12-03T13:05:00Z\n\
                         [old](x),aaaaaaaaaaaa,test,60,101,Test CPU,2,2026-12-03T14:00:00Z\n";
        let clock: Vec<ClockRow> = records::table::from_reader(clock_csv.as_bytes()).unwrap();
        let md = section(&Clock {
            phases: &phases,
            ladder: &[],
            clock: &clock,
            build: &[],
        });
        assert!(md.starts_with("### The newcomer's clock\n"), "{md}");
        assert!(
            md.contains("**a partial run**, not a whole reproduction: selection --paper demo; skipped: explain (--skip-explain)"),
            "{md}"
        );
        assert!(md.contains("4.0 s in all"), "{md}");
        assert!(
            md.contains(
                "| runs | 3.0 | 75.0 % | 12 selected runs | 2 of them resumed from the journal |"
            ),
            "{md}"
        );
        assert!(
            md.contains("| explain | skipped | — | — | --skip-explain |"),
            "{md}"
        );
        // Text from the files is escaped: no HTML, no emphasis, no link.
        assert!(md.contains("CPU &lt;b&gt;\\*x\\*&lt;/b&gt;"), "{md}");
        assert!(!md.contains("<b>") && !md.contains("[old](x)"), "{md}");
        assert!(md.contains("\\[old\\](x)"), "{md}");
        assert!(
            md.contains("| HEAD | `0123456789ab` | build (`cargo build --release -p reproduce`) | 5.0 | 0 | Test CPU (2 cores) | 2026-12-03T13:00:00Z |"),
            "{md}"
        );
        assert!(md.contains("benches/clock/clock.sh"), "{md}");
        assert!(
            md.contains("- `0123456789ab` (HEAD): 7.5 min for build + reproduce.\n"),
            "{md}"
        );
        assert!(md.contains("min for test, a step failing.\n"), "{md}");
        assert!(
            !md.contains("`benches/results/clock.csv` is absent"),
            "{md}"
        );
        assert!(
            md.contains("`benches/results/build-profile.csv` is absent"),
            "{md}"
        );
        // A whole run with every phase says so.
        let whole_csv = phases_csv
            .replace("--paper demo,false", "every run,true")
            .lines()
            .filter(|l| !l.contains("skipped"))
            .collect::<Vec<_>>()
            .join("\n");
        let whole: Vec<PhaseRow> = records::table::from_reader(whole_csv.as_bytes()).unwrap();
        let md = section(&Clock {
            phases: &whole,
            ladder: &[],
            clock: &[],
            build: &[],
        });
        assert!(
            md.contains("a whole reproduction (every run, every phase)"),
            "{md}"
        );
        assert!(!md.contains("partial"), "{md}");
        assert!(
            md.contains("`benches/results/clock.csv` is absent: `benches/clock/clock.sh`"),
            "{md}"
        );
    }

    #[test]
    fn where_the_time_goes_renders_from_synthetic_csvs() {
        let phases_csv =
            "phase,status,seconds,share_pct,items,note,selection,whole,machine,cores,git_rev\n\
             explain,ran,6.0,50.0,3,,every run,true,CPU,2,abc\n";
        let phases: Vec<PhaseRow> = records::table::from_reader(phases_csv.as_bytes()).unwrap();
        let ladder = fixtures::ladder_rows(&[
            ("p<i>1</i>", "fixed-step", "ok", 8.0),
            ("p2", "dopri5", "failed", 2.0),
            ("p2", "bdf", "ok", 0.05),
        ]);
        let build_csv = "unit,crate_name,version,kind,workspace,start_s,duration_s,unblocked_by,commit,machine,cores,date,build_wall_s\n\
                         0,faer,0.24.4,lib,false,0,60,,0123456789ab,CPU,2,d,200\n\
                         1,solvers,0.1.0,lib,true,60,40,0,0123456789ab,CPU,2,d,200\n\
                         2,reproduce,0.1.0,bin,true,100,50,1,0123456789ab,CPU,2,d,200\n\
                         3,clap_*x*,4.6,lib,false,0,120,,0123456789ab,CPU,2,d,200\n";
        let build: Vec<BuildUnitRow> = records::table::from_reader(build_csv.as_bytes()).unwrap();
        let clock_csv = "revision,commit,step,seconds,exit_code,machine,cores,date\n\
                         cc915b9,aaaaaaaaaaaa,build,280,0,CPU,2,d\n\
                         cc915b9,aaaaaaaaaaaa,reproduce,12,0,CPU,2,d\n\
                         HEAD,0123456789ab,build,200,0,CPU,2,d\n\
                         HEAD,0123456789ab,reproduce,6.5,0,CPU,2,d\n";
        let clock: Vec<ClockRow> = records::table::from_reader(clock_csv.as_bytes()).unwrap();
        let md = section(&Clock {
            phases: &phases,
            ladder: &ladder,
            clock: &clock,
            build: &build,
        });
        // The rungs: 10.05 core-seconds of the 12 the phase had; the small group folded.
        assert!(
            md.contains("3 rungs took 10.1 core-seconds in all, of the 12.0"),
            "{md}"
        );
        assert!(
            md.contains(
                "| p&lt;i&gt;1&lt;/i&gt; | fixed-step | completed | 1 | 8.0 | 79.6 % | 4.0 |"
            ),
            "{md}"
        );
        assert!(
            md.contains("| p2 | dopri5 | stopped early | 1 | 2.0 |"),
            "{md}"
        );
        assert!(
            md.contains(
                "under 1 % of the rungs' time, together: groups 1, rungs 1, core-seconds 0.1."
            ),
            "{md}"
        );
        // Floor 5.0 s against a limit of 6.0 s (half of 12 s): within; the build is not.
        assert!(md.contains("at most 6.0 s (half of cc915b9's)"), "{md}");
        assert!(
            md.contains("need at least 5.0 s on these cores: within the target"),
            "{md}"
        );
        assert!(
            md.contains("Its 4 units took 270.0 s of one core each (90.0 s of them"),
            "{md}"
        );
        assert!(md.contains("ends before 135.0 s (the CPU bound)"), "{md}");
        assert!(md.contains("is 150.0 s of work"), "{md}");
        assert!(
            md.contains(
                "| faer 0.24.4 | lib | 0.0 | 60.0 |\n| **solvers 0.1.0** | lib | 60.0 | 40.0 |"
            ),
            "{md}"
        );
        assert!(
            md.contains("| clap\\_\\*x\\* 4.6 | lib | 120.0 | 44.4 % |"),
            "{md}"
        );
        assert!(
            md.contains("at most 140.0 s (half of cc915b9's): the bounds above exceed it"),
            "{md}"
        );
        assert!(!md.contains("is absent"), "{md}");
    }
}
