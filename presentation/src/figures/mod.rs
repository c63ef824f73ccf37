//! The report's figures, drawn from the committed results as SVG (plotters, no font files).
//!
//! [`render_all`] reads `results/runs.csv` and every run's trace in `results/traces/` and writes
//! into `report/figures/`:
//!
//! - `<experiment>__<variant-slug>__<solver-slug>.svg`, one per run: (a) the desired and actual
//!   end-effector path in the x-y plane over the arm's motion (its skeleton at a dozen instants
//!   in light grey, the start pose darker; equal aspect), (b) the position error over time (log
//!   scale), (c) the joint angles relative to theta(0), so the drift is the value at t = T,
//!   (d) the joint velocities, and for acceleration-level runs (e) the joint accelerations and
//!   (f) the torques. A failed run is drawn up to its failure, with the time in the title.
//! - `<experiment>__overview.svg`, one per experiment: the position error of every run on one
//!   log-scale plot and, where neural runs exist, their distance to the exact QP optimum.
//!
//! - `inference-<paper>-<table>__profiles.svg`, one per table of `results/inference.csv`: the
//!   setup inference's profiles ([`profile`]).
//!
//! The output is a function of the inputs only (no timestamps, sorted inputs, integer pixel
//! coordinates), so unchanged results give byte-identical figures.

mod arm;
mod layout;
mod legend;
mod overview;
mod panels;
pub mod profile;
mod run_figure;
mod scale;
mod style;
mod trace;

use records::runs::{read_runs, write_atomic, RunRow};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use trace::Trace;

/// The run's file stem (see [`simulation::naming::run_stem`]).
fn run_stem(run: &RunRow) -> String {
    simulation::naming::run_stem(&run.variant, &run.solver)
}

/// Whether `name` follows this module's naming scheme (`<experiment>__<...>.svg`), i.e. is a
/// figure that [`render_all`] owns and may replace or delete.
fn is_figure_name(name: &str) -> bool {
    name.ends_with(".svg") && name.contains("__")
}

/// Renders every figure of the results under `root` into `root/report/figures/` and returns
/// the written paths, sorted. Figures in that directory that no longer correspond to a run or
/// an experiment are deleted. Fails, naming the file, on an unreadable `runs.csv`, a missing or
/// malformed trace, or two runs whose names give the same file name.
pub fn render_all(root: &Path) -> Result<Vec<PathBuf>, String> {
    let mut runs = read_runs(&root.join("results").join("runs.csv"))?;
    runs.sort_by_key(RunRow::key);
    let traces_dir = root.join("results").join("traces");
    let traces = runs
        .iter()
        .map(|run| {
            Trace::read(
                &traces_dir
                    .join(&run.experiment)
                    .join(format!("{}.csv", run_stem(run))),
            )
        })
        .collect::<Result<Vec<_>, _>>()?;

    let mut figures: BTreeMap<String, String> = BTreeMap::new();
    let mut add = |name: String, svg: String| match figures.insert(name.clone(), svg) {
        None => Ok(()),
        Some(_) => Err(format!(
            "two figures would be written to {name}: rename a variant or a solver"
        )),
    };
    let mut by_experiment: BTreeMap<&str, Vec<(&RunRow, &Trace)>> = BTreeMap::new();
    for (run, trace) in runs.iter().zip(&traces) {
        add(
            format!("{}__{}.svg", run.experiment, run_stem(run)),
            run_figure::render(run, trace)?,
        )?;
        by_experiment
            .entry(&run.experiment)
            .or_default()
            .push((run, trace));
    }
    for (experiment, members) in &by_experiment {
        add(
            format!("{experiment}__overview.svg"),
            overview::render(experiment, members)?,
        )?;
    }

    let inference: Vec<explain::inference::InferenceRow> =
        explain::read_csv(&root.join("results").join("inference.csv"))?;
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
        if rows.iter().any(|r| r.kind.starts_with("profile: ")) {
            add(
                profile::file_name(paper, table),
                profile::render(paper, table, &rows)?,
            )?;
        }
    }

    let out_dir = root.join("report").join("figures");
    std::fs::create_dir_all(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    let stale = std::fs::read_dir(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    for entry in stale {
        let path = entry
            .map_err(|e| format!("{}: {e}", out_dir.display()))?
            .path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default();
        if is_figure_name(name) && !figures.contains_key(name) {
            std::fs::remove_file(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        }
    }
    figures
        .into_iter()
        .map(|(name, svg)| {
            let path = out_dir.join(name);
            write_atomic(&path, svg.as_bytes()).map_err(|e| format!("{}: {e}", path.display()))?;
            Ok(path)
        })
        .collect()
}
