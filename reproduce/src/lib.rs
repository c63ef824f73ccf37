//! The logic of the `reproduce` binary: runs driftbench's experiments and writes `results/` and
//! `report/`. The binary (`main.rs`) parses the command line ([`Cli`]) into the global options
//! and a [`Mode`] with its options ([`options`]), calls [`run`](fn@run) and prints the
//! [`ReproduceError`] it may return (its exit code: [`Exit`]). A program may call
//! [`run`](fn@run) with options it built itself: the library never sees the command line.
//!
//! One module per mode, each private: `run` (the default, the gate against a baseline, with
//! its journal and its [`phases`] clock), `shard` (a shard in flat memory), `report`,
//! `explanation`, `inference`, `merge`, `list` (and robots), [`cost`], `score` (a trajectory
//! made elsewhere, [`score_file`], also `driftbench.score` in Python); the task cards the report
//! mode writes (`task_card`, [`task_cards`]); beside them what the modes share: the options
//! ([`options`]), the command line (`cli`), the project's directories (`project`), the
//! experiment files with every run checked ([`load_experiments`], [`experiments_from_toml`]),
//! the papers as data (`papers`), the selection of runs (`select`), the results directory
//! (`results`), the summary printed (`summary`) and the code revision embedded at build time
//! ([`REVISION`]).
//!
//! Three modules are public, each a vocabulary of its own: [`options`] (what a program builds
//! to call [`run`](fn@run)), [`cost`] (the cost harness, which the benches time) and [`phases`]
//! (the phase table's schema, which the benches read); everything else other crates and the
//! tests use is re-exported here.

mod baseline;
mod cli;
pub mod cost;
mod error;
mod experiments;
mod explanation;
mod inference;
mod journal;
mod list;
mod merge;
pub mod options;
mod papers;
pub mod phases;
mod project;
mod report;
mod results;
mod revision;
mod run;
mod score;
mod select;
mod shard;
mod summary;
mod task_card;
mod timing;

pub use cli::Cli;
pub use error::{Exit, ReproduceError, ScoreError};
pub use experiments::{from_toml as experiments_from_toml, load_dir as load_experiments};
pub use options::{GlobalOptions, Mode};
pub use revision::REVISION;
pub use score::{score_file, Scored, Warning as ScoreWarning};
pub use shard::CHUNK_VAR as SHARD_CHUNK_VAR;
pub use task_card::{cards as task_cards, MAX_SWEEP_CARDS, TASKS as TASK_CARDS};

use catalog::PaperFile;
use options::SelectionOptions;
use project::{resolve_shard, set_threads, Project};
use results::{experiment_files, Described};
use run::{Output, Plan};
use spec::RunSpec;
use std::process::ExitCode;
use store::shard::Shard;
use summary::emit;

/// Runs `mode` on the project of `global`; the exit code.
pub fn run(global: &GlobalOptions, mode: Mode) -> Result<ExitCode, ReproduceError> {
    // The setup phase of a run's clock (crate::phases) begins here.
    let started = std::time::Instant::now();
    set_threads(global.threads)?;
    let git_rev = revision::REVISION;
    let env = |v: &str| std::env::var(v).ok();
    let project = |shard: Option<Shard>| Project::resolve(global, shard);

    match mode {
        // The suite's robots are compiled in (built-in models and the embedded robot files):
        // listing them needs no project; in one, the papers' own robot files are listed too.
        Mode::Robots => {
            let _ = project(None);
            emit(&list::robots());
            Ok(ExitCode::SUCCESS)
        }
        Mode::Score(o) => {
            score::score(&project(None)?, &o, git_rev)?;
            Ok(ExitCode::SUCCESS)
        }
        Mode::Report => {
            report::report_only(&project(None)?, git_rev)?;
            Ok(ExitCode::SUCCESS)
        }
        Mode::Cost(o) => {
            cost::dof_cost(&project(None)?, o.dry_run, git_rev)?;
            Ok(ExitCode::SUCCESS)
        }
        Mode::Merge(o) => {
            let project = project(None)?;
            let files = experiment_files(&project)?;
            merge::merge_shards(&project, &o.dirs, &files, git_rev, !o.no_report)
        }
        Mode::Infer(o) => {
            let project = project(None)?;
            let files = experiment_files(&project)?;
            inference::infer_mode(&project, &o, &Described::new(&files), git_rev)?;
            Ok(ExitCode::SUCCESS)
        }
        Mode::Explain(o) => {
            let project = project(None)?;
            let files = experiment_files(&project)?;
            let jobs = selected(&files, &o.selection)?;
            explanation::explain_mode(&project, &o, &jobs, &Described::new(&files), git_rev)?;
            Ok(ExitCode::SUCCESS)
        }
        Mode::List(o) => {
            let shard = o
                .shard
                .map(|s| resolve_shard(s, o.shards, env))
                .transpose()?;
            let project = project(shard)?;
            let files = experiment_files(&project)?;
            list_runs(&project, &files, &o.selection, shard, o.shards)?;
            Ok(ExitCode::SUCCESS)
        }
        Mode::Run(o) => run_selection(&project(None)?, &o, started),
        Mode::Check(o) => check_against_baseline(&project(None)?, &o, started),
        Mode::Shard(o) => {
            let shard = resolve_shard(o.shard, o.shards, env)?;
            run_shard(&project(Some(shard))?, &o, shard)
        }
    }
}

