//! Setup inference: the parameters the papers leave open, fitted to one published table.
//!
//! # The problem
//!
//! A published drift table gives, per column c and joint i, d_paper[c, i] = theta_i(T) -
//! theta_i(0). The papers do not publish the pose of their paths (in-plane rotation psi, the
//! start phase on the curve, the size where docs/paths.md marks it "assumed", the direction) nor
//! which reading of the RMP coefficient they integrated (jia2019 (2.11): tau Lambda as printed,
//! tau Lambda / 2 by the expansion with Lambda = 2 mu, or tau mu with the text's mu = 5). With a
//! setup s the scheme's exact drift is d(s)[c, i] (the exact column: the scheme decides the
//! drift, the papers' solvers add < 1 % where they converge; see the attribution). We minimise
//!
//! ```text
//!   rel_residual(s) = || d(s) - d_paper ||_F / || d_paper ||_F
//! ```
//!
//! over the continuous parameters (psi, phase, log of the size factor) by Nelder-Mead (argmin)
//! from several starts, for every combination of the discrete ones (direction, RMP reading), all
//! columns of the table sharing one setup. One evaluation is one exact run per distinct scheme
//! of the table, run in parallel. A profile fixes one continuous parameter on a grid and
//! re-fits the others: a flat profile means the table does not determine that parameter.
//!
//! The exact runs here use RelTol 1e-6 / AbsTol 1e-8 ([`inference_integrator`], with the
//! experiment's method):
//! the ladder shows their drift within ~1e-4 relative of the converged one, far below the
//! residuals a fit can reach. An inferred setup is always shown as "inferred setup (fitted to
//! the paper)" beside the declared one, never instead of it.

use argmin::core::{CostFunction, Error as ArgminError, Executor, State};
use argmin::solver::neldermead::NelderMead;
use rayon::prelude::*;
use records::paper_values::{PaperValue, MAPPINGS};
use records::runs::RunRow;
use schemes::spec::{RmpReading, SchemeSpec};
use serde::{Deserialize, Serialize};
use simulation::experiment::{Job, SolverChoice};
use simulation::run::run_job;
use simulation::simulate::Scoring;
use solvers::ode::{IntegratorSettings, Method};
use std::f64::consts::PI;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// The exact column's tolerances during inference (see the module doc); the method stays the
/// experiment's (Dormand-Prince, BDF for kong2019's stiff finite-time scheme).
pub fn inference_integrator() -> IntegratorSettings {
    IntegratorSettings {
        method: Method::Dopri5,
        rtol: 1e-6,
        atol: 1e-8,
        max_steps: 200_000,
        max_step: None,
        ..IntegratorSettings::default()
    }
}

/// Penalty residual of a setup whose run fails (an unreachable pose, an infeasible QP); the
/// report prints such points as failed.
pub const FAILED: f64 = 10.0;

/// One candidate setup of a table.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Setup {
    /// In-plane rotation of every path of the table (rad).
    pub rotation: f64,
    /// Start phase on the closed curves (fraction of the cycle).
    pub phase: f64,
    /// Factor on every path's size (1 = the declared size).
    pub scale_factor: f64,
    /// Paths travelled backwards.
    pub reverse: bool,
    /// Reading of the RMP coefficient (schemes that have one).
    pub rmp: RmpReading,
}

impl Setup {
    /// The declared setup: the experiment files as they are.
    pub const DECLARED: Setup = Setup {
        rotation: 0.0,
        phase: 0.0,
        scale_factor: 1.0,
        reverse: false,
        rmp: RmpReading::Printed,
    };

    /// `job` under this setup (the job's own pose is the origin of rotation and phase).
    pub fn apply(&self, job: &Job) -> Job {
        let mut j = job.clone();
        j.path.rotation += self.rotation;
        j.path.phase = (j.path.phase + self.phase).rem_euclid(1.0);
        if self.scale_factor != 1.0 {
            let base = j
                .path
                .scale
                .or_else(|| schemes::paths::default_scale(&j.path.name))
                .unwrap_or(1.0);
            j.path.scale = Some(base * self.scale_factor);
        }
        j.path.reverse ^= self.reverse;
        match &mut j.scheme {
            SchemeSpec::Jia2019 { rmp, .. } | SchemeSpec::Zhong2021 { rmp, .. } => *rmp = self.rmp,
            _ => {}
        }
        j
    }
}

