//! The journal of a run (records::journal): an interrupted run's journal folded into runs.csv
//! before anything runs (its runs of this code revision whose traces match the journal's seal
//! are not run again, and their traces are recorded in the results directory's manifest), and
//! each run checkpointed, with its trace and its seal, as it finishes.

use crate::error::ReproduceError;
use crate::results::Described;
use catalog::experiment::Job;
use catalog::run_key::RunKey;
use records::results_dir::ResultsDir;
use records::runs::{merge, RunRow};
use simulation::row::run_row;
use simulation::run::RunRecord;
use simulation::runner::run_jobs_with;
use std::collections::HashSet;

/// Folds the journal of an interrupted run into `kept` (the stored rows, written back, with
/// the manifest) and removes from `to_run` the runs it holds from revision `git_rev`; rows of
/// another revision, whose trace does not match its seal, or that no experiment file
/// describes (`all`), are said and not folded.
pub fn resume(
    results: &ResultsDir,
    git_rev: &str,
    all: &Described,
    kept: &mut Vec<RunRow>,
    to_run: &mut Vec<Job>,
) -> Result<(), ReproduceError> {
    let recovered = records::journal::recover(results, git_rev)?;
    let journal = records::journal::path(results.path());
    for r in &recovered.other_revision {
        eprintln!(
            "not folded from {}: {} (written by revision {}, this is {git_rev}); it is run again",
            journal.display(),
            r.key(),
            r.git_rev
        );
    }
    for r in &recovered.unsealed {
        eprintln!(
            "not folded from {}: {} (its trace is missing, or not the one {} sealed); it is run again",
            journal.display(),
            r.key(),
            records::journal::seal_path(results.path()).display()
        );
    }
    let described = all.keys();
    let (fold, undescribed): (Vec<RunRow>, Vec<RunRow>) = recovered
        .current
        .into_iter()
        .partition(|r| described.contains(&r.key()));
    for r in &undescribed {
        eprintln!(
            "not folded from {}: {} (no experiment file describes it)",
            journal.display(),
            r.key()
        );
    }
    if !fold.is_empty() {
        let done: HashSet<RunKey> = fold.iter().map(RunRow::key).collect();
        *kept = merge(std::mem::take(kept), fold);
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
    Ok(records::journal::remove(results.path())?)
}

/// Removes from `to_run` the runs a shard directory already holds: rows of `kept` (its
/// `runs.csv`, the journal just folded in) of this revision `git_rev` whose trace the
/// directory's manifest records. An earlier start of the shard finished them, whether its
/// journal was folded by this start or by one before: a shard's resume is cumulative over every
/// attempt, and a finished shard started again runs nothing.
pub fn skip_finished(results: &ResultsDir, git_rev: &str, kept: &[RunRow], to_run: &mut Vec<Job>) {
    let traced: HashSet<String> = results.tracked().listed("traces/").into_iter().collect();
    let done: HashSet<RunKey> = kept
        .iter()
        .filter(|r| r.git_rev == git_rev)
        .map(RunRow::key)
        .filter(|k| {
            let rel = ResultsDir::trace_rel(k);
            traced.contains(&rel.to_string_lossy().replace('\\', "/"))
        })
        .collect();
    let before = to_run.len();
    to_run.retain(|j| !done.contains(&j.key()));
    if before > to_run.len() {
        eprintln!(
            "the shard holds {} of its runs from earlier starts of this revision ({}); they are not run again",
            before - to_run.len(),
            results.runs_path().display()
        );
    }
}

/// Runs `to_run` (in parallel), each checkpointed in a journal of `results` when given (sized
/// for the most joints among `jobs`, the selection). Returns the records and the keys of the
/// runs the journal could not checkpoint (whose traces are written again at the end).
pub fn run_journaled(
    results: Option<&ResultsDir>,
    jobs: &[Job],
    to_run: &[Job],
    git_rev: &str,
) -> Result<(Vec<RunRecord>, HashSet<RunKey>), ReproduceError> {
    let journal = results
        .map(|r| {
            let joints = jobs
                .iter()
                .filter_map(|j| {
                    robots::registry::robot_by_name(&j.robot)
                        .ok()
                        .map(|r| r.dof())
                })
                .max();
            records::journal::Journal::open(r, joints.unwrap_or(0))
        })
        .transpose()?;
    let unjournaled = std::sync::Mutex::new(HashSet::new());
    let records = run_jobs_with(to_run, true, |r| {
        if let Some(j) = &journal {
            if let Err(e) = j.record(&run_row(r, git_rev), &r.run.trace) {
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
