//! The report's figures, drawn from the committed results as SVG and, beside each SVG, as a PNG
//! of the same drawing (plotters; the PNG's text in the embedded DejaVu Sans, so no system font
//! is read), for viewers that do not render SVG.
//!
//! [`render_all`] reads `results/runs.csv` and every run's trace in `results/traces/` and writes
//! into `report/figures/` (each name below also as `.png`):
//!
//! - `<experiment>__<variant-slug>__<solver-slug>.svg`, one per run: (a) the desired and actual
//!   end-effector path in the x-y plane over the arm's motion (its skeleton at a dozen instants
//!   in light grey, the start pose darker; equal aspect), (b) the position error over time (log
//!   scale), (c) the joint angles relative to theta(0), so the drift is the value at t = T,
//!   (d) the joint velocities, and for acceleration-level runs (e) the joint accelerations and
//!   (f) the torques. A failed run is drawn up to its failure, with the time in the title.
//! - `<experiment>__overview.svg`, one per experiment: the position error of every run on one
//!   log-scale plot and, where neural runs exist, their distance to the exact QP optimum.
//! - A large sweep (an experiment of more than [`sweep::MAX_RUN_FIGURES`] runs) draws the two
//!   figures above for [`sweep::MAX_RUN_FIGURES`] of its runs only (its sample: its failures,
//!   its extremes, runs evenly spaced, `analysis::sweep_summary`), reads only their traces,
//!   and draws `<experiment>__sweep.svg` over all its runs from its summary, aggregated as
//!   `runs.csv` was read: the drift norm and the position error against each swept parameter,
//!   a heat map over two, the distribution ([`sweep`]). A merged 10^4-run sweep writes 26
//!   figures, not 10,001, and `runs.csv` is read row by row: what is held of a large sweep is
//!   its sample and its summary, whatever its number of runs.
//!
//! - `inference-<paper>-<table>__profiles.svg`, one per table of `results/inference.csv`: the
//!   setup inference's profiles (`profile`).
//! - `dof-cost__<scheme>.svg`, one per scheme of `results/dof-cost.csv`: the cost against the
//!   number of joints (`dof_cost`).
//! - `control__pareto__<task>.svg`, `control__stability.svg`, `control__cycles.svg`: the
//!   control experiments (`control`).
//!
//! Each figure is drawn once against a generic plotters backend (`layout::Body`) and emitted
//! both ways; figures are drawn in parallel. The output is a function of the inputs only (no
//! timestamps, sorted inputs, integer pixel coordinates), so unchanged results give
//! byte-identical figures.

mod arm;
pub(crate) mod control;
pub(crate) mod dof_cost;
mod layout;
mod legend;
mod overview;
mod panels;
pub(crate) mod profile;
mod run_figure;
mod scale;
mod style;
pub mod sweep;
mod trace;

use crate::error::{FigureError, ReportError};
use analysis::sweep_summary::{Held, SweepSummary};
use layout::Rendered;
use rayon::prelude::*;
use records::control::{ControlRow, CycleRow};
use records::dof_cost::DofCostRow;
use records::inference::InferenceRow;
use records::RunRow;
use spec::RunKey;
use spec::MAIN_H;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use store::{Removal, TrackedDir, TrackedError};
use trace::Trace;

/// The figures' directory inside `report/`.
pub const FIGURES: &str = "figures";

/// The run's file stem (the stem rule is [`spec::slug`]'s).
fn run_stem(run: &RunRow) -> String {
    run.key().stem()
}

/// The file name of the run figure of the run keyed `key` (`<experiment>__<variant>__<solver>.svg`):
/// the one naming rule of run figures, for the report's own and a scored trajectory's.
pub fn run_figure_name(key: &RunKey) -> String {
    format!("{}__{}.svg", key.experiment, key.stem())
}

/// The file name of the overview figure of `experiment` (`<experiment>__overview.svg`).
pub fn overview_name(experiment: &str) -> String {
    format!("{experiment}__overview.svg")
}

/// The run figure of the report for `run` with its trace file `trace`, as SVG text and PNG
/// bytes (for a run outside `results/`: a scored trajectory, `reproduce::score`).
pub fn run_figure(run: &RunRow, trace: &Path) -> Result<(String, Vec<u8>), FigureError> {
    let figure = run_figure::figure(run, &Trace::read(trace)?);
    Ok((figure.svg()?, figure.png()?))
}

/// The SVG name of the figure that file `name` belongs to, if `name` follows this module's
/// naming scheme (`<experiment>__<...>.svg` or its `.png`), i.e. is a file that [`render_all`]
/// owns and may replace or delete.
fn figure_of(name: &str) -> Option<String> {
    if !name.contains("__") {
        return None;
    }
    let stem = name
        .strip_suffix(".svg")
        .or_else(|| name.strip_suffix(".png"))?;
    Some(format!("{stem}.svg"))
}

