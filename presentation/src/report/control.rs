//! The report's sections "At a robot's control rate" and "Many cycles", from the control
//! experiments' result files (`results/control*.csv`, `results/cycles*.csv`, written by the
//! `control` crate; their noise floor: `control_noise`) and, for the networks as the papers
//! integrate them, `results/runs.csv`.
//! What is decided or computed from them (success, the leaderboard of the track, products per
//! millisecond) is [`analysis::control_track`]'s.

use super::control_noise;
use super::markdown::{sci, sci_opt, text, Table, MISSING};
use crate::figures::control::{pareto_name, CYCLES_NAME, STABILITY_NAME};
use analysis::control_claim::ACCURACY;
use analysis::report_model::Control;
use records::control::Verdict;
use records::control::{
    ClaimRow, ControlRow, ControlStatus, Family, NoiseRow, StabilityRow, TrendRow,
};
use std::path::Path;
use store::control::read;
use store::results_dir;
use store::ControlFileError;

/// The control experiments' results (each file empty when absent).
#[derive(Clone, Debug, Default)]
pub struct ControlResults {
    pub runs: Vec<ControlRow>,
    /// The noise floor of each of `runs` (`results/control-noise.csv`).
    pub noise: Vec<NoiseRow>,
    pub stability: Vec<StabilityRow>,
    pub claims: Vec<ClaimRow>,
    pub trends: Vec<TrendRow>,
}

impl ControlResults {
    /// Reads the files in `results`.
    pub fn load(results: &Path) -> Result<Self, ControlFileError> {
        Ok(ControlResults {
            runs: read(results, results_dir::CONTROL)?,
            noise: read(results, results_dir::CONTROL_NOISE)?,
            stability: read(results, results_dir::CONTROL_STABILITY)?,
            claims: read(results, results_dir::CONTROL_CLAIM)?,
            trends: read(results, results_dir::CYCLES_TREND)?,
        })
    }
}

/// The numerical methods of the results, in their order (what this build ran: OSQP only
/// with the `osqp` feature).
fn numerical_methods(results: &ControlResults) -> String {
    let numerical: Vec<&ControlRow> = results
        .runs
        .iter()
        .filter(|r| r.family == Family::Numerical)
        .collect();
    let methods = records::table::distinct(&numerical, |r| r.method.as_str());
    if methods.is_empty() {
        return "no numerical method".to_string();
    }
    let methods: Vec<String> = methods.iter().map(|m| text(m)).collect();
    format!("{}: {}", methods.len(), methods.join(", "))
}

/// An inline figure if it was rendered.
fn figure(figures: &[String], name: &str, alt: &str) -> String {
    if figures.iter().any(|f| f == name) {
        format!("![{alt}](figures/{name})\n\n")
    } else {
        String::new()
    }
}

