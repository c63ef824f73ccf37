//! `reproduce merge DIR...` (`--merge`): finished shard directories (records::shard: manifests,
//! integrity, revision, ownership, traces) checked before anything is written, then their rows
//! and traces merged into the results directory and the report rendered, as a normal run does.

use crate::error::ReproduceError;
use crate::project::Project;
use crate::report::render_report_if_named;
use crate::results::{open_results, plan_pruning, write_results, Described};
use crate::run::report_unexpected;
use crate::select::{check_selection, selected, selection_files};
use catalog::experiment::PaperFile;
use records::runs::RunRow;
use std::process::ExitCode;

/// Merges the shard directories `dirs` (`files`: the experiment files).
pub fn merge_shards(
    project: &Project,
    dirs: &[std::path::PathBuf],
    files: &[PaperFile],
    git_rev: &str,
) -> Result<ExitCode, ReproduceError> {
    let shards = dirs
        .iter()
        .map(|d| records::shard::read_shard(d, project.edits))
        .collect::<Result<Vec<_>, _>>()?;
    let sel = shards
        .first()
        .map(|s| s.manifest.selection.clone())
        .unwrap_or_default();
    check_selection(files, &sel)?;
    let expected: Vec<String> = selected(files, &sel).map(|j| j.key().to_string()).collect();
    let all = &Described::new(files);
    let hash =
        records::shard::experiments_hash(&project.experiments_dir, selection_files(files, &sel))?;
    records::shard::check_shards(&shards, &expected, &hash)?;
    let results = open_results(project, git_rev, all)?;
    let (kept, pruned) = plan_pruning(project, &results, all)?;
    let traces = records::shard::copy_traces(&shards, &results)?;
    let rows: Vec<RunRow> = shards.iter().flat_map(|s| s.rows.clone()).collect();
    let unexpected: Vec<String> = rows
        .iter()
        .filter(|r| !r.completed() && !analysis::gate::expected_to_diverge(r))
        .map(|r| format!("{}: {}", r.key(), r.failure))
        .collect();
    eprintln!(
        "merging {} shard(s): {} runs, {traces} traces",
        shards.len(),
        rows.len()
    );
    write_results(&results, &[], kept, &pruned, rows)?;
    render_report_if_named(project, &results)?;
    Ok(report_unexpected(&unexpected))
}