/// One table's fit: its published per-joint drifts and the exact runs that give ours.
#[derive(Clone, Debug)]
pub struct TableProblem {
    pub paper: String,
    pub table: String,
    /// The distinct exact runs (one per scheme variant of the table).
    pub runs: Vec<Job>,
    /// Published columns: (column name, index into `runs`, per-joint drifts).
    pub columns: Vec<(String, usize, Vec<f64>)>,
    /// Fit the size factor (false where the paper prints the path's size).
    pub fit_scale: bool,
    /// Try the RMP readings (the table has a scheme with an RMP term).
    pub fit_rmp: bool,
}

/// The tables [`problems`] can build: (paper, table).
pub fn table_ids(values: &[PaperValue]) -> Vec<(String, String)> {
    let mut ids: Vec<(String, String)> = values
        .iter()
        .filter(|v| v.table != "text" && v.metric.starts_with("drift_") && v.metric != "drift_norm")
        .map(|v| (v.paper.clone(), v.table.clone()))
        .collect();
    ids.dedup();
    ids
}

/// The fit problem of one published table, from the paper values and the experiment files'
/// jobs (exact columns of the mapped variants).
pub fn problem(
    paper: &str,
    table: &str,
    values: &[PaperValue],
    jobs: &[Job],
) -> Result<TableProblem, String> {
    let mut p = TableProblem {
        paper: paper.to_string(),
        table: table.to_string(),
        runs: Vec::new(),
        columns: Vec::new(),
        fit_scale: true,
        fit_rmp: false,
    };
    let mut seen: Vec<(&str, &str)> = Vec::new();
    for v in values
        .iter()
        .filter(|v| v.paper == paper && v.table == table)
    {
        if seen.contains(&(&v.experiment, &v.column)) {
            continue;
        }
        seen.push((&v.experiment, &v.column));
        let Some(m) = MAPPINGS.iter().find(|m| {
            m.paper == paper
                && m.published_experiment == v.experiment
                && m.published_column == v.column
        }) else {
            continue;
        };
        let drifts: Vec<f64> = (1..=6)
            .map_while(|i| {
                values
                    .iter()
                    .find(|w| {
                        w.paper == paper
                            && w.table == table
                            && w.experiment == v.experiment
                            && w.column == v.column
                            && w.metric == format!("drift_{i}")
                    })
                    .map(|w| w.value)
            })
            .collect();
        if drifts.is_empty() {
            continue;
        }
        let exact = jobs
            .iter()
            .find(|j| {
                j.experiment == m.experiment
                    && j.variant == m.variant
                    && j.solver == SolverChoice::Exact
            })
            .ok_or_else(|| {
                format!(
                    "{paper} {table}: no exact run of {} / {}",
                    m.experiment, m.variant
                )
            })?;
        let job = Job {
            integrator: IntegratorSettings {
                method: exact.integrator.method,
                ..inference_integrator()
            },
            scoring: Scoring::Off,
            ..exact.clone()
        };
        let index = match p.runs.iter().position(|r| r.key() == job.key()) {
            Some(i) => i,
            None => {
                p.runs.push(job.clone());
                p.runs.len() - 1
            }
        };
        if schemes::paths::scale_provenance(&job.path.name) == Some("paper") {
            p.fit_scale = false;
        }
        if matches!(job.scheme, SchemeSpec::Jia2019 { tau, .. } if tau > 0.0)
            || matches!(job.scheme, SchemeSpec::Zhong2021 { delta, .. } if delta > 0.0)
        {
            p.fit_rmp = true;
        }
        p.columns.push((v.column.clone(), index, drifts));
    }
    if p.columns.is_empty() {
        return Err(format!(
            "{paper} {table}: no published per-joint drifts map onto a run"
        ));
    }
    Ok(p)
}

/// How one setup does on a table.
#[derive(Clone, Debug, PartialEq)]
pub struct Evaluation {
    pub setup: Setup,
    pub rel_residual: f64,
    /// Per column, per joint: (ours, paper).
    pub entries: Vec<(String, Vec<(f64, f64)>)>,
    /// Why a run failed, if one did.
    pub failure: Option<String>,
}