/// "At a robot's control rate": the verdict per solver at 1 kHz, the efficiency claim, the
/// stability limits, the leaderboard track, the rounding noise and the figures. Empty without
/// results.
pub fn section(
    results: &ControlResults,
    claim: Verdict,
    model: &Control,
    figures: &[String],
) -> String {
    if results.runs.is_empty() {
        return String::new();
    }
    let h = model.main_h_ms;
    let mut out = String::from("## At a robot's control rate\n\n");
    out.push_str(&format!(
        "A robot runs its redundancy resolution as a discrete loop. Here every scheme of the \
         standard task set is run at a fixed control period h = {h} ms (1 kHz): at each tick the \
         scheme's QP is built at the arm's sampled state, the solver computes the joint command, \
         the command is held over the tick and the arm is integrated exactly between ticks (a \
         held joint velocity or acceleration has a closed-form motion). The networks are stepped \
         as a controller would step them: forward Euler of their dynamics, one step per tick, \
         the QP held; the zeroing networks also in the Taylor-type discrete-time ZNN form \
         (Zhang et al., J. Comput. Appl. Math. 2015). The numerical methods run to their \
         tolerance at every tick, each started from the previous tick's answer where it can be; \
         these results have {}. The LVI methods are those of robio2018 (22)-(27) as printed \
         (94LVI and E47, zhong2021 refs. [26] and [27]), each to |e(y)|_inf <= 1e-10; the active set \
         is hot-started. OSQP (warm-started, eps 1e-7, polished) joins them only in a build \
         with the `osqp` feature (`cargo run --release -p reproduce --features osqp`, which \
         needs CMake). Every tick is scored against the certified exact optimum of its QP. \
         |x - x*| is that of the joint command, relative to max(1, |x*|); drift is \
         |theta(T) - theta0|. Latencies are wall-clock per tick on the machine of the run \
         (under whatever load it had: compare within a table, not across machines); the work \
         columns count products with the LVI matrix M and do not depend on the machine. The \
         runs are independent and run in parallel, one per core, so each latency is measured \
         beside another run. This part of the reproduction adds about a minute on 2 cores, half \
         of it the rounding-noise probes below \
         (tasks: {}).\n\n",
        numerical_methods(results),
        task_list(results)
    ));

    out.push_str(&format!("### Verdict per solver at {h} ms\n\n"));
    out.push_str(&format!(
        "*fits* = the median whole tick within the period (the 99th percentiles and maxima are \
         those of a 2-core machine shared with other builds: preemptions of a few milliseconds \
         show for every method, even for 1 us solves, so they are reported, not judged); \
         *stable* = the command stayed finite and below 1e4; *accurate* = max |x - x*| after the \
         first second <= {}.\n\n",
        sci(ACCURACY)
    ));
    let mut t = Table::new([
        "task",
        "method",
        "fits",
        "stable",
        "accurate",
        "solve p50 / p99 / max (us)",
        "tick p50 / p99 (us)",
        "max |x - x*| after 1 s",
        "max tracking error (m)",
        "drift (rad)",
        "M-products per tick",
    ]);
    for v in &model.verdicts {
        let (r, yes) = (v.row, |b: bool| if b { "yes" } else { "no" }.to_string());
        t.push([
            r.task.clone(),
            r.method.clone(),
            yes(v.fits),
            if r.status == ControlStatus::Ok {
                "yes".to_string()
            } else {
                format!("{} at t = {}", r.status, sci_opt(r.stopped_at))
            },
            yes(v.success),
            format!(
                "{} / {} / {}",
                sci(r.solve_p50_us),
                sci(r.solve_p99_us),
                sci(r.solve_max_us)
            ),
            format!("{} / {}", sci(r.tick_p50_us), sci(r.tick_p99_us)),
            sci(r.max_dx_settled),
            sci(r.max_track_err),
            sci_opt(r.drift),
            sci_opt(r.products_mean),
        ]);
    }
    out.push_str(&t.render());
    out.push('\n');

    out.push_str(&claim_section(results, claim, model));
    out.push_str(&stability_section(results, model, figures));
    out.push_str(&leaderboard(model));
    out.push_str(&control_noise::section(&model.noise));

    out.push_str("### Latency against accuracy\n\n");
    let mut tasks: Vec<&str> = results.runs.iter().map(|r| r.task.as_str()).collect();
    tasks.dedup();
    for task in tasks {
        out.push_str(&figure(figures, &pareto_name(task), task));
    }
    out
}

/// The tasks, as a list.
fn task_list(results: &ControlResults) -> String {
    let mut tasks: Vec<String> = results
        .runs
        .iter()
        .map(|r| format!("`{}`", r.task))
        .collect();
    tasks.dedup();
    tasks.join(", ")
}

