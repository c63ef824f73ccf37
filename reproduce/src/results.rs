//! The results directory as the modes use it (store::results_dir): opened for writing once
//! per mode (the lock, the integrity check of its tables, the migration of rows written before
//! run ids), and written at the end of a run or merge (pruning, merging, runs.csv, manifest).

use crate::error::ReproduceError;
use crate::project::Project;
use catalog::{Found, PaperFile, RunLookup};
use records::{merge_runs, RunRow};
use simulation::RunRecord;
use spec::RunKey;
use spec::RunSpec;
use std::cell::{OnceCell, RefCell};
use store::results_dir::ResultsDir;
use store::KeySet;
use store::LabelIndex;

/// The experiment files of the project, loaded and validated, every run checked
/// ([`crate::experiments`]).
pub fn experiment_files(project: &Project) -> Result<Vec<PaperFile>, ReproduceError> {
    Ok(crate::experiments::load_dir(&project.experiments_dir)?)
}

/// Every run the experiment files describe (what migration and pruning compare the stored
/// runs with), made from the files when asked: as a lookup of run keys decided from their
/// names ([`Described::keys`], what a shard and a merge need: no run made but those of the
/// sweeps whose names are not decided from their axes), as a label index taken as the runs are
/// made (the migration of results written before run ids), or as jobs, collected once on first
/// use (what the gate, the explanation layer, inference and the timing pass need). A shard of a
/// 10^7-run sweep so never makes every run, nor holds anything per run of the sweep
/// (docs/cluster.md).
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

    /// Whether the experiment files describe a run key, and whether it keeps its trace,
    /// decided from the names ([`Keys`]): the runs of the sweeps whose names are not decided
    /// from their axes are made once and held as prints, no other run is made.
    pub fn keys(&self) -> Result<Keys<'a>, ReproduceError> {
        let lookup = RunLookup::new(self.files);
        let undecided = |untraced: bool| -> Result<KeySet, ReproduceError> {
            lookup
                .undecided_runs()
                .filter(|j| j.as_ref().map_or(true, |j| !untraced || !j.keep_trace))
                .map(|j| j.map(|j| j.key().to_string()).map_err(ReproduceError::from))
                .collect()
        };
        Ok(Keys {
            described: undecided(false)?,
            untraced: undecided(true)?,
            lookup,
            unmade: RefCell::new(None),
        })
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

/// Whether the experiment files describe a run key ([`Described::keys`]), in memory and time
/// independent of the number of runs they describe: a key is looked up from its names
/// ([`catalog::RunLookup`]: its experiment by id, its variant by id, a swept one's read back
/// from the id's tokens where the sweep's names are decided from its axes, its solver among
/// that variant's), so a shard's pruning and resume cost in proportion to the rows they check
/// and a merge holds nothing per run of the sweep. Only the runs of the sweeps whose names are
/// not decided from their axes (each of at most `catalog::NAMES_COMPARED` variants) are held,
/// as prints: 16 bytes a run, where a set of the keys themselves is ~200. Two keys share a
/// print with probability ~2^-128 ([`store::KeySet`]).
///
/// The answers are plain yes or no, for the store's callbacks; a variant made to learn its
/// solvers that does not make (a swept one off the lines that fails its checks) answers no and
/// keeps its error, the first one: [`Keys::check`] returns it, and every caller checks it
/// before acting on the answers.
pub struct Keys<'a> {
    lookup: RunLookup<'a>,
    /// The runs of the sweeps whose names are not decided from their axes.
    described: KeySet,
    /// Those of them that keep no trace by choice (their sweep's `traces`).
    untraced: KeySet,
    /// The first variant that did not make while answering.
    unmade: RefCell<Option<ReproduceError>>,
}

impl Keys<'_> {
    /// What the files say of `key`; a variant that does not make is kept ([`Keys::check`])
    /// and answers [`Found::NoRun`].
    fn find(&self, key: &RunKey) -> Found {
        self.lookup.find(key).unwrap_or_else(|e| {
            self.unmade.borrow_mut().get_or_insert(e.into());
            Found::NoRun
        })
    }

    /// Whether an experiment file describes the run `key`.
    pub fn contains(&self, key: &RunKey) -> bool {
        match self.find(key) {
            Found::Run { .. } => true,
            Found::NoRun => false,
            Found::Undecided => self.described.contains(&key.to_string()),
        }
    }

    /// Whether the run `key` keeps its trace: every run but those whose sweep chose not to
    /// (a run no file describes included: its trace, if any, is its own).
    pub fn traced(&self, key: &RunKey) -> bool {
        match self.find(key) {
            Found::Run { keeps_trace } => keeps_trace,
            Found::NoRun => true,
            Found::Undecided => !self.untraced.contains(&key.to_string()),
        }
    }

    /// The first error met while answering (a variant that does not make), if any.
    pub fn check(&self) -> Result<(), ReproduceError> {
        match self.unmade.borrow_mut().take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
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
    let planned = results.plan_pruning(
        results.read_runs()?,
        |row| described.contains(&row.key()),
        project.prune,
        &project.experiments_dir,
    );
    described.check()?;
    Ok(planned?)
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