impl Evaluation {
    /// Largest |d - d_paper| / |d_paper| over the entries.
    pub fn max_entry_error(&self) -> f64 {
        self.entries
            .iter()
            .flat_map(|(_, e)| e.iter())
            .map(|(o, p)| (o - p).abs() / p.abs().max(f64::MIN_POSITIVE))
            .fold(0.0, f64::max)
    }

    /// Entries whose sign agrees with the paper's, and their number.
    pub fn signs_matched(&self) -> (usize, usize) {
        let all: Vec<&(f64, f64)> = self.entries.iter().flat_map(|(_, e)| e.iter()).collect();
        let same = all.iter().filter(|(o, p)| o.signum() == p.signum()).count();
        (same, all.len())
    }
}

/// Runs the table's exact runs under `setup` (in parallel) and compares with the paper.
pub fn evaluate(p: &TableProblem, setup: Setup) -> Evaluation {
    let rows: Vec<RunRow> = p
        .runs
        .par_iter()
        .map(|j| RunRow::from_record(&run_job(&setup.apply(j)), ""))
        .collect();
    let failure = rows
        .iter()
        .find(|r| !r.completed())
        .map(|r| format!("{} / {}: {}", r.experiment, r.variant, r.failure));
    let mut num = 0.0;
    let mut den = 0.0;
    let mut entries = Vec::new();
    for (column, i, paper) in &p.columns {
        let ours = &rows[*i].drift;
        let pairs: Vec<(f64, f64)> = paper
            .iter()
            .enumerate()
            .map(|(k, &d)| (ours.get(k).copied().unwrap_or(f64::NAN), d))
            .collect();
        for (o, d) in &pairs {
            num += (o - d).powi(2);
            den += d * d;
        }
        entries.push((column.clone(), pairs));
    }
    let rel = (num / den).sqrt();
    Evaluation {
        setup,
        rel_residual: if failure.is_some() || !rel.is_finite() {
            FAILED
        } else {
            rel
        },
        entries,
        failure,
    }
}

/// Which continuous parameters are free, in the order of the Nelder-Mead vector.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Free {
    Rotation,
    Phase,
    LogScale,
}

impl Free {
    pub fn name(self) -> &'static str {
        match self {
            Free::Rotation => "rotation",
            Free::Phase => "phase",
            Free::LogScale => "scale_factor",
        }
    }

    /// Initial simplex step.
    fn step(self) -> f64 {
        match self {
            Free::Rotation => 0.3,
            Free::Phase => 0.15,
            Free::LogScale => 0.3,
        }
    }

    /// The profile grid (in the parameter's own units: rad, cycle fraction, factor).
    pub fn grid(self) -> Vec<f64> {
        match self {
            Free::Rotation => (0..8).map(|k| k as f64 * PI / 4.0).collect(),
            Free::Phase => (0..6).map(|k| k as f64 / 6.0).collect(),
            Free::LogScale => vec![0.5, 0.7, 1.0, 1.4, 2.0],
        }
    }

    fn get(self, s: &Setup) -> f64 {
        match self {
            Free::Rotation => s.rotation,
            Free::Phase => s.phase,
            Free::LogScale => s.scale_factor.ln(),
        }
    }

    fn set(self, s: &mut Setup, x: f64) {
        match self {
            Free::Rotation => s.rotation = x.rem_euclid(2.0 * PI),
            Free::Phase => s.phase = x.rem_euclid(1.0),
            // Sizes between a quarter and four times the declared one.
            Free::LogScale => s.scale_factor = x.clamp(-4f64.ln(), 4f64.ln()).exp(),
        }
    }
}

/// The free continuous parameters of a table.
pub fn free_parameters(p: &TableProblem) -> Vec<Free> {
    let mut f = vec![Free::Rotation];
    if p.runs
        .iter()
        .all(|j| schemes::paths::phase_supported(&j.path.name))
    {
        f.push(Free::Phase);
    }
    if p.fit_scale {
        f.push(Free::LogScale);
    }
    f
}

/// The cost function argmin minimises: the relative residual of the setup `base` with the
/// `free` parameters set from the vector.
struct Cost<'a> {
    problem: &'a TableProblem,
    base: Setup,
    free: &'a [Free],
    evaluations: &'a AtomicUsize,
}

