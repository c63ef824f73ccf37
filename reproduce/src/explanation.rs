//! The explanation layer of a run (the explain crate): tolerance ladders and drift attribution
//! of the selected runs of the papers' solvers, written to results/ (ladder.csv,
//! attribution.csv); alone (`reproduce explain`) it re-renders the report too.

use crate::error::ReproduceError;
use crate::options::ExplainOptions;
use crate::papers::load_papers;
use crate::project::Project;
use crate::report::{precheck_report, render_report, report_root};
use crate::results::{open_results, Described};
use spec::RunSpec;
use store::results_dir::ResultsDir;

/// The ladders and attributions of the selected runs `jobs` of the papers' solvers (`all`:
/// every run of the experiment files), written to `results` when given; how many runs were
/// explained.
pub fn explain(
    project: &Project,
    jobs: &[RunSpec],
    all: &[RunSpec],
    git_rev: &str,
    results: Option<&ResultsDir>,
) -> Result<usize, ReproduceError> {
    let papers = load_papers(project)?;
    let targets = explain::targets(jobs, &papers);
    if targets.is_empty() {
        return Ok(0);
    }
    eprintln!(
        "explaining {} runs of the papers' solvers (tolerance ladders, attribution)",
        targets.len()
    );
    let explained = explain::explain(&targets, all, true, git_rev);
    let Some(results) = results else {
        return Ok(targets.len());
    };
    explain::write(results.path(), &explained, all)?;
    results.save()?;
    eprintln!(
        "wrote {} ladder rows and {} attribution rows",
        explained.ladder.len(),
        explained.attribution.len()
    );
    Ok(targets.len())
}

/// The ladders and attributions of the selected runs `jobs` of the papers' solvers, derived
/// afresh and not written (`reproduce check` compares them with the committed ones).
pub fn fresh(
    project: &Project,
    jobs: &[RunSpec],
    all: &[RunSpec],
    git_rev: &str,
) -> Result<explain::Explained, ReproduceError> {
    let papers = load_papers(project)?;
    let targets = explain::targets(jobs, &papers);
    eprintln!(
        "re-explaining {} runs of the papers' solvers for the gate (tolerance ladders, attribution)",
        targets.len()
    );
    Ok(explain::explain(&targets, all, false, git_rev))
}

/// `reproduce explain`: the ladders and attributions of the selected runs `jobs` (`all`: every
/// run of the experiment files), written and followed by the report unless `--dry-run`.
pub fn explain_mode(
    project: &Project,
    options: &ExplainOptions,
    jobs: &[RunSpec],
    all: &Described,
    git_rev: &str,
) -> Result<(), ReproduceError> {
    if options.dry_run {
        return explain(project, jobs, all.jobs()?, git_rev, None).map(drop);
    }
    precheck_report(project, all)?;
    let results = open_results(project, git_rev, all)?;
    explain(project, jobs, all.jobs()?, git_rev, Some(&results))?;
    render_report(project, &report_root(project)?, &results, all)
}
