//! What the leaderboard's text says, from its rows ([`crate::leaderboard`]): on the standard set,
//! the solvers grouped by success, the failed runs, and per measure (distance to the optimum,
//! drift error, time) the best solvers with the others' range of ratios to them; and how the
//! times it ranks by were measured (runs timed alone, the spread of their repetitions).

use crate::leaderboard::{alone_timing, LeaderboardRow, Task, STANDARD_SET};
use records::Timings;

/// The best solvers by one measure (a ratio to the set's best, 1 for the best) and the other
/// solvers' ratios.
#[derive(Clone, Debug, PartialEq)]
pub struct Best {
    /// The solvers whose measure is the smallest.
    pub rows: Vec<LeaderboardRow>,
    /// The other solvers' ratios to the best (those other than 1): smallest and largest; none
    /// when every solver is at 1.
    pub others: Option<(f64, f64)>,
}

/// The rows of `rows` whose `key` is the smallest, and the others' range.
fn best_by(rows: &[&LeaderboardRow], key: fn(&LeaderboardRow) -> f64) -> Best {
    let best = rows.iter().map(|r| key(r)).fold(f64::INFINITY, f64::min);
    let others: Vec<f64> = rows.iter().map(|r| key(r)).filter(|v| *v != 1.0).collect();
    Best {
        rows: rows
            .iter()
            .filter(|r| key(r) == best)
            .map(|r| (*r).clone())
            .collect(),
        others: others
            .iter()
            .copied()
            .reduce(f64::min)
            .zip(others.iter().copied().reduce(f64::max)),
    }
}

/// The reading of the standard set.
#[derive(Clone, Debug, PartialEq)]
pub struct StandardReading {
    /// Tasks in the set.
    pub tasks: usize,
    /// The solvers grouped by runs within tolerance (in rank order, so the most first).
    pub by_success: Vec<(usize, Vec<LeaderboardRow>)>,
    /// Runs of the set that failed.
    pub failed: usize,
    /// Closest to the exact optimum (RMS |x − x*|).
    pub closest: Best,
    /// Closest to the exact column's drift.
    pub drift: Best,
    /// Fastest.
    pub fastest: Best,
}

/// [`StandardReading`] of the leaderboard `rows`; none without a standard set.
pub fn standard_reading(rows: &[LeaderboardRow]) -> Option<StandardReading> {
    let std: Vec<&LeaderboardRow> = rows.iter().filter(|r| r.task_set == STANDARD_SET).collect();
    let first = std.first()?;
    let mut by_success: Vec<(usize, Vec<LeaderboardRow>)> = Vec::new();
    for &r in &std {
        match by_success.last_mut() {
            Some((w, g)) if *w == r.within_tolerance => g.push(r.clone()),
            _ => by_success.push((r.within_tolerance, vec![r.clone()])),
        }
    }
    Some(StandardReading {
        tasks: first.tasks,
        by_success,
        failed: std.iter().map(|r| r.tasks - r.completed).sum(),
        closest: best_by(&std, |r| r.dx_rel),
        drift: best_by(&std, |r| r.drift_rel),
        fastest: best_by(&std, |r| r.time_rel),
    })
}

/// How the standard set's times were measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimingReading {
    /// Runs of the standard set.
    pub runs: usize,
    /// Of them, timed alone.
    pub alone: usize,
    /// Runs timed alone in all (the leaderboard's and the papers' timed runs).
    pub timed: usize,
    /// The repetitions' spread, (max − min) / median, at the median over the timed runs and at
    /// most.
    pub median_spread: f64,
    pub max_spread: f64,
}

/// [`TimingReading`] of the leaderboard `rows` on the standard `tasks`; none without timings.
pub fn timing_reading(
    rows: &[LeaderboardRow],
    timings: &Timings,
    tasks: &[Task],
) -> Option<TimingReading> {
    timings.rows().next()?;
    let standard = rows.iter().filter(|r| r.task_set == STANDARD_SET);
    let spreads: Vec<f64> = timings.rows().map(|r| r.sim_spread()).collect();
    Some(TimingReading {
        runs: standard.clone().map(|r| r.tasks).sum(),
        alone: standard
            .map(|r| alone_timing(timings, &r.solver_id, tasks).0)
            .sum(),
        timed: spreads.len(),
        median_spread: records::percentile(&spreads, 0.5),
        max_spread: spreads.iter().copied().fold(0.0, f64::max),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use spec::SolverKind;

    fn row(solver: &str, within: usize, completed: usize, rel: [f64; 3]) -> LeaderboardRow {
        LeaderboardRow {
            task_set: STANDARD_SET.to_string(),
            tasks: 4,
            rank: 1,
            solver_id: spec::ids::SolverId::new(solver.to_lowercase()).unwrap(),
            solver: solver.to_string(),
            solver_kind: SolverKind::Exact,
            standard_runs: 4,
            completed,
            within_tolerance: within,
            success_pct: 0.0,
            correct_pct: 0.0,
            dx_shm: 0.0,
            dx_rel: rel[0],
            dx_p50: 0.0,
            dx_p95: 0.0,
            drift_shm: 0.0,
            drift_rel: rel[1],
            drift_p50: 0.0,
            drift_p95: 0.0,
            time_shm: 0.0,
            time_rel: rel[2],
            time_p50: 0.0,
            time_p95: 0.0,
        }
    }

    #[test]
    fn the_best_and_the_others_range_per_measure() {
        let rows = [
            row("a", 4, 4, [1.0, 2.0, 1.0]),
            row("b", 4, 3, [1.0, 1.0, 5.0]),
            row("c", 2, 4, [3.0, 4.0, 1.0]),
        ];
        let reading = standard_reading(&rows).unwrap();
        assert_eq!(reading.tasks, 4);
        let groups: Vec<(usize, usize)> = reading
            .by_success
            .iter()
            .map(|(w, g)| (*w, g.len()))
            .collect();
        assert_eq!(groups, [(4, 2), (2, 1)]);
        assert_eq!(reading.failed, 1);
        assert_eq!(reading.closest.rows.len(), 2);
        assert_eq!(reading.closest.others, Some((3.0, 3.0)));
        assert_eq!(reading.drift.others, Some((2.0, 4.0)));
        assert_eq!(reading.fastest.rows.len(), 2);
        let same = [row("a", 4, 4, [1.0, 1.0, 1.0])];
        assert_eq!(standard_reading(&same).unwrap().closest.others, None);
        assert!(standard_reading(&[]).is_none());
        assert!(timing_reading(&rows, &Timings::default(), &[]).is_none());
    }
}
