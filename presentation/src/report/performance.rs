//! Performance: what an instant and a run cost, from `results/dof-cost.csv` (written by
//! `reproduce cost`, see `reproduce::cost`) and from the per-run counts and times of
//! `results/runs.csv`:
//!
//! - per instant at the Jaco2's size (N = 6): each network evaluation against the exact
//!   solvers (the hot-started active set, Clarabel) and the dense KKT floor, median and p95;
//! - per accepted step and per RHS evaluation of the reproduction's own runs, by solver kind;
//! - the cost against the number of joints (figure `dof-cost__<scheme>.svg`) with the fitted
//!   growth exponents, and the whole runs on the n-link arms;
//! - the whole-run times against the papers' MATLAB times (the published compute times that
//!   [`super::cost`] maps), simulation and total, each run timed alone
//!   (`results/leaderboard-timing.csv`, [`records::Timings`]);
//! - the machine the DOF measurement ran on;
//! - the exact reference per recorded QP against its peer DAQP (`results/qp-replay.csv`).
//!
//! Every number is read from `results/`, and what is computed from them (ratios of medians,
//! per-step quotients, fits, crossovers, verdicts against the targets) is the report model's
//! (`analysis::report_model::performance`), built once per render: this module formats it. Without `dof-cost.csv` the section says
//! how to produce it and shows what `runs.csv` gives. The suite's measurements of itself (its
//! build, clock, phases, profiles and speed-up over earlier revisions) are not here: they are
//! the benches' (`benches/REPORT.md`).

use super::cost::{solver_label, timed_papers};
use super::markdown::{percent, sci, sci_opt, text, Table, MISSING};
use crate::figures::dof_cost::quantity_label;
use analysis::papers::Papers;
use analysis::performance::dof::RunCost;
use analysis::performance::instant::{JACO2_N, TARGET_EXACT_OVER_RHS};
use analysis::performance::replay::ReplayTarget;
use analysis::performance::whole_runs::{TARGET_SIMULATION_SPEEDUP, TARGET_TOTAL_SPEEDUP};
use analysis::report_model::performance::{Measured, Performance};
use records::dof_cost::{DofCostRow, Quantity};
use records::index::Runs;
use records::QpReplayRow;
use records::TIMING_REPETITIONS;

/// The `## Performance` section: the model's content `p`, with the measurements it was built
/// on (`measured`, empty where absent: the machine, the networks' names, the replay's
/// revision), the runs and papers (the solvers' and papers' names) and the figures.
pub fn section(
    p: &Performance,
    measured: Measured,
    runs: &Runs,
    papers: &Papers,
    figures: &[String],
) -> String {
    let Measured { dof, qp_replay } = measured;
    let mut out = String::from(
        "## Performance\n\nWhat an instant and a run cost: the networks' evaluations against \
         the exact solvers, against the number of joints, and the whole runs against the papers' \
         MATLAB times. Speed is measured here and in `cargo bench -p driftbench-benches`, never \
         asserted by a test.\n\n",
    );
    if dof.is_empty() {
        out.push_str(
            "`results/dof-cost.csv` is absent: `cargo run --release -p reproduce -- cost` \
             measures the per-instant costs and the cost against the number of joints (about a \
             minute on an idle machine) and re-renders this report. What `results/runs.csv` \
             gives follows.\n\n",
        );
    } else {
        out.push_str(&machine(dof));
        out.push_str(&per_instant(p));
    }
    out.push_str(&replay_table(p, qp_replay));
    out.push_str(&per_solver_kind(p));
    if !dof.is_empty() {
        out.push_str(&dof_curve(p, dof, figures));
        out.push_str(&dof_runs(p, dof));
    }
    out.push_str(&matlab(p, runs, papers));
    out
}

/// The machine and revision of the measurement.
fn machine(dof: &[DofCostRow]) -> String {
    let mut machines: Vec<String> = dof
        .iter()
        .map(|r| {
            format!(
                "{} ({} logical cores available) at revision `{}`",
                r.machine, r.cores, r.git_rev
            )
        })
        .collect();
    machines.dedup();
    format!(
        "**Machine.** `results/dof-cost.csv` was measured on {} by `reproduce cost`, one \
         case after the other on one thread (the CPU model and cores read from `/proc/cpuinfo` \
         and the process's available parallelism at measurement time). \
         Times are comparable within it, not across machines; the wall times of \
         `results/runs.csv` come from the run that wrote them, with runs in parallel on every \
         core.\n\n",
        machines.join("; ")
    )
}

