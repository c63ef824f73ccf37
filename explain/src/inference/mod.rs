//! Setup inference: the parameters the papers leave open, fitted to one published table.
//!
//! # The problem
//!
//! A published drift table gives, per column c and joint i, d_paper[c, i] = theta_i(T) -
//! theta_i(0). The papers do not publish the pose of their paths (in-plane rotation psi, the
//! tilt of the drawing plane about the base x and y axes, the start phase on the curve, the
//! size where the path's size is our assumption, the direction), nor which reading of the RMP
//! coefficient they integrated (jia2019 (2.11): tau Lambda as printed, tau Lambda / 2 by the
//! expansion with Lambda = 2 mu, or tau mu with the text's mu = 5). Beside the pose, the family
//! holds discrete hypotheses ([`family`]): the robot model (the declared one or a variant the
//! group's code documents) and how the drift was computed: the scheme's exact optimum at
//! tight tolerances (the exact column), or the paper's network integrated at MATLAB's default
//! tolerances (BDF, RelTol 1e-3 / AbsTol 1e-6) or at the stated ones. With a setup s the
//! drift is d(s)[c, i]; per column
//!
//! ```text
//!   r_c(s) = || d(s)[c, :] - d_paper[c, :] || / || d_paper[c, :] ||
//! ```
//!
//! and for the table, every column weighted alike whatever its magnitude,
//!
//! ```text
//!   r(s) = sqrt( mean_c r_c(s)^2 ).
//! ```
//!
//! The joint fit minimises r (one setup shared by all columns, as the papers imply); each
//! column fit minimises its r_c alone (its own setup). The search ([`search`]) is global
//! (a Halton sample of the continuous box for every discrete combination), then local
//! (Nelder-Mead from the best few of each objective), then profiles of the joint optimum
//! with the other continuous parameters re-fitted at each grid point. The optimum reported
//! for each objective is the minimum over every evaluation of every stage.
//!
//! One evaluation is one run per distinct run of the table (the exact runs are shared by the
//! columns of one scheme; the network runs are one per column), run in parallel. The exact
//! runs use RelTol 1e-6 / AbsTol 1e-8 ([`inference_integrator`], with the experiment's
//! method): the ladder shows their drift within ~1e-4 relative of the converged one, far below
//! the residuals a fit can reach. An inferred setup is always shown as "inferred setup (fitted
//! to the paper)" beside the declared one, never instead of it.

pub mod family;
pub mod search;

use crate::error::InferenceError;
use analysis::papers::{PaperValue, Papers};
use family::Family;
use rayon::prelude::*;
use records::inference::{
    EntryRow, InferenceRow, Integration, BEST, COLUMN_FIT, DECLARED, FAILED, HYPOTHESIS, LOCAL,
    PHASE, PROFILE, ROTATION, SCALE, TABLE, TILT_X, TILT_Y,
};
use records::RunRow;
use search::{Coordinate, Objective, Outcome, Point, Scores, Target};
use settings::{IntegratorSettings, Method};
use simulation::run_job;
use simulation::run_row;
use spec::RmpReading;
use spec::RunKey;
use spec::RunSpec;
use spec::SchemeSpec;
use spec::Scoring;
use spec::SolverChoice;
use std::f64::consts::PI;
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

/// One candidate setup of a table.
#[derive(Clone, Debug, PartialEq)]
pub struct Setup {
    /// In-plane rotation of every path of the table (rad).
    pub rotation: f64,
    /// Start phase on the closed curves (fraction of the cycle).
    pub phase: f64,
    /// Factor on every path's size (1 = the declared size).
    pub scale_factor: f64,
    /// Tilt of the drawing plane about the base x axis (rad).
    pub tilt_x: f64,
    /// Tilt of the drawing plane about the base y axis (rad).
    pub tilt_y: f64,
    /// Paths travelled backwards.
    pub reverse: bool,
    /// Reading of the RMP coefficient (schemes that have one).
    pub rmp: RmpReading,
    /// Robot model id.
    pub robot: String,
    /// How the drift is computed.
    pub integration: Integration,
}

impl std::fmt::Display for Setup {
    /// The setup in words, as the inference's messages print it.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "rotation {:.4} rad, start phase {:.4}, size x{:.4}, tilt {:.4} rad about x and {:.4} rad about y, {}, RMP reading {}, robot {}, {}",
            self.rotation,
            self.phase,
            self.scale_factor,
            self.tilt_x,
            self.tilt_y,
            if self.reverse { "paths reversed" } else { "paths forwards" },
            self.rmp.label(),
            self.robot,
            self.integration.describe()
        )
    }
}

