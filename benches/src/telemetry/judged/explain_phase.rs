//! Where the explain phase of a reproduction spends its time: the tolerance ladders' rungs
//! (`results/ladder.csv`, [`records::LadderRow`]), each timed by the wall clock as it ran
//! (`wall_s`), against the phase's wall time (`benches/results/phases.csv`, [`reproduce::phases`]).
//!
//! The rungs run in parallel, one per core at a time, so their times add up to core-seconds:
//! with c cores a group of rungs that took s core-seconds in all needs at least s / c of the
//! phase's wall time however the rungs are shared out (its floor). The rungs and the
//! attribution's switch runs together fill the phase; the rungs alone are what the ladder file
//! times.

use records::Status;
use records::{LadderMethod, LadderRow};
use reproduce::phases::{Phase, PhaseRow};

/// The rungs of one paper integrated one way that ended one way.
#[derive(Clone, Debug, PartialEq)]
pub struct RungGroup<'a> {
    /// The paper (the rows' `paper`).
    pub paper: &'a str,
    /// How the rungs integrated.
    pub method: LadderMethod,
    /// Whether they completed or stopped early (at a step cap, diverging, ...).
    pub status: Status,
    /// How many rungs.
    pub rungs: usize,
    /// Their wall times summed (core-seconds).
    pub core_s: f64,
    /// `core_s` over every rung's.
    pub share: f64,
    /// The phase's wall time the group needs at least on the run's cores (s;
    /// [`ExplainCost::floor_s`]).
    pub floor_s: Option<f64>,
}

/// The explain phase's rungs, grouped.
#[derive(Clone, Debug, PartialEq)]
pub struct ExplainCost<'a> {
    /// The explain phase's wall time in the last run (s), when it ran.
    pub phase_s: Option<f64>,
    /// The cores that run had (`None` without `benches/results/phases.csv`).
    pub cores: Option<usize>,
    /// Every rung's wall time, summed (core-seconds).
    pub rung_core_s: f64,
    /// How many rungs.
    pub rungs: usize,
    /// The groups, costliest first.
    pub groups: Vec<RungGroup<'a>>,
}

impl ExplainCost<'_> {
    /// The core-seconds the phase had: its wall time times the cores.
    pub fn phase_core_s(&self) -> Option<f64> {
        Some(self.phase_s? * self.cores? as f64)
    }

    /// The wall time `core_s` core-seconds need at least on the run's cores (s).
    pub fn floor_s(&self, core_s: f64) -> Option<f64> {
        Some(core_s / self.cores?.max(1) as f64)
    }

    /// The groups with at least `share` of the rungs' time, and what the others add up to.
    pub fn split(&self, share: f64) -> (&[RungGroup<'_>], Minor) {
        // The groups are sorted costliest first.
        let major = self.groups.partition_point(|g| g.share >= share);
        let rest = &self.groups[major..];
        let minor = Minor {
            groups: rest.len(),
            rungs: rest.iter().map(|g| g.rungs).sum(),
            core_s: rest.iter().map(|g| g.core_s).sum(),
        };
        (&self.groups[..major], minor)
    }

    /// Whether the rungs alone need more of the phase's wall time than `limit_s` on the run's
    /// cores (their floor above it): the reproduction cannot meet a limit of `limit_s` with
    /// these rungs as they are.
    pub fn rungs_exceed(&self, limit_s: f64) -> Option<bool> {
        Some(self.floor_s(self.rung_core_s)? > limit_s)
    }
}

/// The groups [`ExplainCost::split`] leaves out, together.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Minor {
    /// How many groups.
    pub groups: usize,
    /// Their rungs.
    pub rungs: usize,
    /// Their wall times summed (core-seconds).
    pub core_s: f64,
}

/// The rungs of `ladder` grouped by paper, method and status, with the explain phase of
/// `phases`; `None` without rungs.
pub fn summarise<'a>(ladder: &'a [LadderRow], phases: &[PhaseRow]) -> Option<ExplainCost<'a>> {
    if ladder.is_empty() {
        return None;
    }
    let mut groups: Vec<RungGroup<'a>> = Vec::new();
    for r in ladder {
        let at = groups
            .iter()
            .position(|g| g.paper == r.paper && g.method == r.method && g.status == r.status);
        let g = match at {
            Some(i) => &mut groups[i],
            None => {
                groups.push(RungGroup {
                    paper: &r.paper,
                    method: r.method,
                    status: r.status,
                    rungs: 0,
                    core_s: 0.0,
                    share: 0.0,
                    floor_s: None,
                });
                groups.last_mut().expect("just pushed")
            }
        };
        g.rungs += 1;
        g.core_s += r.wall_s;
    }
    groups.sort_by(|a, b| b.core_s.total_cmp(&a.core_s));
    let explain = phases.iter().find(|p| p.phase == Phase::Explain);
    let mut cost = ExplainCost {
        phase_s: explain.and_then(|p| p.seconds),
        cores: explain.map(|p| p.cores),
        rung_core_s: ladder.iter().map(|r| r.wall_s).sum(),
        rungs: ladder.len(),
        groups: Vec::new(),
    };
    for g in &mut groups {
        g.share = g.core_s / cost.rung_core_s;
        g.floor_s = cost.floor_s(g.core_s);
    }
    cost.groups = groups;
    Some(cost)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rungs_are_grouped_and_set_against_the_phase() {
        let ladder = fixtures::ladder_rows(&[
            ("p1", "fixed-step", "ok", 3.0),
            ("p1", "fixed-step", "ok", 5.0),
            ("p2", "dopri5", "failed", 2.0),
            ("p2", "dopri5", "ok", 0.5),
        ]);
        let phases_csv =
            "phase,status,seconds,share_pct,items,note,selection,whole,machine,cores,git_rev\n\
             explain,ran,6.0,50.0,3,,s,true,CPU,2,abc\n";
        let phases: Vec<PhaseRow> = records::table::from_reader(phases_csv.as_bytes()).unwrap();
        let c = summarise(&ladder, &phases).unwrap();
        assert_eq!(c.rungs, 4);
        assert_eq!(c.rung_core_s, 10.5);
        assert_eq!(c.phase_core_s(), Some(12.0));
        assert_eq!(c.groups.len(), 3);
        assert_eq!(
            (c.groups[0].paper, c.groups[0].rungs, c.groups[0].core_s),
            ("p1", 2, 8.0)
        );
        assert_eq!(c.groups[1].status, Status::Failed);
        assert_eq!(c.floor_s(c.groups[0].core_s), Some(4.0));
        assert_eq!(
            (c.groups[0].floor_s, c.groups[0].share),
            (Some(4.0), 8.0 / 10.5)
        );
        let (major, minor) = c.split(0.1);
        assert_eq!(major.len(), 2);
        assert_eq!((minor.groups, minor.rungs, minor.core_s), (1, 1, 0.5));
        assert_eq!(c.rungs_exceed(5.0), Some(true));
        assert_eq!(c.rungs_exceed(5.25), Some(false));
        let alone = summarise(&ladder, &[]).unwrap();
        assert_eq!((alone.phase_s, alone.floor_s(1.0)), (None, None));
        assert!(summarise(&[], &phases).is_none());
    }
}