/// Median and p95 of each per-call quantity at N = [`JACO2_N`], with ratios to the network RHS
/// and to the KKT floor, and the 7-variable target.
fn per_instant(p: &Performance) -> String {
    let mut out = format!(
        "### Per instant at N = {JACO2_N} (the Jaco2's size)\n\nOne call at states sampled from \
         an exact run of `nlink-{JACO2_N}` (`reproduce::cost`): the network's right-hand \
         side and Jacobian, the scheme's QP assembly, the exact optimum by the hot-started \
         active set (what the exact column and the scorer call) and by Clarabel (the reference \
         of record), and the dense KKT floor (one LU solve of the equality-constrained KKT \
         system of the same QP, size nx + n_eq). Medians and 95th percentiles in microseconds.\n\n"
    );
    let mut t = Table::new([
        "scheme",
        "QP (nx, n_eq, n_in)",
        "quantity",
        "median (us)",
        "p95 (us)",
        "median ÷ network RHS",
        "median ÷ KKT floor",
        "samples",
    ]);
    for s in &p.schemes {
        let scheme = s.scheme;
        for c in &s.per_instant {
            let r = c.row;
            let dims = match (r.nx, r.n_eq, r.n_in) {
                (Some(a), Some(b), Some(c)) => format!("{a}, {b}, {c}"),
                _ => MISSING.to_string(),
            };
            t.push([
                format!("{scheme} {}", r.scheme_name),
                dims,
                quantity_label(c.quantity, &r.network),
                sci_opt(r.median_us),
                sci_opt(r.p95_us),
                sci_opt(c.over_rhs),
                sci_opt(c.over_floor),
                r.samples.to_string(),
            ]);
        }
    }
    if t.is_empty() {
        out.push_str(&format!("No measurement at N = {JACO2_N}.\n\n"));
        return out;
    }
    out.push_str(&t.render());
    out.push('\n');
    // The target on the 7-variable QPs: jia2019's at N = 6 (nx = N + 1).
    for s in &p.schemes {
        let scheme = s.scheme;
        if let Some(e) = &s.exact_over_rhs {
            out.push_str(&format!(
                "On the 7-variable QP ({scheme} {}) the hot-started active set takes {} \
                 times one {} RHS evaluation: the target of at most {} is {}.\n\n",
                e.active_set.scheme_name,
                sci(e.ratio),
                e.rhs.network,
                TARGET_EXACT_OVER_RHS,
                if e.met {
                    "met"
                } else {
                    "not met (the gap is the ratio above)"
                }
            ));
        }
    }
    out
}

/// `### The exact reference per tick against DAQP` (`results/qp-replay.csv`,
/// [`records::QpReplayRow`]): per task, the suite's active set and DAQP, warm and cold, on the
/// same recorded QPs, and how far their answers are apart; then the target's verdict from the
/// ratios. Every text read is escaped.
fn replay_table(p: &Performance, rows: &[QpReplayRow]) -> String {
    let mut out = String::from("### The exact reference per tick against DAQP\n\n");
    let Some(first) = rows.first() else {
        out.push_str(&format!(
            "`results/{}` is absent: `benches/qp_replay/replay.sh` records the QPs along runs \
             and replays them to the suite's active set and to DAQP.\n\n",
            records::QP_REPLAY_FILE
        ));
        return out;
    };
    out.push_str(&format!(
        "The same {} consecutive QPs of each task, recorded through the Python package along a \
         run (one per distinct instant), replayed {} times to the suite's active set (timed in \
         Rust, every answer certified) and to DAQP (installed from PyPI by the bench script \
         only, timed by its own C timers, its primal tolerance tightened to 1e-12). Warm starts \
         each solve from the previous QP's working set, cold from nothing; microseconds per \
         solve, the mean over the QPs of each QP's median, revision `{}` \
         (`benches/qp_replay/replay.sh`).\n\n",
        first.qps,
        first.repeats,
        text(&first.git_rev)
    ));
    let mut t = Table::new([
        "task",
        "QP (n, equalities, inequalities, bounds)",
        "solver",
        "warm (us)",
        "cold (us)",
        "warm ÷ DAQP",
        "cold ÷ DAQP",
        "max |x - x_other|",
    ]);
    for line in &p.replay {
        let r = line.row;
        t.push([
            text(&r.task),
            format!("{}, {}, {}, {}", r.nx, r.n_eq, r.n_in, r.n_bounds),
            text(&r.solver),
            sci_opt(line.warm_us),
            sci_opt(line.cold_us),
            sci_opt(line.warm_over_daqp),
            sci_opt(line.cold_over_daqp),
            sci(r.max_dx_vs_other),
        ]);
    }
    out.push_str(&t.render());
    out.push('\n');
    if let Some(target) = &p.replay_target {
        out.push_str(&replay_verdict(target));
    }
    out
}

