//! `reproduce run` (the default; also `check`, `shard`, `explain`, `infer`): everything that
//! can be checked is checked before anything runs (the gate's baseline, the report directory,
//! the papers, the stored results); then the selected runs run, resumed from and checkpointed in a journal;
//! the summary is printed; and the rows are compared with the baseline (the gate) or written
//! with what follows them (a shard's manifest, or the explanation layer, the control
//! experiments and the report). Runs that fail without their experiment file expecting it are
//! exit code 1.

use crate::cli::Cli;
use crate::error::ReproduceError;
use crate::explanation::{explain, load_papers};
use crate::gate::Baseline;
use crate::inference::infer;
use crate::journal::{resume, run_journaled};
use crate::report::{check_report_dir, render_report_if_named, report_root};
use crate::results::{open_results, plan_pruning, write_results, Described};
use crate::summary::{emit, summary};
use catalog::experiment::Job;
use records::results_dir::ResultsDir;
use records::runs::RunRow;
use simulation::row::run_row;
use simulation::run::RunRecord;
use std::process::ExitCode;

/// Runs `jobs`, the selection of `all` (every run of the experiment files).
pub fn run(
    cli: &Cli,
    all: &Described,
    jobs: &[Job],
    git_rev: &str,
) -> Result<ExitCode, ReproduceError> {
    let baseline = cli
        .check
        .then(|| {
            Baseline::read(
                &cli.project_root,
                &cli.results_dir,
                cli.baseline.as_deref(),
                all.jobs(),
            )
        })
        .transpose()?;
    if !cli.check && !cli.dry_run && cli.shard_resolved.is_none() {
        match report_root(cli) {
            // The report reads papers/ after the runs: a malformed paper is refused before.
            Ok(root) => {
                check_report_dir(&root)?;
                load_papers(cli)?;
            }
            Err(why) => eprintln!(
                "note: results go to {}, but {why}",
                cli.results_dir.display()
            ),
        }
    }
    if let Some(t) = cli.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t as usize)
            .build_global()?;
    }
    // One writer at a time: the lock is held until the process ends.
    let results = (!cli.check && !cli.dry_run)
        .then(|| open_results(cli, git_rev, all))
        .transpose()?;
    if let Some(which) = &cli.infer {
        infer(cli, which, all.jobs(), results.as_ref())?;
        return Ok(ExitCode::SUCCESS);
    }
    if cli.explain_only {
        explain(cli, jobs, all.jobs(), git_rev, results.as_ref())?;
        return Ok(ExitCode::SUCCESS);
    }
    let mut stored = results
        .as_ref()
        .map(|r| plan_pruning(cli, r, all))
        .transpose()?;
    // A shard binds its directory before anything runs (records::shard::Binding); the
    // directory is finished only once its manifest is written again, at the end.
    let binding = match (cli.shard_resolved, &results) {
        (Some(shard), Some(results)) => {
            let binding = records::shard::Binding {
                shard: shard.k,
                shards: shard.n,
                experiments_hash: records::shard::experiments_hash(&cli.experiments_dir)?,
                selection: cli.selection(),
            };
            binding.claim(results)?;
            records::shard::Manifest::remove(&cli.results_dir)?;
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
    if let Some(baseline) = baseline {
        return Ok(baseline.verdict(&rows, cli.exact_only));
    }
    if let (Some(results), Some((kept, pruned))) = (&results, stored) {
        let untraced: Vec<&RunRecord> = records
            .iter()
            .filter(|r| unjournaled.contains(&r.job.key()))
            .collect();
        write_results(results, &untraced, kept, &pruned, rows)?;
        records::journal::remove(results.path())?;
        publish(cli, results, binding.as_ref(), all, jobs, git_rev)?;
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

/// What follows the written rows: a shard's manifest (of its `binding`, written last: the
/// shard is finished); otherwise the explanation layer (unless skipped), the control
/// experiments of a whole, unselected reproduction, and the report.
fn publish(
    cli: &Cli,
    results: &ResultsDir,
    binding: Option<&records::shard::Binding>,
    all: &Described,
    jobs: &[Job],
    git_rev: &str,
) -> Result<(), ReproduceError> {
    if let Some(binding) = binding {
        binding
            .manifest(git_rev, jobs.iter().map(|j| j.key().to_string()).collect())
            .write(&cli.results_dir)?;
        eprintln!(
            "shard {}/{} done: merge with `reproduce --merge {}...`",
            binding.shard,
            binding.shards,
            cli.results_dir.display()
        );
        return Ok(());
    }
    if !cli.skip_explain && !cli.exact_only {
        explain(cli, jobs, all.jobs(), git_rev, Some(results))?;
    }
    // The control experiments (control crate) with a whole, unselected reproduction.
    if !cli.exact_only && cli.paper.is_none() && cli.experiment.is_empty() {
        let budget = control::Budget::default();
        match control::reproduce(&cli.experiments_dir, &cli.results_dir, &budget, |m| {
            eprintln!("{m}")
        }) {
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
        crate::timing::time_alone(
            all.jobs(),
            results,
            &cli.project_root.join("papers"),
            git_rev,
        )?;
        // Its tables are recorded before the report (which may fail) is rendered.
        results.save()?;
    }
    render_report_if_named(cli, results)
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
