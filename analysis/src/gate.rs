//! The regression gate: a fresh run against the committed `results/runs.csv`.
//!
//! A fresh row is compared with the committed row of the same (experiment, variant, solver):
//! - the status must be the same (a run that completed must still complete, a run that failed
//!   is a recorded finding and must still fail);
//! - for completed runs the drift per joint and every measured metric (`records::index::MEASURED`)
//!   must agree to a relative 1e-6 (absolute 1e-12): the simulation is deterministic, so
//!   anything beyond floating-point noise across machines is a change of behaviour;
//! - for every run not stopped by its wall-time budget (which depends on the machine), what the
//!   report's tables show besides the metrics (`records::index::SHOWN`: tolerances, step limit and
//!   effort counts, to the same tolerance) and the integrator must agree, and a failed run must
//!   fail the same way (`failure_kind`) at the same instant (`failed_at`). With the metrics this
//!   is every number the report's claims and tables use, timings aside;
//! - every committed run must still be produced, and every fresh run must be committed;
//! - every neural run must complete, except those whose divergence is itself the finding
//!   (declared in the experiment files as `expected_failure`, recorded in each row);
//! - the explanation's tables that the pages show (the tolerance ladder and the drift
//!   attribution) are compared row by row, with the tolerances [`compare_explanations`] states;
//! - so are the leaderboard ([`compare_leaderboard`]: derived from the runs) and the control
//!   experiments' runs ([`compare_control`]: re-run by a whole `check`).
//!
//! Every difference is one line naming the table, the row and the column.

use crate::leaderboard::LeaderboardRow;
use records::control::ControlRow;
use records::AttributionRow;
use records::FailureKind;
use records::LadderRow;
use records::RunRow;
use std::collections::HashSet;

/// Relative tolerance of the drift comparison.
pub const RELATIVE_TOLERANCE: f64 = 1e-6;

/// Whether `r` is one of the runs its experiment file expects to fail (`expected_failure`).
pub fn expected_to_diverge(r: &RunRow) -> bool {
    !r.expected_failure.is_empty()
}

/// A compared value in a message: the number, or "none" where the row has none.
fn value_text(v: Option<f64>) -> String {
    v.map_or_else(|| "none".to_string(), |v| format!("{v:e}"))
}

fn close(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() <= 1e-12 + RELATIVE_TOLERANCE * a.abs().max(b.abs()),
        (None, None) => true,
        _ => false,
    }
}