/// The replay's target: the suite at or below DAQP warm and cold, its ratios to DAQP over the
/// tasks (where the hot solve's time goes is the benches' sampling profile,
/// `benches/REPORT.md`).
fn replay_verdict(target: &ReplayTarget) -> String {
    let ((wl, wh), (cl, ch)) = (target.warm, target.cold);
    format!(
        "The target, the suite at or below DAQP warm and cold with its answer still \
         certified, is {}: the suite takes {:.2}-{:.2} times DAQP's time warm and \
         {:.2}-{:.2} times cold.\n\n",
        if target.met { "met" } else { "not met" },
        wl,
        wh,
        cl,
        ch
    )
}

/// Per accepted step and per RHS evaluation in the completed runs of `runs.csv`, by solver
/// kind.
fn per_solver_kind(p: &Performance) -> String {
    let mut out = String::from(
        "### Per step in the reproduction's runs\n\nFrom `results/runs.csv`, every completed run \
         by solver kind: the whole run's wall time (`wall_s`: simulation and observation, \
         scoring included) per accepted step, the simulation's (`sim_s`: arm, solver, \
         integrator) per RHS evaluation, and the RHS evaluations a run takes. Medians and 95th \
         percentiles over the runs; the runs ran in parallel, so these include contention.\n\n",
    );
    let mut t = Table::new([
        "solver kind",
        "runs",
        "wall per step, median (us)",
        "p95 (us)",
        "simulation per RHS, median (us)",
        "p95 (us)",
        "RHS evals per run, median",
    ]);
    for k in &p.by_solver_kind {
        let (step, rhs, ev) = (k.wall_per_step_us, k.sim_per_rhs_us, k.rhs_evals);
        t.push([
            k.kind.to_string(),
            k.runs.to_string(),
            sci_opt(step.map(|s| s.median_us)),
            sci_opt(step.map(|s| s.p95_us)),
            sci_opt(rhs.map(|s| s.median_us)),
            sci_opt(rhs.map(|s| s.p95_us)),
            sci_opt(ev.map(|s| s.median_us)),
        ]);
    }
    if t.is_empty() {
        out.push_str("No completed run in `results/runs.csv`.\n\n");
    } else {
        out.push_str(&t.render());
        out.push('\n');
    }
    out
}

/// The figures of the cost against N, the fitted exponents per backend and the crossover of
/// the dense LUs.
fn dof_curve(p: &Performance, dof: &[DofCostRow], figures: &[String]) -> String {
    let largest = p.largest_n;
    let mut out = format!(
        "### Cost against the number of joints\n\nThe n-link arms `nlink-N` (a yaw joint and a \
         planar pitch chain, from their stated home pose) with the VLTCO scheme of \
         jia2019 (2.17) on a four-leaf clover (nx = N + 1, 2N inequality rows, bounds) and the \
         ZNN scheme of kong2019 (22) on a circle (nx = N, equalities only), through the engine's \
         one path (`reproduce::cost`: the joint count is a run-time value), timed \
         at states of an exact run, whole runs included: both schemes up to N = 30, the ZNN \
         scheme alone beyond, up to N = {largest}. \
         The dense LUs (the network \
         Jacobian's LU, the KKT floor) are timed on nalgebra and on faer. k is the growth \
         exponent of median cost ~ c N^k, fitted by least squares on log-log over the measured \
         N, per backend.\n\n"
    );
    for s in &p.schemes {
        let scheme = s.scheme;
        let name = crate::figures::dof_cost::file_name(scheme);
        if figures.contains(&name) {
            out.push_str(&format!("![{scheme}: cost against N](figures/{name})\n\n"));
        }
    }
    let mut t = Table::new([
        "scheme",
        "quantity",
        "backend",
        "k",
        "c (us)",
        "median at the smallest N (us)",
        "median at the largest N (us)",
    ]);
    let at = |point: Option<(usize, f64)>| {
        point.map_or(MISSING.to_string(), |(n, m)| {
            format!("{} (N = {n})", sci(m))
        })
    };
    for e in &p.fit_extents {
        let fit = e.fit;
        t.push([
            format!("{} {}", fit.scheme, fit.scheme_name),
            quantity_label(fit.quantity, &fit.network),
            fit.backend.clone(),
            fit.exponent
                .map_or(MISSING.to_string(), |k| format!("{k:.2}")),
            sci_opt(fit.factor_us),
            at(e.smallest),
            at(e.largest),
        ]);
    }
    if !t.is_empty() {
        out.push_str(&t.render());
        out.push('\n');
    }
    out.push_str(&crossovers(p, dof));
    out
}

