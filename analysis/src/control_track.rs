//! The control-rate track (`results/control.csv`, written by crate `control`): at the main
//! control period [`spec::MAIN_H`], whether a run's whole tick fits the period, whether
//! the run is a success (stable and within [`ACCURACY`] of the exact optimum once settled), the
//! Euler steps a network needs per tick, and the leaderboard of the methods over the tasks; and
//! the networks as the papers integrate them, in products with the LVI matrix per millisecond.

use crate::control_claim::ACCURACY;
use records::control::{steps_needed, ClaimRow, ControlRow, ControlStatus};
use records::RunRow;
use spec::MAIN_H;

/// The main control period, in milliseconds (the unit of [`ControlRow::h_ms`]).
pub fn main_h_ms() -> f64 {
    MAIN_H * 1e3
}

/// Whether the run's median whole tick fits within its control period.
pub fn fits_period(r: &ControlRow) -> bool {
    r.tick_p50_us <= r.h_ms * 1e3
}

/// Whether a run at the main period is a success of the control-rate track: it completed and
/// its command stayed within [`ACCURACY`] of the exact optimum after the first second.
pub fn success(r: &ControlRow) -> bool {
    r.status == ControlStatus::Ok && r.max_dx_settled <= ACCURACY
}

/// The forward-Euler steps per tick of the main period that a network with stability limit
/// `euler_limit_s` needs ([`steps_needed`]).
pub fn steps_per_main_tick(euler_limit_s: f64) -> u64 {
    steps_needed(main_h_ms() * 1e-3, euler_limit_s)
}

/// A network's right-hand sides in a run as the papers integrate it (`r`, its row of
/// `results/runs.csv`), in products with the LVI matrix M per millisecond of the task:
/// RHS evaluations x the claim's products per evaluation / (duration in ms).
pub fn products_per_ms(r: &RunRow, claim: &ClaimRow) -> f64 {
    r.rhs_evals as f64 * claim.products_per_step as f64 / (r.duration * 1e3)
}

/// One method of the control-rate leaderboard.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrackRow<'a> {
    pub method: &'a str,
    /// Its runs at the main period that are a [`success`].
    pub successes: usize,
    /// Its runs at the main period (one per task).
    pub runs: usize,
    /// The worst median tick and the worst 99th percentile over its tasks (us).
    pub worst_median_us: f64,
    pub worst_p99_us: f64,
}

/// The control-rate leaderboard of `runs`: every method at the main period, ranked by
/// successes (most first), then by the worst median tick, then by name.
pub fn track(runs: &[ControlRow]) -> Vec<TrackRow<'_>> {
    let h = main_h_ms();
    let mut methods: Vec<&str> = runs
        .iter()
        .filter(|r| r.h_ms == h)
        .map(|r| r.method.as_str())
        .collect();
    methods.sort_unstable();
    methods.dedup();
    let mut rows: Vec<TrackRow> = methods
        .into_iter()
        .map(|method| {
            let mine: Vec<&ControlRow> = runs
                .iter()
                .filter(|r| r.h_ms == h && r.method == method)
                .collect();
            TrackRow {
                method,
                successes: mine.iter().filter(|r| success(r)).count(),
                runs: mine.len(),
                worst_median_us: mine.iter().map(|r| r.tick_p50_us).fold(0.0, f64::max),
                worst_p99_us: mine.iter().map(|r| r.tick_p99_us).fold(0.0, f64::max),
            }
        })
        .collect();
    rows.sort_by(|a, b| {
        b.successes
            .cmp(&a.successes)
            .then(a.worst_median_us.total_cmp(&b.worst_median_us))
            .then(a.method.cmp(b.method))
    });
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use records::control::Family;

    fn run(method: &str, task: &str, ok: bool, tick_p50_us: f64) -> ControlRow {
        ControlRow {
            task: task.into(),
            paper: "p".into(),
            scheme: "s".into(),
            method: method.into(),
            family: Family::Network,
            h_ms: main_h_ms(),
            substeps: 1,
            status: if ok {
                ControlStatus::Ok
            } else {
                ControlStatus::Diverged
            },
            stopped_at: None,
            ticks: 1000,
            solve_p50_us: 1.0,
            solve_p99_us: 1.0,
            solve_max_us: 1.0,
            tick_p50_us,
            tick_p99_us: 2.0 * tick_p50_us,
            tick_max_us: 3.0 * tick_p50_us,
            max_track_err: 1e-3,
            rms_track_err: 1e-3,
            max_dx: 1e-9,
            rms_dx: 1e-9,
            max_dx_settled: if ok { 1e-9 } else { 1.0 },
            drift: None,
            products_mean: None,
            products_max: None,
            iterations_mean: 1.0,
            iterations_max: 1,
        }
    }

    #[test]
    fn the_track_ranks_by_successes_then_the_worst_median_tick() {
        let runs = [
            run("b", "t1", true, 5.0),
            run("b", "t2", true, 7.0),
            run("a", "t1", true, 9.0),
            run("a", "t2", true, 3.0),
            run("c", "t1", false, 1.0),
            run("c", "t2", true, 1.0),
        ];
        let track = track(&runs);
        let order: Vec<(&str, usize, f64, f64)> = track
            .iter()
            .map(|r| (r.method, r.successes, r.worst_median_us, r.worst_p99_us))
            .collect();
        assert_eq!(
            order,
            [("b", 2, 7.0, 14.0), ("a", 2, 9.0, 18.0), ("c", 1, 1.0, 2.0)]
        );
        assert!(fits_period(&runs[0]) && !success(&runs[4]));
        // A limit of 0.4 ms needs three steps in a 1 ms tick.
        assert_eq!(steps_per_main_tick(main_h_ms() * 1e-3 / 2.5), 3);
    }
}
