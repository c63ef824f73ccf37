//! `reproduce run` (the default; also `check` and `shard`): everything that
//! can be checked is checked before anything runs (the gate's baseline, the report directory,
//! the papers, the stored results); then the selected runs run, resumed from and checkpointed in a journal;
//! the summary is printed; and the rows are compared with the baseline (the gate) or written
//! with what follows them (a shard's manifest, or the explanation layer, the control
//! experiments and the report). Runs that fail without their experiment file expecting it are
//! exit code 1.

use crate::error::ReproduceError;
use crate::explanation::{explain, load_papers};
use crate::gate::Baseline;
use crate::journal::{resume, run_journaled};
use crate::options::SelectionOptions;
use crate::project::Project;
use crate::report::{check_report_dir, render_report_if_named, report_root};
use crate::results::{open_results, plan_pruning, write_results, Described};
use crate::summary::{emit, summary};
use catalog::experiment::Job;
use records::results_dir::ResultsDir;
use records::runs::RunRow;
use records::shard::Shard;
use simulation::row::run_row;
use simulation::run::RunRecord;
use std::process::ExitCode;

/// Where a run's rows go.
#[derive(Debug)]
pub enum Output {
    /// Into the results directory, followed by the explanation layer, the control experiments
    /// (of a whole reproduction) and the report.
    Results,
    /// Nowhere: the summary is printed only.
    DryRun,
    /// Compared with a baseline (the gate); nothing written.
    Gate(Baseline),
    /// Into the shard's own results directory, bound to the shard, with its manifest last.
    Shard(Shard),
}

/// What `reproduce run`, `check` and `shard` do with the selected runs.
#[derive(Debug)]
pub struct Plan<'a> {
    /// The selection the runs were chosen by (a shard records it; a whole one adds the control
    /// experiments).
    pub selection: &'a SelectionOptions,
    /// Where the rows go.
    pub output: Output,
    /// Whether the explanation layer follows written results.
    pub explain: bool,
}

/// Runs `jobs`, the selection of `all` (every run of the experiment files), as `plan` says.
pub fn run(
    project: &Project,
    plan: Plan<'_>,
    all: &Described,
    jobs: &[Job],
    git_rev: &str,
) -> Result<ExitCode, ReproduceError> {
    if matches!(plan.output, Output::Results) {
        precheck_report(project)?;
    }
    let writes = matches!(plan.output, Output::Results | Output::Shard(_));
    // One writer at a time: the lock is held until the process ends.
    let results = writes
        .then(|| open_results(project, git_rev, all))
        .transpose()?;
    let mut stored = results
        .as_ref()
        .map(|r| plan_pruning(project, r, all))
        .transpose()?;
    // A shard binds its directory before anything runs (records::shard::Binding); the
    // directory is finished only once its manifest is written again, at the end.
    let binding = match (&plan.output, &results) {
        (Output::Shard(shard), Some(results)) => {
            let binding = records::shard::Binding {
                shard: shard.k,
                shards: shard.n,
                experiments_hash: records::shard::experiments_hash(&project.experiments_dir)?,
                selection: plan.selection.selection(),
            };
            binding.claim(results)?;
            records::shard::Manifest::remove(&project.results_dir)?;
            Some(binding)
        }
        _ => None,
    };
    let mut to_run: Vec<Job> = jobs.to_vec();
    if let (Some(results), Some((kept, _))) = (&results, stored.as_mut()) {
        resume(results, git_rev, all, kept, &mut to_run)?;
    }
    let (records, unjournaled) = run_journaled(results.as_ref(), jobs, &to_run, git_rev)?;
    let rows: Vec<RunRow> = records.iter().map(|r| run_row(r, git_rev)).collect();
    emit(&summary(&rows));
    // Failed runs, and whether the experiment files' findings expect them (records::gate).
    let failed: Vec<(String, bool)> = rows
        .iter()
        .filter(|r| !r.completed())
        .map(|r| {
            (
                format!("{}: {}", r.key(), r.failure),
                records::gate::expected_to_diverge(r),
            )
        })
        .collect();
    let plan = match plan.output {
        Output::Gate(baseline) => return Ok(baseline.verdict(&rows, plan.selection.exact_only)),
        output => Plan { output, ..plan },
    };
    if let (Some(results), Some((kept, pruned))) = (&results, stored) {
        let untraced: Vec<&RunRecord> = records
            .iter()
            .filter(|r| unjournaled.contains(&r.job.key()))
            .collect();
        write_results(results, &untraced, kept, &pruned, rows)?;
        records::journal::remove(results.path())?;
        publish(
            project,
            &plan,
            results,
            binding.as_ref(),
            all,
            jobs,
            git_rev,
        )?;
    }
    let unexpected: Vec<String> = failed
        .iter()
        .filter(|(_, expected)| !expected)
        .map(|(line, _)| line.clone())
        .collect();
    if !failed.is_empty() {
        eprintln!(
            "{} of {} runs failed, {} of them expected (reasons in the table above and in results/runs.csv)",
            failed.len(),
            records.len(),
            failed.len() - unexpected.len()
        );
    }
    Ok(report_unexpected(&unexpected))
}

