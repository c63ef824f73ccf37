//! The logic of the `reproduce` binary: runs driftbench's experiments and writes `results/` and
//! `report/`. The binary (`main.rs`) parses the command line ([`Cli`]) into the global options
//! and a [`Mode`] with its options ([`options`]), calls [`run`](fn@run) and prints the
//! [`ReproduceError`] it may return. A program may call [`run`](fn@run) with options it built
//! itself: the library never sees the command line.
//!
//! One module per mode: [`run`](mod@run) (the default, the gate of [`gate`], a shard, with its
//! [`journal`]), [`report`], [`explanation`], [`inference`], [`merge`], [`list`] (and robots),
//! [`cost`], [`score`] (a trajectory made elsewhere, also `driftbench.score` in Python); the
//! task cards the report mode writes ([`task_card`]); beside them what the modes share: the
//! options ([`options`]), the command line ([`cli`], [`aliases`]), the project's directories
//! ([`project`]), the selection of runs ([`select`]), the results directory ([`results`]), the
//! summary printed ([`summary`]) and the code revision embedded at build time ([`revision`]).

pub mod aliases;
pub mod cli;
pub mod cost;
pub mod error;
pub mod explanation;
pub mod gate;
pub mod inference;
pub mod journal;
pub mod list;
pub mod merge;
pub mod options;
pub mod project;
pub mod report;
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
pub use options::{GlobalOptions, Mode};

use catalog::experiment::{load_dir, Job, PaperFile};
use options::SelectionOptions;
use project::{resolve_shard, set_threads, Project};
use records::shard::Shard;
use run::{Output, Plan};
use std::process::ExitCode;
use summary::emit;

/// Runs `mode` on the project of `global`; the exit code.
pub fn run(global: &GlobalOptions, mode: Mode) -> Result<ExitCode, ReproduceError> {
    set_threads(global.threads)?;
    let git_rev = revision::REVISION;
    let env = |v: &str| std::env::var(v).ok();
    let project = |shard: Option<Shard>| Project::resolve(global, shard);
    let loaded = |project: &Project| -> Result<(Vec<PaperFile>, Vec<Job>), ReproduceError> {
        let files = load_dir(&project.experiments_dir, simulation::run::check_job)?;
        let all = files.iter().flat_map(|f| f.jobs()).collect();
        Ok((files, all))
    };
    let selected = |files: &[PaperFile], all: &[Job], selection: &SelectionOptions| {
        select::select_jobs(all, files, &selection.selection())
    };
    match mode {
        // The robots are compiled in (built-in models and the embedded robot files): listing
        // them needs no project.
        Mode::Robots => {
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
            let (files, all) = loaded(&project)?;
            merge::merge_shards(&project, &o.dirs, &files, &all, git_rev)
        }
        Mode::Infer(o) => {
            let project = project(None)?;
            let (_, all) = loaded(&project)?;
            inference::infer_mode(&project, &o, &all, git_rev)?;
            Ok(ExitCode::SUCCESS)
        }
        Mode::Explain(o) => {
            let project = project(None)?;
            let (files, all) = loaded(&project)?;
            let jobs = selected(&files, &all, &o.selection)?;
            explanation::explain_mode(&project, &o, &jobs, &all, git_rev)?;
            Ok(ExitCode::SUCCESS)
        }
        Mode::List(o) => {
            let shard = o
                .shard
                .as_deref()
                .map(|s| resolve_shard(s, o.shards, env))
                .transpose()?;
            let project = project(shard)?;
            let (files, all) = loaded(&project)?;
            let jobs = shard_of(shard, selected(&files, &all, &o.selection)?, &project);
            emit(&list::list(&files, &jobs));
            if let (Some(n), None) = (o.shards, shard) {
                emit(&list::shard_plan(&jobs, n));
            }
            Ok(ExitCode::SUCCESS)
        }
        Mode::Run(o) => {
            let project = project(None)?;
            let (files, all) = loaded(&project)?;
            let jobs = selected(&files, &all, &o.selection)?;
            let output = if o.dry_run {
                Output::DryRun
            } else {
                Output::Results
            };
            let plan = Plan {
                selection: &o.selection,
                output,
                explain: !o.skip_explain,
            };
            run::run(&project, plan, &all, &jobs, git_rev)
        }
        Mode::Check(o) => {
            let project = project(None)?;
            let (files, all) = loaded(&project)?;
            let jobs = selected(&files, &all, &o.selection)?;
            let baseline = gate::Baseline::read(
                &project.root,
                &project.results_dir,
                o.baseline.as_deref(),
                &all,
            )?;
            let plan = Plan {
                selection: &o.selection,
                output: Output::Gate(baseline),
                explain: false,
            };
            run::run(&project, plan, &all, &jobs, git_rev)
        }
        Mode::Shard(o) => {
            let shard = resolve_shard(&o.shard, o.shards, env)?;
            let project = project(Some(shard))?;
            let (files, all) = loaded(&project)?;
            let jobs = shard_of(Some(shard), selected(&files, &all, &o.selection)?, &project);
            let plan = Plan {
                selection: &o.selection,
                output: Output::Shard(shard),
                explain: false,
            };
            run::run(&project, plan, &all, &jobs, git_rev)
        }
    }
}

/// The runs of `jobs` that `shard` owns (all of them without a shard), said on stderr.
fn shard_of(shard: Option<Shard>, mut jobs: Vec<Job>, project: &Project) -> Vec<Job> {
    if let Some(shard) = shard {
        let selected = jobs.len();
        jobs.retain(|j| shard.owns(&j.key().to_string()));
        eprintln!(
            "shard {shard}: {} of the {selected} selected runs, into {}",
            jobs.len(),
            project.results_dir.display()
        );
    }
    jobs
}