/// Where faer's LU overtakes nalgebra's, per scheme and dense LU quantity (the model's), and
/// the size production code switches at.
fn crossovers(p: &Performance, dof: &[DofCostRow]) -> String {
    let mut t = Table::new([
        "scheme",
        "quantity",
        "faer faster from N",
        "LU size there",
        "nalgebra ÷ faer at the largest N",
    ]);
    for s in &p.schemes {
        let scheme = s.scheme;
        for &(quantity, c) in &s.crossovers {
            let network = dof
                .iter()
                .find(|r| r.scheme == scheme)
                .map_or("", |r| r.network.as_str());
            t.push([
                scheme.to_string(),
                quantity_label(quantity, network),
                c.n.map_or("never (up to the largest N)".to_string(), |n| n.to_string()),
                c.lu_size.map_or(MISSING.to_string(), |n| n.to_string()),
                format!("{} (N = {})", sci(c.speedup_at_largest), c.largest_n),
            ]);
        }
    }
    if t.is_empty() {
        return String::new();
    }
    format!(
        "**Crossover.** The smallest measured N from which faer's median is below nalgebra's at \
         that and every larger N, and the size of the matrix factorised there (the KKT system: \
         nx + n_eq; the LVI-PDNN Jacobian: nx + n_eq + n_in, N + 3 for the ZNN scheme and 3N + \
         4 for VLTCO). Near the crossover the two are within a few per cent and its N moves between \
         measurements. Production code (`solvers::dense_lu`) factorises dense, unstructured matrices \
         (VP-RNN-PF's W) on faer from a system size of `FAER_CROSSOVER` = {}, set from the \
         network Jacobian's LU above, and on nalgebra below; the KKT solve stays on nalgebra at \
         every size, since its zero and identity blocks are skipped by the in-place \
         elimination and faer's dense LU was slower there at every measured N.\n\n{}\n",
        settings::FAER_CROSSOVER,
        t.render()
    )
}

/// The whole runs of the DOF measurement, per N: time, steps and time per step.
fn dof_runs(p: &Performance, dof: &[DofCostRow]) -> String {
    let mut t = Table::new([
        "scheme",
        "N",
        "exact run, median (s)",
        "steps",
        "per step (us)",
        "network run, median (s)",
        "steps",
        "per step (us)",
    ]);
    for r in &p.runs_at_n {
        let [e0, e1, e2] = run_cells(r.exact);
        let [n0, n1, n2] = run_cells(r.network);
        t.push([
            r.scheme.to_string(),
            r.n.to_string(),
            e0,
            e1,
            e2,
            n0,
            n1,
            n2,
        ]);
    }
    if t.is_empty() {
        return String::new();
    }
    let network = dof
        .iter()
        .find(|r| r.quantity == Quantity::RunNetwork)
        .map_or("the network", |r| r.network.as_str());
    format!(
        "Whole runs on the n-link arms (`simulate` with the experiment files' defaults: the \
         exact column by Dormand-Prince at RelTol 1e-11, {network} by BDF at RelTol 1e-6 scored \
         at every accepted step), median of the repetitions, at every N. The Newton matrix of the BDF runs is factorised by \
         diffsol's nalgebra LU at every N; faer is not measured for whole runs.{}\n\n{}\n",
        large_n_sentence(p),
        t.render()
    )
}

/// The cells of one whole run of the DOF measurement: its median time (failed or not), steps
/// and time per step; [`MISSING`] where it was not measured.
fn run_cells(cost: Option<RunCost>) -> [String; 3] {
    match cost {
        None => [
            MISSING.to_string(),
            MISSING.to_string(),
            MISSING.to_string(),
        ],
        Some(c) => {
            let time = if c.failed {
                format!("{} (failed)", sci_opt(c.seconds))
            } else {
                sci_opt(c.seconds)
            };
            [
                time,
                c.steps.map_or(MISSING.to_string(), |s| s.to_string()),
                sci_opt(c.per_step_us),
            ]
        }
    }
}

