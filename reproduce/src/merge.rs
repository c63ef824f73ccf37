//! `reproduce merge DIR...`: finished shard directories (store::shard: manifests,
//! integrity, revision, ownership, traces) checked before anything is written, then their rows
//! merged into the results directory's `runs.csv` and their traces copied, and the report
//! rendered unless `--no-report` (then `reproduce report` renders it, a step of its own).
//!
//! The merge streams: the shards' `runs.csv` are read row by row and merged in key order
//! with the stored `runs.csv` (store::sorted, a k-way merge: a shard's row replaces a stored
//! one), written row by row, each trace copied file by file as its row passes. The checks
//! compare sums of the runs' keys (store::shard::check_shards), and whether a row's run is
//! described, and keeps its trace, is decided from its key's names (crate::results::Keys:
//! nothing held per run of the sweep). Memory is then one row per shard (and the stored rows
//! it prunes), independent of the number of runs, and time linear in the runs (the selection's runs made once for the sums,
//! two passes over the rows: the checks, then the writing).

use crate::error::ReproduceError;
use crate::project::Project;
use crate::report::render_report_if_named;
use crate::results::{open_results, Described};
use crate::run::report_unexpected;
use crate::select::{check_selection, selected, selection_files};
use catalog::PaperFile;
use records::RunRow;
use spec::RunKey;
use std::cell::RefCell;
use std::collections::HashSet;
use std::process::ExitCode;
use store::sorted::{latest, read_key_ordered, KeyMerge};

/// Merges the shard directories `dirs` (`files`: the experiment files), rendering the report
/// when `report`.
pub fn merge_shards(
    project: &Project,
    dirs: &[std::path::PathBuf],
    files: &[PaperFile],
    git_rev: &str,
    report: bool,
) -> Result<ExitCode, ReproduceError> {
    let all = &Described::new(files);
    let described = all.keys()?;
    let shards = dirs
        .iter()
        .map(|d| store::shard::read_shard(d, project.edits, |k| described.traced(k)))
        .collect::<Result<Vec<_>, _>>();
    described.check()?;
    let shards = shards?;
    let sel = shards
        .first()
        .map(|s| s.manifest.selection.clone())
        .unwrap_or_default();
    check_selection(files, &sel)?;
    let hash =
        store::shard::experiments_hash(&project.experiments_dir, selection_files(files, &sel))?;
    // The selection's runs, made and dropped; the first variant that does not make stops
    // the merge with its error (it stopped the shard that holds it before any run).
    let unmade = RefCell::new(None);
    let checked = store::shard::check_shards(
        &shards,
        || {
            selected(files, &sel)
                .map_while(|j| j.map_err(|e| *unmade.borrow_mut() = Some(e)).ok())
                .map(|j| j.key().to_string())
        },
        &hash,
    );
    if let Some(e) = unmade.into_inner() {
        return Err(e);
    }
    checked?;

    let results = open_results(project, git_rev, all)?;
    let pruned = results.plan_pruning_streamed(
        |row| described.contains(&row.key()),
        project.prune,
        &project.experiments_dir,
    );
    described.check()?;
    let pruned = pruned?;
    for line in results.prune(&pruned)? {
        eprintln!("{line}");
    }
    if !pruned.is_empty() {
        eprintln!(
            "pruned {} stored run(s) that no experiment file describes any more",
            pruned.len()
        );
    }
    let gone: HashSet<RunKey> = pruned.iter().map(RunRow::key).collect();
    let stored = read_key_ordered(&results.runs_path())?;
    let from_shards = store::shard::runs_files(&shards)?;
    let joints = from_shards
        .iter()
        .map(|f| f.joints())
        .fold(stored.joints(), usize::max);
    // Source 0: the stored rows; source i: the rows of shards[i - 1] (which replace a stored
    // row of the same key).
    type Rows<'a> = Box<dyn Iterator<Item = Result<RunRow, ReproduceError>> + 'a>;
    let mut sources: Vec<Rows> = vec![Box::new(
        stored
            .filter(|r| r.as_ref().map_or(true, |r| !gone.contains(&r.key())))
            .map(|r| r.map_err(ReproduceError::from)),
    )];
    for file in from_shards {
        sources.push(Box::new(file.map(|r| r.map_err(ReproduceError::from))));
    }
    let (mut runs, mut unexpected) = (0usize, Vec::new());
    let rows = latest(KeyMerge::new(sources)?, |_| {}).map(|r| {
        let (source, row) = r?;
        if source > 0 {
            let traced = described.traced(&row.key());
            described.check()?;
            if traced {
                store::shard::copy_trace(&shards[source - 1], &row, &results)?;
            }
            runs += 1;
            if !row.completed() && !analysis::gate::expected_to_diverge(&row) {
                unexpected.push(format!("{}: {}", row.key(), row.failure));
            }
        }
        Ok::<_, ReproduceError>(row)
    });
    let written = results.commit_runs(joints, rows)?;
    eprintln!(
        "merged {} shard(s): {runs} runs and the traces they keep; wrote {} ({written} rows)",
        shards.len(),
        results.runs_path().display()
    );
    if report {
        render_report_if_named(project, &results, all)?;
    } else {
        eprintln!("report not rendered (--no-report): render it with `reproduce report`");
    }
    Ok(report_unexpected(&unexpected))
}
