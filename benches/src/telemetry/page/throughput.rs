//! One thread's throughput on a kong2019 ZNN sweep, side by side with an earlier revision, and
//! where a right-hand side's time goes (`benches/results/throughput.csv`,
//! `throughput-profile.csv`; [`crate::telemetry::throughput`] computes, this module formats).

use crate::telemetry::throughput::{
    floor_and_total, side, speedup, ThroughputProfileRow, ThroughputRow, FILE, PROFILE_FILE,
    TARGET_SPEEDUP,
};
use analysis::sci;
use presentation::report::markdown::{percent, Table};

/// The `### Runs per core` subsection.
pub fn section(rows: &[ThroughputRow], profile: &[ThroughputProfileRow]) -> String {
    let mut out = String::from("### Runs per core: a kong2019 ZNN sweep on one thread\n\n");
    let (Some(old), Some(new)) = (side(rows, "old"), side(rows, "new")) else {
        out.push_str(&format!(
            "`benches/results/{FILE}` is absent or lacks a revision: \
             `benches/throughput/kong2019_sweep.sh OLD_CHECKOUT OLD_BINARY NEW_CHECKOUT \
             NEW_BINARY` measures it.\n\n"
        ));
        return out;
    };
    out.push_str(&format!(
        "`benches/throughput/kong2019_sweep.sh` ran a sweep of {} runs (kong2019's ZNN scheme, \
         eq. 22, on the Katana 6M180, the circle of 9 s, Tsitouras 5(4) at RelTol 1e-10, mu x \
         gamma; no exact column, each run scored against the exact optimum at every accepted \
         step) as one shard on one thread pinned to one CPU, under revision `{}` and under \
         revision `{}`, {} and {} passes alternating. Throughput is runs per user CPU second of \
         the process (CPU time, not wall time: the machine was shared); instruction counts \
         where the machine exposes hardware counters.\n\n",
        new.runs, old.commit, new.commit, old.passes, new.passes
    ));
    let mut t = Table::new([
        "revision",
        "passes",
        "user CPU (s), median",
        "runs per CPU second",
        "CPU per RHS (us)",
        "RHS per run",
        "instructions",
    ]);
    for s in [&old, &new] {
        t.push([
            format!("`{}`", s.commit),
            s.passes.to_string(),
            sci(s.user_s),
            sci(s.runs_per_cpu_s),
            sci(s.cpu_us_per_rhs),
            sci(s.rhs_per_run),
            s.instructions
                .map_or_else(|| "not measured".to_string(), sci),
        ]);
    }
    out.push_str(&t.render());
    let ratio = speedup(&old, &new);
    let verdict = if ratio >= TARGET_SPEEDUP {
        "met"
    } else {
        "not met"
    };
    out.push_str(&format!(
        "\n`{}` runs {:.2} times as many runs per CPU second as `{}`: the target of at least \
         {TARGET_SPEEDUP}x is {verdict}.\n\n",
        new.commit, ratio, old.commit
    ));
    if profile.is_empty() {
        out.push_str(&format!(
            "`benches/results/{PROFILE_FILE}` is absent: the same script profiles a pass.\n\n"
        ));
        return out;
    }
    let (floor, total) = floor_and_total(profile);
    out.push_str(&format!(
        "Where a right-hand side's time goes: one more pass of revision `{}` on a smaller sweep, \
         sampled by `perf record` and sorted by `benches/throughput/classify.py`. The \
         right-hand side itself (kinematics, path, QP assembly, the network and the solve of its \
         8 x 8 KKT system) is the floor, {} us of CPU per evaluation; the run spends {} us per evaluation in \
         all, the rest in the integrator, the observer (metrics and the exact QP that scores \
         every accepted step) and start-up.\n\n",
        profile[0].git_rev,
        sci(floor),
        sci(total)
    ));
    let mut t = Table::new([
        "part",
        "category",
        "share of the samples",
        "CPU per RHS (us)",
    ]);
    for r in profile {
        t.push([
            r.part.clone(),
            r.category.clone(),
            percent(r.share, 1),
            sci(r.cpu_us_per_rhs),
        ]);
    }
    out.push_str(&t.render());
    out.push('\n');
    out
}
