//! The leaderboard: every velocity-level solver on the standard task set, scored the way
//! qpbenchmark (github.com/qpsolvers/qpbenchmark) scores QP solvers, written to
//! `results/leaderboard.csv` (one [`LeaderboardRow`] per solver and task set).
//!
//! **Tasks.** A task is one (experiment, variant) of the suite: a scheme on a path with a robot.
//! The standard task set ([`standard_tasks`]) is every task of the cross experiment
//! (`paper == "cross"`: every velocity-level network on every velocity-level scheme, path and
//! robot, the 7-joint Panda included) whose exact column completed, so every neural run has the
//! exact optimum to be scored against.
//!
//! **Solvers.** A solver is a solver id (the parameterised network, e.g.
//! `vp-rnn-pf-sinh`, shown by its label "VP-RNN-PF (sinh)"); the exact column is the reference, not a competitor. A solver that ran on every
//! standard task is ranked in the `standard` set. A solver that ran on some of them only (the
//! zeroing networks, which solve equality-only QPs, run on kong2019's schemes only) is not put
//! in the standard normalisation: it is ranked in a separate set, the tasks it ran on, against
//! every solver that also ran on all of them ([`LeaderboardRow::task_set`] names it), and its
//! count of standard tasks is in [`LeaderboardRow::standard_runs`].
//!
//! **Scores**, per set, as qpbenchmark's `results.py`:
//! - success rate: share of the set's tasks where the run completed *and* is within tolerance
//!   of the exact optimum once settled ([`within_tolerance`]: the RMS distance over t >= 1 s,
//!   after the start-up transient of a network started from zero);
//! - correct rate: share of the set's tasks where the run's own verdict is right: it failed, or
//!   it completed within tolerance. A run that completes but misses the tolerance is the one
//!   incorrect outcome (qpbenchmark: "found" equals "found and valid"). With no failed run it
//!   equals the success rate;
//! - the shifted geometric mean ([`shifted_geometric_mean`]) over the set's tasks of three
//!   per-run values, each divided by the best (smallest) solver's mean of the set (best = 1.0):
//!   the RMS distance to the optimum ([`RunScore::dx`]), the drift's distance from the exact
//!   column's ([`RunScore::drift`]) and the simulation's wall time ([`RunScore::time`]): the
//!   median of the run's repetitions timed alone ([`records::Timings`]), not the parallel
//!   reproduction's `sim_s` (used only for a run without an alone timing; [`alone_timing`]
//!   counts them and gives the repetitions' spread);
//! - the p50 and p95 of each over the set's tasks (the distribution, not only a mean).
//!
//! A failed run, or a missing value, is counted at the metric's penalty, and every value is
//! capped at it (qpbenchmark counts a failure at its time limit), so no completed run counts
//! worse than a failure.

use records::percentile;
use records::table::Row;
use records::RunRow;
use records::Timings;
use serde::{Deserialize, Serialize};
use spec::ids::{ExperimentId, SolverId, VariantId};
use spec::SolverKind;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use store::{IoAction, IoError, RunsError};

/// The `paper` of the experiments that make the standard task set.
pub const STANDARD_PAPER: &str = "cross";

/// The [`LeaderboardRow::task_set`] of the standard set.
pub const STANDARD_SET: &str = "standard";

/// Tolerance on the RMS of |x − x*|_inf after the settling time (`score_rms_dx_after_1s`: over
/// t >= 1 s, rad/s): a run is within tolerance when it completed and its settled RMS distance to
/// the exact optimum is at most this.
///
/// The suite's choice: 1 mrad/s, a thousandth of the arms' joint-velocity limits (1.5 rad/s on
/// the Jaco2, 2.2–2.6 rad/s on the Panda), the scale at which a joint-velocity loop resolves a
/// command. After the settling time (1 s, kong2019's for its network error, the same instant as
/// `net_error_max_after_1s`), because a network starts from the zero state while x*(0) is not
/// zero: over the whole run (`score_rms_dx`) the start-up transient alone can exceed the
/// tolerance (1 rad/s for 5 ms of a 5 s task is RMS 3e-2 rad/s), which measures the initial
/// condition, not how well the network tracks the optimum. How fast a network settles still
/// counts in the ranking: the accuracy mean ([`RunScore::dx`]) is the whole-run RMS. The RMS,
/// not the max, so that a brief excursion does not decide alone. A strictly convex QP has a
/// unique minimiser, so a small distance to it also bounds the objective gap and the violation.
/// VP-RNN-PF's equilibrium is the exponential-penalty optimum, not x*: it sits ~1e-2 rad/s
/// from x* by design, and this tolerance counts that against it.
pub const TOL_RMS_DX: f64 = 1e-3;

