//! The results directory as the modes use it (records::results_dir): opened for writing once
//! per mode (the lock, the integrity check of its tables, the migration of rows written before
//! run ids), and written at the end of a run or merge (pruning, merging, runs.csv, manifest).

use crate::error::ReproduceError;
use crate::project::Project;
use catalog::experiment::{load_dir, Job, PaperFile};
use catalog::run_key::RunKey;
use records::migrate::LabelIndex;
use records::results_dir::ResultsDir;
use records::runs::{merge, RunRow};
use simulation::run::RunRecord;
use std::cell::OnceCell;
use std::collections::HashSet;

/// The experiment files of the project, loaded and validated.
pub fn experiment_files(project: &Project) -> Result<Vec<PaperFile>, ReproduceError> {
    Ok(load_dir(
        &project.experiments_dir,
        simulation::run::check_job,
    )?)
}

/// Every run the experiment files describe (what migration and pruning compare the stored
/// runs with), made from the files when asked: as keys or a label index, taken as the runs
/// are made (what a shard needs), or as jobs, collected once on first use (what the gate, the
/// explanation layer, inference and the timing pass need). A shard of a 10^6-run sweep so never
/// holds every run as a [`Job`] (docs/cluster.md).
pub struct Described<'a> {
    files: &'a [PaperFile],
    jobs: OnceCell<Vec<Job>>,
}

impl<'a> Described<'a> {
    pub fn new(files: &'a [PaperFile]) -> Self {
        Described {
            files,
            jobs: OnceCell::new(),
        }
    }

    /// The experiment files.
    pub fn files(&self) -> &'a [PaperFile] {
        self.files
    }

    /// Every run, in file order, collected on the first call.
    pub fn jobs(&self) -> &[Job] {
        self.jobs
            .get_or_init(|| self.files.iter().flat_map(PaperFile::jobs).collect())
    }

    /// The run keys (`experiment / variant / solver`).
    pub fn keys(&self) -> HashSet<RunKey> {
        self.runs().map(|j| j.key()).collect()
    }

    /// The index by labels by which results written before run ids are migrated.
    fn label_index(&self) -> LabelIndex {
        LabelIndex::new(self.runs())
    }

    /// The runs, made one variant at a time.
    fn runs(&self) -> impl Iterator<Item = Job> + '_ {
        self.files.iter().flat_map(PaperFile::iter_jobs)
    }
}

/// Opens the results directory for writing (records::results_dir): the lock, the integrity
/// check of its tables, the removal of this program's own stale temporary files.
/// `all`: every run of the experiment files, by which results written before run ids are
/// migrated.
pub fn open_results(
    project: &Project,
    git_rev: &str,
    all: &Described,
) -> Result<ResultsDir, ReproduceError> {
    let (results, removed) = ResultsDir::open(&project.results_dir, git_rev, project.edits)?;
    if !removed.is_empty() {
        eprintln!(
            "removed {} stale temporary file(s) of interrupted runs under {}",
            removed.len(),
            project.results_dir.display()
        );
    }
    // Results written before run ids are migrated once (records::migrate).
    for done in results.migrate_ids(|| all.label_index())? {
        eprintln!(
            "migrated to run ids under {}: {done}",
            project.results_dir.display()
        );
    }
    Ok(results)
}

/// The stored rows split into those an experiment file still describes (kept) and those it
/// does not (to prune); refuses to prune more than a quarter of them without `--prune`
/// ([`Project::prune`]).
pub fn plan_pruning(
    project: &Project,
    results: &ResultsDir,
    all: &Described,
) -> Result<(Vec<RunRow>, Vec<RunRow>), ReproduceError> {
    let described = all.keys();
    Ok(results.plan_pruning(
        results.read_runs()?,
        |row| described.contains(&row.key()),
        project.prune,
        &project.experiments_dir,
    )?)
}

/// Prunes the stored rows no experiment file describes (said run by run; their traces only if
/// this program wrote them), merges the fresh rows into the kept ones, writes the traces of
/// `untraced` (the runs the journal could not checkpoint) and runs.csv, and saves the manifest.
pub fn write_results(
    results: &ResultsDir,
    untraced: &[&RunRecord],
    kept: Vec<RunRow>,
    pruned: &[RunRow],
    rows: Vec<RunRow>,
) -> Result<(), ReproduceError> {
    for line in results.prune(pruned)? {
        eprintln!("{line}");
    }
    if !pruned.is_empty() {
        eprintln!(
            "pruned {} stored run(s) that no experiment file describes any more",
            pruned.len()
        );
    }
    let merged = merge(kept, rows);
    for r in untraced {
        results.write_trace(&r.job.key(), &r.run.trace)?;
    }
    results.write_runs(&merged)?;
    results.save()?;
    eprintln!(
        "wrote {} ({} rows)",
        results.runs_path().display(),
        merged.len()
    );
    Ok(())
}