/// Every difference between `committed` (read from the baseline called `baseline`, for the
/// messages) and `fresh` that the gate rejects, one line each. `committed` should hold the rows
/// of the same selection of runs as `fresh`. Linear in the rows (keys in hash maps).
pub fn compare(committed: &[RunRow], fresh: &[RunRow], baseline: &str) -> Vec<String> {
    let mut problems = Vec::new();
    let fresh_by_key: std::collections::HashMap<_, &RunRow> =
        fresh.iter().map(|f| (f.key(), f)).collect();
    let committed_keys: std::collections::HashSet<_> = committed.iter().map(RunRow::key).collect();
    for c in committed {
        let Some(&f) = fresh_by_key.get(&c.key()) else {
            problems.push(format!("{}: in {baseline} but no longer produced", c.key()));
            continue;
        };
        if f.status != c.status {
            problems.push(format!(
                "{}: status {} -> {} ({})",
                c.key(),
                c.status,
                f.status,
                f.failure
            ));
            continue;
        }
        if c.failure_kind != f.failure_kind {
            problems.push(format!(
                "{}: failure_kind {} -> {}",
                c.key(),
                c.failure_kind.map_or("none", |k| k.id()),
                f.failure_kind.map_or("none", |k| k.id())
            ));
            continue;
        }
        if c.failure_kind != Some(FailureKind::WallTime) {
            if c.integrator != f.integrator {
                problems.push(format!(
                    "{}: integrator {} -> {}",
                    c.key(),
                    c.integrator,
                    f.integrator
                ));
            }
            let failed_at = ("failed_at".to_string(), c.failed_at, f.failed_at);
            let shown = records::index::SHOWN
                .iter()
                .map(|(name, column)| (name.to_string(), column(c), column(f)));
            for (name, a, b) in std::iter::once(failed_at).chain(shown) {
                if !close(a, b) {
                    problems.push(format!(
                        "{}: {name} {} -> {}",
                        c.key(),
                        value_text(a),
                        value_text(b)
                    ));
                }
            }
        }
        if c.completed() {
            if c.drift.len() != f.drift.len() {
                problems.push(format!(
                    "{}: {} joint drifts -> {}",
                    c.key(),
                    c.drift.len(),
                    f.drift.len()
                ));
            }
            let joints = c
                .drift
                .iter()
                .zip(&f.drift)
                .enumerate()
                .map(|(i, (a, b))| (format!("drift_{}", i + 1), Some(*a), Some(*b)));
            let totals = records::index::MEASURED
                .iter()
                .map(|(name, column)| (name.to_string(), column(c), column(f)));
            for (name, a, b) in joints.chain(totals) {
                if !close(a, b) {
                    problems.push(format!(
                        "{}: {name} {} -> {}",
                        c.key(),
                        value_text(a),
                        value_text(b)
                    ));
                }
            }
        }
    }
    for f in fresh {
        if !committed_keys.contains(&f.key()) {
            problems.push(format!(
                "{}: new run, not in {baseline} (run the reproduction and commit results/)",
                f.key()
            ));
        }
        if !f.is_exact() && !f.completed() && !expected_to_diverge(f) {
            problems.push(format!("{}: neural run failed: {}", f.key(), f.failure));
        }
    }
    problems
}

/// [`compare`] on a selection: the baseline's rows of the experiments `fresh` covers (only
/// their exact rows with `exact_only`) against `fresh`.
pub fn compare_selection(
    baseline: Vec<RunRow>,
    fresh: &[RunRow],
    exact_only: bool,
    baseline_name: &str,
) -> Vec<String> {
    let experiments: HashSet<&str> = fresh.iter().map(|f| f.experiment.as_str()).collect();
    let committed: Vec<RunRow> = baseline
        .into_iter()
        .filter(|c| experiments.contains(c.experiment.as_str()))
        .filter(|c| !exact_only || c.is_exact())
        .collect();
    compare(&committed, fresh, baseline_name)
}

