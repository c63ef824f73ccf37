//! The figures written by the figure generator into `report/figures/`, linked from the
//! report under their experiment: `<experiment>__<variant>__<solver>.svg` and
//! `<experiment>__overview.svg`.

use records::error::{IoAction, IoError};
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

/// The figures of one experiment as Markdown: the overview shown inline, then every figure
/// linked, as a paragraph; nothing when it has none.
pub fn links(figures: &[String], experiment: &str) -> String {
    let prefix = format!("{experiment}__");
    let mine: Vec<&String> = figures.iter().filter(|f| f.starts_with(&prefix)).collect();
    if mine.is_empty() {
        return String::new();
    }
    let mut out = String::new();
    if let Some(overview) = mine.iter().find(|f| f.ends_with("__overview.svg")) {
        out.push_str(&format!(
            "![{experiment}: overview](figures/{overview})\n\n"
        ));
    }
    let items: Vec<String> = mine
        .iter()
        .filter(|f| !f.ends_with("__overview.svg"))
        .map(|f| {
            format!(
                "[{}](figures/{f})",
                f.trim_start_matches(&prefix)
                    .trim_end_matches(".svg")
                    .replace("__", " / ")
            )
        })
        .collect();
    if !items.is_empty() {
        out.push_str(&format!(
            "Figures of `{experiment}` (variant / solver): {}\n\n",
            items.join(" · ")
        ));
    }
    out
}
