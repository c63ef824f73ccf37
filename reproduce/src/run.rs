//! `reproduce run` (the default; also `check`): everything that can be checked is checked
//! before anything runs (the gate's baseline, the report directory, the papers, the stored
//! results); then the selected runs run, resumed from and checkpointed in a journal; the
//! summary is printed; and the rows are compared with the baseline (the gate: with a whole
//! selection, the control experiments re-run too) or written with what follows them (the
//! explanation layer, the control experiments and the report), a run into `results/` timed
//! phase by phase ([`crate::phases`]: printed, and written where `--phases FILE` says). A
//! shard (`reproduce shard`) does not come here: [`crate::shard`] makes its runs as it runs
//! them and holds nothing per run. Runs that fail without their experiment file expecting it
//! are exit code 1.

use crate::baseline::Baseline;
use crate::error::ReproduceError;
use crate::explanation::explain;
use crate::journal::{resume, run_journaled};
use crate::options::SelectionOptions;
use crate::phases::{Phase, PhaseClock};
use crate::project::Project;
use crate::report::{held_runs, precheck_report, render_figures, render_pages, report_root};
use crate::results::{open_results, plan_pruning, write_results, Described};
use crate::summary::{emit, summary};
use records::RunRow;
use simulation::run_row;
use simulation::RunRecord;
use spec::{RunKey, RunSpec};
use std::process::ExitCode;
use std::time::Instant;
use store::results_dir::ResultsDir;

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
}

/// What `reproduce run` and `check` do with the selected runs.
#[derive(Debug)]
pub struct Plan<'a> {
    /// The selection the runs were chosen by (a whole one adds the control experiments).
    pub selection: &'a SelectionOptions,
    /// Where the rows go.
    pub output: Output,
    /// Whether the explanation layer follows written results.
    pub explain: bool,
    /// When the mode began: the start of the setup phase of the run's clock.
    pub started: Instant,
    /// Where the phase table is written as CSV (`--phases FILE`), if anywhere.
    pub phases: Option<&'a std::path::Path>,
}

/// Runs `jobs`, the selection of `all` (every run of the experiment files), as `plan` says.
pub fn run(
    project: &Project,
    plan: Plan<'_>,
    all: &Described,
    jobs: &[RunSpec],
    git_rev: &str,
) -> Result<ExitCode, ReproduceError> {
    if matches!(plan.output, Output::Results) {
        precheck_report(project, all)?;
    }
    let writes = matches!(plan.output, Output::Results);
    // One writer at a time: the lock is held until the process ends.
    let results = writes
        .then(|| open_results(project, git_rev, all))
        .transpose()?;
    let mut stored = results
        .as_ref()
        .map(|r| plan_pruning(project, r, all))
        .transpose()?;
    let mut to_run: Vec<RunSpec> = jobs.to_vec();
    if let (Some(results), Some((kept, _))) = (&results, stored.as_mut()) {
        resume(results, git_rev, all, kept, &mut to_run)?;
    }
    let mut clock = PhaseClock::since(plan.started);
    clock.lap(Phase::Setup, None);
    let resumed = jobs.len() - to_run.len();
    let (records, unjournaled) = run_journaled(results.as_ref(), jobs, &to_run, git_rev)?;
    let rows: Vec<RunRow> = records.iter().map(|r| run_row(r, git_rev)).collect();
    emit(&summary(&rows));
    // Failed runs, and whether the experiment files' findings expect them (analysis::gate).
    let failed: Vec<(String, bool)> = rows
        .iter()
        .filter(|r| !r.completed())
        .map(failure)
        .collect();
    let plan = match plan.output {
        Output::Gate(baseline) => {
            // The explanation the pages show, re-derived for the selected runs and compared
            // (the ladder and the attribution), where the baseline holds one.
            let explained = (!plan.selection.exact_only && baseline.explains(jobs))
                .then(|| crate::explanation::fresh(project, jobs, all.jobs()?, git_rev))
                .transpose()?;
            // The control experiments, re-run by a whole check where their runs are committed.
            let control = (plan.selection.is_whole() && !baseline.control.is_empty())
                .then(|| fresh_control(project, all.jobs()?))
                .transpose()?;
            return Ok(baseline.verdict(
                &rows,
                plan.selection.exact_only,
                explained.as_ref(),
                control.as_deref(),
            ));
        }
        output => Plan { output, ..plan },
    };
    if let (Some(results), Some((kept, pruned))) = (&results, stored) {
        let untraced: Vec<&RunRecord> = records
            .iter()
            .filter(|r| unjournaled.contains(&r.job.key()))
            .collect();
        write_results(results, &untraced, kept, &pruned, rows)?;
        store::journal::remove(results.path())?;
        clock.lap_noted(
            Phase::Runs,
            Some(jobs.len()),
            if resumed > 0 {
                format!("{resumed} of them resumed from the journal, not run again")
            } else {
                String::new()
            },
        );
        publish(project, &plan, results, all, jobs, git_rev, clock)?;
    }
    Ok(summarise_failures(
        &failed,
        records.len(),
        std::path::Path::new("results/runs.csv"),
    ))
}

