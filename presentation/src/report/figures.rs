//! The figures written by the figure generator into `report/figures/`, linked from the
//! report under their experiment: `<experiment>__<variant>__<solver>.svg`,
//! `<experiment>__overview.svg` and, for a large sweep, `<experiment>__sweep.svg` with a table
//! of its extremes and failures (`crate::figures::sweep`).

use super::markdown::{sci, sci_opt, text, Table};
use analysis::sweep_summary::{SweepSummary, SKETCH_BINS};
use records::index::Runs;
use spec::RunKey;
use std::path::Path;
use store::{IoAction, IoError};

/// The `.svg` file names in `dir`, sorted; none when the folder does not exist.
pub fn list(dir: &Path) -> Result<Vec<String>, IoError> {
    if !dir.is_dir() {
        return Ok(Vec::new());
    }
    let mut names = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(IoError::at(dir, IoAction::List))? {
        let name = entry
            .map_err(IoError::at(dir, IoAction::List))?
            .file_name()
            .to_string_lossy()
            .into_owned();
        if name.ends_with(".svg") {
            names.push(name);
        }
    }
    names.sort();
    Ok(names)
}

/// The figures of one experiment as Markdown: the overview shown inline, a large sweep's
/// figure and its table of extremes and failures (`sweep_section`), then every run's figure
/// linked (by its variant and solver ids, in file-name order), as a paragraph; only the
/// figures present in `figures` (the names in `report/figures/`); nothing when there are none.
/// `summaries`: every large sweep's summary (the report model's).
pub fn links(
    figures: &[String],
    runs: &Runs,
    experiment: &str,
    summaries: &[SweepSummary],
) -> String {
    let present = |name: &String| figures.contains(name);
    let mut out = String::new();
    let sweep = crate::figures::sweep::sweep_name(experiment);
    let summary = summaries.iter().find(|s| s.experiment == experiment);
    if let (true, Some(summary)) = (present(&sweep), summary) {
        out.push_str(&sweep_section(summary, experiment, &sweep));
    }
    let overview = crate::figures::overview_name(experiment);
    if present(&overview) {
        out.push_str(&format!(
            "![{experiment}: overview](figures/{overview})\n\n"
        ));
    }
    let mut named: Vec<(String, RunKey)> = runs
        .of_experiment(experiment)
        .map(|r| (crate::figures::run_figure_name(&r.key()), r.key()))
        .filter(|(name, _)| present(name))
        .collect();
    named.sort();
    named.dedup();
    let items: Vec<String> = named
        .iter()
        .map(|(name, key)| format!("[{} / {}](figures/{name})", key.variant, key.solver))
        .collect();
    if !items.is_empty() {
        out.push_str(&format!(
            "Figures of `{experiment}` (variant / solver): {}\n\n",
            items.join(" · ")
        ));
    }
    out
}

/// A large sweep's section: its figure over the parameters inline, then a table of its
/// extremes and of its first failures (`s`, [`analysis::sweep_summary`]), and what the
/// per-run figures show.
fn sweep_section(s: &SweepSummary, experiment: &str, figure: &str) -> String {
    use crate::figures::sweep::{MAX_RUN_FIGURES, MAX_VALUES};
    let mut t = Table::new([
        "",
        "run (variant / solver)",
        "drift norm (failed: when)",
        "max position error (failed: why)",
    ]);
    for (extreme, r) in s.extremes() {
        t.push([
            extreme.name().to_string(),
            format!("{} / {}", text(&r.variant), text(&r.solver)),
            sci_opt(r.drift_norm),
            sci_opt(r.max_pos_err),
        ]);
    }
    for r in &s.failures {
        t.push([
            "failed".to_string(),
            format!("{} / {}", text(&r.variant), text(&r.solver)),
            r.failed_at.map_or("failed".to_string(), |t| {
                format!("failed at t = {}", sci(t))
            }),
            text(&r.failure),
        ]);
    }
    format!(
        "![{experiment}: the sweep over its parameters](figures/{figure})\n\n{} runs, {} failed{}. A sweep of more than {MAX_RUN_FIGURES} runs draws a figure of its own (and the overview) for {MAX_RUN_FIGURES} of its runs only: its failures, its extremes and runs evenly spaced in key order. The sweep figure is drawn from aggregates of every run: per value of a parameter (or per interval of its range, where it takes more than {MAX_VALUES} values) the smallest, median and largest drift norm and position error, the heat map's median per cell and the distribution; each median is read from a histogram of {SKETCH_BINS} bins of log10 over the sweep's range of the quantity, so it lies within half a bin of the exact median.\n\n{}\n",
        s.runs,
        s.failed,
        if s.failed > s.failures.len() {
            format!(" (the first {} listed)", s.failures.len())
        } else {
            String::new()
        },
        t.render()
    )
}
