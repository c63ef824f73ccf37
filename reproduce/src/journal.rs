//! The journal of a run (store::journal): an interrupted run's journal folded into runs.csv
//! before anything runs (its runs of this code revision whose traces match the journal's seal
//! are not run again, and their traces are recorded in the results directory's manifest), and
//! each run checkpointed, with its trace and its seal, as it finishes. A run into `results/`
//! folds into the rows it holds ([`resume`]); a shard folds by streaming ([`fold`]: the
//! journal's rows read back one at a time in key order, appended to `runs.csv` as a part after
//! each chunk, and merged with `runs.csv` and its parts row by row at its start and end), so
//! that it holds nothing per run but its key and writes each row a bounded number of times.

use crate::error::ReproduceError;
use crate::results::{Described, Keys};
use records::{merge_runs, RunRow};
use simulation::run_jobs_with;
use simulation::run_row;
use simulation::RunRecord;
use spec::RunKey;
use spec::RunSpec;
use std::collections::HashSet;
use store::journal::Recovered;
use store::results_dir::ResultsDir;
use store::sorted::{latest, read_key_ordered, KeyMerge};
use store::KeySet;

/// The journal of `results` recovered (store::journal::recover) and said: rows of another
/// revision, whose trace does not match its seal, or that no experiment file describes
/// (`described`) are named and left out of [`Recovered::current`] (they are run again).
fn recover(
    results: &ResultsDir,
    git_rev: &str,
    described: &Keys,
) -> Result<Recovered, ReproduceError> {
    let recovered = store::journal::recover(results, git_rev, |k| described.traced(k));
    described.check()?;
    let mut recovered = recovered?;
    let journal = store::journal::path(results.path());
    for (key, rev) in &recovered.other_revision {
        eprintln!(
            "not folded from {}: {key} (written by revision {rev}, this is {git_rev}); it is run again",
            journal.display(),
        );
    }
    for key in &recovered.unsealed {
        eprintln!(
            "not folded from {}: {key} (its trace is missing, or not the one {} sealed); it is run again",
            journal.display(),
            store::journal::seal_path(results.path()).display()
        );
    }
    let mut kept = Vec::with_capacity(recovered.current.len());
    for e in std::mem::take(&mut recovered.current) {
        let keep = described.contains(&e.key);
        described.check()?;
        if keep {
            kept.push(e);
        } else {
            eprintln!(
                "not folded from {}: {} (no experiment file describes it)",
                journal.display(),
                e.key
            );
        }
    }
    recovered.current = kept;
    Ok(recovered)
}

/// Folds the journal of an interrupted run into `kept` (the stored rows, written back, with
/// the manifest) and removes from `to_run` the runs it holds from revision `git_rev`; rows of
/// another revision, whose trace does not match its seal, or that no experiment file
/// describes (`all`), are said and not folded.
pub fn resume(
    results: &ResultsDir,
    git_rev: &str,
    all: &Described,
    kept: &mut Vec<RunRow>,
    to_run: &mut Vec<RunSpec>,
) -> Result<(), ReproduceError> {
    let recovered = recover(results, git_rev, &all.keys()?)?;
    if !recovered.current.is_empty() {
        let fold: Vec<RunRow> = recovered.rows(results.path())?.collect::<Result<_, _>>()?;
        let done: HashSet<RunKey> = fold.iter().map(RunRow::key).collect();
        *kept = merge_runs(std::mem::take(kept), fold);
        results.write_runs(kept)?;
        results.save()?;
        let before = to_run.len();
        to_run.retain(|j| !done.contains(&j.key()));
        eprintln!(
            "folded {} run(s) of an interrupted run into {}; resuming: {} of the selected runs already done",
            done.len(),
            results.runs_path().display(),
            before - to_run.len()
        );
    }
    Ok(store::journal::remove(results.path())?)
}