impl Setup {
    /// The declared setup on `robot`: the experiment files as they are, exact column.
    pub fn declared(robot: &str) -> Self {
        Self {
            rotation: 0.0,
            phase: 0.0,
            scale_factor: 1.0,
            tilt_x: 0.0,
            tilt_y: 0.0,
            reverse: false,
            rmp: RmpReading::Printed,
            robot: robot.to_string(),
            integration: Integration::Exact,
        }
    }

    /// `job` under this setup (the job's own pose is the origin of rotation, tilt and phase).
    /// The integrator is the caller's business ([`TableProblem::jobs`]).
    pub fn apply(&self, job: &RunSpec) -> RunSpec {
        let mut j = job.clone();
        j.robot = self.robot.clone();
        j.path.rotation += self.rotation;
        j.path.tilt_x += self.tilt_x;
        j.path.tilt_y += self.tilt_y;
        j.path.phase = (j.path.phase + self.phase).rem_euclid(1.0);
        if self.scale_factor != 1.0 {
            let base = j
                .path
                .scale
                .or_else(|| spec::default_scale(&j.path.name))
                .unwrap_or(1.0);
            j.path.scale = Some(base * self.scale_factor);
        }
        j.path.reverse ^= self.reverse;
        match &mut j.scheme {
            SchemeSpec::Vltco { rmp, .. } | SchemeSpec::Cmco { rmp, .. } => *rmp = self.rmp,
            _ => {}
        }
        j
    }
}

/// One published column of a table.
#[derive(Clone, Debug)]
pub struct Column {
    pub name: String,
    /// Index into [`TableProblem::exact`].
    pub exact: usize,
    /// Index into [`TableProblem::network`].
    pub network: usize,
    /// Published per-joint drifts.
    pub paper: Vec<f64>,
}

/// One table's fit: its published per-joint drifts and the runs that give ours.
#[derive(Clone, Debug)]
pub struct TableProblem {
    pub paper: String,
    pub table: String,
    /// The distinct exact runs (one per scheme variant of the table).
    pub exact: Vec<RunSpec>,
    /// The paper's network run of each column (as the experiment integrates it).
    pub network: Vec<RunSpec>,
    pub columns: Vec<Column>,
    /// Fit the size factor (false where the paper prints the path's size).
    pub fit_scale: bool,
    /// Try the RMP readings (the table has a scheme with an RMP term).
    pub fit_rmp: bool,
}

impl TableProblem {
    /// The declared robot (every run of a table uses one).
    pub fn robot(&self) -> &str {
        &self.exact[0].robot
    }

    /// The runs of one evaluation under `setup`, and per column the index of its run.
    pub fn jobs(&self, setup: &Setup) -> (Vec<RunSpec>, Vec<usize>) {
        match setup.integration {
            Integration::Exact => (
                self.exact.iter().map(|j| setup.apply(j)).collect(),
                self.columns.iter().map(|c| c.exact).collect(),
            ),
            network => (
                self.network
                    .iter()
                    .map(|j| RunSpec {
                        integrator: network.integrator(&j.integrator),
                        ..setup.apply(j)
                    })
                    .collect(),
                self.columns.iter().map(|c| c.network).collect(),
            ),
        }
    }

