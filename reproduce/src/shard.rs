//! `reproduce shard K/N`: the shard's runs into its own directory in memory flat in
//! the number of runs (docs/cluster.md, "What a shard and a merge hold"). The directory is
//! bound to the shard (store::shard::Binding) before anything runs; whether a stored or
//! journaled run is still described is decided from its key's names
//! ([`crate::results::Keys`]: no run of the sweep made but the shard's own, so its pruning
//! and resume cost in proportion to the shard); an interrupted start's
//! journal is folded into `runs.csv`, and the runs any earlier start finished are skipped
//! (their keys held as 16-byte prints, [`crate::journal::finished`]); the shard's runs are made
//! from the experiment files as they are taken ([`Kept::runs`]) and run [`CHUNK`] at a time,
//! each checkpointed (trace, seal, journal row) and dropped as it finishes; after each chunk
//! the journal is appended to `runs.csv` as a part by streaming ([`crate::journal::fold`]:
//! the journal and its index never hold more than a chunk's rows, and each row is written
//! once), the summary printed row by row as it is folded; at the end the parts are merged
//! into `runs.csv` once; and the shard's manifest is written last, with the count and the key
//! sum of the runs assigned to it (store::KeySum), not their list.

use crate::error::ReproduceError;
use crate::journal::{finished, fold, joint_count, kept_trace, FoldAt};
use crate::options::SelectionOptions;
use crate::project::Project;
use crate::results::{open_results, Described};
use crate::run::{failure, summarise_failures};
use crate::select::{selection_files, Kept};
use crate::summary::{emit, Summary};
use records::RunRow;
use simulation::run_jobs_into;
use simulation::run_row;
use simulation::RunRecord;
use spec::RunSpec;
use std::process::ExitCode;
use store::shard::{Binding, Shard};
use store::KeySum;

/// How many runs a shard makes and runs at a time: what it holds of its runs is this many
/// [`RunSpec`]s (~1 KB each) and the records of the runs in flight, whatever their number. A
/// chunk ends when its slowest run does, so with `t` threads at most `t - 1` threads wait
/// once per chunk, ~t / CHUNK of the time.
pub const CHUNK: usize = 4096;

/// A test hook: with `DRIFTBENCH_SHARD_CHUNK=n` (a whole number, at least 1) in the
/// environment a shard runs `n` runs at a time instead of `CHUNK`, so that a test of a few
/// runs folds between chunks (`reproduce/tests/shards.rs` kills such a shard at every durable
/// step). Any other value is ignored.
pub const CHUNK_VAR: &str = "DRIFTBENCH_SHARD_CHUNK";

/// The runs a shard runs at a time: [`CHUNK`], or what [`CHUNK_VAR`] says.
fn chunk_size() -> usize {
    std::env::var(CHUNK_VAR)
        .ok()
        .and_then(|v| v.parse().ok())
        .filter(|&n| n >= 1)
        .unwrap_or(CHUNK)
}

/// What a shard keeps of a finished run: nothing of a run checkpointed in the journal but
/// whether it failed (and whether its experiment file expects it), the whole record of a run
/// the journal could not take.
enum Outcome {
    /// Checkpointed; `Some` for a failed run: its line for the user and whether it is expected.
    Journaled(Option<(String, bool)>),
    /// Not checkpointed (the warning said why): its trace and row are written at the end.
    Unjournaled(Box<RunRecord>),
}

