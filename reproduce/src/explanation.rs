//! The explanation layer of a run (the explain crate): tolerance ladders and drift attribution
//! of the selected runs of the papers' solvers, written to results/ (ladder.csv,
//! attribution.csv); alone (`reproduce explain`) it re-renders the report too.

use crate::cli::Cli;
use crate::error::ReproduceError;
use crate::report::{render_report, report_root};
use catalog::experiment::Job;
use records::results_dir::ResultsDir;

/// The papers as data (`papers/` under the project root).
pub fn load_papers(cli: &Cli) -> Result<records::papers::Papers, ReproduceError> {
    Ok(records::papers::Papers::load(
        &cli.project_root.join("papers"),
    )?)
}

/// The ladders and attributions of the selected runs `jobs` of the papers' solvers (`all`:
/// every run of the experiment files), written to `results` when given.
pub fn explain(
    cli: &Cli,
    jobs: &[Job],
    all: &[Job],
    git_rev: &str,
    results: Option<&ResultsDir>,
) -> Result<(), ReproduceError> {
    let papers = load_papers(cli)?;
    let targets = explain::targets(jobs, &papers);
    if targets.is_empty() {
        return Ok(());
    }
    eprintln!(
        "explaining {} runs of the papers' solvers (tolerance ladders, attribution)",
        targets.len()
    );
    let explained = explain::explain(&targets, all, true, git_rev);
    let Some(results) = results else {
        return Ok(());
    };
    explain::write(results.path(), &explained, all)?;
    results.save()?;
    eprintln!(
        "wrote {} ladder rows and {} attribution rows",
        explained.ladder.len(),
        explained.attribution.len()
    );
    if cli.explain_only {
        render_report(cli, &report_root(cli)?, results)?;
    }
    Ok(())
}
