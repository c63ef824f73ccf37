//! Where a cold build's time goes (`benches/results/build-profile.csv`, [`crate::telemetry::build_profile`]).
//!
//! A build of units u with durations d_u on c cores cannot end before either bound:
//!
//! - the CPU bound, sum_u d_u / c: all the work, perfectly shared out;
//! - the critical path: the chain of units each waiting for the one before, found by following
//!   `unblocked_by` back from the unit that ends last. Its units' durations add up to what no
//!   number of cores can shorten; the rest of the chain's span is time it waited for a core.
//!
//! The larger bound says which kind of cut can shorten the build: less work (fewer or cheaper
//! units) when the CPU bound is near the wall time, a shorter chain (splitting or cheapening its
//! units) when the path is.

use crate::telemetry::build_profile::BuildUnitRow;
use std::collections::HashMap;

/// How many of the costliest units [`summarise`] lists.
pub const COSTLIEST: usize = 12;

/// A build's profile: its bounds, its critical path and its costliest units.
#[derive(Clone, Debug, PartialEq)]
pub struct BuildProfile<'a> {
    /// The commit built (the first row's).
    pub commit: &'a str,
    /// The machine (the first row's).
    pub machine: &'a str,
    /// Logical cores: cargo's parallel jobs.
    pub cores: usize,
    /// The build's wall time as the script timed it (s).
    pub wall_s: f64,
    /// Every unit's duration, summed (s): the build's CPU time.
    pub unit_s: f64,
    /// The workspace's own units' durations, summed (s).
    pub workspace_unit_s: f64,
    /// The CPU bound, `unit_s / cores` (s).
    pub cpu_bound_s: f64,
    /// The critical path, in build order.
    pub critical_path: Vec<&'a BuildUnitRow>,
    /// The critical path's units' durations, summed (s).
    pub critical_s: f64,
    /// The costliest units, longest first (at most [`COSTLIEST`]).
    pub costliest: Vec<&'a BuildUnitRow>,
}

impl BuildProfile<'_> {
    /// A unit's duration over the build's CPU time.
    pub fn share(&self, unit: &BuildUnitRow) -> f64 {
        unit.duration_s / self.unit_s
    }

    /// Whether no schedule on these cores could end the build within `limit_s`: the larger of
    /// the CPU bound and the critical path exceeds it.
    pub fn bounds_exceed(&self, limit_s: f64) -> bool {
        self.cpu_bound_s.max(self.critical_s) > limit_s
    }
}

/// The profile of `rows` (one build), `None` without rows.
pub fn summarise(rows: &[BuildUnitRow]) -> Option<BuildProfile<'_>> {
    let first = rows.first()?;
    let unit_s: f64 = rows.iter().map(|r| r.duration_s).sum();
    let critical_path = critical_path(rows);
    let mut costliest: Vec<&BuildUnitRow> = rows.iter().collect();
    costliest.sort_by(|a, b| {
        b.duration_s
            .total_cmp(&a.duration_s)
            .then(a.unit.cmp(&b.unit))
    });
    costliest.truncate(COSTLIEST);
    Some(BuildProfile {
        commit: &first.commit,
        machine: &first.machine,
        cores: first.cores,
        wall_s: first.build_wall_s,
        unit_s,
        workspace_unit_s: rows
            .iter()
            .filter(|r| r.workspace)
            .map(|r| r.duration_s)
            .sum(),
        cpu_bound_s: unit_s / first.cores.max(1) as f64,
        critical_s: critical_path.iter().map(|r| r.duration_s).sum(),
        critical_path,
        costliest,
    })
}

/// The chain that ends with the last unit to end, each unit preceded by the one that unblocked
/// it, in build order. A reference to a unit the file lacks, or a loop (a file not written by
/// cargo), ends the chain there.
pub fn critical_path(rows: &[BuildUnitRow]) -> Vec<&BuildUnitRow> {
    let by_unit: HashMap<usize, &BuildUnitRow> = rows.iter().map(|r| (r.unit, r)).collect();
    let Some(last) = rows
        .iter()
        .max_by(|a, b| a.end_s().total_cmp(&b.end_s()).then(b.unit.cmp(&a.unit)))
    else {
        return Vec::new();
    };
    let mut chain = vec![last];
    while let Some(next) = chain
        .last()
        .and_then(|r| r.unblocked_by)
        .and_then(|u| by_unit.get(&u))
    {
        if chain.len() >= rows.len() || chain.iter().any(|r| r.unit == next.unit) {
            break;
        }
        chain.push(next);
    }
    chain.reverse();
    chain
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(csv_rows: &str) -> Vec<BuildUnitRow> {
        let csv = format!(
            "unit,crate_name,version,kind,workspace,start_s,duration_s,unblocked_by,commit,machine,cores,date,build_wall_s\n{csv_rows}"
        );
        records::table::from_reader(csv.as_bytes()).unwrap()
    }

    #[test]
    fn the_path_follows_the_last_dependency_back_from_the_last_unit() {
        // a (0-10) unblocks c; b (0-4) unblocks d; c (10-30) unblocks e; d (4-8); e (30-35).
        let r = rows(
            "0,a,1,lib,false,0,10,,c0,CPU,2,d,36\n\
             1,b,1,lib,false,0,4,,c0,CPU,2,d,36\n\
             2,c,1,lib,false,10,20,0,c0,CPU,2,d,36\n\
             3,d,1,lib,true,4,4,1,c0,CPU,2,d,36\n\
             4,e,1,bin,true,30,5,2,c0,CPU,2,d,36\n",
        );
        let p = summarise(&r).unwrap();
        let names: Vec<&str> = p
            .critical_path
            .iter()
            .map(|r| r.crate_name.as_str())
            .collect();
        assert_eq!(names, ["a", "c", "e"]);
        assert_eq!(p.critical_s, 35.0);
        assert_eq!(p.unit_s, 43.0);
        assert_eq!(p.workspace_unit_s, 9.0);
        assert_eq!(p.cpu_bound_s, 21.5);
        assert_eq!(p.wall_s, 36.0);
        assert_eq!(p.costliest[0].crate_name, "c");
        assert_eq!(p.costliest.len(), 5);
        assert_eq!(p.share(p.costliest[0]), 20.0 / 43.0);
        assert!(p.bounds_exceed(34.0) && !p.bounds_exceed(35.0));
    }

    #[test]
    fn a_loop_or_a_missing_unit_ends_the_path() {
        let looped = rows(
            "0,a,1,lib,false,0,10,1,c0,CPU,2,d,20\n\
             1,b,1,lib,false,10,10,0,c0,CPU,2,d,20\n",
        );
        assert_eq!(critical_path(&looped).len(), 2);
        let missing = rows("0,a,1,lib,false,5,10,7,c0,CPU,2,d,20\n");
        assert_eq!(critical_path(&missing).len(), 1);
        assert!(summarise(&[]).is_none());
    }
}