    /// The runs of the mapped run `key` among `jobs`: the exact column of its task and the
    /// paper's solver.
    fn runs_of<'j>(
        &self,
        key: &RunKey,
        jobs: &'j [RunSpec],
    ) -> Result<(&'j RunSpec, &'j RunSpec), InferenceError> {
        let no_run = |what, experiment: &str, variant: &str| InferenceError::NoRun {
            paper: self.paper.clone(),
            table: self.table.clone(),
            what,
            experiment: experiment.to_string(),
            variant: variant.to_string(),
        };
        let exact = jobs
            .iter()
            .find(|j| j.task() == key.task() && j.solver == SolverChoice::Exact)
            .ok_or_else(|| no_run("exact", &key.experiment, &key.variant))?;
        let network = jobs
            .iter()
            .find(|j| j.key() == *key)
            .ok_or_else(|| no_run("network", &key.experiment, &key.variant))?;
        Ok((exact, network))
    }

    /// Adds the published column `name`, its per-joint drifts `paper`, and its runs: the paper's
    /// `network` as the experiment integrates it, and the `exact` column at the inference's
    /// tolerances ([`inference_integrator`]; one run shared by the columns of a scheme
    /// variant). A path whose size the paper prints keeps it; a scheme with an RMP term has its
    /// readings tried.
    fn add_column(&mut self, name: String, exact: &RunSpec, network: &RunSpec, paper: Vec<f64>) {
        let exact = RunSpec {
            integrator: IntegratorSettings {
                method: exact.integrator.method,
                ..inference_integrator()
            },
            scoring: Scoring::Off,
            ..exact.clone()
        };
        let index = match self.exact.iter().position(|r| r.key() == exact.key()) {
            Some(i) => i,
            None => {
                self.exact.push(exact.clone());
                self.exact.len() - 1
            }
        };
        self.network.push(RunSpec {
            scoring: Scoring::Off,
            ..network.clone()
        });
        if spec::scale_provenance(&exact.path.name) == Some("paper") {
            self.fit_scale = false;
        }
        if matches!(exact.scheme, SchemeSpec::Vltco { tau, .. } if tau > 0.0)
            || matches!(exact.scheme, SchemeSpec::Cmco { delta, .. } if delta > 0.0)
        {
            self.fit_rmp = true;
        }
        self.columns.push(Column {
            name,
            exact: index,
            network: self.network.len() - 1,
            paper,
        });
    }
}

/// The fit problem of one published table, from the paper values and the experiment files'
/// jobs (the exact column and the paper's solver of each mapped variant).
pub fn problem(
    paper: &str,
    table: &str,
    papers: &Papers,
    jobs: &[RunSpec],
) -> Result<TableProblem, InferenceError> {
    let mut p = TableProblem {
        paper: paper.to_string(),
        table: table.to_string(),
        exact: Vec::new(),
        network: Vec::new(),
        columns: Vec::new(),
        fit_scale: true,
        fit_rmp: false,
    };
    let mut seen: Vec<(&str, &str)> = Vec::new();
    for v in papers
        .values
        .iter()
        .filter(|v| v.paper == paper && v.table == table)
    {
        if seen.contains(&(&v.experiment, &v.column)) {
            continue;
        }
        seen.push((&v.experiment, &v.column));
        let Some(m) = papers.mapping_of(v) else {
            continue;
        };
        let drifts = published_drifts(&papers.values, v);
        if drifts.is_empty() {
            continue;
        }
        let (exact, network) = p.runs_of(&m.run, jobs)?;
        p.add_column(v.column.clone(), exact, network, drifts);
    }
    if p.columns.is_empty() {
        return Err(InferenceError::NoColumns {
            paper: paper.to_string(),
            table: table.to_string(),
        });
    }
    Ok(p)
}

/// The published per-joint drifts of `v`'s column among `values`: drift_1, drift_2, ... up to
/// the first joint the paper does not print.
fn published_drifts(values: &[PaperValue], v: &PaperValue) -> Vec<f64> {
    (1..=6)
        .map_while(|i| {
            values
                .iter()
                .find(|w| {
                    w.paper == v.paper
                        && w.table == v.table
                        && w.experiment == v.experiment
                        && w.column == v.column
                        && w.metric == format!("drift_{i}")
                })
                .map(|w| w.value)
        })
        .collect()
}

/// How one setup does on a table.
#[derive(Clone, Debug, PartialEq)]
pub struct Evaluation {
    pub setup: Setup,
    /// r(s) of the module doc ([`FAILED`] if a run failed).
    pub rel_residual: f64,
    /// r_c(s) per column ([`FAILED`] where the column's run failed).
    pub column_residuals: Vec<f64>,
    /// Per column, per joint: (ours, paper).
    pub entries: Vec<(String, Vec<(f64, f64)>)>,
    /// Why a run failed, if one did.
    pub failure: Option<String>,
}

impl Evaluation {
    /// The entries of objective `t` (every column, or one).
    fn pairs(&self, t: Target) -> Vec<(f64, f64)> {
        self.entries
            .iter()
            .enumerate()
            .filter(|(c, _)| t == Target::Joint || t == Target::Column(*c))
            .flat_map(|(_, (_, e))| e.iter().copied())
            .collect()
    }