/// The explanation's rows (`results/ladder.csv`, `results/attribution.csv`) that the pages
/// show, compared as [`compare`] compares runs, with these tolerances per column:
/// - ladder: one row per (run, method, rtol, atol, max_step); `status` and `as_run` equal; the
///   drift per joint, `drift_norm`, `max_pos_err` and `rel_change` to a relative
///   [`RELATIVE_TOLERANCE`] (absolute 1e-12); `stable_digits` (−log10 of `rel_change`) to
///   0.01 digit; `steps`, `rejected` and `rhs_evals` to the same relative tolerance; `wall_s`
///   not compared (the machine's);
/// - attribution: one row per (run, component); the drift per joint, `drift_norm`, `share`
///   and `max_pos_err` to a relative [`RELATIVE_TOLERANCE`].
///
/// Only committed rows of the runs `fresh` explains are compared (a selection); a committed
/// row missing from `fresh`, or a fresh row not committed, is a difference.
pub fn compare_explanations(
    committed: (&[LadderRow], &[AttributionRow]),
    fresh: (&[LadderRow], &[AttributionRow]),
    baseline: &str,
) -> Vec<String> {
    let ladder_key = |r: &LadderRow| {
        format!(
            "{} {} {} rtol {:e} atol {:e} max_step {}",
            store::results_dir::LADDER,
            r.key(),
            r.method.id(),
            r.rtol,
            r.atol,
            value_text(r.max_step)
        )
    };
    let attribution_key = |r: &AttributionRow| {
        format!(
            "{} {} {}",
            store::results_dir::ATTRIBUTION,
            r.key(),
            r.component.label()
        )
    };
    let mut problems = compare_rows(committed.0, fresh.0, ladder_key, baseline, |c, f| {
        let mut p = Vec::new();
        if c.status != f.status || c.as_run != f.as_run {
            p.push(format!("status {} -> {}", c.status, f.status));
        }
        let stable = match (c.stable_digits, f.stable_digits) {
            (Some(a), Some(b)) => (a - b).abs() <= 0.01,
            (a, b) => a.is_none() && b.is_none(),
        };
        if !stable {
            p.push(format!(
                "stable_digits {} -> {}",
                value_text(c.stable_digits),
                value_text(f.stable_digits)
            ));
        }
        let counts = [
            ("steps", c.steps, f.steps),
            ("rejected", c.rejected, f.rejected),
            ("rhs_evals", c.rhs_evals, f.rhs_evals),
        ]
        .map(|(n, a, b)| (n, Some(a as f64), Some(b as f64)));
        let numbers = [
            ("drift_norm", c.drift_norm, f.drift_norm),
            ("max_pos_err", c.max_pos_err, f.max_pos_err),
            ("rel_change", c.rel_change, f.rel_change),
        ];
        p.extend(differing(
            &c.drift,
            &f.drift,
            numbers.into_iter().chain(counts),
        ));
        p
    });
    problems.extend(compare_rows(
        committed.1,
        fresh.1,
        attribution_key,
        baseline,
        |c, f| {
            let numbers = [
                ("drift_norm", c.drift_norm, f.drift_norm),
                ("share", c.share, f.share),
                ("max_pos_err", c.max_pos_err, f.max_pos_err),
            ];
            differing(&c.drift, &f.drift, numbers)
        },
    ));
    problems
}

/// The leaderboard (`results/leaderboard.csv`) derived afresh from the runs against the
/// committed one: one row per (task set, solver id); `tasks`, `rank`, `standard_runs`,
/// `completed` and `within_tolerance` equal; `success_pct`, `correct_pct` and the accuracy
/// columns (`dx_*`, `drift_*`) to a relative [`RELATIVE_TOLERANCE`] (absolute 1e-12); the
/// time columns (`time_*`, the machine's, from `results/leaderboard-timing.csv`) not compared.
pub fn compare_leaderboard(
    committed: &[LeaderboardRow],
    fresh: &[LeaderboardRow],
    baseline: &str,
) -> Vec<String> {
    let key = |r: &LeaderboardRow| {
        format!(
            "{} {} {}",
            store::results_dir::LEADERBOARD,
            r.task_set,
            r.solver_id
        )
    };
    let committed: Vec<&LeaderboardRow> = committed.iter().collect();
    compare_keyed(&committed, fresh, key, baseline, |c, f| {
        let counts = [
            ("tasks", c.tasks, f.tasks),
            ("rank", c.rank, f.rank),
            ("standard_runs", c.standard_runs, f.standard_runs),
            ("completed", c.completed, f.completed),
            ("within_tolerance", c.within_tolerance, f.within_tolerance),
        ];
        let mut p: Vec<String> = counts
            .into_iter()
            .filter(|(_, a, b)| a != b)
            .map(|(n, a, b)| format!("{n} {a} -> {b}"))
            .collect();
        p.extend(differing(
            &[],
            &[],
            [
                ("success_pct", c.success_pct, f.success_pct),
                ("correct_pct", c.correct_pct, f.correct_pct),
                ("dx_shm", c.dx_shm, f.dx_shm),
                ("dx_rel", c.dx_rel, f.dx_rel),
                ("dx_p50", c.dx_p50, f.dx_p50),
                ("dx_p95", c.dx_p95, f.dx_p95),
                ("drift_shm", c.drift_shm, f.drift_shm),
                ("drift_rel", c.drift_rel, f.drift_rel),
                ("drift_p50", c.drift_p50, f.drift_p50),
                ("drift_p95", c.drift_p95, f.drift_p95),
            ]
            .map(|(n, a, b)| (n, Some(a), Some(b))),
        ));
        p
    })
}

