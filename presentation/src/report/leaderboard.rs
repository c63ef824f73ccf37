//! The leaderboard section: every velocity-level solver on the standard task set, scored as
//! qpbenchmark scores QP solvers ([`analysis::leaderboard`], also `results/leaderboard.csv`):
//! the ranking, the distributions, a reading generated from the numbers
//! ([`analysis::leaderboard_reading`]), how the times were measured (alone, repeated:
//! [`records::Timings`]) and the definitions.

use super::markdown::{percent, sci, times, Table, MISSING};
use analysis::leaderboard::{
    LeaderboardRow, PENALTY_DRIFT, PENALTY_DX, SHIFT_DRIFT, SHIFT_DX, SHIFT_TIME_S, STANDARD_PAPER,
    STANDARD_SET, TIME_LIMIT_FACTOR, TOL_RMS_DX,
};
use analysis::leaderboard_reading::{Best, StandardReading, TimingReading};
use analysis::report_model::Leaderboard;
use records::{Timings, TIMING_REPETITIONS};

/// The whole section (`## Leaderboard`) of the leaderboard `model` (timed in `timings`), empty
/// when there is no standard task.
pub fn section(model: &Leaderboard, timings: &Timings) -> String {
    let Leaderboard {
        tasks,
        rows,
        alone,
        reading: standard,
        timing: timed,
    } = model;
    if tasks.is_empty() || rows.is_empty() {
        return String::new();
    }
    let mut out = format!(
        "## Leaderboard\n\nEvery velocity-level solver on the standard task set — the {} tasks \
         (experiment · variant) of the `{STANDARD_PAPER}` experiment, every velocity-level scheme, \
         path and robot, the 7-joint Panda included — scored as \
         [qpbenchmark](https://github.com/qpsolvers/qpbenchmark) scores QP solvers: success and \
         correct rates against stated tolerances, and shifted geometric means normalised to the \
         best solver (1.00 = best), with medians and 95th percentiles. The same numbers are in \
         `results/leaderboard.csv`; the definitions follow the tables.\n\n",
        tasks.len()
    );
    out.push_str(&reading(rows, standard.as_ref(), tasks.len()));
    out.push('\n');
    out.push_str(&timing(timings, timed.as_ref()));
    for set in sets(rows) {
        let members: Vec<(&LeaderboardRow, (usize, f64))> = rows
            .iter()
            .zip(alone.iter().copied())
            .filter(|(r, _)| r.task_set == set)
            .collect();
        let ranked: Vec<&LeaderboardRow> = members.iter().map(|(r, _)| *r).collect();
        let n = ranked[0].tasks;
        if set == STANDARD_SET {
            out.push_str(&format!("### Standard set ({n} tasks)\n\n"));
        } else {
            let partial: Vec<&str> = ranked
                .iter()
                .filter(|r| r.standard_runs < tasks.len())
                .map(|r| r.solver.as_str())
                .collect();
            out.push_str(&format!(
                "### The {n} tasks of {} (not on every standard task)\n\n{} ran on {n} of the {} \
                 standard tasks only, so they are not in the standard ranking; here every solver \
                 that ran on all of those tasks is ranked on them, normalised among themselves.\n\n",
                join_and(&partial),
                join_and(&partial),
                tasks.len()
            ));
        }
        out.push_str(&ranking(&ranked));
        out.push('\n');
        out.push_str(&distributions(&members));
        out.push('\n');
    }
    out.push_str(&definitions());
    out
}

/// The first `n` solvers of the standard set's ranking of the leaderboard `model` (the front
/// page), empty without a leaderboard.
pub fn top(model: &Leaderboard, n: usize) -> String {
    let top: Vec<&LeaderboardRow> = model
        .rows
        .iter()
        .filter(|r| r.task_set == STANDARD_SET)
        .take(n)
        .collect();
    if top.is_empty() {
        return String::new();
    }
    ranking(&top)
}

/// The task sets in the rows' order.
fn sets(rows: &[LeaderboardRow]) -> Vec<&str> {
    records::table::distinct(rows, |r| &r.task_set)
}