/// Shift of the shifted geometric mean of |x − x*| (rad/s): a hundredth of [`TOL_RMS_DX`].
/// Two solvers both a hundred times inside the tolerance count as about equally accurate, so
/// integrator-level differences (1e-8 to 1e-6 rad/s) do not make large ratios.
pub const SHIFT_DX: f64 = 1e-5;

/// Penalty (and cap) of |x − x*| (rad/s) for a failed run: 1 rad/s, the order of the joint-velocity
/// limits, where the command has nothing to do with x*.
pub const PENALTY_DX: f64 = 1.0;

/// Shift of the shifted geometric mean of the relative drift error: 1e-3. The papers print drift
/// with three significant digits, so relative errors below a part in a thousand print the same
/// number.
pub const SHIFT_DRIFT: f64 = 1e-3;

/// Penalty (and cap) of the relative drift error for a failed run (which has no drift): 1, a
/// drift as far from the exact column's as that is from zero.
pub const PENALTY_DRIFT: f64 = 1.0;

/// Shift of the shifted geometric mean of wall time (s): 10 ms. qpbenchmark shifts its runtimes
/// by 10 s; ours are 1 ms to 15 s of simulation on 5–15 s tasks, and below ~10 ms a run's time
/// is mostly setup, and its repetitions differ by a large fraction of it.
pub const SHIFT_TIME_S: f64 = 1e-2;

/// The time limit, as a multiple of the task's simulated duration: a failed run counts at
/// `TIME_LIMIT_FACTOR * duration` seconds (qpbenchmark counts a failure at its time limit), and
/// times are capped there. Ten times slower than real time is useless to the arm it would drive.
pub const TIME_LIMIT_FACTOR: f64 = 10.0;

/// One task: an (experiment, variant).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Task {
    /// The experiment's id.
    pub experiment: ExperimentId,
    /// The variant's id.
    pub variant: VariantId,
}

impl Task {
    fn of(r: &RunRow) -> Self {
        Task {
            experiment: r.experiment.clone(),
            variant: r.variant_id.clone(),
        }
    }
}

/// The standard task set: the tasks of [`STANDARD_PAPER`] whose exact column completed, sorted.
pub fn standard_tasks(rows: &[RunRow]) -> Vec<Task> {
    let set: BTreeSet<Task> = rows
        .iter()
        .filter(|r| r.paper == STANDARD_PAPER && r.is_exact() && r.completed())
        .map(Task::of)
        .collect();
    set.into_iter().collect()
}

/// Whether a run completed within [`TOL_RMS_DX`] of the exact optimum once settled (its
/// `score_rms_dx_after_1s`; a row without it, e.g. of a results file older than the column, is
/// not within tolerance).
pub fn within_tolerance(r: &RunRow) -> bool {
    r.completed() && r.score_rms_dx_after_1s.is_some_and(|v| v <= TOL_RMS_DX)
}

/// The value a metric counts at: a failed run or a missing (or NaN) value at `penalty`, every
/// other value capped at `penalty`.
pub fn counted(value: Option<f64>, completed: bool, penalty: f64) -> f64 {
    match value {
        Some(v) if completed && !v.is_nan() => v.min(penalty),
        _ => penalty,
    }
}

