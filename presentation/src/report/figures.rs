//! The figures written by the figure generator into `report/figures/`, linked from the
//! report under their experiment: `<experiment>__<variant>__<solver>.svg` and
//! `<experiment>__overview.svg`.

use catalog::run_key::RunKey;
use records::error::{IoAction, IoError};
use records::index::Runs;
use std::path::Path;

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

/// The figures of one experiment as Markdown: the overview shown inline, then every run's
/// figure linked (by its variant and solver ids, in file-name order), as a paragraph; only the
/// figures present in `figures` (the names in `report/figures/`); nothing when there are none.
pub fn links(figures: &[String], runs: &Runs, experiment: &str) -> String {
    let present = |name: &String| figures.contains(name);
    let mut out = String::new();
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
