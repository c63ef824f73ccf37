//! `reproduce infer TABLE`: setup inference (explain::inference) of the selected
//! published tables with the family of `experiments/inference/family.toml`, each table written
//! as it is fitted, then the report re-rendered.

use crate::error::ReproduceError;
use crate::options::{InferOptions, Tables};
use crate::papers::load_papers;
use crate::project::Project;
use crate::report::{precheck_report, render_report, report_root};
use crate::results::{open_results, Described};
use store::results_dir::ResultsDir;

/// The tables of `ids` (paper, table) that `which` selects; none is an error listing the
/// known ones (a paper or table well formed but absent from the papers' files).
pub fn select_tables<'a>(
    ids: &'a [(String, String)],
    which: &Tables,
) -> Result<Vec<&'a (String, String)>, ReproduceError> {
    let selected: Vec<&(String, String)> = ids.iter().filter(|(p, t)| which.take(p, t)).collect();
    if selected.is_empty() {
        return Err(ReproduceError::UnknownTable {
            which: which.to_string(),
            known: ids.iter().map(|(p, t)| format!("{p}:{t}")).collect(),
        });
    }
    Ok(selected)
}

/// `reproduce infer TABLE`: the tables `options.table` selects fitted over `all` (every run of
/// the experiment files), each written as it is fitted and the report re-rendered, unless
/// `--dry-run`.
pub fn infer_mode(
    project: &Project,
    options: &InferOptions,
    all: &Described,
    git_rev: &str,
) -> Result<(), ReproduceError> {
    if options.dry_run {
        return infer(project, &options.table, all, None);
    }
    precheck_report(project, all)?;
    let results = open_results(project, git_rev, all)?;
    infer(project, &options.table, all, Some(&results))
}

/// Fits the tables `which` selects over the runs of `all` (every run of the experiment files);
/// writes each to `results` when given, then renders the report.
pub fn infer(
    project: &Project,
    which: &Tables,
    all: &Described,
    results: Option<&ResultsDir>,
) -> Result<(), ReproduceError> {
    let jobs = all.jobs()?;
    use analysis::papers::table_ids;
    use explain::inference::{family::Family, fit, problem, rows, search::Target};
    let root = report_root(project)?;
    let papers = load_papers(project)?;
    let family = Family::load(&project.experiments_dir)?;
    let ids = table_ids(&papers.values);
    for (paper, table) in select_tables(&ids, which)? {
        let p = problem(paper, table, &papers, jobs)?;
        eprintln!(
            "inferring the setup of {paper} {table}: {} columns, {} exact and {} network runs",
            p.columns.len(),
            p.exact.len(),
            p.network.len()
        );
        let f = fit(&p, &family);
        let best = f.outcome.best(Target::Joint);
        eprintln!(
            "  declared: residual {:.3}; best fit: residual {:.3} ({}), {} evaluations in {:.0} s",
            f.outcome.declared.scores.joint,
            best.scores.joint,
            best.detail.setup,
            f.outcome.evaluations,
            f.wall_s
        );
        // Each table is written as soon as it is fitted: an interrupted `infer all` keeps the
        // tables it finished.
        let (r, e) = rows(&p, &f);
        if let Some(results) = results {
            explain::write_inference(results.path(), &r, &e)?;
            results.save()?;
        }
    }
    match results {
        Some(results) => render_report(project, &root, results, all),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ids() -> Vec<(String, String)> {
        [("a", "T1"), ("a", "T2"), ("b", "T1")]
            .iter()
            .map(|(p, t)| (p.to_string(), t.to_string()))
            .collect()
    }

    fn names(which: &str) -> Vec<String> {
        let ids = ids();
        select_tables(&ids, &which.parse().unwrap())
            .unwrap()
            .iter()
            .map(|(p, t)| format!("{p}:{t}"))
            .collect()
    }

    #[test]
    fn tables_are_selected_by_all_paper_or_id_lists() {
        assert_eq!(names("all"), ["a:T1", "a:T2", "b:T1"]);
        assert_eq!(names("a"), ["a:T1", "a:T2"]);
        assert_eq!(names("a:T2, b"), ["a:T2", "b:T1"]);
        assert_eq!(names("b:T1"), ["b:T1"]);
    }

    #[test]
    fn no_such_table_lists_the_known_ones() {
        let ids = ids();
        let err = select_tables(&ids, &"a:T3".parse().unwrap()).unwrap_err();
        assert_eq!(
            err.to_string(),
            "infer \"a:T3\": no such table (known: all, a paper, or one of a:T1, a:T2, b:T1)"
        );
    }
}