impl Cost<'_> {
    fn setup(&self, x: &[f64]) -> Setup {
        let mut s = self.base;
        for (f, v) in self.free.iter().zip(x) {
            f.set(&mut s, *v);
        }
        s
    }
}

impl CostFunction for Cost<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, x: &Self::Param) -> Result<f64, ArgminError> {
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        Ok(evaluate(self.problem, self.setup(x)).rel_residual)
    }
}

/// Nelder-Mead over `free` from `start` (at most `iters` iterations).
fn nelder_mead(
    problem: &TableProblem,
    start: Setup,
    free: &[Free],
    iters: u64,
    evaluations: &AtomicUsize,
) -> Setup {
    if free.is_empty() {
        return start;
    }
    let x0: Vec<f64> = free.iter().map(|f| f.get(&start)).collect();
    let mut simplex = vec![x0.clone()];
    for (k, f) in free.iter().enumerate() {
        let mut x = x0.clone();
        x[k] += f.step();
        simplex.push(x);
    }
    let cost = Cost {
        problem,
        base: start,
        free,
        evaluations,
    };
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(1e-5)
        .expect("a non-negative tolerance");
    let best = Executor::new(cost, solver)
        .configure(|s| s.max_iters(iters))
        .run()
        .ok()
        .and_then(|r| r.state().get_best_param().cloned())
        .unwrap_or(x0);
    let mut s = start;
    for (f, v) in free.iter().zip(&best) {
        f.set(&mut s, *v);
    }
    s
}

/// Budget of one fit.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    /// Nelder-Mead iterations per start.
    pub iterations: u64,
    /// Nelder-Mead iterations per profile point.
    pub profile_iterations: u64,
    /// Compute the profiles.
    pub profiles: bool,
}

impl Default for Budget {
    fn default() -> Self {
        Self {
            iterations: 60,
            profile_iterations: 20,
            profiles: true,
        }
    }
}

/// Everything a fit finds.
#[derive(Clone, Debug)]
pub struct Fit {
    pub declared: Evaluation,
    /// The best setup of every start (discrete combination x start), best first.
    pub starts: Vec<Evaluation>,
    /// Per free parameter: (parameter, [(value, best residual with the others re-fitted)]).
    pub profiles: Vec<(Free, Vec<(f64, f64)>)>,
    pub evaluations: usize,
    pub wall_s: f64,
}

impl Fit {
    pub fn best(&self) -> &Evaluation {
        &self.starts[0]
    }
}

/// The starts: every discrete combination (direction x RMP reading) from four poses, a quarter
/// turn (and, where the phase is free, a quarter cycle) apart.
pub fn starts(p: &TableProblem) -> Vec<Setup> {
    let phase_free = free_parameters(p).contains(&Free::Phase);
    let readings: &[RmpReading] = if p.fit_rmp {
        &[
            RmpReading::Printed,
            RmpReading::Expansion,
            RmpReading::TextGain,
        ]
    } else {
        &[RmpReading::Printed]
    };
    let mut out = Vec::new();
    for &reverse in &[false, true] {
        for &rmp in readings {
            for k in 0..4 {
                let (rotation, phase) = (f64::from(k) * PI / 2.0, f64::from(k) / 4.0);
                out.push(Setup {
                    rotation,
                    phase: if phase_free { phase } else { 0.0 },
                    reverse,
                    rmp,
                    ..Setup::DECLARED
                });
            }
        }
    }
    out
}