/// `reproduce` (the default mode): the selected runs into `results/` (or nowhere with
/// `--dry-run`), the explanation layer unless skipped, and the report; `started` is when the
/// run's setup phase began.
fn run_selection(
    project: &Project,
    o: &options::RunOptions,
    started: std::time::Instant,
) -> Result<ExitCode, ReproduceError> {
    let files = experiment_files(project)?;
    let jobs = selected(&files, &o.selection)?;
    let output = if o.dry_run {
        Output::DryRun
    } else {
        Output::Results
    };
    let plan = Plan {
        selection: &o.selection,
        output,
        explain: !o.skip_explain,
        started,
        phases: o.phases.as_deref(),
    };
    run::run(
        project,
        plan,
        &Described::new(&files),
        &jobs,
        revision::REVISION,
    )
}

/// `reproduce check`: the selected runs against the committed rows or `--baseline` (the
/// regression gate), nothing written.
fn check_against_baseline(
    project: &Project,
    o: &options::CheckOptions,
    started: std::time::Instant,
) -> Result<ExitCode, ReproduceError> {
    let files = experiment_files(project)?;
    let all = Described::new(&files);
    let jobs = selected(&files, &o.selection)?;
    let baseline = baseline::Baseline::read(
        &project.root,
        &project.results_dir,
        o.baseline.as_deref(),
        all.jobs()?,
    )?;
    let plan = Plan {
        selection: &o.selection,
        output: Output::Gate(baseline),
        explain: false,
        started,
        phases: None,
    };
    run::run(project, plan, &all, &jobs, revision::REVISION)
}

/// `reproduce shard K/N`: the runs of the selection that `shard` owns, into its own results
/// directory (the `project`'s), made as they are run ([`shard`](mod@shard)).
fn run_shard(
    project: &Project,
    o: &options::ShardOptions,
    shard: Shard,
) -> Result<ExitCode, ReproduceError> {
    let files = experiment_files(project)?;
    let selection = o.selection.selection();
    select::check_selection(&files, &selection)?;
    let kept = select::Kept {
        selection: &selection,
        shard: Some(shard),
    };
    let total = kept.total(&files);
    say_shard(project, shard, kept.owned_in(0, total), total);
    crate::shard::run_shard(
        project,
        &o.selection,
        shard,
        &Described::new(&files),
        kept,
        revision::REVISION,
    )
}

/// The runs of `files` that `selection` keeps, collected (a shard makes its own as it runs
/// them instead: [`run_shard`]); every other run is made from the files when needed
/// (results::Described).
fn selected(
    files: &[PaperFile],
    selection: &SelectionOptions,
) -> Result<Vec<RunSpec>, ReproduceError> {
    let selection = selection.selection();
    select::check_selection(files, &selection)?;
    select::selected(files, &selection).collect()
}

/// `list` (with a shard: the shard's runs; with `shards`: the count per shard), the runs made
/// from `files` as they are written rather than collected, and with a shard only the shard's
/// made: a list of 10^6 runs holds none of them, and a shard's list makes its runs alone
/// (docs/cluster.md).
fn list_runs(
    project: &Project,
    files: &[PaperFile],
    selection: &SelectionOptions,
    shard: Option<Shard>,
    shards: Option<usize>,
) -> Result<(), ReproduceError> {
    let selection = selection.selection();
    select::check_selection(files, &selection)?;
    let kept = select::Kept {
        selection: &selection,
        shard,
    };
    let total = kept.total(files);
    if let Some(shard) = shard {
        say_shard(project, shard, kept.owned_in(0, total), total);
    }
    // As `summary::emit`: a closed standard output (`reproduce list | head`) ends the list and
    // is no error.
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    list::list(&mut out, files, kept)?;
    let _ = std::io::Write::flush(&mut out);
    if let (Some(n), None) = (shards, shard) {
        emit(&list::shard_plan(total, n));
    }
    Ok(())
}

/// The line a shard starts with: how many of the selected runs are its, and where it writes.
fn say_shard(project: &Project, shard: Shard, owned: usize, selected: usize) {
    eprintln!(
        "shard {shard}: {owned} of the {selected} selected runs, into {}",
        project.results_dir.display()
    );
}