/// The drift's distance from the exact column's, relative to the exact drift:
/// |d − d*|_2 / |d*|_2 over the per-joint drift vectors when both rows have them (same joint
/// count), else |‖d‖ − ‖d*‖| / ‖d*‖ from the norms. Infinite when the exact drift is zero and
/// the run's is not; `None` when either drift is missing (a failed run).
pub fn relative_drift(run: &RunRow, exact: &RunRow) -> Option<f64> {
    let (distance, reference) = if !run.drift.is_empty() && run.drift.len() == exact.drift.len() {
        let distance = run
            .drift
            .iter()
            .zip(&exact.drift)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt();
        let reference = exact.drift.iter().map(|b| b * b).sum::<f64>().sqrt();
        (distance, reference)
    } else {
        let (d, e) = (run.drift_norm?, exact.drift_norm?);
        ((d - e).abs(), e)
    };
    Some(if distance == 0.0 {
        0.0
    } else {
        distance / reference
    })
}

/// One neural run as the leaderboard counts it.
#[derive(Clone, Debug, PartialEq)]
pub struct RunScore {
    pub task: Task,
    pub completed: bool,
    /// Completed within [`TOL_RMS_DX`] once settled ([`within_tolerance`]).
    pub within_tolerance: bool,
    /// RMS |x − x*|_inf over the whole run (rad/s), counted ([`counted`], [`PENALTY_DX`]).
    pub dx: f64,
    /// [`relative_drift`] against the task's exact column, counted ([`PENALTY_DRIFT`]).
    pub drift: f64,
    /// `sim_s` (s): the median timed alone if there is one, else the parallel run's; counted
    /// at the time limit ([`TIME_LIMIT_FACTOR`] × duration).
    pub time: f64,
}

/// Scores `run` against the exact column `exact` of the same task, its time from `timings`.
pub fn score_run(run: &RunRow, exact: &RunRow, timings: &Timings) -> RunScore {
    let completed = run.completed();
    let alone = timings.get(&run.key());
    let sim_s = alone.map_or(run.sim_s, |t| t.sim_s_median);
    RunScore {
        task: Task::of(run),
        completed,
        within_tolerance: within_tolerance(run),
        dx: counted(run.score_rms_dx, completed, PENALTY_DX),
        drift: counted(relative_drift(run, exact), completed, PENALTY_DRIFT),
        time: counted(Some(sim_s), completed, TIME_LIMIT_FACTOR * run.duration),
    }
}

/// The shifted geometric mean exp(mean(ln(v_i + shift))) − shift of non-negative values
/// (<http://plato.asu.edu/ftp/shgeom.html>, qpbenchmark's `shgeom`); NaN for no values.
/// `shift` is in the values' unit and must be positive (qpbenchmark requires at least 1 for its
/// metrics; ours live far below 1, so each has its own shift).
pub fn shifted_geometric_mean(values: &[f64], shift: f64) -> f64 {
    assert!(shift > 0.0, "the shift must be positive (got {shift})");
    assert!(
        values.iter().all(|v| *v >= 0.0),
        "shifted geometric mean of negative values: {values:?}"
    );
    if values.is_empty() {
        return f64::NAN;
    }
    let mean_log = values.iter().map(|v| (v + shift).ln()).sum::<f64>() / values.len() as f64;
    // A mean lies between the extremes; clamping removes the round-off (so that equal values,
    // zeros included, are their own mean exactly).
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (mean_log.exp() - shift).clamp(lo, hi)
}

/// `value` relative to the best (smallest) of its set: 1.0 for the best.
fn ratio(value: f64, best: f64) -> f64 {
    if value == best {
        1.0
    } else {
        value / best
    }
}