    /// Largest |d - d_paper| / |d_paper| over the entries of objective `t`.
    pub fn max_entry_error(&self, t: Target) -> f64 {
        self.pairs(t)
            .iter()
            .map(|(o, p)| (o - p).abs() / p.abs().max(f64::MIN_POSITIVE))
            .fold(0.0, f64::max)
    }

    /// Entries of objective `t` whose sign agrees with the paper's, and their number.
    pub fn signs_matched(&self, t: Target) -> (usize, usize) {
        let all = self.pairs(t);
        let same = all.iter().filter(|(o, p)| o.signum() == p.signum()).count();
        (same, all.len())
    }
}

/// Runs the table's runs under `setup` (in parallel) and compares with the paper.
pub fn evaluate(p: &TableProblem, setup: Setup) -> Evaluation {
    let (jobs, index) = p.jobs(&setup);
    let rows: Vec<RunRow> = jobs.par_iter().map(|j| run_row(&run_job(j), "")).collect();
    let failure = rows
        .iter()
        .find(|r| !r.completed())
        .map(|r| format!("{} / {}: {}", r.experiment, r.variant, r.failure));
    let mut entries = Vec::new();
    let mut column_residuals = Vec::new();
    for (column, &i) in p.columns.iter().zip(&index) {
        let ours = &rows[i].drift;
        let pairs: Vec<(f64, f64)> = column
            .paper
            .iter()
            .enumerate()
            .map(|(k, &d)| (ours.get(k).copied().unwrap_or(f64::NAN), d))
            .collect();
        let num: f64 = pairs.iter().map(|(o, d)| (o - d).powi(2)).sum();
        let den: f64 = pairs.iter().map(|(_, d)| d * d).sum();
        let r = (num / den).sqrt();
        column_residuals.push(if rows[i].completed() && r.is_finite() {
            r
        } else {
            FAILED
        });
        entries.push((column.name.clone(), pairs));
    }
    let mean_square =
        column_residuals.iter().map(|r| r * r).sum::<f64>() / column_residuals.len().max(1) as f64;
    Evaluation {
        setup,
        rel_residual: if failure.is_some() {
            FAILED
        } else {
            mean_square.sqrt()
        },
        column_residuals,
        entries,
        failure,
    }
}

/// One discrete combination of the family.
#[derive(Clone, Debug, PartialEq)]
pub struct Discrete {
    pub robot: String,
    pub integration: Integration,
    pub reverse: bool,
    pub rmp: RmpReading,
}

/// A table as the search sees it: the discrete combinations of the family and its box.
pub struct TableObjective<'a> {
    pub problem: &'a TableProblem,
    pub combos: Vec<Discrete>,
    pub coordinates: Vec<Coordinate>,
}

impl<'a> TableObjective<'a> {
    /// The family's combinations (the declared one first) and box on `problem`.
    pub fn new(problem: &'a TableProblem, family: &Family) -> Self {
        let mut robots = vec![problem.robot().to_string()];
        robots.extend(family.variants_of(problem.robot()).iter().cloned());
        let mut integrations = vec![Integration::Exact];
        integrations.extend(family.network.iter().copied());
        let directions: &[bool] = if family.direction {
            &[false, true]
        } else {
            &[false]
        };
        let readings: &[RmpReading] = if family.rmp_readings && problem.fit_rmp {
            &[
                RmpReading::Printed,
                RmpReading::Expansion,
                RmpReading::TextGain,
            ]
        } else {
            &[RmpReading::Printed]
        };
        let mut combos = Vec::new();
        for robot in &robots {
            for &integration in &integrations {
                for &reverse in directions {
                    for &rmp in readings {
                        combos.push(Discrete {
                            robot: robot.clone(),
                            integration,
                            reverse,
                            rmp,
                        });
                    }
                }
            }
        }
        let phase = problem
            .exact
            .iter()
            .all(|j| spec::phase_supported(&j.path.name));
        let mut coordinates = Vec::new();
        // Profile grids: every 45 degrees of rotation, every sixth of the cycle, seven sizes
        // (geometric) and seven tilts, 30 degrees apart.
        let mut add = |on: bool, name, lo, hi, periodic, grid| {
            if on {
                coordinates.push(Coordinate {
                    name,
                    lo,
                    hi,
                    periodic,
                    grid,
                });
            }
        };
        add(family.rotation, ROTATION, 0.0, 2.0 * PI, true, 8);
        add(family.phase && phase, PHASE, 0.0, 1.0, true, 6);
        // Sizes between a quarter and four times the declared one.
        let four = 4f64.ln();
        add(
            family.scale && problem.fit_scale,
            SCALE,
            -four,
            four,
            false,
            7,
        );
        add(family.tilt, TILT_X, -PI / 2.0, PI / 2.0, false, 7);
        add(family.tilt, TILT_Y, -PI / 2.0, PI / 2.0, false, 7);
        Self {
            problem,
            combos,
            coordinates,
        }
    }

