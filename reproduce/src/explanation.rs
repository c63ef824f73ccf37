//! The explanation layer of a run (the explain crate): tolerance ladders and drift attribution
//! of the selected runs of the papers' solvers, written to results/ (ladder.csv,
//! attribution.csv); alone (`reproduce explain`) it re-renders the report too.

use crate::error::ReproduceError;
use crate::options::ExplainOptions;
use crate::project::Project;
use crate::report::{render_report, report_root};
use crate::results::{open_results, Described};
use crate::run::precheck_report;
use catalog::experiment::Job;
use records::results_dir::ResultsDir;

/// The papers as data (`papers/` under the project root). Their published numbers that
/// contradict the paper's own are warned on stderr, once per process, with file and line.
pub fn load_papers(project: &Project) -> Result<analysis::papers::Papers, ReproduceError> {
    static WARNED: std::sync::Once = std::sync::Once::new();
    let root = &project.root;
    let papers = analysis::papers::Papers::load(&root.join("papers"))?;
    WARNED.call_once(|| {
        for w in &papers.warnings {
            let file = w.file.strip_prefix(root).unwrap_or(&w.file);
            eprintln!("warning: {}:{}: {}", file.display(), w.line, w.message);
        }
    });
    Ok(papers)
}

/// The papers as data ([`load_papers`]), with what they name checked against every run of the
/// experiment files (`all`), before anything runs: a mapping that names no run of a defined
/// experiment, or a claim that selects none, is refused; what names an experiment the files do
/// not define is said on stderr, once per process ([`analysis::paper_runs::check_runs`]).
pub fn load_checked_papers(
    project: &Project,
    all: &Described,
) -> Result<analysis::papers::Papers, ReproduceError> {
    static NOTED: std::sync::Once = std::sync::Once::new();
    let papers = load_papers(project)?;
    let keys: Vec<_> = all.jobs().iter().map(Job::key).collect();
    let absent = analysis::paper_runs::check_runs(&papers, &project.root.join("papers"), &keys)?;
    NOTED.call_once(|| {
        if let Some(first) = absent.first() {
            let file = first
                .file
                .strip_prefix(&project.root)
                .unwrap_or(&first.file);
            let first = analysis::paper_runs::Absent {
                file: file.to_path_buf(),
                ..first.clone()
            };
            eprintln!(
                "note: {first}{}",
                match absent.len() {
                    1 => String::new(),
                    n => format!(" (and {} more such names)", n - 1),
                }
            );
        }
    });
    Ok(papers)
}

/// The ladders and attributions of the selected runs `jobs` of the papers' solvers (`all`:
/// every run of the experiment files), written to `results` when given; how many runs were
/// explained.
pub fn explain(
    project: &Project,
    jobs: &[Job],
    all: &[Job],
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

/// `reproduce explain`: the ladders and attributions of the selected runs `jobs` (`all`: every
/// run of the experiment files), written and followed by the report unless `--dry-run`.
pub fn explain_mode(
    project: &Project,
    options: &ExplainOptions,
    jobs: &[Job],
    all: &Described,
    git_rev: &str,
) -> Result<(), ReproduceError> {
    if options.dry_run {
        return explain(project, jobs, all.jobs(), git_rev, None).map(drop);
    }
    precheck_report(project, all)?;
    let results = open_results(project, git_rev, all)?;
    explain(project, jobs, all.jobs(), git_rev, Some(&results))?;
    render_report(project, &report_root(project)?, &results)
}