/// A percentage of tasks.
fn pct(v: f64) -> String {
    format!("{v:.0} %")
}

/// The ranking table of one set.
pub fn ranking(rows: &[&LeaderboardRow]) -> String {
    let mut t = Table::new([
        "rank",
        "solver",
        "kind",
        "standard tasks run",
        "completed",
        "success rate",
        "correct rate",
        "RMS |x − x*| (shm, × best)",
        "drift error (shm, × best)",
        "sim time (shm, × best)",
    ]);
    for r in rows {
        t.push([
            r.rank.to_string(),
            r.solver.clone(),
            r.solver_kind.to_string(),
            r.standard_runs.to_string(),
            format!("{} / {}", r.completed, r.tasks),
            format!(
                "{} ({} / {})",
                pct(r.success_pct),
                r.within_tolerance,
                r.tasks
            ),
            pct(r.correct_pct),
            times(r.dx_rel),
            times(r.drift_rel),
            times(r.time_rel),
        ]);
    }
    t.render()
}

/// The absolute shifted geometric means, medians and 95th percentiles of one set's `rows`, each
/// with its runs timed alone and their largest spread.
fn distributions(rows: &[(&LeaderboardRow, (usize, f64))]) -> String {
    let mut t = Table::new([
        "solver",
        "RMS |x − x*| shm (rad/s)",
        "p50",
        "p95",
        "drift error shm",
        "p50",
        "p95",
        "sim time shm (s)",
        "p50",
        "p95",
        "timed alone",
        "largest spread of the repetitions",
    ]);
    for &(r, (alone, spread)) in rows {
        t.push([
            r.solver.clone(),
            sci(r.dx_shm),
            sci(r.dx_p50),
            sci(r.dx_p95),
            sci(r.drift_shm),
            sci(r.drift_p50),
            sci(r.drift_p95),
            sci(r.time_shm),
            sci(r.time_p50),
            sci(r.time_p95),
            format!("{alone} / {}", r.tasks),
            if spread.is_nan() {
                MISSING.to_string()
            } else {
                percent(spread, 0)
            },
        ]);
    }
    t.render()
}