/// zhong2021's efficiency claim (its overall verdict `claim`), with its numbers.
fn claim_section(results: &ControlResults, claim: Verdict, model: &Control) -> String {
    let mut out = format!("### The efficiency claim: {}\n\n", claim.label());
    out.push_str(
        "zhong2021 §1: \"compared with numerical methods [26], [27], neural network methods can \
         process information in parallel and have higher computational efficiency\". [26] and \
         [27] are E47 and 94LVI, two of the six LVI methods of robio2018 (22)-(27). All of them and the \
         networks work on the LVI of the same QP (the one LVI-PDNN solves) and spend their time \
         in one operation, a product of the LVI matrix M with a vector, so the cost per tick is \
         counted in those products: the same on every machine and under any load, so the \
         verdict does not depend on either. A network needs at least ceil(h / s_max) Euler \
         steps per tick to be stable at all (s_max its stability limit, below); the LVI methods \
         are counted over the whole task, warm-started, to their tolerance (which meets the \
         accuracy asked for). The network is compared with the cheapest of the six that solves \
         the task at every tick (the table names it): as printed (robio2018 (22), (23)), E47 and 94LVI \
         fail at the first tick on some of these QPs (`report/deviations.md`), so the claim is \
         tested against the numerical family they belong to, at its cheapest. FAIL when the \
         network's lower bound exceeds that method's mean; PASS when the network's checked cost (twice the lower bound, \
         run over the first 20 ticks) is below it and meets the accuracy. Latencies beside them \
         are for the record only.\n\n",
    );
    let mut t = Table::new([
        "task",
        "network",
        "s_max (s)",
        "steps per tick needed",
        "network products per tick (lower bound)",
        "check: max |x - x*| (p50 us per tick)",
        "numerical",
        "its products per tick, mean (max)",
        "its max |x - x*| (p50 us per tick)",
        "network ÷ numerical",
        "verdict",
    ]);
    for c in &results.claims {
        t.push([
            c.task.clone(),
            c.network.clone(),
            sci(c.euler_limit_s),
            c.steps_needed.to_string(),
            sci(c.network_products),
            format!("{} ({})", sci(c.check_max_dx), sci(c.check_solve_p50_us)),
            c.numerical.clone(),
            format!(
                "{} ({})",
                sci(c.numerical_products_mean),
                c.numerical_products_max
            ),
            format!(
                "{} ({})",
                sci(c.numerical_max_dx),
                sci(c.numerical_solve_p50_us)
            ),
            sci(c.cost_ratio),
            c.verdict.label().to_string(),
        ]);
    }
    out.push_str(&t.render());
    out.push('\n');
    out.push_str(&papers_integration(model));
    out
}

/// The networks as the papers integrate them (a stiff variable-step solver, `results/runs.csv`):
/// right-hand sides per millisecond of the task, in products with M.
fn papers_integration(model: &Control) -> String {
    let mut t = Table::new([
        "run (as the papers integrate it)",
        "RHS evaluations",
        "Jacobians",
        "duration (s)",
        "products with M per ms (RHS only)",
        "max |x - x*| (score)",
    ]);
    for &(c, r, products) in &model.as_integrated {
        t.push([
            format!("{} / {} / {}", c.experiment, r.variant, r.solver),
            r.rhs_evals.to_string(),
            r.jac_evals.to_string(),
            sci(r.duration),
            sci(products),
            sci_opt(r.score_max_dx),
        ]);
    }
    if model.as_integrated.is_empty() {
        return String::new();
    }
    format!(
        "The same networks as the papers integrate them (BDF with the network's analytic \
         Jacobian, RelTol 1e-6): their right-hand sides cost the products below per millisecond \
         of motion, fewer than E47's per tick, plus the Jacobians and their LU factorisations. \
         Two things keep this from rescuing the claim: the accuracy is not the one asked for \
         (the score column, |x - x*| at the accepted steps, is 1e-5 to 4e-3, against E47's ~1e-9), and \
         an implicit integrator that factorises the network's Jacobian and iterates Newton on it \
         is itself a numerical method (a Newton method on the piecewise-linear LVI), not a \
         network relaxing in parallel: the efficiency is the integrator's.\n\n{}\n",
        t.render()
    )
}

