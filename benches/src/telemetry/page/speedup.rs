//! Against an earlier revision: every paper's runs timed alone under an earlier revision of
//! driftbench and under this one (`benches/results/speedup.csv`, [`crate::telemetry::speedup`]).
//!
//! Per paper: the runs' summed median times, old and new, for the simulation (`sim_s`) and the
//! whole run (`wall_s`); the speed-up old / new, and its smallest, median and largest value over
//! the runs; the runs whose status changed and the largest change of a drift norm. The target
//! applies to the papers that publish no compute time (the timed papers have theirs against the
//! MATLAB times). Where a paper misses it, the paper's sampling profile (`benches/results/profile.csv`,
//! [`crate::telemetry::profile`]) says where its time goes: the share of each part of the process, and
//! the integration's ratio to its floor r ([`crate::telemetry::profile::integration_floor_ratio`]: the
//! samples of the simulation and the exact column over those of the RHS, Jacobian and LU work,
//! the exact column's QP solves included). Removing every sample outside the floor divides the
//! integration's time by r at most, so a paper with r below the target cannot meet it by
//! removing overhead alone. The speed-ups, verdicts and shares are computed by
//! [`crate::telemetry::judged::speedup`] and [`crate::telemetry::judged::profile`]; this module formats.

use crate::telemetry::judged::profile::part_shares;
use crate::telemetry::judged::speedup::{
    floor_bound, paper_lines, FloorBound, SpeedupTarget, TARGET_OTHER_SPEEDUP,
};
use crate::telemetry::profile::ProfileRow;
use crate::telemetry::speedup::SpeedupRow;
use analysis::papers::Papers;
use presentation::report::markdown::{percent, sci, Table, MISSING};

/// The `### Against an earlier revision` subsection.
pub fn section(rows: &[SpeedupRow], profile: &[ProfileRow], papers: &Papers) -> String {
    let Some(first) = rows.first() else {
        return format!(
            "### Against an earlier revision\n\n`benches/results/{}` is absent: \
             `benches/speedup/papers.sh OLD_CHECKOUT OLD_BINARY` measures it.\n\n",
            crate::telemetry::speedup::FILE
        );
    };
    let timed = papers.timed_papers();
    let mut t = Table::new([
        "paper",
        "runs",
        "simulation: earlier (s)",
        "simulation: now (s)",
        "speed-up",
        "per run: min, median, max",
        "whole runs: earlier (s)",
        "whole runs: now (s)",
        "speed-up",
        "status changes",
        "largest drift change (rad)",
        "target",
    ]);
    let mut missed = Vec::new();
    for line in paper_lines(rows, &timed) {
        let p = &line.paper;
        let target = match line.target {
            SpeedupTarget::MatlabTimes => "MATLAB times".to_string(),
            SpeedupTarget::Met => format!("{TARGET_OTHER_SPEEDUP}x met"),
            SpeedupTarget::NotMet => {
                missed.push(p.paper.clone());
                format!("{TARGET_OTHER_SPEEDUP}x not met")
            }
        };
        t.push([
            p.paper.clone(),
            p.runs.to_string(),
            sci(p.old_sim_s),
            sci(p.new_sim_s),
            format!("{:.2}", line.simulation),
            format!(
                "{:.2}, {:.2}, {:.2}",
                p.min_sim_speedup, p.median_sim_speedup, p.max_sim_speedup
            ),
            sci(p.old_wall_s),
            sci(p.new_wall_s),
            format!("{:.2}", line.whole),
            p.status_changes.to_string(),
            sci(p.max_drift_change),
            target,
        ]);
    }
    let mut out = format!(
        "### Against an earlier revision\n\n`benches/speedup/papers.sh` ran each paper's runs \
         (`reproduce shard 1/1 --paper PAPER --threads 1`: no explanation runs, no timing \
         pass) under revision `{}` and under revision `{}`, on one thread pinned to one CPU, {} \
         passes per revision, the two revisions alternating pass by pass. A run's time is the \
         median over its passes and a paper's the sum over its runs (`benches/results/{}`). Runs are \
         matched by experiment, variant and solver label, the exact column by its kind (it was \
         renamed). The target: every run of a paper that publishes no compute time at least \
         {TARGET_OTHER_SPEEDUP}x faster in simulation, with the same status and drifts.\n\n{}\n",
        first.old_rev,
        first.new_rev,
        first.passes,
        crate::telemetry::speedup::FILE,
        t.render()
    );
    for paper in missed {
        out.push_str(&why_missed(&paper, profile));
    }
    out
}

/// Where a paper that missed the target spends its time, from its profile.
fn why_missed(paper: &str, profile: &[ProfileRow]) -> String {
    let rows = crate::telemetry::profile::of_paper(profile, paper);
    if rows.is_empty() {
        return format!(
            "**{paper}** has no profile in `benches/results/{}`.\n\n",
            crate::telemetry::profile::FILE
        );
    }
    let shares: Vec<String> = part_shares(&rows)
        .iter()
        .map(|(part, share)| format!("{part} {}", percent(*share, 0)))
        .collect();
    let bound = match floor_bound(&rows) {
        FloorBound::Below(r) => format!(
            "; its integration (the simulation and the exact column: what `sim_s` times) runs at \
             {r:.2} times its floor (RHS, Jacobian and LU work; every exact-column sample is a \
             right-hand side, i.e. a QP solve), so removing every sample outside the floor would \
             make it at most {r:.2}x faster: the target needs fewer or cheaper RHS, Jacobian and \
             LU evaluations"
        ),
        FloorBound::Above(r) => format!("; its integration runs at {r:.2} times its floor"),
        FloorBound::NoFloor => format!("; the profile has no floor samples ({MISSING})"),
    };
    format!(
        "**{paper}.** Its profile (below) splits the process into {}{bound}.\n\n",
        shares.join(", ")
    )
}