/// The control experiments (control crate) run afresh for the gate, written into a scratch
/// directory (removed after) and read back: `results/` is not touched.
/// `jobs` is every run of the experiment files (the tasks are found among them).
fn fresh_control(
    project: &Project,
    jobs: &[RunSpec],
) -> Result<Vec<records::control::ControlRow>, ReproduceError> {
    let scratch =
        std::env::temp_dir().join(format!("driftbench-check-control-{}", std::process::id()));
    std::fs::create_dir_all(&scratch)
        .map_err(store::IoError::at(&scratch, store::IoAction::Write))?;
    eprintln!("re-running the control experiments for the gate");
    let ran = catalog::load_task_set(&project.experiments_dir)
        .map_err(ReproduceError::from)
        .and_then(|set| {
            control::reproduce(&set, jobs, &scratch, |m| eprintln!("{m}"))
                .map_err(ReproduceError::from)
        })
        .and_then(|_| {
            store::control::read(&scratch, store::results_dir::CONTROL)
                .map_err(|e| control::ControlError::from(e).into())
        });
    // The scratch copy is the gate's own; failing to remove it loses nothing.
    let _ = std::fs::remove_dir_all(&scratch);
    ran
}

/// zhong2021's efficiency claim judged from the control experiments' `checks`
/// (`analysis::control_claim::judge`), its rows written to `results/control-claim.csv` in
/// `results`; the overall verdict.
fn judge_claim(
    results: &std::path::Path,
    checks: Vec<records::control::ClaimCheck>,
) -> Result<records::control::Verdict, ReproduceError> {
    let claims: Vec<records::control::ClaimRow> = checks
        .into_iter()
        .map(analysis::control_claim::judge)
        .collect();
    store::control::write(results, store::results_dir::CONTROL_CLAIM, &claims)
        .map_err(control::ControlError::from)?;
    let verdicts: Vec<records::control::Verdict> = claims.iter().map(|c| c.verdict).collect();
    Ok(analysis::control_claim::overall(&verdicts))
}