/// One solver on one task set: `results/leaderboard.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LeaderboardRow {
    /// [`STANDARD_SET`], or `tasks of <solvers>`: the tasks those solvers (which did not run on
    /// every standard task) ran on, shared by every solver of the row's set.
    pub task_set: String,
    /// Tasks in the set.
    pub tasks: usize,
    /// 1 = best of the set: by success rate (higher first), then the normalised shifted
    /// geometric means of |x − x*|, of the drift error and of time (lower first), then label.
    pub rank: usize,
    /// The solver's id (identity); `solver` is its label.
    pub solver_id: SolverId,
    pub solver: String,
    pub solver_kind: SolverKind,
    /// Runs of this solver on the standard task set.
    pub standard_runs: usize,
    /// Runs of the set that completed.
    pub completed: usize,
    /// Runs of the set that completed within [`TOL_RMS_DX`].
    pub within_tolerance: usize,
    /// 100 × within_tolerance / tasks.
    pub success_pct: f64,
    /// 100 × (tasks − completed outside tolerance) / tasks.
    pub correct_pct: f64,
    /// Shifted geometric mean of RMS |x − x*| (rad/s, shift [`SHIFT_DX`]).
    pub dx_shm: f64,
    /// `dx_shm` over the set's best.
    pub dx_rel: f64,
    pub dx_p50: f64,
    pub dx_p95: f64,
    /// Shifted geometric mean of the relative drift error (shift [`SHIFT_DRIFT`]).
    pub drift_shm: f64,
    pub drift_rel: f64,
    pub drift_p50: f64,
    pub drift_p95: f64,
    /// Shifted geometric mean of `sim_s` (s, shift [`SHIFT_TIME_S`]).
    pub time_shm: f64,
    pub time_rel: f64,
    pub time_p50: f64,
    pub time_p95: f64,
}

impl Row for LeaderboardRow {}

/// One solver's runs on the standard tasks.
struct Entrant<'a> {
    id: &'a SolverId,
    solver: &'a str,
    kind: SolverKind,
    runs: BTreeMap<Task, &'a RunRow>,
}

/// The leaderboard of `rows` (all of `results/runs.csv`): the standard set first, then one set
/// per distinct task subset of the solvers that did not run on every standard task (larger
/// subsets first); within a set, by rank.
pub fn leaderboard(rows: &[RunRow], timings: &Timings) -> Vec<LeaderboardRow> {
    let tasks = standard_tasks(rows);
    let exact: BTreeMap<Task, &RunRow> = rows
        .iter()
        .filter(|r| r.is_exact() && r.completed())
        .map(|r| (Task::of(r), r))
        .filter(|(t, _)| tasks.binary_search(t).is_ok())
        .collect();
    let mut entrants: BTreeMap<&str, Entrant> = BTreeMap::new();
    for r in rows.iter().filter(|r| !r.is_exact()) {
        let task = Task::of(r);
        if exact.contains_key(&task) {
            entrants
                .entry(r.solver_id.as_str())
                .or_insert_with(|| Entrant {
                    id: &r.solver_id,
                    solver: &r.solver,
                    kind: r.solver_kind,
                    runs: BTreeMap::new(),
                })
                .runs
                .insert(task, r);
        }
    }
    let covers = |e: &Entrant, set: &[Task]| set.iter().all(|t| e.runs.contains_key(t));

    // The sets: the standard one, then each partial solver's own tasks.
    let mut sets: Vec<(String, Vec<Task>)> = vec![(STANDARD_SET.to_string(), tasks.clone())];
    let mut partial: BTreeMap<Vec<Task>, Vec<&str>> = BTreeMap::new();
    for e in entrants.values().filter(|e| !covers(e, &tasks)) {
        partial
            .entry(e.runs.keys().cloned().collect())
            .or_default()
            .push(e.solver);
    }
    let mut partial: Vec<(Vec<Task>, Vec<&str>)> = partial.into_iter().collect();
    partial.sort_by_key(|(set, solvers)| (std::cmp::Reverse(set.len()), solvers.clone()));
    sets.extend(
        partial
            .into_iter()
            .map(|(set, solvers)| (format!("tasks of {}", solvers.join(", ")), set)),
    );

    let mut out = Vec::new();
    for (name, set) in sets {
        let members: Vec<&Entrant> = entrants.values().filter(|e| covers(e, &set)).collect();
        if set.is_empty() || members.is_empty() {
            continue;
        }
        out.extend(rank_set(&name, &set, &members, &exact, timings));
    }
    out
}