/// One figure to draw, by kind, with what it is drawn from.
enum Job<'a> {
    Run(&'a RunRow, &'a Trace),
    Overview(&'a str, Vec<(&'a RunRow, &'a Trace)>),
    Sweep(&'a str, &'a SweepSummary),
    Profiles(&'a str, &'a str, Vec<&'a InferenceRow>),
    DofCost(&'a str, Vec<&'a DofCostRow>),
    Pareto(&'a str, f64, Vec<&'a ControlRow>),
    Stability(Vec<&'a ControlRow>),
    Cycles(&'a [CycleRow]),
}

impl Job<'_> {
    /// The figure as SVG and PNG.
    fn render(&self) -> Result<Rendered, FigureError> {
        match self {
            Job::Run(run, trace) => run_figure::figure(run, trace).render(),
            Job::Overview(experiment, members) => overview::figure(experiment, members).render(),
            Job::Sweep(experiment, summary) => sweep::figure(experiment, summary).render(),
            Job::Profiles(paper, table, rows) => profile::figure(paper, table, rows).render(),
            Job::DofCost(scheme, rows) => dof_cost::figure(scheme, rows).render(),
            Job::Pareto(task, h, rows) => control::pareto(task, *h, rows).render(),
            Job::Stability(rows) => control::stability(rows).render(),
            Job::Cycles(rows) => control::cycles(rows).render(),
        }
    }
}

/// Renders every figure of the results under `root` into `root/report/figures/`, each as an SVG
/// and a PNG with the same stem, and returns the SVGs' paths, sorted. Figures (SVG or PNG) in
/// that directory that no longer correspond to a run or an experiment are deleted if this
/// program wrote them and nobody edited them since (`report/manifest.toml`); a `report/` or
/// `report/figures/` that is a symbolic link leading out of the project is refused. Fails,
/// naming the file, on an unreadable `runs.csv`, a missing or malformed trace, or two runs whose
/// names give the same file name. The runs drawn are those the report holds, `held`
/// (`analysis::sweep_summary::Held`, read with `traced`). The runs `traced` says no to keep no
/// trace by choice (their sweep's `traces`): they get no figure of their own, and a large
/// sweep's figures of its own runs are chosen among those that keep one (its sweep figure
/// still has every row).
pub fn render_all(
    root: &Path,
    held: &Held,
    traced: &dyn Fn(&RunKey) -> bool,
) -> Result<Vec<PathBuf>, ReportError> {
    render(root, None, held, traced)
}

/// [`render_all`] for one paper only (`reproduce run --paper X`): the figures of `paper`'s runs
/// and experiments and its inference profiles; the figures of other papers, the cost and the
/// control figures are left as they are, and only figures of `paper`'s experiments are removed
/// as stale.
pub fn render_paper(
    root: &Path,
    paper: &str,
    held: &Held,
    traced: &dyn Fn(&RunKey) -> bool,
) -> Result<Vec<PathBuf>, ReportError> {
    render(root, Some(paper), held, traced)
}

/// Renders the figures of every paper, or of `paper` alone ([`render_paper`]).
fn render(
    root: &Path,
    paper: Option<&str>,
    held: &Held,
    traced: &dyn Fn(&RunKey) -> bool,
) -> Result<Vec<PathBuf>, ReportError> {
    let inputs = Inputs::read(&root.join(store::results_dir::DIR), paper, held, traced)?;
    let mut jobs = Jobs::default();
    jobs.add_runs(&inputs.runs, &inputs.traces, &inputs.sweeps)?;
    match paper {
        None => {
            jobs.add_profiles(&inputs.inference)?;
            jobs.add_dof_cost(&inputs.dof_cost)?;
            jobs.add_control(&inputs.control, &inputs.cycles)?;
        }
        Some(p) => {
            let own: Vec<InferenceRow> = inputs
                .inference
                .iter()
                .filter(|r| r.paper == p)
                .cloned()
                .collect();
            return write_rendered(root, jobs_with_profiles(jobs, &own)?, |name| {
                name.starts_with(&format!("inference-{p}-"))
                    || inputs
                        .runs
                        .iter()
                        .any(|r| name.starts_with(&format!("{}__", r.experiment)))
            });
        }
    }
    write_rendered(root, jobs, |_| true)
}

/// `jobs` with the inference profiles of `inference` added.
fn jobs_with_profiles<'a>(
    mut jobs: Jobs<'a>,
    inference: &'a [InferenceRow],
) -> Result<Jobs<'a>, ReportError> {
    jobs.add_profiles(inference)?;
    Ok(jobs)
}