/// Fits one table: the declared setup, multi-start Nelder-Mead, profiles of the best.
pub fn fit(p: &TableProblem, budget: Budget) -> Fit {
    let started = Instant::now();
    let evaluations = AtomicUsize::new(0);
    let free = free_parameters(p);
    let declared = evaluate(p, Setup::DECLARED);
    let mut results: Vec<Evaluation> = starts(p)
        .par_iter()
        .map(|s| {
            let best = nelder_mead(p, *s, &free, budget.iterations, &evaluations);
            evaluate(p, best)
        })
        .collect();
    results.sort_by(|a, b| a.rel_residual.total_cmp(&b.rel_residual));
    let best = results[0].setup;
    let profiles = if budget.profiles {
        free.iter()
            .map(|&f| {
                let others: Vec<Free> = free.iter().copied().filter(|g| *g != f).collect();
                let points = f
                    .grid()
                    .par_iter()
                    .map(|&v| {
                        let mut s = best;
                        f.set(&mut s, if f == Free::LogScale { v.ln() } else { v });
                        let s = nelder_mead(p, s, &others, budget.profile_iterations, &evaluations);
                        (v, evaluate(p, s).rel_residual)
                    })
                    .collect();
                (f, points)
            })
            .collect()
    } else {
        Vec::new()
    };
    Fit {
        declared,
        starts: results,
        profiles,
        evaluations: evaluations.load(Ordering::Relaxed) + 1,
        wall_s: started.elapsed().as_secs_f64(),
    }
}

/// One row of `results/inference.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct InferenceRow {
    pub paper: String,
    pub table: String,
    /// `declared`, `best fit`, `start`, or `profile: <parameter>`.
    pub kind: String,
    pub rotation: f64,
    pub phase: f64,
    pub scale_factor: f64,
    pub reverse: bool,
    pub rmp: String,
    pub rel_residual: f64,
    pub max_entry_error: Option<f64>,
    pub signs_matched: Option<usize>,
    pub entries: Option<usize>,
    pub evaluations: usize,
    pub wall_s: f64,
}

impl records::table::Row for InferenceRow {}

/// One entry of the declared and the best-fit setup, for `results/inference-entries.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EntryRow {
    pub paper: String,
    pub table: String,
    /// `declared` or `best fit`.
    pub setup: String,
    pub column: String,
    pub joint: usize,
    pub ours: f64,
    pub paper_value: f64,
    pub rel_error: f64,
    pub sign_matched: bool,
}

impl records::table::Row for EntryRow {}

/// The rows of one fit.
pub fn rows(p: &TableProblem, f: &Fit) -> (Vec<InferenceRow>, Vec<EntryRow>) {
    let row = |kind: &str, e: &Evaluation, evaluations: usize, wall_s: f64| {
        let (same, n) = e.signs_matched();
        InferenceRow {
            paper: p.paper.clone(),
            table: p.table.clone(),
            kind: kind.to_string(),
            rotation: e.setup.rotation,
            phase: e.setup.phase,
            scale_factor: e.setup.scale_factor,
            reverse: e.setup.reverse,
            rmp: e.setup.rmp.label().to_string(),
            rel_residual: e.rel_residual,
            max_entry_error: Some(e.max_entry_error()),
            signs_matched: Some(same),
            entries: Some(n),
            evaluations,
            wall_s,
        }
    };
    let mut out = vec![
        row("declared", &f.declared, 1, 0.0),
        row("best fit", f.best(), f.evaluations, f.wall_s),
    ];
    out.extend(f.starts.iter().skip(1).map(|e| row("start", e, 0, 0.0)));
    for (free, points) in &f.profiles {
        for (v, r) in points {
            let mut s = f.best().setup;
            free.set(&mut s, if *free == Free::LogScale { v.ln() } else { *v });
            out.push(InferenceRow {
                kind: format!("profile: {}", free.name()),
                rotation: s.rotation,
                phase: s.phase,
                scale_factor: s.scale_factor,
                rel_residual: *r,
                max_entry_error: None,
                signs_matched: None,
                entries: None,
                evaluations: 0,
                wall_s: 0.0,
                ..row("profile", f.best(), 0, 0.0)
            });
        }
    }
    let mut entries = Vec::new();
    for (label, e) in [("declared", &f.declared), ("best fit", f.best())] {
        for (column, pairs) in &e.entries {
            for (k, (o, d)) in pairs.iter().enumerate() {
                entries.push(EntryRow {
                    paper: p.paper.clone(),
                    table: p.table.clone(),
                    setup: label.to_string(),
                    column: column.clone(),
                    joint: k + 1,
                    ours: *o,
                    paper_value: *d,
                    rel_error: (o - d).abs() / d.abs().max(f64::MIN_POSITIVE),
                    sign_matched: o.signum() == d.signum(),
                });
            }
        }
    }
    (out, entries)
}
