//! `reproduce shard` (`--shard K/N`): the shard's runs into its own directory in memory flat in
//! the number of runs (docs/cluster.md). The directory is bound to the shard
//! (store::shard::Binding) before anything runs; an interrupted start's journal is folded
//! into `runs.csv` and the runs an earlier start finished are skipped; each run, as it
//! finishes, is checkpointed (trace, seal, journal row) and dropped; at the end the journal is
//! folded into `runs.csv` by streaming ([`crate::journal::fold`]), the summary printed row by
//! row as it is folded, and the shard's manifest written last.

use crate::error::ReproduceError;
use crate::journal::{fold, joints, kept_trace, skip_finished};
use crate::options::SelectionOptions;
use crate::project::Project;
use crate::results::{open_results, Described};
use crate::run::{failure, summarise_failures};
use crate::select::selection_files;
use crate::summary::{emit, Summary};
use records::RunRow;
use simulation::run_jobs_into;
use simulation::run_row;
use simulation::RunRecord;
use spec::RunSpec;
use std::process::ExitCode;
use store::shard::{Binding, Shard};

/// What a shard keeps of a finished run: nothing of a run checkpointed in the journal but
/// whether it failed (and whether its experiment file expects it), the whole record of a run
/// the journal could not take.
enum Kept {
    /// Checkpointed; `Some` for a failed run: its line for the user and whether it is expected.
    Journaled(Option<(String, bool)>),
    /// Not checkpointed (the warning said why): its trace and row are written at the end.
    Unjournaled(Box<RunRecord>),
}

/// Runs `jobs`, shard `shard`'s runs of the selection `selection` (of `all`, every run of the
/// experiment files), into the shard's directory.
pub fn run_shard(
    project: &Project,
    selection: &SelectionOptions,
    shard: Shard,
    all: &Described,
    jobs: &[RunSpec],
    git_rev: &str,
) -> Result<ExitCode, ReproduceError> {
    // One writer at a time: the lock is held until the process ends.
    let results = open_results(project, git_rev, all)?;
    let described = all.keys();
    let pruned = results.plan_pruning_streamed(
        |row| described.contains(&row.key()),
        project.prune,
        &project.experiments_dir,
    )?;
    // The directory is finished only once its manifest is written again, at the end.
    let binding = Binding {
        shard: shard.k,
        shards: shard.n,
        experiments_hash: store::shard::experiments_hash(
            &project.experiments_dir,
            selection_files(all.files(), &selection.selection()),
        )?,
        selection: selection.selection(),
    };
    binding.claim(&results)?;
    store::shard::Manifest::remove(&project.results_dir)?;
    fold(
        &results,
        git_rev,
        &described,
        &pruned,
        Vec::new(),
        false,
        |_| {},
    )?;
    let to_run = skip_finished(&results, git_rev, jobs)?;

    let journal = store::journal::Journal::open(&results, joints(jobs))?;
    let kept = run_jobs_into(&to_run, true, |r| {
        let row = run_row(&r, git_rev);
        match journal.record(&row, kept_trace(&r)) {
            Ok(()) => Kept::Journaled((!row.completed()).then(|| failure(&row))),
            Err(e) => {
                eprintln!("warning: run not checkpointed: {e}");
                Kept::Unjournaled(Box::new(r))
            }
        }
    });
    drop(journal);
    let mut failed = Vec::new();
    let mut unjournaled = Vec::new();
    for k in kept {
        match k {
            Kept::Journaled(f) => failed.extend(f),
            Kept::Unjournaled(r) => {
                if let Some(trace) = kept_trace(&r) {
                    results.write_trace(&r.job.key(), trace)?;
                }
                let row = run_row(&r, git_rev);
                if !row.completed() {
                    failed.push(failure(&row));
                }
                unjournaled.push(row);
            }
        }
    }
    unjournaled.sort_by_key(RunRow::key);
    let mut summary = Summary::default();
    fold(
        &results,
        git_rev,
        &described,
        &[],
        unjournaled,
        true,
        |row| {
            let mut line = String::new();
            summary.push(row, &mut line);
            emit(&line);
        },
    )?;
    let mut end = String::new();
    summary.finish(&mut end);
    emit(&end);

    binding
        .manifest(git_rev, jobs.iter().map(|j| j.key().to_string()).collect())
        .write(&project.results_dir)?;
    eprintln!(
        "shard {}/{} done: merge with `reproduce merge {}...`",
        binding.shard,
        binding.shards,
        project.results_dir.display()
    );
    Ok(summarise_failures(
        &failed,
        to_run.len(),
        &results.runs_path(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What a shard keeps per run while its runs go on is a few words: a checkpointed run's
    /// record (its trace, tens of KB) is dropped as it is written, and only a run the journal
    /// could not take is kept, boxed. A record held inline would fail here.
    #[test]
    fn a_shard_keeps_a_few_words_per_run() {
        assert!(std::mem::size_of::<Kept>() <= 4 * std::mem::size_of::<usize>());
        assert!(std::mem::size_of::<RunRecord>() > std::mem::size_of::<Kept>());
    }
}
