//! The runs a command line selects: `--paper`, `--experiment` (repeatable) and `--exact-only`
//! narrow the runs the experiment files describe; a paper or experiment no file names is an
//! error that lists the known ones.

use crate::error::ReproduceError;
use catalog::experiment::{Job, PaperFile, SolverChoice};
use records::shard::Selection;
use std::collections::HashSet;

/// The runs of `files` that `selection` keeps, in file order, made as they are taken (a
/// caller collects what it needs: a shard only its own runs). [`check_selection`] first.
pub fn selected<'a>(
    files: &'a [PaperFile],
    selection: &'a Selection,
) -> impl Iterator<Item = Job> + 'a {
    files
        .iter()
        .flat_map(PaperFile::iter_jobs)
        .filter(|j| selects(selection, j))
}

/// The names of the experiment files of `files` that `selection` draws its runs from: the
/// files of its paper (all without `--paper`) that define one of its experiments (any without
/// `--experiment`). A shard is bound to these files only (records::shard::experiments_hash):
/// another file added beside them does not make the shard's runs another sweep's.
pub fn selection_files<'a>(
    files: &'a [PaperFile],
    selection: &Selection,
) -> impl Iterator<Item = &'a str> + 'a {
    let paper = selection.paper.clone();
    let experiments = selection.experiments.clone();
    files
        .iter()
        .filter(move |f| {
            paper.as_ref().is_none_or(|p| &f.paper == p)
                && (experiments.is_empty()
                    || f.experiments.iter().any(|e| experiments.contains(&e.id)))
        })
        .map(|f| f.file_name.as_str())
}

/// A paper or experiment of `selection` that no file of `files` names is an error listing the
/// known ones (every experiment of a file has runs: a variant that runs nothing is refused at
/// load).
pub fn check_selection(files: &[PaperFile], selection: &Selection) -> Result<(), ReproduceError> {
    if let Some(p) = &selection.paper {
        if !files.iter().any(|f| &f.paper == p) {
            return Err(ReproduceError::UnknownPaper {
                paper: p.clone(),
                known: files.iter().map(|f| f.paper.clone()).collect(),
            });
        }
    }
    let ids: HashSet<&str> = files
        .iter()
        .flat_map(|f| &f.experiments)
        .map(|e| e.id.as_str())
        .collect();
    for e in &selection.experiments {
        if !ids.contains(e.as_str()) {
            let mut known: Vec<String> = ids.iter().map(|id| id.to_string()).collect();
            known.sort_unstable();
            return Err(ReproduceError::UnknownExperiment {
                experiment: e.clone(),
                known,
            });
        }
    }
    Ok(())
}

/// Whether `selection` keeps `job` (its paper, its experiment, the exact column only).
pub fn selects(selection: &Selection, job: &Job) -> bool {
    selection.paper.as_ref().is_none_or(|p| &job.paper == p)
        && (selection.experiments.is_empty()
            || selection.experiments.iter().any(|e| job.experiment == *e))
        && (!selection.exact_only || job.solver == SolverChoice::Exact)
}

#[cfg(test)]
mod tests {
    use super::*;
    use catalog::experiment::load_dir;
    use std::path::Path;

    /// The project's experiment files and their runs.
    fn project() -> (Vec<PaperFile>, Vec<Job>) {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../experiments");
        let files =
            load_dir(&dir, simulation::run::check_job).expect("the project's experiment files");
        let all = files.iter().flat_map(|f| f.jobs()).collect();
        (files, all)
    }

    fn select(
        paper: Option<&str>,
        experiments: &[&str],
        exact_only: bool,
    ) -> Result<Vec<Job>, ReproduceError> {
        let (files, _) = project();
        let selection = Selection {
            paper: paper.map(String::from),
            experiments: experiments.iter().map(|e| e.to_string()).collect(),
            exact_only,
        };
        check_selection(&files, &selection)?;
        Ok(selected(&files, &selection).collect())
    }

    #[test]
    fn no_flag_selects_every_run() {
        let (_, all) = project();
        let keys = |jobs: &[Job]| jobs.iter().map(Job::key).collect::<Vec<_>>();
        assert_eq!(keys(&select(None, &[], false).unwrap()), keys(&all));
    }

    #[test]
    fn a_paper_selects_exactly_its_runs() {
        let (files, all) = project();
        let paper = &files[0].paper;
        let jobs = select(Some(paper), &[], false).unwrap();
        assert!(!jobs.is_empty());
        assert!(jobs.iter().all(|j| &j.paper == paper));
        assert_eq!(jobs.len(), all.iter().filter(|j| &j.paper == paper).count());
        assert!(jobs.len() < all.len(), "one paper of several");
    }

    #[test]
    fn experiments_and_exact_only_narrow_the_selection() {
        let (_, all) = project();
        let (a, b) = (&all[0].experiment, &all.last().unwrap().experiment);
        assert_ne!(a, b);
        let jobs = select(None, &[a, b], false).unwrap();
        let expected = all
            .iter()
            .filter(|j| &j.experiment == a || &j.experiment == b)
            .count();
        assert_eq!(jobs.len(), expected);
        let exact = select(None, &[a, b], true).unwrap();
        assert!(!exact.is_empty() && exact.len() < jobs.len());
        assert!(exact.iter().all(|j| j.solver == SolverChoice::Exact));
    }

    #[test]
    fn a_selection_reads_the_files_of_its_paper_and_experiments_only() {
        let (files, _) = project();
        let names = |paper: Option<&str>, experiments: &[&str]| {
            let selection = Selection {
                paper: paper.map(String::from),
                experiments: experiments.iter().map(|e| e.to_string()).collect(),
                exact_only: false,
            };
            selection_files(&files, &selection).collect::<Vec<_>>()
        };
        let every: Vec<&str> = files.iter().map(|f| f.file_name.as_str()).collect();
        assert!(every.iter().all(|n| n.ends_with(".toml")), "{every:?}");
        assert_eq!(names(None, &[]), every);
        let kong = files.iter().find(|f| f.paper == "kong2019").unwrap();
        assert_eq!(names(Some("kong2019"), &[]), [kong.file_name.as_str()]);
        let one = &kong.experiments[0].id;
        assert_eq!(names(None, &[one]), [kong.file_name.as_str()]);
    }

    #[test]
    fn an_unknown_paper_or_experiment_names_the_known_ones() {
        let (files, _) = project();
        match select(Some("nopaper"), &[], false) {
            Err(ReproduceError::UnknownPaper { paper, known }) => {
                assert_eq!(paper, "nopaper");
                assert_eq!(
                    known,
                    files.iter().map(|f| f.paper.clone()).collect::<Vec<_>>()
                );
            }
            other => panic!("{other:?}"),
        }
        let err = select(None, &["nope"], false).unwrap_err();
        let ReproduceError::UnknownExperiment { experiment, known } = &err else {
            panic!("{err:?}");
        };
        assert_eq!(experiment, "nope");
        assert!(known.windows(2).all(|w| w[0] < w[1]), "sorted and distinct");
        assert!(err
            .to_string()
            .starts_with("unknown experiment \"nope\" (known: "));
    }
}
