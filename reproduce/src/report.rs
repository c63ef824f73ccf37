//! The report (presentation): rendered beside the results directory (`<root>/results` ->
//! `<root>/report`) after every mode that writes results, or alone (`reproduce report`) from
//! the stored results without running anything; what it needs is checked before anything runs
//! ([`precheck_report`]).

use crate::error::ReproduceError;
use crate::papers::load_checked_papers;
use crate::project::Project;
use crate::results::{experiment_files, open_results, Described};
use analysis::sweep_summary::Held;
use catalog::PaperFile;
use spec::RunKey;
use std::path::{Path, PathBuf};
use store::results_dir::ResultsDir;

/// `reproduce report`: re-renders report/ from the stored results. The experiment files are
/// loaded (and every run checked) once: to check the papers, to open the results, and for the
/// render (the runs that keep no trace, the task cards).
pub fn report_only(project: &Project, git_rev: &str) -> Result<(), ReproduceError> {
    let root = report_root(project)?;
    check_report_dir(&root)?;
    let files = experiment_files(project)?;
    let all = Described::new(&files);
    load_checked_papers(project, &all)?;
    let results = open_results(project, git_rev, &all)?;
    render_report(project, &root, &results, &all)
}

/// The report is rendered beside the results directory: `<root>/results` -> `<root>/report`.
pub fn report_root(project: &Project) -> Result<PathBuf, ReproduceError> {
    match project.results_dir.file_name() {
        Some(name) if name == store::results_dir::DIR => Ok(project
            .results_dir
            .parent()
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("."))),
        _ => Err(ReproduceError::ResultsNotNamedResults(
            project.results_dir.clone(),
        )),
    }
}

/// Checks, before anything runs, that `root/report` and its figures directory lie inside the
/// project (no symbolic link leading elsewhere) and that the report can be written there.
pub fn check_report_dir(root: &Path) -> Result<(), ReproduceError> {
    let report = store::TrackedDir::open_within(root, "report")?;
    report.resolve(Path::new(presentation::figures::FIGURES))?;
    Ok(store::check_writable(report.path())?)
}

/// Before anything runs in a mode that renders the report: papers/ loads and names only runs
/// of the experiment files `all` (the report reads it after the runs, so a malformed paper is
/// refused now), then the report's directory lies inside the project and can be written
/// (created only then: a run refused for its papers leaves no empty `report/`). A results
/// directory not named `results` gets no report, which is said.
pub fn precheck_report(project: &Project, all: &Described) -> Result<(), ReproduceError> {
    match report_root(project) {
        Ok(root) => {
            load_checked_papers(project, all)?;
            check_report_dir(&root)?;
        }
        Err(why) => eprintln!(
            "note: results go to {}, but {why}",
            project.results_dir.display()
        ),
    }
    Ok(())
}

/// Figures first (the report links them), then the report's pages ([`render_pages`]), both
/// from the runs the report holds ([`held_runs`]: `runs.csv` read twice, row by row, once for
/// both); `all`: the experiment files (the runs that keep no trace, the task cards).
pub fn render_report(
    project: &Project,
    root: &Path,
    results: &ResultsDir,
    all: &Described,
) -> Result<(), ReproduceError> {
    let keys = all.keys()?;
    let traced = |key: &RunKey| keys.traced(key);
    let held = held_runs(results, &traced)?;
    render_figures(root, None, &held, &traced)?;
    keys.check()?;
    render_pages(project, root, results, all.files(), held)
}

/// The runs the report holds (`analysis::sweep_summary::Held`): every run of an experiment of
/// at most 24 runs, a large sweep's sample among the runs that keep a trace (`traced`)
/// and its summary; `results/runs.csv` is read twice, row by row. The figures and the pages
/// are drawn from the same runs.
pub fn held_runs(
    results: &ResultsDir,
    traced: &dyn Fn(&RunKey) -> bool,
) -> Result<Held, ReproduceError> {
    Ok(Held::read(&results.runs_path(), traced)?)
}

/// The report's figures under `root/report/figures/`; how many, said on stderr. First removes
/// this program's own temporary files that a killed write left in report/ and its
/// sub-directories (a kill while a page or figure was written, e.g. on a full disk;
/// `store::results_dir::remove_own_tmp`). Called with the results directory's lock held,
/// which guards report/ too, so no other process's temporary file is in flight. With `paper`,
/// only that paper's figures are drawn (`presentation::figures::render_paper`); the runs
/// `traced` says no to keep no trace by choice and get no figure of their own.
pub fn render_figures(
    root: &Path,
    paper: Option<&str>,
    held: &Held,
    traced: &dyn Fn(&RunKey) -> bool,
) -> Result<usize, ReproduceError> {
    let report = store::TrackedDir::open_within(root, "report")?;
    let removed = store::results_dir::remove_own_tmp(report.owned());
    if !removed.is_empty() {
        eprintln!(
            "removed {} stale temporary file(s) of interrupted writes under {}",
            removed.len(),
            report.path().display()
        );
    }
    let figures = match paper {
        Some(p) => presentation::figures::render_paper(root, p, held, traced)?.len(),
        None => presentation::figures::render_all(root, held, traced)?.len(),
    };
    eprintln!("wrote {figures} figures");
    Ok(figures)
}

/// The report's pages, its task cards (of the experiment files `files`), then the leaderboard
/// table (recorded in the results directory's manifest), from the runs the report holds
/// (`held`, [`held_runs`]).
pub fn render_pages(
    project: &Project,
    root: &Path,
    results: &ResultsDir,
    files: &[PaperFile],
    held: Held,
) -> Result<(), ReproduceError> {
    let inputs = presentation::report::Inputs::load(root, &project.root.join("papers"), held)?;
    let report = presentation::report::render(root, &inputs)?;
    crate::task_card::write_all(files, root)?;
    analysis::leaderboard::write(results.path(), inputs.runs.all())?;
    results.save()?;
    eprintln!("wrote {}", report.display());
    Ok(())
}

/// [`render_report`] where the results directory allows a report; otherwise says why not.
pub fn render_report_if_named(
    project: &Project,
    results: &ResultsDir,
    all: &Described,
) -> Result<(), ReproduceError> {
    match report_root(project) {
        Ok(root) => render_report(project, &root, results, all),
        Err(why) => {
            eprintln!("report not rendered: {why}");
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cli(results: &str) -> Project {
        let global = crate::options::GlobalOptions {
            root: Some("/p".into()),
            results_dir: Some(results.into()),
            ..Default::default()
        };
        Project::resolve(&global, None).unwrap()
    }

    #[test]
    fn the_report_goes_beside_a_directory_named_results_only() {
        assert_eq!(
            report_root(&cli("/p/results")).unwrap(),
            PathBuf::from("/p")
        );
        assert_eq!(report_root(&cli("results")).unwrap(), PathBuf::from(""));
        let err = report_root(&cli("/p/results-shard-1-of-2")).unwrap_err();
        assert!(
            matches!(&err, ReproduceError::ResultsNotNamedResults(d) if d == Path::new("/p/results-shard-1-of-2")),
            "{err:?}"
        );
        assert!(err.to_string().contains("use --dry-run"), "{err}");
    }
}