/// The control experiments' runs (`results/control.csv`) of a fresh `check` against the
/// committed ones: one row per (task, method, h_ms, substeps); `status`, `ticks`,
/// `products_max` and `iterations_max` equal; `stopped_at`, the tracking errors
/// (`max_track_err`, `rms_track_err`), |x − x*| (`max_dx`, `rms_dx`, `max_dx_settled`),
/// `drift`, `products_mean` and `iterations_mean` to a relative [`RELATIVE_TOLERANCE`]
/// (absolute 1e-12); the durations (`solve_*_us`, `tick_*_us`, the machine's) not compared.
pub fn compare_control(
    committed: &[ControlRow],
    fresh: &[ControlRow],
    baseline: &str,
) -> Vec<String> {
    let key = |r: &ControlRow| {
        format!(
            "{} {} {} h_ms {} substeps {}",
            store::results_dir::CONTROL,
            r.task,
            r.method,
            r.h_ms,
            r.substeps
        )
    };
    let committed: Vec<&ControlRow> = committed.iter().collect();
    compare_keyed(&committed, fresh, key, baseline, |c, f| {
        let mut p = Vec::new();
        if c.status != f.status {
            p.push(format!("status {} -> {}", c.status, f.status));
        }
        let counts = [
            ("ticks", c.ticks as u64, f.ticks as u64),
            (
                "iterations_max",
                u64::from(c.iterations_max),
                u64::from(f.iterations_max),
            ),
        ];
        if c.products_max != f.products_max {
            let shown = |v: Option<u64>| v.map_or("none".to_string(), |v| v.to_string());
            p.push(format!(
                "products_max {} -> {}",
                shown(c.products_max),
                shown(f.products_max)
            ));
        }
        p.extend(
            counts
                .into_iter()
                .filter(|(_, a, b)| a != b)
                .map(|(n, a, b)| format!("{n} {a} -> {b}")),
        );
        p.extend(differing(
            &[],
            &[],
            [
                ("stopped_at", c.stopped_at, f.stopped_at),
                (
                    "max_track_err",
                    Some(c.max_track_err),
                    Some(f.max_track_err),
                ),
                (
                    "rms_track_err",
                    Some(c.rms_track_err),
                    Some(f.rms_track_err),
                ),
                ("max_dx", Some(c.max_dx), Some(f.max_dx)),
                ("rms_dx", Some(c.rms_dx), Some(f.rms_dx)),
                (
                    "max_dx_settled",
                    Some(c.max_dx_settled),
                    Some(f.max_dx_settled),
                ),
                ("drift", c.drift, f.drift),
                ("products_mean", c.products_mean, f.products_mean),
                (
                    "iterations_mean",
                    Some(c.iterations_mean),
                    Some(f.iterations_mean),
                ),
            ],
        ));
        p
    })
}

/// The columns of two rows that differ beyond [`close`]: the per-joint drifts, then `numbers`
/// (name, committed, fresh).
fn differing<'a>(
    committed: &[f64],
    fresh: &[f64],
    numbers: impl IntoIterator<Item = (&'a str, Option<f64>, Option<f64>)>,
) -> Vec<String> {
    let mut p = Vec::new();
    if committed.len() != fresh.len() {
        p.push(format!(
            "{} joint drifts -> {}",
            committed.len(),
            fresh.len()
        ));
    }
    let joints = committed
        .iter()
        .zip(fresh)
        .enumerate()
        .map(|(i, (a, b))| (format!("drift_{}", i + 1), Some(*a), Some(*b)));
    let named = numbers.into_iter().map(|(n, a, b)| (n.to_string(), a, b));
    for (name, a, b) in joints.chain(named) {
        if !close(a, b) {
            p.push(format!("{name} {} -> {}", value_text(a), value_text(b)));
        }
    }
    p
}