    /// The setup of a search point.
    pub fn setup(&self, p: &Point) -> Setup {
        let d = &self.combos[p.combo];
        let mut s = Setup {
            reverse: d.reverse,
            rmp: d.rmp,
            integration: d.integration,
            ..Setup::declared(&d.robot)
        };
        for (c, &v) in self.coordinates.iter().zip(&p.x) {
            match c.name {
                ROTATION => s.rotation = v,
                PHASE => s.phase = v,
                SCALE => s.scale_factor = v.exp(),
                TILT_X => s.tilt_x = v,
                _ => s.tilt_y = v,
            }
        }
        s
    }
}

impl Objective for TableObjective<'_> {
    type Detail = Evaluation;

    fn combos(&self) -> usize {
        self.combos.len()
    }

    fn coordinates(&self) -> &[Coordinate] {
        &self.coordinates
    }

    fn columns(&self) -> usize {
        self.problem.columns.len()
    }

    fn declared(&self) -> Point {
        Point {
            combo: 0,
            x: vec![0.0; self.coordinates.len()],
        }
    }

    fn evaluate(&self, p: &Point) -> (Scores, Evaluation) {
        let e = evaluate(self.problem, self.setup(p));
        (
            Scores {
                joint: e.rel_residual,
                columns: e.column_residuals.clone(),
            },
            e,
        )
    }
}

/// Everything a fit finds.
#[derive(Clone, Debug)]
pub struct Fit {
    pub outcome: Outcome<Evaluation>,
    pub combos: Vec<Discrete>,
    pub coordinates: Vec<Coordinate>,
    pub wall_s: f64,
}

/// Fits one table with the family's search (see the module doc).
pub fn fit(p: &TableProblem, family: &Family) -> Fit {
    let started = Instant::now();
    let objective = TableObjective::new(p, family);
    let outcome = search::search(&objective, family.budget());
    Fit {
        outcome,
        combos: objective.combos,
        coordinates: objective.coordinates,
        wall_s: started.elapsed().as_secs_f64(),
    }
}

/// The rows of one fit.
pub fn rows(p: &TableProblem, f: &Fit) -> (Vec<InferenceRow>, Vec<EntryRow>) {
    let rows = FitRows::new(p, f);
    let mut out = rows.declared_and_best();
    out.extend(rows.hypotheses());
    out.extend(rows.local_optima());
    out.extend(rows.profiles());
    (out, rows.entries())
}

/// One fit as rows: what its rows share.
struct FitRows<'a> {
    problem: &'a TableProblem,
    fit: &'a Fit,
    /// The fit's search space, to read the setup of a point.
    objective: TableObjective<'a>,
    /// Every objective: the whole table, then each column.
    targets: Vec<Target>,
}

impl<'a> FitRows<'a> {
    fn new(problem: &'a TableProblem, fit: &'a Fit) -> Self {
        FitRows {
            problem,
            fit,
            objective: TableObjective {
                problem,
                combos: fit.combos.clone(),
                coordinates: fit.coordinates.clone(),
            },
            targets: std::iter::once(Target::Joint)
                .chain((0..problem.columns.len()).map(Target::Column))
                .collect(),
        }
    }

    /// The row of the setup at `point` of kind `kind` for objective `t`, with its scores `s`
    /// and, where evaluated in full, its evaluation `e` (entry errors and signs).
    fn row(
        &self,
        kind: &str,
        t: Target,
        point: &Point,
        s: &Scores,
        e: Option<&Evaluation>,
    ) -> InferenceRow {
        let p = self.problem;
        let setup = self.objective.setup(point);
        let signs = e.map(|e| e.signs_matched(t));
        InferenceRow {
            paper: p.paper.clone(),
            table: p.table.clone(),
            kind: kind.to_string(),
            objective: match t {
                Target::Joint => TABLE.to_string(),
                Target::Column(c) => p.columns[c].name.clone(),
            },
            robot: setup.robot.clone(),
            integration: setup.integration,
            rotation: setup.rotation,
            phase: setup.phase,
            scale_factor: setup.scale_factor,
            tilt_x: setup.tilt_x,
            tilt_y: setup.tilt_y,
            reverse: setup.reverse,
            rmp: setup.rmp,
            rel_residual: s.get(t),
            table_residual: s.joint,
            column_residuals: s
                .columns
                .iter()
                .map(|r| r.to_string())
                .collect::<Vec<_>>()
                .join(";"),
            max_entry_error: e.map(|e| e.max_entry_error(t)),
            signs_matched: signs.map(|s| s.0),
            entries: signs.map(|s| s.1),
            evaluations: 0,
            wall_s: 0.0,
        }
    }