/// Before anything runs in a mode that renders the report: its directory lies inside the
/// project and can be written, and papers/ loads (the report reads it after the runs, so a
/// malformed paper is refused now). A results directory not named `results` gets no report,
/// which is said.
pub fn precheck_report(project: &Project) -> Result<(), ReproduceError> {
    match report_root(project) {
        Ok(root) => {
            check_report_dir(&root)?;
            load_papers(project)?;
        }
        Err(why) => eprintln!(
            "note: results go to {}, but {why}",
            project.results_dir.display()
        ),
    }
    Ok(())
}

/// What follows the written rows: a shard's manifest (of its `binding`, written last: the
/// shard is finished); otherwise the explanation layer (unless skipped), the control
/// experiments of a whole, unselected reproduction, and the report.
fn publish(
    project: &Project,
    plan: &Plan<'_>,
    results: &ResultsDir,
    binding: Option<&records::shard::Binding>,
    all: &Described,
    jobs: &[Job],
    git_rev: &str,
) -> Result<(), ReproduceError> {
    if let Some(binding) = binding {
        binding
            .manifest(git_rev, jobs.iter().map(|j| j.key().to_string()).collect())
            .write(&project.results_dir)?;
        eprintln!(
            "shard {}/{} done: merge with `reproduce merge {}...`",
            binding.shard,
            binding.shards,
            project.results_dir.display()
        );
        return Ok(());
    }
    if plan.explain && !plan.selection.exact_only {
        explain(project, jobs, all.jobs(), git_rev, Some(results))?;
    }
    // The control experiments (control crate) with a whole, unselected reproduction.
    if plan.selection.is_whole() {
        let budget = control::Budget::default();
        match control::reproduce(
            &project.experiments_dir,
            &project.results_dir,
            &budget,
            |m| eprintln!("{m}"),
        ) {
            Ok(s) => eprintln!(
                "control: {} runs, {} many-cycles runs, efficiency claim {}",
                s.control_runs,
                s.cycle_runs,
                s.verdict.label()
            ),
            Err(
                e @ (control::ControlError::UnknownTask(_) | control::ControlError::NoTaskSet(_)),
            ) => {
                eprintln!("control experiments skipped: {e}")
            }
            Err(e) => return Err(e.into()),
        }
        crate::timing::time_alone(all.jobs(), results, &project.root.join("papers"), git_rev)?;
        // Its tables are recorded before the report (which may fail) is rendered.
        results.save()?;
    }
    render_report_if_named(project, results)
}

/// Says the failures no experiment file expects (`unexpected`, one line each): exit code 1 if
/// there are any.
pub fn report_unexpected(unexpected: &[String]) -> ExitCode {
    if unexpected.is_empty() {
        return ExitCode::SUCCESS;
    }
    eprintln!("unexpected failures (exit code 1):");
    for line in unexpected {
        eprintln!("  {line}");
    }
    ExitCode::from(1)
}