/// What follows the written rows of a run into `results/`: the explanation layer (unless
/// skipped), the control experiments and the timing pass of a whole, unselected reproduction,
/// and the report, each a phase of `clock`, whose table ends the run (printed, and written to
/// `plan.phases` where given).
fn publish(
    project: &Project,
    plan: &Plan<'_>,
    results: &ResultsDir,
    all: &Described,
    jobs: &[RunSpec],
    git_rev: &str,
    mut clock: PhaseClock,
) -> Result<(), ReproduceError> {
    if !plan.explain {
        clock.skip(Phase::Explain, "--skip-explain".to_string());
    } else if plan.selection.exact_only {
        clock.skip(
            Phase::Explain,
            "--exact-only: no solver runs to explain".to_string(),
        );
    } else {
        let explained = explain(project, jobs, all.jobs()?, git_rev, Some(results))?;
        clock.lap(Phase::Explain, Some(explained));
    }
    // The control experiments (control crate) with a whole, unselected reproduction.
    if plan.selection.is_whole() {
        // The task set is the orchestrator's to read (catalog::load_task_set); the control crate
        // takes it as data. A project without one, or whose tasks are not among its runs,
        // has no control experiments.
        let ran = catalog::load_task_set(&project.experiments_dir)
            .map_err(ReproduceError::from)
            .and_then(|set| {
                control::reproduce(&set, all.jobs()?, &project.results_dir, |m| {
                    eprintln!("{m}")
                })
                .map_err(ReproduceError::from)
            });
        match ran {
            Ok(s) => {
                let verdict = judge_claim(&project.results_dir, s.claim_checks)?;
                eprintln!(
                    "control: {} runs, {} many-cycles runs, efficiency claim {}",
                    s.control_runs,
                    s.cycle_runs,
                    verdict.label()
                );
                clock.lap(Phase::Control, Some(s.control_runs + s.cycle_runs));
            }
            Err(
                e @ (ReproduceError::Control(control::ControlError::UnknownTask(_))
                | ReproduceError::TaskSet(catalog::TaskSetError::Missing(_))),
            ) => {
                eprintln!("control experiments skipped: {e}");
                clock.skip(Phase::Control, e.to_string());
            }
            Err(e) => return Err(e),
        }
        let timed =
            crate::timing::time_alone(all.jobs()?, results, &project.root.join("papers"), git_rev)?;
        // Its tables are recorded before the report (which may fail) is rendered.
        results.save()?;
        clock.lap(Phase::Timing, Some(timed));
    } else {
        let why = "only with a whole reproduction (no selection flags)";
        clock.skip(Phase::Control, why.to_string());
        clock.skip(Phase::Timing, why.to_string());
    }
    match report_root(project) {
        Ok(root) => {
            // `run --paper X` draws X's figures only (the pages are all re-rendered: they
            // are cheap, and the front page summarises every paper).
            let keys = all.keys()?;
            let traced = |key: &RunKey| keys.traced(key);
            let held = held_runs(results, &traced)?;
            let paper = plan.selection.paper.as_deref();
            let figures = render_figures(&root, paper, &held, &traced)?;
            keys.check()?;
            clock.lap(Phase::Figures, Some(figures));
            render_pages(project, &root, results, all.files(), held)?;
            clock.lap(Phase::Report, None);
        }
        Err(why) => {
            eprintln!("report not rendered: {why}");
            clock.skip(Phase::Figures, why.to_string());
            clock.skip(Phase::Report, why.to_string());
        }
    }
    let (machine, cores) = crate::cost::machine();
    let rows = clock.rows(&crate::phases::RunContext {
        selection: plan.selection.selection().to_string(),
        whole: plan.selection.is_whole(),
        machine,
        cores,
        git_rev: git_rev.to_string(),
    });
    if let Some(path) = plan.phases {
        crate::phases::write(path, &rows)?;
        eprintln!("phase table written to {}", path.display());
    }
    eprint!("{}", crate::phases::table(&rows));
    Ok(())
}

/// A failed run's line for the user, and whether its experiment file expects the failure
/// (analysis::gate).
pub(crate) fn failure(row: &RunRow) -> (String, bool) {
    (
        format!("{}: {}", row.key(), row.failure),
        analysis::gate::expected_to_diverge(row),
    )
}

/// Says how many of `total` runs failed (`failed`: each failure's line and whether its
/// experiment file expects it) and how many of them were expected, their reasons in `table`;
/// then the unexpected ones ([`report_unexpected`]).
pub(crate) fn summarise_failures(
    failed: &[(String, bool)],
    total: usize,
    table: &std::path::Path,
) -> ExitCode {
    let unexpected: Vec<String> = failed
        .iter()
        .filter(|(_, expected)| !expected)
        .map(|(line, _)| line.clone())
        .collect();
    if !failed.is_empty() {
        eprintln!(
            "{} of {total} runs failed, {} of them expected (reasons in the table above and in {})",
            failed.len(),
            failed.len() - unexpected.len(),
            table.display()
        );
    }
    report_unexpected(&unexpected)
}

/// Says the failures no experiment file expects (`unexpected`, one line each):
/// [`Exit::UnexpectedFailure`](crate::error::Exit::UnexpectedFailure) (exit code 1) if there
/// are any.
pub fn report_unexpected(unexpected: &[String]) -> ExitCode {
    if unexpected.is_empty() {
        return ExitCode::SUCCESS;
    }
    eprintln!(
        "unexpected failures (exit code {}):",
        crate::error::Exit::UnexpectedFailure.code()
    );
    for line in unexpected {
        eprintln!("  {line}");
    }
    crate::error::Exit::UnexpectedFailure.into()
}