/// Draws `jobs` in parallel and writes them ([`write_figures`]; `in_scope`: which stale
/// figures it may remove).
fn write_rendered(
    root: &Path,
    jobs: Jobs,
    in_scope: impl Fn(&str) -> bool,
) -> Result<Vec<PathBuf>, ReportError> {
    let figures: BTreeMap<String, Rendered> = jobs
        .0
        .into_par_iter()
        .map(|(name, job)| {
            job.render()
                .map(|figure| (name.clone(), figure))
                .map_err(|error| ReportError::Figure {
                    name: name.clone(),
                    error,
                })
        })
        .collect::<Result<_, _>>()?;
    write_figures(root, figures, in_scope)
}

/// What the figures are drawn from: the files of the results directory.
struct Inputs {
    /// The runs held of `runs.csv` (every run of a small experiment, a large sweep's sample:
    /// [`Held`]), sorted by run key.
    runs: Vec<RunRow>,
    /// The trace of each run that gets a figure of its own (every run held that keeps a
    /// trace), in the order of `runs`; `None` for the others (their traces are not read).
    traces: Vec<Option<Trace>>,
    /// Every large sweep's summary.
    sweeps: Vec<SweepSummary>,
    /// `inference.csv` (absent = empty).
    inference: Vec<InferenceRow>,
    /// `dof-cost.csv` (absent = empty).
    dof_cost: Vec<DofCostRow>,
    /// `control.csv` (absent = empty).
    control: Vec<ControlRow>,
    /// `cycles.csv` (absent = empty).
    cycles: Vec<CycleRow>,
}

impl Inputs {
    /// Reads the inputs from the results directory `results` and the runs it holds, `held`
    /// (of `paper`'s runs only, when given: the others' traces are not read; nor are the
    /// traces of a large sweep's runs outside its sample, nor those `traced` says no to, which keep
    /// none by choice).
    fn read(
        results: &Path,
        paper: Option<&str>,
        held: &Held,
        traced: &dyn Fn(&RunKey) -> bool,
    ) -> Result<Self, ReportError> {
        let in_paper = |p: &str| paper.is_none_or(|paper| p == paper);
        let runs: Vec<RunRow> = held
            .runs
            .all()
            .iter()
            .filter(|r| in_paper(&r.paper))
            .cloned()
            .collect();
        let sweeps: Vec<SweepSummary> = held
            .sweeps
            .iter()
            .filter(|s| in_paper(&s.paper))
            .cloned()
            .collect();
        let traces_dir = results.join(store::results_dir::TRACES);
        let traces = runs
            .iter()
            .map(|run| {
                traced(&run.key())
                    .then(|| {
                        Trace::read(
                            &traces_dir
                                .join(&run.experiment)
                                .join(format!("{}.csv", run_stem(run))),
                        )
                    })
                    .transpose()
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Inputs {
            runs,
            traces,
            sweeps,
            inference: store::table::read_if_present(&results.join(store::results_dir::INFERENCE))?,
            dof_cost: store::dof_cost::read(results)?,
            control: store::control::read(results, store::results_dir::CONTROL)?,
            cycles: store::control::read(results, store::results_dir::CYCLES)?,
        })
    }
}

/// The indices of `runs` by experiment, each list in the order of `runs`.
fn by_experiment(runs: &[RunRow]) -> BTreeMap<&str, Vec<usize>> {
    let mut out: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for (i, r) in runs.iter().enumerate() {
        out.entry(r.experiment.as_str()).or_default().push(i);
    }
    out
}

/// The figures to draw, by file name (each name once).
#[derive(Default)]
struct Jobs<'a>(BTreeMap<String, Job<'a>>);

impl<'a> Jobs<'a> {
    /// Adds the figure `job` as `name`; two figures of one name are an error.
    fn add(&mut self, name: String, job: Job<'a>) -> Result<(), ReportError> {
        match self.0.insert(name.clone(), job) {
            None => Ok(()),
            Some(_) => Err(ReportError::SameFigure(name)),
        }
    }

