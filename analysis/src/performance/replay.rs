//! The exact reference per tick against DAQP (`results/qp-replay.csv`): per task, the suite's
//! active set and DAQP on the same recorded QPs, warm and cold, and each time as a multiple of
//! DAQP's; the target is the suite at or below DAQP's time, warm and cold.

use records::{QpReplayRow, QP_REPLAY_SUITE};

/// One solver on one task: its mean time per solve warm and cold (us), and each over DAQP's
/// on the same task and start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReplayLine<'a> {
    /// The first row of the (task, solver): its sizes and answers' distance.
    pub row: &'a QpReplayRow,
    pub warm_us: Option<f64>,
    pub cold_us: Option<f64>,
    pub warm_over_daqp: Option<f64>,
    pub cold_over_daqp: Option<f64>,
}

/// The mean time per solve of `solver` on `task` from `start` (`warm` or `cold`).
fn mean_us(rows: &[QpReplayRow], task: &str, solver: &str, start: &str) -> Option<f64> {
    rows.iter()
        .find(|r| r.task == task && r.solver == solver && r.start == start)
        .map(|r| r.mean_us)
}

/// DAQP's mean time per solve on `task` from `start`.
fn daqp_us(rows: &[QpReplayRow], task: &str, start: &str) -> Option<f64> {
    rows.iter()
        .find(|r| r.task == task && r.solver != QP_REPLAY_SUITE && r.start == start)
        .map(|r| r.mean_us)
}

/// One line per (task, solver), in file order.
pub fn lines(rows: &[QpReplayRow]) -> Vec<ReplayLine<'_>> {
    let mut seen: Vec<(&str, &str)> = Vec::new();
    let mut out = Vec::new();
    for r in rows {
        if seen.contains(&(r.task.as_str(), r.solver.as_str())) {
            continue;
        }
        seen.push((&r.task, &r.solver));
        let (warm, cold) = (
            mean_us(rows, &r.task, &r.solver, "warm"),
            mean_us(rows, &r.task, &r.solver, "cold"),
        );
        let over = |x: Option<f64>, d: Option<f64>| x.zip(d).map(|(x, d)| x / d);
        out.push(ReplayLine {
            row: r,
            warm_us: warm,
            cold_us: cold,
            warm_over_daqp: over(warm, daqp_us(rows, &r.task, "warm")),
            cold_over_daqp: over(cold, daqp_us(rows, &r.task, "cold")),
        });
    }
    out
}

/// The suite's time over DAQP's across the tasks, warm and cold (smallest, largest), and
/// whether the target (at most 1 for both) is met.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReplayTarget {
    pub warm: (f64, f64),
    pub cold: (f64, f64),
    pub met: bool,
}

/// [`ReplayTarget`], where the suite has a ratio to DAQP warm and cold.
pub fn target(rows: &[QpReplayRow]) -> Option<ReplayTarget> {
    let span = |start: &str| -> Option<(f64, f64)> {
        let ratios: Vec<f64> = rows
            .iter()
            .filter(|r| r.solver == QP_REPLAY_SUITE && r.start == start)
            .filter_map(|r| daqp_us(rows, &r.task, start).map(|d| r.mean_us / d))
            .collect();
        let lo = ratios.iter().copied().reduce(f64::min)?;
        Some((lo, ratios.iter().copied().fold(lo, f64::max)))
    };
    let (warm, cold) = (span("warm")?, span("cold")?);
    Some(ReplayTarget {
        warm,
        cold,
        met: warm.1 <= 1.0 && cold.1 <= 1.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_suite_is_priced_in_daqp_times() {
        let task = |task: &str, times: &[(&str, &str, f64)]| {
            fixtures::replay_rows(task, times, [7, 3, 12, 13], 1e-15)
        };
        let rows = [
            task(
                "a",
                &[
                    (QP_REPLAY_SUITE, "warm", 1.5),
                    (QP_REPLAY_SUITE, "cold", 3.0),
                    ("daqp 9", "warm", 1.0),
                    ("daqp 9", "cold", 1.5),
                ],
            ),
            task(
                "b",
                &[
                    (QP_REPLAY_SUITE, "warm", 0.5),
                    (QP_REPLAY_SUITE, "cold", 1.0),
                    ("daqp 9", "warm", 1.0),
                    ("daqp 9", "cold", 1.0),
                ],
            ),
        ]
        .concat();
        let lines = lines(&rows);
        assert_eq!(lines.len(), 4);
        assert_eq!(
            (lines[0].warm_over_daqp, lines[0].cold_over_daqp),
            (Some(1.5), Some(2.0))
        );
        assert_eq!(lines[1].warm_over_daqp, Some(1.0));
        let t = target(&rows).unwrap();
        assert_eq!((t.warm, t.cold, t.met), ((0.5, 1.5), (1.0, 2.0), false));
        assert!(target(&rows[4..]).is_some_and(|t| t.met));
        assert!(target(&[]).is_none());
    }
}