/// "a", "a and b", "a, b and c".
fn join_and(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [one] => one.to_string(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// One paragraph reading the standard set (its `standard` reading,
/// [`analysis::leaderboard_reading`]) and a sentence per other set of `rows`.
fn reading(
    rows: &[LeaderboardRow],
    standard: Option<&StandardReading>,
    standard_tasks: usize,
) -> String {
    let mut s = match standard {
        None => vec![format!(
            "No solver ran on all {standard_tasks} standard tasks, so there is no standard ranking."
        )],
        Some(reading) => standard_sentences(reading),
    };
    for set in sets(rows).into_iter().filter(|s| *s != STANDARD_SET) {
        s.push(other_set_sentence(rows, set, standard_tasks));
    }
    format!("{}\n", s.join(" "))
}

/// "a", "a and b", "a, b and c" of the solvers' labels.
fn names<'r>(rows: impl IntoIterator<Item = &'r LeaderboardRow>) -> String {
    join_and(
        &rows
            .into_iter()
            .map(|r| r.solver.as_str())
            .collect::<Vec<_>>(),
    )
}

/// The others' ratios to the best: "2.00×", "2.00× to 5.00×", or "the same".
fn others(best: &Best) -> String {
    match best.others {
        Some((lo, hi)) if lo == hi => format!("{}×", times(lo)),
        Some((lo, hi)) => format!("{}× to {}×", times(lo), times(hi)),
        None => "the same".to_string(),
    }
}

/// The standard set's sentences: success, failures, and the best per measure.
fn standard_sentences(r: &StandardReading) -> Vec<String> {
    let n = r.tasks;
    let (w, top) = &r.by_success[0];
    let rest: Vec<String> = r.by_success[1..]
        .iter()
        .map(|(w, g)| format!("{} on {w}", names(g)))
        .collect();
    let mut s = vec![format!(
        "On the standard set, {} {} within tolerance (RMS |x − x*| after 1 s ≤ {} rad/s) on {w} of \
         {n} tasks{}",
        names(top),
        if top.len() == 1 { "is" } else { "are" },
        sci(TOL_RMS_DX),
        if rest.is_empty() {
            ".".to_string()
        } else {
            format!("; {}.", rest.join(", "))
        }
    )];
    s.push(if r.failed == 0 {
        "Every run completed, so the correct rate equals the success rate: each miss is a run \
         that completed outside the tolerance."
            .to_string()
    } else {
        format!(
            "{} runs failed and count at the penalties; a failure is not an incorrect \
             outcome (the correct rate counts only completed runs outside the tolerance).",
            r.failed
        )
    });
    let acc = &r.closest;
    s.push(format!(
        "The closest to the exact optimum is {} (shifted geometric mean of the RMS distance \
         {} rad/s, median {}); the others' means are {} that.",
        names(&acc.rows),
        sci(acc.rows[0].dx_shm),
        sci(acc.rows[0].dx_p50),
        others(acc)
    ));
    let drift = &r.drift;
    s.push(format!(
        "{} reproduce{} the exact column's drift most closely (relative error: shifted \
         geometric mean {}, 95th percentile {}); the others are {} that.",
        names(&drift.rows),
        if drift.rows.len() == 1 { "s" } else { "" },
        sci(drift.rows[0].drift_shm),
        sci(drift.rows[0].drift_p95),
        others(drift)
    ));
    let fast = &r.fastest;
    s.push(format!(
        "{} {} fastest (shifted geometric mean of the simulation time {} s, median {} s); the \
         others take {} as long.",
        names(&fast.rows),
        if fast.rows.len() == 1 { "is" } else { "are" },
        sci(fast.rows[0].time_shm),
        sci(fast.rows[0].time_p50),
        others(fast)
    ));
    s
}

/// The sentence of a set other than the standard one: who ran on its tasks only, who ranks
/// first there, and where each of them stands.
fn other_set_sentence(rows: &[LeaderboardRow], set: &str, standard_tasks: usize) -> String {
    let members: Vec<&LeaderboardRow> = rows.iter().filter(|r| r.task_set == set).collect();
    let partial: Vec<&LeaderboardRow> = members
        .iter()
        .copied()
        .filter(|r| r.standard_runs < standard_tasks)
        .collect();
    let n = members[0].tasks;
    let first = members[0];
    format!(
        "{} ran on {n} of the {standard_tasks} standard tasks only; on those, {} ranks first \
         ({} / {n} within tolerance), and {}.",
        names(partial.iter().copied()),
        first.solver,
        first.within_tolerance,
        join_and(
            &partial
                .iter()
                .map(|r| format!(
                    "{} is within tolerance on {} / {n} (rank {} of {})",
                    r.solver,
                    r.within_tolerance,
                    r.rank,
                    members.len()
                ))
                .collect::<Vec<_>>()
                .iter()
                .map(String::as_str)
                .collect::<Vec<_>>()
        )
    )
}

/// How the times the ranking uses were measured: alone, repeated ([`records::Timings`]), on
/// which machine and revision (the first of `timings`; `reading`: how); or that they come
/// from the parallel reproduction.
fn timing(timings: &Timings, reading: Option<&TimingReading>) -> String {
    let (Some(first), Some(t)) = (timings.rows().next(), reading) else {
        return format!(
            "**Times.** `results/{}` is absent: the times are the parallel reproduction's \
             `sim_s`, where a run shares the cores with its neighbours.\n\n",
            records::TIMING_FILE
        );
    };
    format!(
        "**Times.** After the parallel reproduction, every run of the leaderboard (and every run \
         the papers publish a MATLAB time for) was run again {TIMING_REPETITIONS} times, one run at a \
         time on one thread, on {} ({} logical cores available) at revision `{}`; the ranking \
         uses the median of the repetitions' `sim_s` ({} of the {} standard-set runs \
         timed so; any other counts its parallel `sim_s`). The repetitions' spread, \
         (max − min) / median, is {} at the median over the {} timed runs and at most \
         {}: time ratios closer to 1 than that do not order two solvers. Every timed run \
         with its median, minimum and maximum: `results/{}`.\n\n",
        first.machine,
        first.cores,
        first.git_rev,
        t.alone,
        t.runs,
        percent(t.median_spread, 0),
        t.timed,
        percent(t.max_spread, 0),
        records::TIMING_FILE
    )
}

/// The definitions: task set, tolerances, shifts, penalties, ranking.
fn definitions() -> String {
    format!(
        "**Definitions** (constants in `analysis::leaderboard`; the suite's choices, not tuned to \
         the results):\n\n\
         - *Task set.* The standard set is every task of the `{STANDARD_PAPER}` experiment whose \
         exact column completed. Solvers are grouped by label (the parameterised network); a \
         solver that did not run on every standard task is ranked separately, on the tasks it ran \
         on, against every solver that also ran on all of them, and normalised there.\n\
         - *Success rate*: share of the set's tasks where the run completed and its RMS \
         |x − x*|_inf after the settling time (over t ≥ 1 s, `score_rms_dx_after_1s`) is \
         at most {tol} rad/s — a thousandth of the arms' joint-velocity limits. After the \
         settling time, because a network starts from the zero state while x*(0) is not zero: \
         over the whole run the start-up transient alone can exceed the tolerance, which \
         measures the initial condition, not the tracking; how fast a network settles still \
         counts in the rank, through the whole-run RMS below. The RMS, not the max, so that a \
         brief excursion does not decide alone. VP-RNN-PF's equilibrium is the \
         exponential-penalty optimum, not x*: it sits ~1e-2 rad/s from x* by design, and the \
         tolerance counts that against it.\n\
         - *Correct rate* (qpbenchmark's): share of the set's tasks where the run's verdict is \
         right — it failed, or it completed within tolerance; a run that completes outside the \
         tolerance is the one incorrect outcome.\n\
         - *Shifted geometric mean* exp(mean ln(v + sh)) − sh over the set's tasks, divided by \
         the best solver's (× best; 1.00 = best). Shifts: RMS |x − x*| sh = {sdx} rad/s (a \
         hundredth of the tolerance: solvers both far inside it count as about equal); drift \
         error sh = {sdrift} (drift is printed with three significant digits); sim time sh = \
         {stime} s (qpbenchmark shifts its runtimes by 10 s; ours are 1 ms to 15 s \
         on 5–15 s tasks, and below ~10 ms a run's time is mostly setup).\n\
         - *Drift error*: the relative distance of the per-joint drift vectors, \
         |θ(T) − θ(0) − d*| / |d*|, d* the exact column's drift on the same task (from the \
         norms when the joint counts differ).\n\
         - *Sim time*: `sim_s`, the wall time of the simulation proper (arm, network, \
         integrator), without the scoring: the median of the run's repetitions timed alone \
         (**Times** above).\n\
         - *Penalties.* A failed run counts at {pdx} rad/s for |x − x*| (the order of the joint \
         velocity limits), {pdrift} for the drift error (a drift as far from the exact one as that \
         is from zero) and at the time limit, {limit} × the task's duration, for time \
         (qpbenchmark counts a failure at its time limit); every value is capped there, so no \
         completed run counts worse than a failure.\n\
         - *Percentiles* p50 and p95 over the set's tasks, linearly interpolated between ranks.\n\
         - *Rank*: success rate, then the normalised means of |x − x*|, drift error and time.\n\n",
        tol = sci(TOL_RMS_DX),
        sdx = sci(SHIFT_DX),
        sdrift = sci(SHIFT_DRIFT),
        stime = sci(SHIFT_TIME_S),
        pdx = sci(PENALTY_DX),
        pdrift = sci(PENALTY_DRIFT),
        limit = TIME_LIMIT_FACTOR,
    )
}