/// The growth exponents of the whole runs over the large joint counts alone (N past the
/// two-scheme sweep, the model's): one sentence, empty when fewer than two such N were
/// measured.
fn large_n_sentence(p: &Performance) -> String {
    let parts: Vec<String> = p
        .large_n_fits
        .iter()
        .map(|f| {
            format!(
                "{} {}: k = {:.2} over {} N",
                f.scheme,
                quantity_label(f.quantity, f.network),
                f.fit.k,
                f.fit.points
            )
        })
        .collect();
    if parts.is_empty() {
        return String::new();
    }
    format!(
        " Fitted over N > {} alone (median ~ c N^k): {}.",
        p.largest_registry_n,
        parts.join("; ")
    )
}

/// The whole runs against the papers' MATLAB compute times: simulation (`sim_s`) and total
/// (`wall_s`, scoring and observation included), the medians of the runs timed alone
/// ([`records::Timings`]; the parallel reproduction's times for a run without), with the
/// smallest speedups.
fn matlab(p: &Performance, runs: &Runs, papers: &Papers) -> String {
    let mut t = Table::new([
        "experiment",
        "solver",
        "paper (MATLAB, s)",
        "ours: simulation (s)",
        "ours: total (s)",
        "spread of the repetitions (sim, total)",
        "paper ÷ simulation",
        "paper ÷ total",
    ]);
    let comparison = &p.matlab;
    for line in &comparison.lines {
        t.push([
            line.experiment.to_string(),
            solver_label(runs, line.experiment, line.solver),
            sci(line.paper_s),
            sci_opt(line.ours.map(|p| p.0)),
            sci_opt(line.ours.map(|p| p.1)),
            line.timing.map_or(MISSING.to_string(), |t| {
                format!(
                    "{}, {}",
                    percent(t.sim_spread(), 0),
                    percent(t.wall_spread(), 0)
                )
            }),
            sci_opt(line.paper_over_simulation),
            sci_opt(line.paper_over_total),
        ]);
    }
    if t.is_empty() {
        return String::new();
    }
    let mut out = format!(
        "### Whole runs against the papers' MATLAB times\n\nThe published compute times \
         ({}) beside our runs: the simulation alone (`sim_s`: arm, network, integrator) \
         and the whole run (`wall_s`: with the observation at every accepted step, i.e. metrics \
         and the exact solves that score the run). Each run was timed alone: run {TIMING_REPETITIONS} \
         times, one run at a time on one thread, after the parallel reproduction; the median is \
         shown, with the spread (max − min) / median of the repetitions ({} of the {} \
         runs so timed, `results/{}`; any other shows the parallel reproduction's time, where it \
         shared the cores). Different machines and languages: the speedups say how far apart, \
         not which implementation is better.\n\n",
        timed_papers(papers),
        comparison.alone,
        comparison.shown,
        records::TIMING_FILE
    );
    out.push_str(&t.render());
    out.push('\n');
    if let Some(smallest) = comparison.smallest {
        let verdict = |met: bool| if met { "met" } else { "not met" };
        out.push_str(&format!(
            "Smallest speedup over these runs: {} for the simulation (the target of {}x is {}) \
             and {} for the whole run (the target of {}x is {}).\n\n",
            sci(smallest.simulation),
            TARGET_SIMULATION_SPEEDUP,
            verdict(smallest.simulation_met),
            sci(smallest.total),
            TARGET_TOTAL_SPEEDUP,
            verdict(smallest.total_met),
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use records::Timings;
    use records::QP_REPLAY_SUITE;

    /// The section on the measurements `dof` and `qp_replay`, without runs, papers or
    /// timings, its model built as the report builds it.
    fn render(dof: &[DofCostRow], qp_replay: &[QpReplayRow], figures: &[String]) -> String {
        let (runs, papers, timings) =
            (Runs::new(Vec::new()), Papers::default(), Timings::default());
        let measured = Measured { dof, qp_replay };
        let model = Performance::build(measured, &runs, &timings, &papers);
        section(&model, measured, &runs, &papers, figures)
    }

    /// The fixture `dof-cost.csv` of scheme jia2019 ([`fixtures::dof_cost`]) with its fits.
    fn synthetic() -> Vec<DofCostRow> {
        let rows = fixtures::dof_cost("jia2019");
        let fits = analysis::fits::fit_rows(&rows);
        rows.into_iter().chain(fits).collect()
    }

    #[test]
    fn the_section_renders_from_a_synthetic_csv() {
        let dof = synthetic();
        let figures = vec!["dof-cost__jia2019.svg".to_string()];
        let replay = fixtures::replay_rows(
            "t / v",
            &[
                (QP_REPLAY_SUITE, "warm", 1.5),
                (QP_REPLAY_SUITE, "cold", 3.0),
                ("daqp 9", "warm", 1.0),
                ("daqp 9", "cold", 1.5),
            ],
            [7, 3, 12, 13],
            1e-15,
        );
        let md = render(&dof, &replay, &figures);
        assert!(md.starts_with("## Performance\n"), "{md}");
        assert!(
            md.contains("Test CPU (2 logical cores available) at revision `abc`"),
            "{md}"
        );
        // N = 6: the RHS median 36 us, the active set 108 us = 3x the RHS, 6x the floor.
        assert!(md.contains("| jia2019 VLTCO | 7, 3, 12 | LVI-PDNN RHS | 3.60e1 | 5.40e1 | 1.00e0 | 2.00e0 | 300 |"), "{md}");
        assert!(
            md.contains("| exact: active set, hot-started | 1.08e2 | 1.62e2 | 3.00e0 | 6.00e0 |"),
            "{md}"
        );
        assert!(
            md.contains(
                "takes 3.00e0 times one LVI-PDNN RHS evaluation: the target of at most 5 is met"
            ),
            "{md}"
        );
        assert!(
            md.contains("![jia2019: cost against N](figures/dof-cost__jia2019.svg)"),
            "{md}"
        );
        // Exact power laws: k = 2 and k = 1.
        assert!(md.contains("| jia2019 VLTCO | LVI-PDNN RHS | nalgebra | 2.00 | 1.00e0 | 9.00e0 (N = 3) | 1.44e2 (N = 12) |"), "{md}");
        assert!(
            md.contains("| jia2019 VLTCO | whole run, exact column | nalgebra | 1.00 |"),
            "{md}"
        );
        // The faer floor has its own fit and a crossover at N = 12 (KKT size 13 + 3), where
        // nalgebra's 72 us over faer's 36 us is 2.
        assert!(
            md.contains("| jia2019 VLTCO | dense KKT floor (one LU) | faer |"),
            "{md}"
        );
        assert!(
            md.contains("| jia2019 | dense KKT floor (one LU) | 12 | 16 | 2.00e0 (N = 12) |"),
            "{md}"
        );
        // Whole runs: 6e4 us = 6e-2 s over 1000 steps = 60 us a step.
        assert!(
            md.contains("| jia2019 | 6 | 6.00e-2 | 1000 | 6.00e1 | — | — | — |"),
            "{md}"
        );
        // The replay against DAQP: the suite's ratios, and the target's verdict.
        assert!(
            md.contains("| t / v | 7, 3, 12, 13 | active-set | 1.50e0 | 3.00e0 | 1.50e0 | 2.00e0 | 1.00e-15 |"),
            "{md}"
        );
        assert!(
            md.contains("is not met: the suite takes 1.50-1.50 times DAQP's time warm and 2.00-2.00 times cold"),
            "{md}"
        );
        // Every measurement is there, and none of the suite's measurements of itself.
        assert!(!md.contains("is absent"), "{md}");
        for own in [
            "newcomer's clock",
            "phases.csv",
            "speedup.csv",
            "profile.csv",
            "build",
        ] {
            assert!(!md.contains(own), "{own}: {md}");
        }
    }

    #[test]
    fn a_met_replay_target_is_said_without_the_profile() {
        // The suite at 0.5 and 0.8 of DAQP's time: met, and no gap for the profile to explain.
        let rows = fixtures::replay_rows(
            "t / v",
            &[
                (QP_REPLAY_SUITE, "warm", 0.5),
                (QP_REPLAY_SUITE, "cold", 0.8),
                ("daqp 9", "warm", 1.0),
                ("daqp 9", "cold", 1.0),
            ],
            [5, 3, 0, 0],
            1e-16,
        );
        let md = render(&[], &rows, &[]);
        assert!(
            md.contains(
                "is met: the suite takes 0.50-0.50 times DAQP's time warm and 0.80-0.80 times \
                 cold.\n"
            ),
            "{md}"
        );
        assert!(!md.contains("sampling profile"), "{md}");
    }

    #[test]
    fn without_the_csv_the_section_says_how_to_produce_it() {
        let md = render(&[], &[], &[]);
        assert!(md.contains("`results/dof-cost.csv` is absent"), "{md}");
        assert!(md.contains("-p reproduce -- cost`"), "{md}");
        assert!(md.contains("No completed run"), "{md}");
    }
}