    /// A figure per run that has its trace read (each run of an experiment, or the sample of
    /// a large sweep), an overview per experiment of those runs, and a sweep figure per large
    /// sweep from its summary (`sweeps`).
    fn add_runs(
        &mut self,
        runs: &'a [RunRow],
        traces: &'a [Option<Trace>],
        sweeps: &'a [SweepSummary],
    ) -> Result<(), ReportError> {
        let mut experiments = by_experiment(runs);
        // A large sweep none of whose runs keeps a trace holds no run: its overview is empty.
        for s in sweeps {
            experiments.entry(s.experiment.as_str()).or_default();
        }
        for (experiment, indices) in experiments {
            let mut members = Vec::new();
            for &i in &indices {
                if let Some(trace) = &traces[i] {
                    let run = &runs[i];
                    self.add(run_figure_name(&run.key()), Job::Run(run, trace))?;
                    members.push((run, trace));
                }
            }
            self.add(
                overview_name(experiment),
                Job::Overview(experiment, members),
            )?;
        }
        for s in sweeps {
            self.add(
                sweep::sweep_name(&s.experiment),
                Job::Sweep(&s.experiment, s),
            )?;
        }
        Ok(())
    }

    /// The inference profiles of each published table that has any.
    fn add_profiles(&mut self, inference: &'a [InferenceRow]) -> Result<(), ReportError> {
        let mut tables: Vec<(&str, &str)> = inference
            .iter()
            .map(|r| (r.paper.as_str(), r.table.as_str()))
            .collect();
        tables.dedup();
        for (paper, table) in tables {
            let rows: Vec<_> = inference
                .iter()
                .filter(|r| r.paper == paper && r.table == table)
                .collect();
            if rows.iter().any(|r| r.profile().is_some()) {
                self.add(
                    profile::file_name(paper, table),
                    Job::Profiles(paper, table, rows),
                )?;
            }
        }
        Ok(())
    }

    /// The cost against the number of joints, one figure per scheme.
    fn add_dof_cost(&mut self, dof_rows: &'a [DofCostRow]) -> Result<(), ReportError> {
        let mut schemes: Vec<&str> = dof_rows.iter().map(|r| r.scheme.as_str()).collect();
        schemes.sort_unstable();
        schemes.dedup();
        for scheme in schemes {
            let rows: Vec<&DofCostRow> = dof_rows.iter().filter(|r| r.scheme == scheme).collect();
            self.add(dof_cost::file_name(scheme), Job::DofCost(scheme, rows))?;
        }
        Ok(())
    }

    /// The control experiments: a Pareto figure per task at the main period, the stability
    /// figure and the many-cycles figure (each where its rows exist).
    fn add_control(
        &mut self,
        control_rows: &'a [ControlRow],
        cycle_rows: &'a [CycleRow],
    ) -> Result<(), ReportError> {
        let mut tasks: Vec<&str> = control_rows.iter().map(|r| r.task.as_str()).collect();
        tasks.dedup();
        let h_main = MAIN_H * 1e3;
        for task in tasks {
            let rows: Vec<&ControlRow> = control_rows.iter().filter(|r| r.task == task).collect();
            self.add(control::pareto_name(task), Job::Pareto(task, h_main, rows))?;
        }
        if !control_rows.is_empty() {
            self.add(
                control::STABILITY_NAME.to_string(),
                Job::Stability(control_rows.iter().collect()),
            )?;
        }
        if !cycle_rows.is_empty() {
            self.add(control::CYCLES_NAME.to_string(), Job::Cycles(cycle_rows))?;
        }
        Ok(())
    }
}

/// Writes the rendered `figures` (SVG and PNG) into `root/report/figures/` and removes the
/// stale ones among those `in_scope` says were drawn (by SVG name): only those this program
/// wrote (listed in report/manifest.toml) and nobody edited since; anything else in the
/// directory is left alone. Returns the SVGs' paths, sorted.
fn write_figures(
    root: &Path,
    figures: BTreeMap<String, Rendered>,
    in_scope: impl Fn(&str) -> bool,
) -> Result<Vec<PathBuf>, ReportError> {
    let report = TrackedDir::open_within(root, "report")?;
    let rel = |name: &str| Path::new(FIGURES).join(name);
    for listed in report.listed(&format!("{FIGURES}/"))? {
        let name = listed.trim_start_matches(&format!("{FIGURES}/"));
        if figure_of(name).is_some_and(|svg| in_scope(&svg) && !figures.contains_key(&svg)) {
            if let Removal::Kept(why) = report.remove(&rel(name))? {
                eprintln!("note: {why}");
            }
        }
    }
    let write = |name: &str, bytes: &[u8]| report.write(&rel(name), bytes);
    let written = figures
        .into_iter()
        .map(|(name, figure)| {
            write(&name, figure.svg.as_bytes())?;
            let png = Path::new(&name).with_extension("png");
            write(&png.to_string_lossy(), &figure.png)?;
            Ok(report.path().join(rel(&name)))
        })
        .collect::<Result<Vec<PathBuf>, TrackedError>>()?;
    report.save()?;
    Ok(written)
}