    /// The declared setup for every objective, then the best setup for every objective (the
    /// whole table's with the search's evaluations and wall time).
    fn declared_and_best(&self) -> Vec<InferenceRow> {
        let outcome = &self.fit.outcome;
        let d = &outcome.declared;
        let mut out = Vec::new();
        for &t in &self.targets {
            out.push(self.row(DECLARED, t, &d.point, &d.scores, Some(&d.detail)));
        }
        for &t in &self.targets {
            let b = outcome.best(t);
            let mut r = self.row(BEST, t, &b.point, &b.scores, Some(&b.detail));
            if t == Target::Joint {
                r.evaluations = outcome.evaluations;
                r.wall_s = self.fit.wall_s;
            }
            out.push(r);
        }
        out
    }

    /// The best of each hypothesis (robot x integration), every objective.
    fn hypotheses(&self) -> Vec<InferenceRow> {
        let combos = &self.fit.combos;
        let mut hypotheses: Vec<(&str, Integration)> = Vec::new();
        for c in combos {
            if !hypotheses.contains(&(c.robot.as_str(), c.integration)) {
                hypotheses.push((c.robot.as_str(), c.integration));
            }
        }
        let mut out = Vec::new();
        for (robot, integration) in &hypotheses {
            for &t in &self.targets {
                let of =
                    |k: usize| combos[k].robot == *robot && combos[k].integration == *integration;
                if let Some(b) = self.fit.outcome.best_where(t, of) {
                    out.push(self.row(HYPOTHESIS, t, &b.point, &b.scores, Some(&b.detail)));
                }
            }
        }
        out
    }

    /// The local optima of the Nelder-Mead starts.
    fn local_optima(&self) -> Vec<InferenceRow> {
        self.fit
            .outcome
            .local
            .iter()
            .map(|l| self.row(LOCAL, l.target, &l.point, &l.scores, None))
            .collect()
    }

    /// The points of the joint optimum's profiles, each profile's kind naming its coordinate.
    fn profiles(&self) -> Vec<InferenceRow> {
        let mut out = Vec::new();
        for profile in &self.fit.outcome.profiles {
            let name = self.fit.coordinates[profile.coordinate].name;
            let kind = format!(
                "{PROFILE} ({}): {name}",
                if profile.refitted {
                    "re-fitted"
                } else {
                    "slice"
                }
            );
            for q in &profile.points {
                out.push(self.row(&kind, Target::Joint, &q.point, &q.scores, None));
            }
        }
        out
    }

    /// The per-joint entries, ours beside the paper's: of the declared setup and of the whole
    /// table's best, every column; of each column's own best, that column.
    fn entries(&self) -> Vec<EntryRow> {
        let outcome = &self.fit.outcome;
        let mut entries = Vec::new();
        self.push_entries(&mut entries, DECLARED, &outcome.declared.detail, None);
        self.push_entries(
            &mut entries,
            BEST,
            &outcome.best(Target::Joint).detail,
            None,
        );
        for c in 0..self.problem.columns.len() {
            let best = &outcome.best(Target::Column(c)).detail;
            self.push_entries(&mut entries, COLUMN_FIT, best, Some(c));
        }
        entries
    }

    /// Pushes onto `entries` the entries of `e` labelled `label`: of every column, or of the
    /// column `only`.
    fn push_entries(
        &self,
        entries: &mut Vec<EntryRow>,
        label: &str,
        e: &Evaluation,
        only: Option<usize>,
    ) {
        for (c, (column, pairs)) in e.entries.iter().enumerate() {
            if only.is_some_and(|o| o != c) {
                continue;
            }
            for (k, (o, d)) in pairs.iter().enumerate() {
                entries.push(EntryRow {
                    paper: self.problem.paper.clone(),
                    table: self.problem.table.clone(),
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
}