/// Runs shard `shard`'s runs of the selection `selection` (`kept`: which runs of `all`, every
/// run of the experiment files, are the shard's) into the shard's directory.
pub fn run_shard(
    project: &Project,
    selection: &SelectionOptions,
    shard: Shard,
    all: &Described,
    kept: Kept<'_>,
    git_rev: &str,
) -> Result<ExitCode, ReproduceError> {
    // One writer at a time: the lock is held until the process ends.
    let results = open_results(project, git_rev, all)?;
    let described = all.keys()?;
    let pruned = results.plan_pruning_streamed(
        |row| described.contains(&row.key()),
        project.prune,
        &project.experiments_dir,
    );
    described.check()?;
    let pruned = pruned?;
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
        FoldAt::Start,
        |_| {},
    )?;
    drop(pruned);
    let done = finished(&results, git_rev, &described)?;

    // One pass over the shard's runs, made and dropped: what it was assigned (the manifest's
    // count and key sum), the most joints among them (the journal's columns), how many are
    // done. A variant of the shard's that does not make stops it here, before anything runs
    // (another shard's is that shard's to refuse, and the merge refuses it too).
    let (mut assigned, mut joints, mut skipped) = (KeySum::default(), 0, 0);
    for job in kept.runs(all.files()) {
        let job = job?;
        let key = job.key().to_string();
        skipped += usize::from(done.contains(&key));
        assigned.add(&key);
        joints = joints.max(joint_count(&job));
    }
    if skipped > 0 {
        eprintln!(
            "resuming: {skipped} of the selected runs already done: the shard holds {skipped} of its runs from earlier starts of this revision ({}); they are not run again",
            results.runs_path().display()
        );
    }
    let to_run = assigned.count - skipped;

    let mut failed = Vec::new();
    let mut summary = Summary::default();
    let mut say = |row: &RunRow| {
        let mut line = String::new();
        summary.push(row, &mut line);
        emit(&line);
    };
    let mut jobs = kept.runs(all.files()).filter(|j| {
        j.as_ref()
            .map_or(true, |j| !done.contains(&j.key().to_string()))
    });
    let (size, mut ran) = (chunk_size(), 0);
    loop {
        let chunk: Vec<RunSpec> = jobs.by_ref().take(size).collect::<Result<_, _>>()?;
        ran += chunk.len();
        // The last chunk is folded at the end, with the runs the journal could not take.
        let at = if chunk.len() < size || ran == to_run {
            FoldAt::End
        } else {
            FoldAt::Chunk
        };
        let journal = store::journal::Journal::open(&results, joints)?;
        let outcomes = run_jobs_into(&chunk, to_run <= size, |r| {
            let row = run_row(&r, git_rev);
            match journal.record(&row, kept_trace(&r)) {
                Ok(()) => Outcome::Journaled((!row.completed()).then(|| failure(&row))),
                Err(e) => {
                    eprintln!("warning: run not checkpointed: {e}");
                    Outcome::Unjournaled(Box::new(r))
                }
            }
        });
        drop(journal);
        drop(chunk);
        if to_run > size {
            eprintln!("shard {shard}: {ran} of {to_run} runs done");
        }
        let mut unjournaled = Vec::new();
        for outcome in outcomes {
            match outcome {
                Outcome::Journaled(f) => failed.extend(f),
                Outcome::Unjournaled(r) => {
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
        fold(
            &results,
            git_rev,
            &described,
            &[],
            unjournaled,
            at,
            &mut say,
        )?;
        if at == FoldAt::End {
            break;
        }
    }
    let mut end = String::new();
    summary.finish(&mut end);
    emit(&end);

    binding
        .manifest(git_rev, assigned)
        .write(&project.results_dir)?;
    eprintln!(
        "shard {}/{} done: merge with `reproduce merge {}...`",
        binding.shard,
        binding.shards,
        project.results_dir.display()
    );
    Ok(summarise_failures(&failed, to_run, &results.runs_path()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What a shard keeps per run while its runs go on is a few words: a checkpointed run's
    /// record (its trace, tens of KB) is dropped as it is written, and only a run the journal
    /// could not take is kept, boxed. A record held inline would fail here.
    #[test]
    fn a_shard_keeps_a_few_words_per_run() {
        assert!(std::mem::size_of::<Outcome>() <= 4 * std::mem::size_of::<usize>());
        assert!(std::mem::size_of::<RunRecord>() > std::mem::size_of::<Outcome>());
    }
}