/// When a shard folds its journal ([`fold`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FoldAt {
    /// At its start: an interrupted start's journal and parts, merged into `runs.csv` and
    /// said; with nothing to fold or prune nothing is written.
    Start,
    /// After each chunk of its runs but the last (crate::shard::CHUNK): what the chunk
    /// checkpointed, appended to `runs.csv` as a part (`ResultsDir::append_part`), so that
    /// the journal, and its index at the fold, never hold more than a chunk's rows and no row
    /// is written twice; with nothing to fold nothing is written.
    Chunk,
    /// At its end: `runs.csv` is always written, its parts merged into it.
    End,
}

/// Folds the journal of `results` and `unjournaled` (rows whose traces are written, in key
/// order) by streaming; `fresh` is told each row folded from the journal or `unjournaled`.
/// After a chunk ([`FoldAt::Chunk`]) they are appended to `runs.csv` as its next part, written
/// row by row: each run's row is written once, so a shard of R runs writes ~R rows in its
/// parts, where rewriting `runs.csv` after every chunk wrote ~R^2 / 8,192. At the start and
/// the end `runs.csv`, its parts (in order: a later row of a key replaces an earlier one), the
/// journal and `unjournaled` are merged in key order into a new `runs.csv` (a k-way merge,
/// [`store::sorted`]: one row per source in memory), leaving out the stored rows `pruned`
/// (their traces removed), and the parts are removed once it is committed. The journal's
/// rows are read back one at a time: what is held per run is its key (the journal's index,
/// the described keys), never its row or trace. The journal is removed once its rows are
/// committed. Returns how many rows were folded from the journal.
pub fn fold(
    results: &ResultsDir,
    git_rev: &str,
    described: &Keys,
    pruned: &[RunRow],
    unjournaled: Vec<RunRow>,
    at: FoldAt,
    mut fresh: impl FnMut(&RunRow),
) -> Result<usize, ReproduceError> {
    type Rows<'a> = Box<dyn Iterator<Item = Result<RunRow, ReproduceError>> + 'a>;
    let recovered = recover(results, git_rev, described)?;
    let folded = recovered.current.len();
    let news = folded > 0 || !unjournaled.is_empty();
    let fresh_joints = recovered
        .joints
        .max(unjournaled.iter().map(|r| r.drift.len()).max().unwrap_or(0));
    let journaled: Rows = if folded > 0 {
        Box::new(
            recovered
                .rows(results.path())?
                .map(|r| r.map_err(ReproduceError::from)),
        )
    } else {
        Box::new(std::iter::empty())
    };
    let fresh_rows: [Rows; 2] = [journaled, Box::new(unjournaled.into_iter().map(Ok))];
    if at == FoldAt::Chunk {
        if news {
            let rows = latest(KeyMerge::new(fresh_rows.into())?, |_| {}).map(|r| {
                r.map(|(_, row)| {
                    fresh(&row);
                    row
                })
            });
            results.append_part(fresh_joints, rows)?;
        }
        store::journal::remove(results.path())?;
        return Ok(folded);
    }
    let parts = results.parts()?;
    if at == FoldAt::End || news || !pruned.is_empty() || !parts.is_empty() {
        for line in results.prune(pruned)? {
            eprintln!("{line}");
        }
        let gone: HashSet<RunKey> = pruned.iter().map(RunRow::key).collect();
        let stored = read_key_ordered(&results.runs_path())?;
        let mut joints = stored.joints().max(fresh_joints);
        let mut sources: Vec<Rows> = vec![Box::new(
            stored
                .filter(move |r| r.as_ref().map_or(true, |r| !gone.contains(&r.key())))
                .map(|r| r.map_err(ReproduceError::from)),
        )];
        for part in &parts {
            let part = read_key_ordered(part)?;
            joints = joints.max(part.joints());
            sources.push(Box::new(part.map(|r| r.map_err(ReproduceError::from))));
        }
        // Rows from the sources after the stored ones (runs.csv and its parts) are fresh.
        let stored_sources = sources.len();
        sources.extend(fresh_rows);
        let rows = latest(KeyMerge::new(sources)?, |_| {}).map(|r| {
            r.map(|(source, row)| {
                if source >= stored_sources {
                    fresh(&row);
                }
                row
            })
        });
        results.commit_runs(joints, rows)?;
        results.remove_parts()?;
        if folded > 0 && at == FoldAt::Start {
            eprintln!(
                "folded {folded} run(s) of an interrupted run into {}",
                results.runs_path().display()
            );
        }
    }
    store::journal::remove(results.path())?;
    Ok(folded)
}

