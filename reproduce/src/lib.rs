//! The logic of the `reproduce` binary: runs driftbench's experiments and writes `results/` and
//! `report/`. The binary (`main.rs`) parses the command line ([`Cli`]), calls [`run`](fn@run)
//! and prints the [`ReproduceError`] it may return.
//!
//! One module per mode: [`run`](mod@run) (the default, the gate of [`gate`], a shard, with its
//! [`journal`]), [`report`], [`explanation`], [`inference`], [`merge`], [`list`] (and robots),
//! [`cost`], [`score`] (a trajectory made elsewhere, also `driftbench.score` in Python); the
//! task cards the report mode writes ([`task_card`]); beside them what the modes share: the
//! command line ([`cli`], [`commands`], [`resolve`]), the selection of runs ([`select`]), the
//! results directory ([`results`]), the summary printed ([`summary`]) and the code revision
//! embedded at build time ([`revision`]).

pub mod cli;
pub mod commands;
pub mod cost;
pub mod error;
pub mod explanation;
pub mod gate;
pub mod inference;
pub mod journal;
pub mod list;
pub mod merge;
pub mod report;
pub mod resolve;
pub mod results;
pub mod revision;
pub mod run;
pub mod score;
pub mod select;
pub mod summary;
pub mod task_card;
pub mod timing;

pub use cli::Cli;
pub use error::ReproduceError;

use catalog::experiment::Job;
use std::process::ExitCode;
use summary::emit;

/// Runs the mode the command line `cli` asks for (its directories resolved first:
/// [`Cli::resolve`]); the exit code.
pub fn run(cli: Cli) -> Result<ExitCode, ReproduceError> {
    // The robots are compiled in (built-in models and the embedded robot files): listing them
    // needs no project.
    if cli.robots {
        emit(&list::robots());
        return Ok(ExitCode::SUCCESS);
    }
    let cli = &cli.resolve()?;
    let git_rev = revision::REVISION;
    if let (Some(file), Some(task)) = (&cli.score, &cli.task) {
        score::score(cli, file, task, git_rev)?;
        return Ok(ExitCode::SUCCESS);
    }
    if cli.report_only {
        report::report_only(cli, git_rev)?;
        return Ok(ExitCode::SUCCESS);
    }
    if cli.dof_cost {
        cost::dof_cost(cli, git_rev)?;
        return Ok(ExitCode::SUCCESS);
    }
    let files = results::experiment_files(cli)?;
    if cli.list && cli.merge.is_empty() {
        list_runs(cli, &files)?;
        return Ok(ExitCode::SUCCESS);
    }
    if !cli.merge.is_empty() {
        return merge::merge_shards(cli, &files, git_rev);
    }
    let selection = cli.selection();
    select::check_selection(&files, &selection)?;
    // Only the runs this process runs are collected (a shard's: an eighth of a 10^6-run
    // selection); every other run is made from the files when needed (results::Described).
    let mut selected = 0;
    let jobs: Vec<Job> = select::selected(&files, &selection)
        .inspect(|_| selected += 1)
        .filter(|j| owns(cli, j))
        .collect();
    if let Some(shard) = cli.shard_resolved {
        say_shard(cli, shard, jobs.len(), selected);
    }
    run::run(cli, &results::Described::new(&files), &jobs, git_rev)
}

/// `--list` (with `--shard K/N`: the shard's runs; with `--shards N`: the count per shard),
/// the runs made from `files` as they are written rather than collected: a list of 10^6 runs
/// holds none of them (docs/cluster.md).
fn list_runs(cli: &Cli, files: &[catalog::experiment::PaperFile]) -> Result<(), ReproduceError> {
    let selection = cli.selection();
    select::check_selection(files, &selection)?;
    if let Some(shard) = cli.shard_resolved {
        let owned = select::selected(files, &selection)
            .filter(|j| owns(cli, j))
            .count();
        say_shard(
            cli,
            shard,
            owned,
            select::selected(files, &selection).count(),
        );
    }
    // As `summary::emit`: a closed standard output (`reproduce --list | head`) ends the list
    // and is no error.
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    let _ = list::list(&mut out, files, |j| {
        select::selects(&selection, j) && owns(cli, j)
    })
    .and_then(|()| std::io::Write::flush(&mut out));
    if let (Some(n), None) = (cli.shards, cli.shard_resolved) {
        emit(&list::shard_plan(select::selected(files, &selection), n));
    }
    Ok(())
}

/// Whether `job` is the shard's of `--shard` (every job is, without it).
fn owns(cli: &Cli, job: &Job) -> bool {
    cli.shard_resolved
        .is_none_or(|shard| shard.owns(&job.key().to_string()))
}

/// The line a shard starts with: how many of the selected runs are its, and where it writes.
fn say_shard(cli: &Cli, shard: records::shard::Shard, owned: usize, selected: usize) {
    eprintln!(
        "shard {shard}: {owned} of the {selected} selected runs, into {}",
        cli.results_dir.display()
    );
}
