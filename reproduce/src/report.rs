//! The report (presentation): rendered beside the results directory (`<root>/results` ->
//! `<root>/report`) after every mode that writes results, or alone (`reproduce report`) from
//! the stored results without running anything.

use crate::cli::Cli;
use crate::error::ReproduceError;
use crate::results::{experiment_files, open_results, Described};
use records::results_dir::ResultsDir;
use std::path::{Path, PathBuf};

/// `reproduce report` (`--report-only`): re-renders report/ from the stored results.
pub fn report_only(cli: &Cli, git_rev: &str) -> Result<(), ReproduceError> {
    let root = report_root(cli)?;
    check_report_dir(&root)?;
    let results = open_results(cli, git_rev, &Described::new(&experiment_files(cli)?))?;
    render_report(cli, &root, &results)
}

/// The report is rendered beside the results directory: `<root>/results` -> `<root>/report`.
pub fn report_root(cli: &Cli) -> Result<PathBuf, ReproduceError> {
    match cli.results_dir.file_name() {
        Some(name) if name == records::results_dir::DIR => Ok(cli
            .results_dir
            .parent()
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("."))),
        _ => Err(ReproduceError::ResultsNotNamedResults(
            cli.results_dir.clone(),
        )),
    }
}

/// Checks, before anything runs, that `root/report` and its figures directory lie inside the
/// project (no symbolic link leading elsewhere) and that the report can be written there.
pub fn check_report_dir(root: &Path) -> Result<(), ReproduceError> {
    let report = records::tracked_dir::TrackedDir::open_within(root, "report")?;
    report.resolve(Path::new(presentation::figures::FIGURES))?;
    Ok(records::runs::check_writable(report.path())?)
}

/// Figures first (the report links them), then REPORT.md, then the leaderboard table (recorded
/// in the results directory's manifest).
pub fn render_report(cli: &Cli, root: &Path, results: &ResultsDir) -> Result<(), ReproduceError> {
    let figures = presentation::figures::render_all(root)?;
    let report = presentation::report::render(root, &cli.project_root.join("papers"))?;
    crate::task_card::write_all(root)?;
    records::leaderboard::write(results.path(), &results.read_runs()?)?;
    results.save()?;
    eprintln!("wrote {} figures and {}", figures.len(), report.display());
    Ok(())
}

/// [`render_report`] where the results directory allows a report; otherwise says why not.
pub fn render_report_if_named(cli: &Cli, results: &ResultsDir) -> Result<(), ReproduceError> {
    match report_root(cli) {
        Ok(root) => render_report(cli, &root, results),
        Err(why) => {
            eprintln!("report not rendered: {why}");
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cli(results: &str) -> Cli {
        let args = ["reproduce", "--root", "/p", "--results-dir", results];
        Cli::parse_from_args(args.iter().map(|a| a.to_string()).collect())
            .unwrap()
            .resolve()
            .unwrap()
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