/// The networks' Euler stability limits beside their gains, and the stability figure.
fn stability_section(results: &ControlResults, model: &Control, figures: &[String]) -> String {
    let mut out = String::from(
        "### Stability limits\n\n\
         s_max is the largest forward-Euler step at which the network contracts, from the \
         spectrum of its Jacobian (|1 + s lambda| <= 1 for every eigenvalue), the smallest over \
         states sampled along the task (the network's start and the exact optimum every 250 \
         ticks). gain x s_max is what the papers' gain allows; the sweep column is the largest \
         control period (0.1 to 10 ms, one step per tick) at which the network did not diverge. \
         A network whose nonlinearity saturates (the finite-time network's sign-power, the \
         power-sigmoid) may chatter without diverging beyond its linear limit: its accuracy, in \
         the table above, says what that is worth.\n\n",
    );
    let mut t = Table::new([
        "task",
        "network",
        "gain",
        "s_max (s)",
        "gain x s_max",
        "steps per 1 ms tick",
        "largest period without divergence (ms)",
    ]);
    for (s, steps) in results.stability.iter().zip(&model.steps_per_tick) {
        t.push([
            s.task.clone(),
            s.network.clone(),
            format!("{} = {}", s.gain_name, sci(s.gain)),
            sci_opt(s.euler_limit_s),
            sci_opt(s.gain_x_limit),
            steps
                .map(|n| n.to_string())
                .unwrap_or_else(|| MISSING.to_string()),
            s.largest_stable_h_ms
                .map(sci)
                .unwrap_or_else(|| "diverged at every period".to_string()),
        ]);
    }
    out.push_str(&t.render());
    out.push('\n');
    out.push_str(&figure(figures, STABILITY_NAME, "stability against h"));
    out
}

/// The control-rate leaderboard track: per method, successes at the main period over the
/// tasks it ran, and its worst tick latency p99.
fn leaderboard(model: &Control) -> String {
    let h = model.main_h_ms;
    let mut t = Table::new([
        "method",
        "success",
        "worst median tick (us)",
        "worst tick p99 (us)",
    ]);
    for r in &model.track {
        t.push([
            r.method.to_string(),
            format!("{} / {}", r.successes, r.runs),
            sci(r.worst_median_us),
            sci(r.worst_p99_us),
        ]);
    }
    format!(
        "### Leaderboard: control rate\n\nSuccess = stable and within {} of the exact optimum \
         after the first second at h = {h} ms; ranked by successes, then by the worst median \
         tick over the tasks (the p99 beside it carries the shared machine's preemptions).\n\n{}\n",
        sci(ACCURACY),
        t.render()
    )
}

/// "Many cycles": each run's trend over K cycles and under the rounding-noise probe (the classes
/// it changes: `model`'s), and the figure.
pub fn cycles_section(results: &ControlResults, model: &Control, figures: &[String]) -> String {
    if results.trends.is_empty() {
        return String::new();
    }
    let mut out = String::from("## Many cycles\n\n");
    out.push_str(
        "The papers claim repetitive motion from one cycle. Here each task's path is repeated K \
         times back to back, at the control period (the exact optimum and every network form \
         that was stable at that period) and in continuous time (the exact column as the papers \
         integrate it: Dormand-Prince 5(4) at RelTol 1e-11, the drift read at each c T), and the \
         drift |theta(cT) - theta0| is recorded after \
         every cycle c. A run is a *limit cycle* when the last cycle moved the arm's end pose by \
         less than 1e-9 rad or 1e-3 of the first cycle's drift, *accumulating* when the line \
         fitted through the second half of the cycles rises by at least 10 % of the final drift \
         over that half (the rate is its slope), *bounded* otherwise. A network that diverges \
         before the end is listed with the cycles it completed.\n\n",
    );
    let mut t = Table::new([
        "task",
        "method",
        "period",
        "status",
        "cycles",
        "drift after cycle 1 (rad)",
        "after the last (rad)",
        "rate (rad/cycle)",
        "trend",
        "trend under the probe",
    ]);
    for r in &results.trends {
        t.push([
            r.task.clone(),
            r.method.clone(),
            r.h_ms
                .map(|h| format!("{h} ms"))
                .unwrap_or_else(|| "continuous".to_string()),
            r.failure.clone().unwrap_or_else(|| r.status.to_string()),
            r.cycles.to_string(),
            sci_opt(r.drift_first),
            sci_opt(r.drift_last),
            sci_opt(r.rate),
            r.class
                .map_or_else(|| MISSING.to_string(), |c| c.label().to_string()),
            control_noise::class_under_noise(r),
        ]);
    }
    out.push_str(&t.render());
    out.push('\n');
    out.push_str(&control_noise::trend_changes(model));
    out.push_str(&figure(figures, CYCLES_NAME, "drift against cycle"));
    out
}