/// The differences between `committed` rows (of the runs `fresh` has) and `fresh`, matched by
/// `key` and compared by `diff`, one line each, prefixed by the key.
fn compare_rows<T>(
    committed: &[T],
    fresh: &[T],
    key: impl Fn(&T) -> String,
    baseline: &str,
    diff: impl Fn(&T, &T) -> Vec<String>,
) -> Vec<String>
where
    T: HasRunKey,
{
    let runs: HashSet<spec::RunKey> = fresh.iter().map(HasRunKey::run_key).collect();
    let explained: Vec<&T> = committed
        .iter()
        .filter(|c| runs.contains(&c.run_key()))
        .collect();
    compare_keyed(&explained, fresh, key, baseline, diff)
}

/// The differences between every row of `committed` and `fresh`, matched by `key` and compared
/// by `diff`, one line each, prefixed by the key; a committed row missing from `fresh`, or a
/// fresh row not committed, is a difference. Sorted.
fn compare_keyed<T>(
    committed: &[&T],
    fresh: &[T],
    key: impl Fn(&T) -> String,
    baseline: &str,
    diff: impl Fn(&T, &T) -> Vec<String>,
) -> Vec<String> {
    let fresh_by: std::collections::HashMap<String, &T> =
        fresh.iter().map(|f| (key(f), f)).collect();
    let mut problems = Vec::new();
    let mut seen = HashSet::new();
    for &c in committed {
        let k = key(c);
        seen.insert(k.clone());
        match fresh_by.get(&k) {
            None => problems.push(format!("{k}: in {baseline} but no longer produced")),
            Some(f) => problems.extend(diff(c, f).into_iter().map(|d| format!("{k}: {d}"))),
        }
    }
    for k in fresh_by.keys().filter(|k| !seen.contains(*k)) {
        problems.push(format!("{k}: new row, not in {baseline}"));
    }
    problems.sort();
    problems
}

/// A row of a table keyed by its run.
trait HasRunKey {
    fn run_key(&self) -> spec::RunKey;
}

impl HasRunKey for LadderRow {
    fn run_key(&self) -> spec::RunKey {
        self.key()
    }
}