/// The trace of a finished run, if its job keeps one (`RunSpec::keep_trace`).
pub fn kept_trace(r: &RunRecord) -> Option<&[records::TracePoint]> {
    r.job.keep_trace.then_some(&r.run.trace[..])
}

/// The runs a shard directory holds already, finished: the rows of its `runs.csv` (read row
/// by row) of this revision `git_rev` whose trace the directory's manifest records, or that
/// keep no trace by choice (`described`). An earlier start of the shard finished them,
/// whether its journal was folded by this start or by one before: a shard's resume is
/// cumulative over every attempt, and a finished shard started again runs nothing. Held as
/// their keys' prints, 16 bytes a run ([`store::KeySet`]).
pub fn finished(
    results: &ResultsDir,
    git_rev: &str,
    described: &Keys,
) -> Result<KeySet, ReproduceError> {
    let mut failed = None;
    let done: KeySet = read_key_ordered(&results.runs_path())?
        .map(|row| -> Result<Option<String>, ReproduceError> {
            let row = row?;
            let key = row.key();
            let finished = row.git_rev == git_rev
                && (!described.traced(&key)
                    || results.tracked().lists(&ResultsDir::trace_rel(&key))?);
            described.check()?;
            Ok(finished.then(|| key.to_string()))
        })
        .map_while(|r| r.map_err(|e| failed = Some(e)).ok())
        .flatten()
        .collect();
    match failed {
        Some(e) => Err(e),
        None => Ok(done),
    }
}

/// The joints of the arm of `job` (0 for a robot the registry does not know: the run fails
/// at its start, with a row of no per-joint values).
pub fn joint_count(job: &RunSpec) -> usize {
    robots::robot_by_name(&job.robot).map_or(0, |r| r.dof())
}

/// The most joints among the arms of `jobs` (the per-joint columns of their rows).
pub fn joints(jobs: &[RunSpec]) -> usize {
    jobs.iter().map(joint_count).max().unwrap_or(0)
}

/// Runs `to_run` (in parallel), each checkpointed in a journal of `results` when given (sized
/// for the most joints among `jobs`, the selection). Returns the records and the keys of the
/// runs the journal could not checkpoint (whose traces are written again at the end).
pub fn run_journaled(
    results: Option<&ResultsDir>,
    jobs: &[RunSpec],
    to_run: &[RunSpec],
    git_rev: &str,
) -> Result<(Vec<RunRecord>, HashSet<RunKey>), ReproduceError> {
    let journal = results
        .map(|r| store::journal::Journal::open(r, joints(jobs)))
        .transpose()?;
    let unjournaled = std::sync::Mutex::new(HashSet::new());
    let records = run_jobs_with(to_run, true, |r| {
        if let Some(j) = &journal {
            if let Err(e) = j.record(&run_row(r, git_rev), kept_trace(r)) {
                eprintln!("warning: run not checkpointed: {e}");
                unjournaled
                    .lock()
                    .unwrap_or_else(|p| p.into_inner())
                    .insert(r.job.key());
            }
        }
    });
    drop(journal);
    let unjournaled = unjournaled.into_inner().unwrap_or_else(|p| p.into_inner());
    Ok((records, unjournaled))
}