/// The rows of one task set, ranked.
fn rank_set(
    name: &str,
    set: &[Task],
    members: &[&Entrant],
    exact: &BTreeMap<Task, &RunRow>,
    timings: &Timings,
) -> Vec<LeaderboardRow> {
    let mut rows: Vec<LeaderboardRow> = members
        .iter()
        .map(|e| {
            let scores: Vec<RunScore> = set
                .iter()
                .map(|t| score_run(e.runs[t], exact[t], timings))
                .collect();
            let n = scores.len();
            let completed = scores.iter().filter(|s| s.completed).count();
            let within = scores.iter().filter(|s| s.within_tolerance).count();
            let incorrect = scores
                .iter()
                .filter(|s| s.completed && !s.within_tolerance)
                .count();
            let values = |f: fn(&RunScore) -> f64| scores.iter().map(f).collect::<Vec<f64>>();
            let (dx, drift, time) = (values(|s| s.dx), values(|s| s.drift), values(|s| s.time));
            LeaderboardRow {
                task_set: name.to_string(),
                tasks: n,
                rank: 0,
                solver_id: e.id.clone(),
                solver: e.solver.to_string(),
                solver_kind: e.kind,
                standard_runs: e.runs.len(),
                completed,
                within_tolerance: within,
                success_pct: 100.0 * within as f64 / n as f64,
                correct_pct: 100.0 * (n - incorrect) as f64 / n as f64,
                dx_shm: shifted_geometric_mean(&dx, SHIFT_DX),
                dx_rel: f64::NAN,
                dx_p50: percentile(&dx, 0.5),
                dx_p95: percentile(&dx, 0.95),
                drift_shm: shifted_geometric_mean(&drift, SHIFT_DRIFT),
                drift_rel: f64::NAN,
                drift_p50: percentile(&drift, 0.5),
                drift_p95: percentile(&drift, 0.95),
                time_shm: shifted_geometric_mean(&time, SHIFT_TIME_S),
                time_rel: f64::NAN,
                time_p50: percentile(&time, 0.5),
                time_p95: percentile(&time, 0.95),
            }
        })
        .collect();
    let best = |f: fn(&LeaderboardRow) -> f64| rows.iter().map(f).fold(f64::INFINITY, f64::min);
    let (dx, drift, time) = (
        best(|r| r.dx_shm),
        best(|r| r.drift_shm),
        best(|r| r.time_shm),
    );
    for r in &mut rows {
        r.dx_rel = ratio(r.dx_shm, dx);
        r.drift_rel = ratio(r.drift_shm, drift);
        r.time_rel = ratio(r.time_shm, time);
    }
    rows.sort_by(|a, b| {
        b.success_pct
            .total_cmp(&a.success_pct)
            .then(a.dx_rel.total_cmp(&b.dx_rel))
            .then(a.drift_rel.total_cmp(&b.drift_rel))
            .then(a.time_rel.total_cmp(&b.time_rel))
            .then(a.solver.cmp(&b.solver))
    });
    for (i, r) in rows.iter_mut().enumerate() {
        r.rank = i + 1;
    }
    rows
}

/// How many of `solver_id`'s runs on `tasks` were timed alone, and the largest
/// (max − min) / median of their repetitions' `sim_s` (NaN when none was).
pub fn alone_timing(timings: &Timings, solver_id: &SolverId, tasks: &[Task]) -> (usize, f64) {
    let spreads: Vec<f64> = tasks
        .iter()
        .filter_map(|t| {
            timings.get(&spec::RunKey::new(
                t.experiment.clone(),
                t.variant.clone(),
                solver_id.clone(),
            ))
        })
        .map(|r| r.sim_spread())
        .collect();
    let max = spreads.iter().copied().reduce(f64::max).unwrap_or(f64::NAN);
    (spreads.len(), max)
}

/// The leaderboard as CSV (see [`records::table`]).
pub fn leaderboard_csv(rows: &[LeaderboardRow]) -> Result<Vec<u8>, csv::Error> {
    records::table::to_csv(rows)
}

