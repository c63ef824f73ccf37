//! The results directory as the modes use it (store::results_dir): opened for writing once
//! per mode (the lock, the integrity check of its tables, the migration of rows written before
//! run ids), and written at the end of a run or merge (pruning, merging, runs.csv, manifest).

use crate::error::ReproduceError;
use crate::project::Project;
use catalog::PaperFile;
use records::{merge_runs, RunRow};
use simulation::RunRecord;
use spec::RunKey;
use spec::RunSpec;
use std::cell::{OnceCell, RefCell};
use std::collections::HashSet;
use store::results_dir::ResultsDir;
use store::KeySet;
use store::LabelIndex;

/// The experiment files of the project, loaded and validated, every run checked
/// ([`crate::experiments`]).
pub fn experiment_files(project: &Project) -> Result<Vec<PaperFile>, ReproduceError> {
    Ok(crate::experiments::load_dir(&project.experiments_dir)?)
}

/// Every run the experiment files describe (what migration and pruning compare the stored
/// runs with), made from the files when asked: as keys or a label index, taken as the runs
/// are made (what a shard needs), or as jobs, collected once on first use (what the gate, the
/// explanation layer, inference and the timing pass need). A shard of a 10^6-run sweep so never
/// holds every run as a [`RunSpec`] (docs/cluster.md).
pub struct Described<'a> {
    files: &'a [PaperFile],
    jobs: OnceCell<Vec<RunSpec>>,
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
    pub fn jobs(&self) -> Result<&[RunSpec], ReproduceError> {
        if let Some(jobs) = self.jobs.get() {
            return Ok(jobs);
        }
        let jobs = self.runs().collect::<Result<Vec<_>, _>>()?;
        Ok(self.jobs.get_or_init(|| jobs))
    }

    /// The run keys (`experiment / variant / solver`), and which of them keep no trace, as
    /// sets of their prints (16 bytes a run: [`store::KeySet`]).
    pub fn keys(&self) -> Result<Keys, ReproduceError> {
        Ok(Keys {
            described: self
                .runs()
                .map(|j| j.map(|j| j.key().to_string()))
                .collect::<Result<_, _>>()?,
            untraced: self
                .untraced_runs()
                .map(|j| j.map(|j| j.key().to_string()))
                .collect::<Result<_, _>>()?,
        })
    }

    /// The run keys that keep no trace by choice (their sweep's `traces`), what the figures
    /// leave out.
    pub fn untraced(&self) -> Result<HashSet<RunKey>, ReproduceError> {
        self.untraced_runs().map(|j| j.map(|j| j.key())).collect()
    }

    /// The runs that keep no trace by choice.
    fn untraced_runs(&self) -> impl Iterator<Item = Result<RunSpec, ReproduceError>> + '_ {
        self.runs()
            .filter(|j| j.as_ref().map_or(true, |j| !j.keep_trace))
    }

    /// The index by labels by which results written before run ids are migrated, of the runs
    /// made before the first variant that does not make (kept in `failed`, which the caller
    /// reports: [`open_results`]).
    fn label_index(&self, failed: &RefCell<Option<ReproduceError>>) -> LabelIndex {
        LabelIndex::new(
            self.runs()
                .map_while(|j| j.map_err(|e| *failed.borrow_mut() = Some(e)).ok()),
        )
    }

    /// Every run's key, in file order, made as the runs are taken (no run is held: a key is
    /// ~0.1 KB, a run's [`RunSpec`] ~0.7 KB).
    pub fn run_keys(&self) -> Result<Vec<RunKey>, ReproduceError> {
        self.runs().map(|j| j.map(|j| j.key())).collect()
    }

    /// The runs, made one variant at a time.
    fn runs(&self) -> impl Iterator<Item = Result<RunSpec, ReproduceError>> + '_ {
        self.files
            .iter()
            .flat_map(PaperFile::iter_jobs)
            .map(|j| j.map_err(ReproduceError::from))
    }
}

/// The keys of the runs the experiment files describe ([`Described::keys`]), by their prints:
/// 16 bytes a run, where a set of the keys themselves is ~200 (a sweep of 10^5 runs: 1.6 MB,
/// not 20 MB). Two keys share a print with probability ~2^-128 ([`store::KeySet`]).
#[derive(Default)]
pub struct Keys {
    described: KeySet,
    /// The described runs that keep no trace by choice (their sweep's `traces`).
    untraced: KeySet,
}

impl Keys {
    /// Whether an experiment file describes the run `key`.
    pub fn contains(&self, key: &RunKey) -> bool {
        self.described.contains(&key.to_string())
    }

    /// Whether the run `key` keeps its trace: every run but those whose sweep chose not to
    /// (a run no file describes included: its trace, if any, is its own).
    pub fn traced(&self, key: &RunKey) -> bool {
        self.untraced.is_empty() || !self.untraced.contains(&key.to_string())
    }
}

/// Opens the results directory for writing (store::results_dir): the lock, the integrity
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
    // Results written before run ids are migrated once (store::migrate).
    let failed = RefCell::new(None);
    for done in results.migrate_ids(|| all.label_index(&failed))? {
        eprintln!(
            "migrated to run ids under {}: {done}",
            project.results_dir.display()
        );
    }
    match failed.into_inner() {
        Some(e) => Err(e),
        None => Ok(results),
    }
}

/// The stored rows split into those an experiment file still describes (kept) and those it
/// does not (to prune); refuses to prune more than a quarter of them without `--prune`
/// ([`Project::prune`]).
pub fn plan_pruning(
    project: &Project,
    results: &ResultsDir,
    all: &Described,
) -> Result<(Vec<RunRow>, Vec<RunRow>), ReproduceError> {
    let described = all.keys()?;
    Ok(results.plan_pruning(
        results.read_runs()?,
        |row| described.contains(&row.key()),
        project.prune,
        &project.experiments_dir,
    )?)
}

/// Prunes the stored rows no experiment file describes (said run by run; their traces only if
/// this program wrote them), merges the fresh rows into the kept ones, writes the traces of
/// `untraced` (the runs the journal could not checkpoint; those that keep one) and runs.csv,
/// and saves the manifest.
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
    let merged = merge_runs(kept, rows);
    for r in untraced {
        if let Some(trace) = crate::journal::kept_trace(r) {
            results.write_trace(&r.job.key(), trace)?;
        }
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