impl HasRunKey for AttributionRow {
    fn run_key(&self) -> spec::RunKey {
        self.key()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The audit's case: a doctored `final_pos_err` (which a kong2019 claim reads) is a gate
    /// difference, as is every other measured metric; a timing is not.
    #[test]
    fn every_measured_metric_is_compared_and_no_timing() {
        let mut row = RunRow::blank(
            &spec::RunKey::from_ids("e", "v", "s").unwrap(),
            spec::SolverKind::Network(settings::NetworkKind::Znn),
        );
        row.final_pos_err = Some(1e-5);
        row.score_rms_dx = Some(2e-4);
        let committed = vec![row.clone()];
        assert!(compare(&committed, &committed, "b").is_empty());
        let mut doctored = row.clone();
        doctored.final_pos_err = Some(0.99);
        let problems = compare(&committed, &[doctored], "b");
        assert_eq!(problems.len(), 1, "{problems:?}");
        assert!(problems[0].contains("final_pos_err"), "{problems:?}");
        assert_eq!(problems[0], "e / v / s: final_pos_err 1e-5 -> 9.9e-1");
        let mut lost = row.clone();
        lost.score_rms_dx = None;
        assert!(compare(&committed, &[lost], "b")[0].contains("score_rms_dx"));
        let mut slower = row;
        slower.wall_s += 10.0;
        slower.sim_s += 10.0;
        assert!(compare(&committed, &[slower], "b").is_empty());
    }

    /// What the report's tables show besides the metrics (effort counts, tolerances, the
    /// integrator, where and how a failed run stopped) is compared too, but for a run stopped
    /// by its wall-time budget, whose effort depends on the machine.
    #[test]
    fn what_the_tables_show_is_compared_but_where_the_wall_clock_decides() {
        let mut row = RunRow::blank(
            &spec::RunKey::from_ids("e", "v", "s").unwrap(),
            spec::SolverKind::Network(settings::NetworkKind::Znn),
        );
        row.steps = 200;
        row.rhs_evals = 300;
        row.score_samples = Some(201);
        row.integrator = "bdf".into();
        let committed = vec![row.clone()];
        for (name, edit) in [
            (
                "steps",
                (|r: &mut RunRow| r.steps = 99_999) as fn(&mut RunRow),
            ),
            ("rejected", |r| r.rejected = 7),
            ("rhs_evals", |r| r.rhs_evals = 1),
            ("jac_evals", |r| r.jac_evals = 3),
            ("qp_solves", |r| r.qp_solves = 5),
            ("score_samples", |r| r.score_samples = None),
            ("score_failures", |r| r.score_failures = 2),
            ("rtol", |r| r.rtol = 1e-3),
            ("atol", |r| r.atol = 1e-3),
            ("max_step", |r| r.max_step = Some(0.1)),
            ("integrator", |r| r.integrator = "dopri5".into()),
        ] {
            let mut doctored = row.clone();
            edit(&mut doctored);
            let problems = compare(&committed, &[doctored], "b");
            assert_eq!(problems.len(), 1, "{name}: {problems:?}");
            assert!(problems[0].contains(name), "{name}: {problems:?}");
        }
        let mut failed = row.clone();
        failed.status = records::Status::Failed;
        failed.failure_kind = Some(FailureKind::Diverged);
        failed.failed_at = Some(6.78);
        failed.expected_failure = "its divergence is the finding".into();
        let committed = vec![failed.clone()];
        assert!(compare(&committed, &committed, "b").is_empty());
        let mut later = failed.clone();
        later.failed_at = Some(9.99);
        assert!(compare(&committed, &[later], "b")[0].contains("failed_at"));
        let mut other = failed.clone();
        other.failure_kind = Some(FailureKind::NonFinite);
        assert!(compare(&committed, &[other], "b")[0].contains("failure_kind"));
        // Out of wall time: where it stopped and its effort are the machine's.
        failed.failure_kind = Some(FailureKind::WallTime);
        let committed = vec![failed.clone()];
        let mut slower = failed;
        slower.failed_at = Some(1.0);
        slower.steps = 10;
        slower.rhs_evals = 20;
        assert!(compare(&committed, &[slower], "b").is_empty());
    }

    /// A doctored ladder or attribution number is a difference; the ladder's wall time is
    /// not; a row of a run not explained now is not compared.
    #[test]
    fn a_doctored_ladder_or_attribution_number_is_a_difference() {
        let ladder = fixtures::ladder_rows(&[("p", "dopri5", "ok", 1.0), ("p", "bdf", "ok", 2.0)]);
        let attribution: Vec<AttributionRow> = records::table::from_reader(
            "paper,experiment,variant_id,solver_id,variant,solver,component,drift_1,drift_norm,share,max_pos_err,note\n\
             p,e,v,s,V,S,run,0.1,0.1,1.0,0.001,\n"
                .as_bytes(),
        )
        .unwrap();
        let same = compare_explanations((&ladder, &attribution), (&ladder, &attribution), "b");
        assert!(same.is_empty(), "{same:?}");
        let mut slower = ladder.clone();
        slower[0].wall_s = 99.0;
        assert!(
            compare_explanations((&ladder, &attribution), (&slower, &attribution), "b").is_empty()
        );
        let mut doctored = ladder.clone();
        doctored[1].drift_norm = Some(0.2);
        let p = compare_explanations((&ladder, &attribution), (&doctored, &attribution), "b");
        assert_eq!(
            p,
            ["ladder.csv e / v / s bdf rtol 1e-6 atol 1e-8 max_step none: drift_norm 1e-1 -> 2e-1"]
        );
        let mut share = attribution.clone();
        share[0].share = Some(0.5);
        let p = compare_explanations((&ladder, &attribution), (&ladder, &share), "b");
        assert_eq!(p.len(), 1, "{p:?}");
        assert!(p[0].contains("share 1e0 -> 5e-1"), "{p:?}");
        let p = compare_explanations((&ladder, &attribution), (&ladder[..1], &attribution), "b");
        assert_eq!(p.len(), 1, "a lost rung: {p:?}");
        let p = compare_explanations((&ladder, &attribution), (&[], &[]), "b");
        assert!(p.is_empty(), "nothing explained now: {p:?}");
    }

    /// A doctored control or leaderboard number is a difference naming the table, the row and
    /// the column; a duration or a time is not.
    #[test]
    fn a_doctored_control_or_leaderboard_number_is_a_difference() {
        let control: Vec<ControlRow> = records::table::from_reader(
            "task,paper,scheme,method,family,h_ms,substeps,status,stopped_at,ticks,solve_p50_us,solve_p99_us,solve_max_us,tick_p50_us,tick_p99_us,tick_max_us,max_track_err,rms_track_err,max_dx,rms_dx,max_dx_settled,drift,products_mean,products_max,iterations_mean,iterations_max\n\
             e / v,p,S,M4,numerical,1.0,1,ok,,5000,320.8,4452.7,18392.0,322.2,4454.6,18395.0,0.00053,0.00034,6.9e-10,1.9e-10,6.9e-10,0.0017,676.8,2045,333.9,1018\n"
                .as_bytes(),
        )
        .unwrap();
        assert!(compare_control(&control, &control, "b").is_empty());
        let mut slower = control.clone();
        slower[0].solve_p50_us *= 3.0;
        slower[0].tick_max_us *= 3.0;
        assert!(compare_control(&control, &slower, "b").is_empty());
        let mut doctored = control.clone();
        doctored[0].max_dx = 1e-3;
        assert_eq!(
            compare_control(&control, &doctored, "b"),
            ["control.csv e / v M4 h_ms 1 substeps 1: max_dx 6.9e-10 -> 1e-3"]
        );
        let mut doctored = control.clone();
        doctored[0].products_max = None;
        assert_eq!(
            compare_control(&control, &doctored, "b"),
            ["control.csv e / v M4 h_ms 1 substeps 1: products_max 2045 -> none"]
        );
        assert_eq!(
            compare_control(&control, &[], "b"),
            ["control.csv e / v M4 h_ms 1 substeps 1: in b but no longer produced"]
        );

        let board: Vec<LeaderboardRow> = records::table::from_reader(
            "task_set,tasks,rank,solver_id,solver,solver_kind,standard_runs,completed,within_tolerance,success_pct,correct_pct,dx_shm,dx_rel,dx_p50,dx_p95,drift_shm,drift_rel,drift_p50,drift_p95,time_shm,time_rel,time_p50,time_p95\n\
             standard,15,1,lvi-pdnn,LVI-PDNN,lvi-pdnn,15,15,15,100.0,100.0,1.1e-5,1.0,1.0e-5,5.9e-5,0.0021,1.08,0.00077,0.059,0.0179,1.56,0.026,0.054\n"
                .as_bytes(),
        )
        .unwrap();
        assert!(compare_leaderboard(&board, &board, "b").is_empty());
        let mut slower = board.clone();
        slower[0].time_shm *= 2.0;
        slower[0].time_p95 *= 2.0;
        assert!(compare_leaderboard(&board, &slower, "b").is_empty());
        let mut doctored = board.clone();
        doctored[0].drift_shm = 0.5;
        doctored[0].within_tolerance = 14;
        assert_eq!(
            compare_leaderboard(&board, &doctored, "b"),
            [
                "leaderboard.csv standard lvi-pdnn: drift_shm 2.1e-3 -> 5e-1",
                "leaderboard.csv standard lvi-pdnn: within_tolerance 15 -> 14"
            ]
        );
    }
}