/// Writes `results_dir/leaderboard.csv` (atomically) from `runs`; returns its path.
pub fn write(results_dir: &Path, runs: &[RunRow]) -> Result<PathBuf, RunsError> {
    let timings = store::timing::read(results_dir)?;
    let path = results_dir.join(store::results_dir::LEADERBOARD);
    let bytes =
        leaderboard_csv(&leaderboard(runs, &timings)).map_err(|source| RunsError::Write {
            path: path.clone(),
            source,
        })?;
    store::write_atomic(&path, &bytes).map_err(IoError::at(&path, IoAction::Write))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use records::Status;

    /// A completed run of `solver` (its label; its id is the label in lower case) on task `exp`
    /// with the given RMS distance, per-joint drift and time; `solver == "exact"` makes the
    /// exact column.
    fn run(solver: &str, exp: &str, rms: f64, drift: &[f64], sim_s: f64) -> RunRow {
        let key = spec::RunKey::from_ids(exp, "v", &solver.to_lowercase()).unwrap();
        let mut r = RunRow::blank(&key, SolverKind::Exact);
        r.solver = solver.into();
        r.paper = "cross".into();
        r.solver_kind = if solver == "exact" {
            SolverKind::Exact
        } else {
            // A, B, C, ...: the networks in their order (any kind will do).
            SolverKind::Network(
                settings::NetworkKind::ALL[usize::from(solver.as_bytes()[0] - b'A')],
            )
        };
        r.drift = drift.to_vec();
        r.drift_norm = Some(drift.iter().map(|d| d * d).sum::<f64>().sqrt());
        if solver != "exact" {
            r.score_rms_dx = Some(rms);
            r.score_rms_dx_after_1s = Some(rms);
        }
        r.sim_s = sim_s;
        r
    }

    fn failed(mut r: RunRow) -> RunRow {
        r.status = Status::Failed;
        r.drift.clear();
        r.drift_norm = None;
        r
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300)
    }

    #[test]
    fn success_is_judged_after_the_settling_time_accuracy_over_the_whole_run() {
        // A start-up transient puts the whole-run RMS above the tolerance; settled, the run is
        // well inside it.
        let mut r = run("A", "t1", 3e-2, &[0.1], 1.0);
        r.score_rms_dx_after_1s = Some(1e-5);
        assert!(within_tolerance(&r));
        let exact = run("exact", "t1", 0.0, &[0.1], 1.0);
        let s = score_run(&r, &exact, &Timings::default());
        assert!(s.within_tolerance && s.dx == 3e-2);
        // Settled outside the tolerance, or without the settled value (an older file): not.
        r.score_rms_dx_after_1s = Some(2e-3);
        assert!(!within_tolerance(&r));
        r.score_rms_dx_after_1s = None;
        assert!(!within_tolerance(&r));
    }

    #[test]
    fn shifted_geometric_mean_by_hand() {
        // (1 + 1) (7 + 1) = 16, sqrt = 4, minus the shift: 3.
        assert!(close(shifted_geometric_mean(&[1.0, 7.0], 1.0), 3.0));
        // (0 + 2) (6 + 2) (30 + 2) = 512, cube root 8, minus 2: 6.
        assert!(close(shifted_geometric_mean(&[0.0, 6.0, 30.0], 2.0), 6.0));
        // Equal values: the value itself, whatever the shift.
        assert_eq!(shifted_geometric_mean(&[0.25; 4], 1e-3), 0.25);
        assert_eq!(shifted_geometric_mean(&[0.0; 3], 1e-3), 0.0);
        assert!(shifted_geometric_mean(&[], 1.0).is_nan());
    }

    #[test]
    fn failed_runs_count_at_the_penalty_and_values_are_capped() {
        assert_eq!(counted(Some(0.5), true, 1.0), 0.5);
        assert_eq!(counted(Some(3.0), true, 1.0), 1.0);
        assert_eq!(counted(Some(0.5), false, 1.0), 1.0);
        assert_eq!(counted(None, true, 1.0), 1.0);
        let exact = run("exact", "t", 0.0, &[0.3, 0.4], 1.0);
        let f = failed(run("A", "t", 1e-6, &[0.3, 0.4], 0.2));
        let s = score_run(&f, &exact, &Timings::default());
        assert!(!s.completed && !s.within_tolerance);
        assert_eq!(
            (s.dx, s.drift, s.time),
            (PENALTY_DX, PENALTY_DRIFT, TIME_LIMIT_FACTOR * 5.0)
        );
    }

    #[test]
    fn relative_drift_of_vectors_and_of_norms() {
        let exact = run("exact", "t", 0.0, &[0.3, 0.4], 1.0);
        // |(0.3, 0.4) - (0.3, 0.5)| / 0.5 = 0.2.
        let a = run("A", "t", 0.0, &[0.3, 0.5], 1.0);
        assert!(close(relative_drift(&a, &exact).unwrap(), 0.2));
        // A different joint count: from the norms, |0.6 - 0.5| / 0.5.
        let mut b = run("B", "t", 0.0, &[0.6], 1.0);
        b.drift.clear();
        assert!(close(relative_drift(&b, &exact).unwrap(), 0.2));
        let zero = run("exact", "t", 0.0, &[0.0, 0.0], 1.0);
        assert_eq!(relative_drift(&a, &zero), Some(f64::INFINITY));
        assert_eq!(relative_drift(&zero, &zero), Some(0.0));
    }

    /// Two tasks; A within tolerance on both, B on one, C fails one; D runs on task 1 only.
    fn board() -> Vec<RunRow> {
        vec![
            run("exact", "t1", 0.0, &[1.0, 0.0], 1.0),
            run("exact", "t2", 0.0, &[0.0, 2.0], 1.0),
            run("A", "t1", 1e-5, &[1.0, 0.0], 0.01),
            run("A", "t2", 1e-5, &[0.0, 2.0], 0.01),
            run("B", "t1", 1e-4, &[1.1, 0.0], 0.02),
            run("B", "t2", 1e-2, &[0.0, 2.2], 0.02),
            run("C", "t1", 1e-4, &[1.0, 0.0], 0.01),
            failed(run("C", "t2", 0.0, &[], 0.001)),
            run("D", "t1", 2e-3, &[1.0, 0.0], 0.01),
            // Not a standard task (another paper): ignored.
            RunRow {
                paper: "jia2019".into(),
                ..run("A", "elsewhere", 0.5, &[9.0, 9.0], 99.0)
            },
        ]
    }

    #[test]
    fn success_correct_normalisation_and_sets() {
        let rows = leaderboard(&board(), &Timings::default());
        let get = |set: &str, s: &str| {
            rows.iter()
                .find(|r| r.task_set == set && r.solver == s)
                .unwrap_or_else(|| panic!("no {s} in {set}: {rows:#?}"))
        };
        let std: Vec<&str> = rows
            .iter()
            .filter(|r| r.task_set == STANDARD_SET)
            .map(|r| r.solver.as_str())
            .collect();
        // D did not run on t2: not in the standard set; ranked by success, then accuracy.
        assert_eq!(std, ["A", "B", "C"]);
        let (a, b, c) = (
            get(STANDARD_SET, "A"),
            get(STANDARD_SET, "B"),
            get(STANDARD_SET, "C"),
        );
        assert_eq!((a.rank, b.rank, c.rank), (1, 2, 3));
        assert_eq!((a.tasks, a.standard_runs), (2, 2));
        // Success: within tolerance over all tasks. Correct: a failure is correct, a completed
        // run outside tolerance is not.
        assert_eq!((a.success_pct, a.correct_pct), (100.0, 100.0));
        assert_eq!((b.success_pct, b.correct_pct), (50.0, 50.0));
        assert_eq!((c.success_pct, c.correct_pct), (50.0, 100.0));
        assert_eq!((c.completed, c.within_tolerance), (1, 1));
        // |x - x*|: A's equal values are their own mean; B: sqrt((1e-4 + sh)(1e-2 + sh)) - sh.
        let b_dx = ((1e-4 + SHIFT_DX) * (1e-2 + SHIFT_DX)).sqrt() - SHIFT_DX;
        assert!(close(b.dx_shm, b_dx), "{}", b.dx_shm);
        assert!(close(a.dx_shm, 1e-5));
        assert_eq!(a.dx_rel, 1.0);
        assert!(close(b.dx_rel, b_dx / 1e-5));
        // C: 1e-4 and the failure at the penalty.
        let c_dx = ((1e-4 + SHIFT_DX) * (PENALTY_DX + SHIFT_DX)).sqrt() - SHIFT_DX;
        assert!(close(c.dx_shm, c_dx));
        // Drift: B is 10 % off on both tasks: shm 0.1; C: 0 and the penalty.
        assert!(close(b.drift_shm, 0.1));
        let c_drift = (SHIFT_DRIFT * (PENALTY_DRIFT + SHIFT_DRIFT)).sqrt() - SHIFT_DRIFT;
        assert!(close(c.drift_shm, c_drift));
        // Time: A and B take 10 and 20 ms everywhere; C's failure counts at 10 x 5 s.
        assert!(close(a.time_shm, 0.01) && close(b.time_shm, 0.02));
        assert!(close(b.time_rel, 2.0) && a.time_rel == 1.0);
        let c_time = ((0.01 + SHIFT_TIME_S) * (50.0 + SHIFT_TIME_S)).sqrt() - SHIFT_TIME_S;
        assert!(close(c.time_shm, c_time));
        assert!(close(c.time_p50, (0.01 + 50.0) / 2.0));
        assert!(close(c.time_p95, 0.01 + 0.95 * (50.0 - 0.01)));

        // D's set: task t1, shared by everyone; D has 1 standard run; normalised there.
        let set = "tasks of D";
        let d = get(set, "D");
        assert_eq!((d.tasks, d.standard_runs, d.success_pct), (1, 1, 0.0));
        assert_eq!(rows.iter().filter(|r| r.task_set == set).count(), 4);
        let b1 = get(set, "B");
        assert_eq!(b1.success_pct, 100.0);
        // A and C match the exact drift on t1 (shm 0): B's ratio to it is infinite.
        assert!(
            close(b1.drift_shm, 0.1) && b1.drift_rel.is_infinite(),
            "{b1:?}"
        );
        assert!(close(get(set, "C").time_rel, 1.0));
    }

    #[test]
    fn alone_timings_replace_the_parallel_times() {
        use records::TimingRow;
        use spec::RunKey;
        // A timed alone at 40, 50 and 90 ms on t1 (median 50 ms), 50 ms three times on t2;
        // B not timed alone keeps its parallel 20 ms and now ranks faster.
        let timed = |task: &str, s: [f64; 3]| {
            let samples: Vec<(f64, f64)> = s.iter().map(|&v| (v, v)).collect();
            TimingRow::from_samples(
                &RunKey::from_ids(task, "v", "a").unwrap(),
                &samples,
                "cpu",
                2,
                "r",
            )
        };
        let timings = Timings::new(vec![
            timed("t1", [0.04, 0.09, 0.05]),
            timed("t2", [0.05; 3]),
        ]);
        let rows = leaderboard(&board(), &timings);
        let get = |s: &str| {
            rows.iter()
                .find(|r| r.task_set == STANDARD_SET && r.solver == s)
                .unwrap()
        };
        let (a, b) = (get("A"), get("B"));
        assert!(close(a.time_shm, 0.05) && close(b.time_shm, 0.02));
        assert!(close(a.time_rel, 2.5) && b.time_rel == 1.0);
        let tasks = standard_tasks(&board());
        let id = |s: &str| SolverId::new(s).unwrap();
        let (a_alone, a_spread) = alone_timing(&timings, &id("a"), &tasks);
        let (b_alone, b_spread) = alone_timing(&timings, &id("b"), &tasks);
        assert_eq!((a_alone, b_alone), (2, 0));
        assert!(close(a_spread, 1.0) && b_spread.is_nan());
    }

    #[test]
    fn the_csv_has_a_header_and_one_line_per_row() {
        let rows = leaderboard(&board(), &Timings::default());
        let text = String::from_utf8(leaderboard_csv(&rows).unwrap()).unwrap();
        assert!(
            text.starts_with("task_set,tasks,rank,solver_id,solver,solver_kind,"),
            "{text}"
        );
        assert_eq!(text.lines().count(), rows.len() + 1);
        let back: Vec<LeaderboardRow> = records::table::from_reader(text.as_bytes()).unwrap();
        assert_eq!(back.len(), rows.len());
    }
}
