//! `cargo run --release -p reproduce`: runs driftbench's experiments and writes `results/`.

mod commands;

use clap::{CommandFactory, FromArgMatches, Parser};
use records::results_dir::ResultsDir;
use records::runs::{check_rows, merge, RunRow};
use records::tracked_dir::Edits;
use simulation::experiment::{load_dir, Job, PaperFile};
use simulation::run::RunRecord;
use simulation::run_key::RunKey;
use simulation::runner::run_jobs_with;
use std::collections::HashSet;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Regenerates the tables and error data of four papers on drift-free redundancy resolution
/// (jia2019, zhang2018, zhong2021, kong2019), solving every scheme's QP exactly with Clarabel
/// along every run and scoring each paper's neural solver against that optimum.
///
/// With no flags (or `run`): runs every experiment in experiments/*.toml (in parallel), writes
/// results/runs.csv (one row per run) and results/traces/, and prints a summary table. Each
/// other mode is a subcommand or, equally, its flag (listed below the options).
#[derive(Parser, Debug)]
#[command(version, about, long_about)]
struct Cli {
    /// Run only this paper's experiments (jia2019, zhang2018, zhong2021, kong2019; `cross` is
    /// the suite's own cross experiment: every velocity-level solver on every velocity-level
    /// scheme and path).
    #[arg(long)]
    paper: Option<String>,
    /// Run only this experiment (an id of docs/experiments.md, e.g. jia2019-clover). Repeatable.
    #[arg(long)]
    experiment: Vec<String>,
    /// Run only the exact column (the QP solved to optimality in the loop: certified active set, Clarabel where it cannot certify), no neural solvers.
    #[arg(long)]
    exact_only: bool,
    /// List the experiments and their runs, then exit.
    #[arg(long)]
    list: bool,
    /// List the robots experiment files can name (Jaco2 variants, Katana 6M180, Franka Panda,
    /// the n-link family) with their joint counts and check values (tip position and singular
    /// values of J at a stated pose), then exit.
    #[arg(long)]
    robots: bool,
    /// The project root: the directory with experiments/, results/ and report/ (default: the
    /// nearest directory at or above the working directory that has an experiments/ folder).
    #[arg(long, value_name = "DIR")]
    root: Option<PathBuf>,
    /// Directory of the experiment files (default: ROOT/experiments).
    #[arg(long = "experiments-dir", value_name = "DIR")]
    experiments_dir_arg: Option<PathBuf>,
    /// Directory results are written to (default: ROOT/results); the report goes beside it.
    #[arg(long = "results-dir", value_name = "DIR")]
    results_dir_arg: Option<PathBuf>,
    /// The resolved project root, experiments and results directories.
    #[arg(skip)]
    project_root: PathBuf,
    #[arg(skip)]
    experiments_dir: PathBuf,
    #[arg(skip)]
    results_dir: PathBuf,
    /// Do not write results/ or report/ (print the summary only).
    #[arg(long)]
    dry_run: bool,
    /// The regression gate: run the selected experiments and compare them with the committed
    /// results/runs.csv of git HEAD (or --baseline; status, drifts, max position error); write nothing; exit 1 on any
    /// difference. `cargo test --workspace --release` runs the same gate over everything.
    #[arg(long)]
    check: bool,
    /// The gate's baseline (default: git HEAD's committed results/runs.csv, or the results
    /// directory's runs.csv outside a checkout). Read before anything runs.
    #[arg(long, value_name = "FILE", requires = "check")]
    baseline: Option<PathBuf>,
    /// Re-render report/REPORT.md and report/figures/ from the stored results/ without running
    /// anything, then exit.
    #[arg(long, conflicts_with_all = ["paper", "experiment", "exact_only", "list", "check", "baseline", "skip_explain", "explain_only", "infer", "dof_cost", "shard", "shards", "merge", "dry_run", "prune"])]
    report_only: bool,
    /// Worker threads (default: all cores; at most MAX_THREADS_PER_CORE times the cores).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    threads: Option<u64>,
    /// Take result files that differ from results/manifest.toml (edited, truncated, copied in
    /// by hand) as they are, instead of refusing to start. Say it only when the edit is
    /// deliberate; the manifest is then written anew.
    #[arg(long)]
    accept_edited: bool,
    /// Allow pruning more than a quarter of the stored runs (those no experiment file
    /// describes any more). Without it such a run stops before anything runs, naming the
    /// experiments directory and the count: an empty or wrong --experiments-dir must not wipe
    /// the results.
    #[arg(long)]
    prune: bool,
    /// Skip the explanation runs (tolerance ladders, drift attribution) that a normal run
    /// adds for the selected runs of the papers' solvers and of the group-code experiments.
    #[arg(long, conflicts_with = "explain_only")]
    skip_explain: bool,
    /// Run only the explanation runs of the selection (ladders and attribution; writes
    /// results/ladder.csv and results/attribution.csv and the report), not the runs themselves.
    #[arg(long)]
    explain_only: bool,
    /// Setup inference: fit the parameters the papers leave open (path pose and plane tilt,
    /// size where it is assumed, direction, RMP reading; robot variant and MATLAB-default
    /// tolerances as discrete hypotheses; experiments/inference/family.toml) to a published
    /// drift table, jointly and column by column; `all`, a paper
    /// (`jia2019`), one table (`jia2019:T2`) or a comma-separated list of these. Writes
    /// results/inference.csv and
    /// results/inference-entries.csv (each table as it finishes), then re-renders the report.
    /// Takes minutes per table.
    #[arg(long, value_name = "TABLE")]
    infer: Option<String>,
    /// Cost against the number of joints: time scheme build, network RHS and Jacobian, the
    /// exact solve (active set and Clarabel), the dense KKT floor and whole runs on the n-link
    /// arms (N = 3 ... 30; kong2019 to N = 200 on dynamic-size types, the dense LUs on nalgebra
    /// and faer) with jia2019's and kong2019's schemes (crate cost), write
    /// results/dof-cost.csv (with the fitted growth exponents and the machine), then re-render
    /// the report. Takes about a minute; run it on an otherwise idle machine.
    #[arg(long, conflicts_with_all = ["check", "report_only", "explain_only", "infer", "merge", "shard"])]
    dof_cost: bool,
    /// Cluster runs (docs/cluster.md): run only shard K of N of the selected runs (K = 1..N; a
    /// run's shard is a stable hash of its key) into ROOT/results-shard-K-of-N/ (or
    /// --results-dir): runs.csv, traces/ and, written last, shard.toml. Implies --skip-explain
    /// and renders no report. A shard started again resumes from its journal. `--shard auto` (or
    /// `--shard` alone) takes K and N from a Slurm job array (SLURM_ARRAY_TASK_ID, minus
    /// SLURM_ARRAY_TASK_MIN - 1, of SLURM_ARRAY_TASK_COUNT) or a Kubernetes Indexed Job
    /// (JOB_COMPLETION_INDEX + 1, of --shards or DRIFTBENCH_SHARDS). With --list: the shard's runs.
    #[arg(long, value_name = "K/N", num_args = 0..=1, default_missing_value = "auto",
          conflicts_with_all = ["check", "report_only", "explain_only", "infer", "merge"])]
    shard: Option<String>,
    /// The number of shards N for `--shard auto` under Kubernetes; with --list and no --shard:
    /// print how many of the selected runs each of N shards gets.
    #[arg(long, value_name = "N")]
    shards: Option<usize>,
    /// Merge finished shard directories (of `--shard K/N`) into results/ and render the report:
    /// checks that they agree on N and on the experiment files and that every selected run (the
    /// selection the shards were given) is in exactly one shard; otherwise names the missing
    /// or duplicated runs (and the shard that should have produced them), writes nothing and
    /// exits 2. Does not run the explanation layer: run `reproduce --explain-only` afterwards
    /// if wanted.
    #[arg(long, value_name = "DIR", num_args = 1..,
          conflicts_with_all = ["check", "report_only", "explain_only", "infer", "paper", "experiment", "exact_only", "dry_run", "list", "skip_explain"])]
    merge: Vec<PathBuf>,
    /// The resolved shard of `--shard`.
    #[arg(skip)]
    shard_resolved: Option<records::shard::Shard>,
    /// Score a trajectory produced elsewhere (CSV: t, theta_1..n, optionally thetadot_1..n) on
    /// the task --task, as a run is scored; writes scores.csv, its trace and figure under
    /// --score-out, then exits (presentation::score).
    #[arg(long, value_name = "FILE", requires = "task")]
    score: Option<PathBuf>,
    /// The task of --score: "<experiment> / <variant>".
    #[arg(long, value_name = "ID", requires = "score")]
    task: Option<String>,
    /// Where --score writes (default: scores/ in the working directory).
    #[arg(long = "score-out", value_name = "DIR", default_value = "scores")]
    score_out: PathBuf,
}

/// `--threads` may ask for at most this many worker threads per core: more only adds
/// contention, and a mistyped count (100000) must not stall the machine before it says so.
const MAX_THREADS_PER_CORE: usize = 4;

fn main() -> ExitCode {
    let args = commands::to_flags(std::env::args().collect());
    let cli = Cli::command()
        .after_help(commands::help())
        .get_matches_from(args);
    let cli = match Cli::from_arg_matches(&cli) {
        Ok(cli) => cli,
        Err(e) => e.exit(),
    };
    match resolve_dirs(cli).and_then(real_main) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// Fills in the project root (`--root`, else found from the working directory) and the
/// experiments and results directories under it, unless given; checks the thread count.
fn resolve_dirs(mut cli: Cli) -> Result<Cli, String> {
    if let Some(t) = cli.threads {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let max = MAX_THREADS_PER_CORE * cores;
        if t as usize > max {
            return Err(format!(
                "--threads {t}: at most {max} ({MAX_THREADS_PER_CORE} per core; this machine has {cores})"
            ));
        }
    }
    let root = match &cli.root {
        Some(r) => r.clone(),
        None => simulation::root::from_current_dir().map_err(|e| e.to_string())?,
    };
    cli.experiments_dir = cli
        .experiments_dir_arg
        .clone()
        .unwrap_or_else(|| root.join("experiments"));
    cli.shard_resolved = match cli.shard.as_deref() {
        None => None,
        Some("auto") => Some(
            records::shard::Shard::from_env(|v| std::env::var(v).ok(), cli.shards)
                .map_err(|e| e.to_string())?,
        ),
        Some(kn) => Some(records::shard::Shard::parse(kn).map_err(|e| e.to_string())?),
    };
    let results = match cli.shard_resolved {
        Some(s) => s.dir_name(),
        None => "results".to_string(),
    };
    cli.results_dir = cli
        .results_dir_arg
        .clone()
        .unwrap_or_else(|| root.join(results));
    cli.project_root = root;
    Ok(cli)
}

/// Opens the results directory for writing (records::results_dir): the lock, the integrity
/// check of its tables, the removal of this program's own stale temporary files.
/// Every run the experiment files describe (what migration and pruning compare the stored
/// runs with).
fn all_jobs(cli: &Cli) -> Result<Vec<Job>, String> {
    Ok(load_dir(&cli.experiments_dir)
        .map_err(|e| e.to_string())?
        .iter()
        .flat_map(|f| f.jobs())
        .collect())
}

/// `all`: every run of the experiment files ([`all_jobs`]), by which results written before
/// run ids are migrated.
fn open_results(cli: &Cli, git_rev: &str, all: &[Job]) -> Result<ResultsDir, String> {
    let edits = if cli.accept_edited {
        Edits::Accept
    } else {
        Edits::Refuse
    };
    let (results, removed) =
        ResultsDir::open(&cli.results_dir, git_rev, edits).map_err(|e| e.to_string())?;
    if !removed.is_empty() {
        eprintln!(
            "removed {} stale temporary file(s) of interrupted runs under {}",
            removed.len(),
            cli.results_dir.display()
        );
    }
    // Results written before run ids are migrated once (records::migrate).
    for done in results.migrate_ids(all).map_err(|e| e.to_string())? {
        eprintln!(
            "migrated to run ids under {}: {done}",
            cli.results_dir.display()
        );
    }
    Ok(results)
}

fn real_main(cli: Cli) -> Result<ExitCode, String> {
    if cli.robots {
        print_robot_check_values();
        return Ok(ExitCode::SUCCESS);
    }
    let git_rev = simulation::root::git_revision(&cli.project_root);
    if let (Some(file), Some(task)) = (&cli.score, &cli.task) {
        let task = presentation::score::find_task(&cli.experiments_dir, task)
            .map_err(|e| e.to_string())?;
        let s = presentation::score::score_file(&task, file, &cli.score_out, &git_rev)
            .map_err(|e| e.to_string())?;
        print_summary(std::slice::from_ref(&s.row));
        eprintln!(
            "wrote {}, {} and {}",
            s.scores.display(),
            s.trace.display(),
            s.figure.display()
        );
        return Ok(ExitCode::SUCCESS);
    }
    if cli.report_only {
        let root = report_root(&cli)?;
        check_report_dir(&root)?;
        let results = open_results(&cli, &git_rev, &all_jobs(&cli)?)?;
        render_report(&cli, &root, &results)?;
        return Ok(ExitCode::SUCCESS);
    }
    if cli.dof_cost {
        dof_cost(&cli, &git_rev)?;
        return Ok(ExitCode::SUCCESS);
    }
    let files = load_dir(&cli.experiments_dir).map_err(|e| e.to_string())?;
    let all: Vec<Job> = files.iter().flat_map(|f| f.jobs()).collect();
    if !cli.merge.is_empty() {
        return merge_shards(&cli, &files, &all, &git_rev);
    }
    let mut jobs = select_jobs(&all, &files, &selection(&cli))?;
    let selected = jobs.len();
    if let Some(shard) = cli.shard_resolved {
        jobs.retain(|j| shard.owns(&j.key().to_string()));
        eprintln!(
            "shard {shard}: {} of the {selected} selected runs, into {}",
            jobs.len(),
            cli.results_dir.display()
        );
    }
    if cli.list {
        print_list(&files, &jobs);
        if let (Some(n), None) = (cli.shards, cli.shard_resolved) {
            let keys: Vec<String> = jobs.iter().map(|j| j.key().to_string()).collect();
            let counts = records::shard::plan(keys.iter().map(String::as_str), n);
            for (k, c) in counts.iter().enumerate() {
                println!("shard {}/{n}: {c} runs", k + 1);
            }
        }
        return Ok(ExitCode::SUCCESS);
    }
    // Everything that can be checked is checked before anything runs: the gate's baseline,
    // the report directory, the stored results (readable, unedited, not pruned wholesale).
    let baseline = cli
        .check
        .then(|| {
            baseline(
                &cli.project_root,
                &cli.results_dir,
                cli.baseline.as_deref(),
                &all,
            )
        })
        .transpose()?;
    if !cli.check && !cli.dry_run && cli.shard_resolved.is_none() {
        match report_root(&cli) {
            Ok(root) => check_report_dir(&root)?,
            Err(why) => eprintln!(
                "note: results go to {}, but {why}",
                cli.results_dir.display()
            ),
        }
    }
    if let Some(t) = cli.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t as usize)
            .build_global()
            .map_err(|e| e.to_string())?;
    }
    // One writer at a time: the lock is held until the process ends.
    let results = (!cli.check && !cli.dry_run)
        .then(|| open_results(&cli, &git_rev, &all))
        .transpose()?;
    if let Some(which) = &cli.infer {
        infer(&cli, which, &all, results.as_ref())?;
        return Ok(ExitCode::SUCCESS);
    }
    if cli.explain_only {
        explain(&cli, &jobs, &all, &git_rev, results.as_ref())?;
        return Ok(ExitCode::SUCCESS);
    }
    let described = described_keys(&all);
    let mut stored = match &results {
        Some(r) => Some(
            r.plan_pruning(
                r.read_runs().map_err(|e| e.to_string())?,
                |row| described.contains(&row.key()),
                cli.prune,
                &cli.experiments_dir,
            )
            .map_err(|e| e.to_string())?,
        ),
        None => None,
    };
    // A shard directory is finished only once its manifest is written again, at the end.
    if cli.shard_resolved.is_some() && results.is_some() {
        records::shard::Manifest::remove(&cli.results_dir).map_err(|e| e.to_string())?;
    }
    // Resume: fold the journal of an interrupted run into runs.csv; the runs it holds from this
    // code revision are not run again (records::journal).
    let mut to_run: Vec<Job> = jobs.clone();
    if let (Some(results), Some((kept, _))) = (&results, stored.as_mut()) {
        let recovered =
            records::journal::recover(results.path(), &git_rev).map_err(|e| e.to_string())?;
        for r in &recovered.other_revision {
            eprintln!(
                "not folded from {}: {} (written by revision {}, this is {git_rev}); it is run again",
                records::journal::path(results.path()).display(),
                r.key(),
                r.git_rev
            );
        }
        let (fold, undescribed): (Vec<RunRow>, Vec<RunRow>) = recovered
            .current
            .into_iter()
            .partition(|r| described.contains(&r.key()));
        for r in &undescribed {
            eprintln!(
                "not folded from {}: {} (no experiment file describes it)",
                records::journal::path(results.path()).display(),
                r.key()
            );
        }
        if !fold.is_empty() {
            let done: HashSet<RunKey> = fold.iter().map(RunRow::key).collect();
            *kept = merge(std::mem::take(kept), fold);
            results.write_runs(kept).map_err(|e| e.to_string())?;
            results.save().map_err(|e| e.to_string())?;
            let before = to_run.len();
            to_run.retain(|j| !done.contains(&j.key()));
            eprintln!(
                "folded {} run(s) of an interrupted run into {}; resuming: {} of the selected runs already done",
                done.len(),
                results.runs_path().display(),
                before - to_run.len()
            );
        }
        records::journal::remove(results.path()).map_err(|e| e.to_string())?;
    }
    let journal = results
        .as_ref()
        .map(|r| {
            let joints = jobs
                .iter()
                .filter_map(|j| {
                    simulation::robot_registry::robot_by_name(&j.robot).map(|r| r.dof())
                })
                .max();
            records::journal::Journal::open(r, &git_rev, joints.unwrap_or(0))
        })
        .transpose()
        .map_err(|e| e.to_string())?;
    // The journal writes each run's trace as the run finishes; the runs it could not
    // checkpoint are remembered, and only their traces are written again at the end.
    let unjournaled = std::sync::Mutex::new(HashSet::new());
    let records = run_jobs_with(&to_run, true, |r| {
        if let Some(j) = &journal {
            if let Err(e) = j.record(r) {
                eprintln!("warning: run not checkpointed: {e}");
                unjournaled
                    .lock()
                    .unwrap_or_else(|p| p.into_inner())
                    .insert(r.job.key());
            }
        }
    });
    drop(journal);
    let unjournaled = unjournaled.into_inner().unwrap_or_else(|p| p.into_inner());
    let rows: Vec<RunRow> = records
        .iter()
        .map(|r| RunRow::from_record(r, &git_rev))
        .collect();
    print_summary(&rows);
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
    if let Some((baseline_rows, baseline_name)) = baseline {
        return Ok(check(baseline_rows, &baseline_name, &rows, cli.exact_only));
    }
    if let (Some(results), Some((kept, pruned))) = (&results, stored) {
        let untraced: Vec<&RunRecord> = records
            .iter()
            .filter(|r| unjournaled.contains(&r.job.key()))
            .collect();
        write_results(results, &untraced, kept, &pruned, rows)?;
        records::journal::remove(results.path()).map_err(|e| e.to_string())?;
        if let Some(shard) = cli.shard_resolved {
            records::shard::Manifest {
                shard: shard.k,
                shards: shard.n,
                git_rev: git_rev.clone(),
                experiments_hash: records::shard::experiments_hash(&cli.experiments_dir)
                    .map_err(|e| e.to_string())?,
                runs: jobs.iter().map(|j| j.key().to_string()).collect(),
                selection: selection(&cli),
            }
            .write(&cli.results_dir)
            .map_err(|e| e.to_string())?;
            eprintln!(
                "shard {shard} done: merge with `reproduce --merge {}...`",
                cli.results_dir.display()
            );
        } else {
            if !cli.skip_explain && !cli.exact_only {
                explain(&cli, &jobs, &all, &git_rev, Some(results))?;
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
                    Err(e @ control::ControlError::UnknownTask(_)) => {
                        eprintln!("control experiments skipped: {e}")
                    }
                    Err(e) => return Err(e.to_string()),
                }
                // Its tables are recorded before the report (which may fail) is rendered.
                results.save().map_err(|e| e.to_string())?;
            }
            match report_root(&cli) {
                Ok(root) => render_report(&cli, &root, results)?,
                Err(why) => eprintln!("report not rendered: {why}"),
            }
        }
    }
    let unexpected: Vec<&String> = failed
        .iter()
        .filter(|(_, expected)| !expected)
        .map(|(line, _)| line)
        .collect();
    if !failed.is_empty() {
        eprintln!(
            "{} of {} runs failed, {} of them expected (reasons in the table above and in results/runs.csv)",
            failed.len(),
            records.len(),
            failed.len() - unexpected.len()
        );
    }
    if !unexpected.is_empty() {
        eprintln!("unexpected failures (exit code 1):");
        for line in &unexpected {
            eprintln!("  {line}");
        }
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

/// The run keys (`experiment / variant / solver`) the experiment files describe.
fn described_keys(all: &[Job]) -> HashSet<RunKey> {
    all.iter().map(Job::key).collect()
}

/// The papers as data (`papers/` under the project root).
fn load_papers(cli: &Cli) -> Result<records::papers::Papers, String> {
    records::papers::Papers::load(&cli.project_root.join("papers")).map_err(|e| e.to_string())
}

/// The ladders and attributions of the selected runs of the papers' solvers (see
/// `explain`), written to results/ and rendered into the report.
fn explain(
    cli: &Cli,
    jobs: &[Job],
    all: &[Job],
    git_rev: &str,
    results: Option<&ResultsDir>,
) -> Result<(), String> {
    let papers = load_papers(cli)?;
    let targets = explain::targets(jobs, &papers);
    if targets.is_empty() {
        return Ok(());
    }
    eprintln!(
        "explaining {} runs of the papers' solvers (tolerance ladders, attribution)",
        targets.len()
    );
    let explained = explain::explain(&targets, all, true, git_rev);
    let Some(results) = results else {
        return Ok(());
    };
    explain::write(results.path(), &explained, all).map_err(|e| e.to_string())?;
    results.save().map_err(|e| e.to_string())?;
    eprintln!(
        "wrote {} ladder rows and {} attribution rows",
        explained.ladder.len(),
        explained.attribution.len()
    );
    if cli.explain_only {
        render_report(cli, &report_root(cli)?, results)?;
    }
    Ok(())
}

/// `--infer`: fits the selected published tables with the family of
/// `experiments/inference/family.toml` (see `explain::inference`).
fn infer(cli: &Cli, which: &str, jobs: &[Job], results: Option<&ResultsDir>) -> Result<(), String> {
    use explain::inference::{family::Family, fit, problem, rows, search::Target, table_ids};
    let root = report_root(cli)?;
    let papers = load_papers(cli)?;
    let family = Family::load(&cli.experiments_dir.join("inference").join("family.toml"))
        .map_err(|e| e.to_string())?;
    let ids = table_ids(&papers.values);
    let wanted: Vec<&str> = which.split(',').map(str::trim).collect();
    let selected: Vec<&(String, String)> = ids
        .iter()
        .filter(|(p, t)| {
            wanted
                .iter()
                .any(|w| *w == "all" || w == p || *w == format!("{p}:{t}"))
        })
        .collect();
    if selected.is_empty() {
        let known: Vec<String> = ids.iter().map(|(p, t)| format!("{p}:{t}")).collect();
        return Err(format!(
            "--infer {which}: no such table (known: all, a paper, or one of {})",
            known.join(", ")
        ));
    }
    for (paper, table) in selected {
        let p = problem(paper, table, &papers, jobs).map_err(|e| e.to_string())?;
        eprintln!(
            "inferring the setup of {paper} {table}: {} columns, {} exact and {} network runs",
            p.columns.len(),
            p.exact.len(),
            p.network.len()
        );
        let f = fit(&p, &family);
        let best = f.outcome.best(Target::Joint);
        eprintln!(
            "  declared: residual {:.3}; best fit: residual {:.3} ({:?}), {} evaluations in {:.0} s",
            f.outcome.declared.scores.joint,
            best.scores.joint,
            best.detail.setup,
            f.outcome.evaluations,
            f.wall_s
        );
        // Each table is written as soon as it is fitted: an interrupted --infer all keeps the
        // tables it finished.
        let (r, e) = rows(&p, &f);
        if let Some(results) = results {
            explain::write_inference(results.path(), &r, &e).map_err(|e| e.to_string())?;
            results.save().map_err(|e| e.to_string())?;
        }
    }
    match results {
        Some(results) => render_report(cli, &root, results),
        None => Ok(()),
    }
}

/// `--dof-cost`: measures the cost against the number of joints (crate `cost`),
/// writes results/dof-cost.csv and re-renders the report.
fn dof_cost(cli: &Cli, git_rev: &str) -> Result<(), String> {
    use cost::{machine, measure_all, Budget};
    let (cpu, cores) = machine();
    let root = report_root(cli)?;
    let results = (!cli.dry_run)
        .then(|| open_results(cli, git_rev, &all_jobs(cli)?))
        .transpose()?;
    eprintln!("measuring the cost against the number of joints on {cpu} ({cores} cores)");
    let started = std::time::Instant::now();
    let measurements = measure_all(&Budget::default(), |case| {
        eprintln!(
            "  {} nlink-{}: done at {:.1} s",
            case.scheme.id(),
            case.n,
            started.elapsed().as_secs_f64()
        );
    });
    let rows = records::dof_cost::rows(&measurements, &cpu, cores, git_rev);
    for fit in rows.iter().filter(|r| r.is_fit()) {
        eprintln!(
            "  {} {} ({}): cost ~ N^{:.2}",
            fit.scheme,
            fit.quantity,
            fit.backend,
            fit.exponent.unwrap_or(f64::NAN)
        );
    }
    let Some(results) = results else {
        return Ok(());
    };
    let path = records::dof_cost::write(results.path(), &rows).map_err(|e| e.to_string())?;
    results.save().map_err(|e| e.to_string())?;
    eprintln!("wrote {} ({} rows)", path.display(), rows.len());
    render_report(cli, &root, &results)
}

/// The gate's baseline, read before anything runs: `file` when given; otherwise the committed
/// `results/runs.csv` of git HEAD (so a run followed by `--check` compares with what is
/// committed, not with what the run just wrote); outside a checkout, or for another results
/// directory, its `runs.csv`. Returns the rows and a name for messages.
fn baseline(
    root: &std::path::Path,
    results_dir: &std::path::Path,
    file: Option<&std::path::Path>,
    all: &[Job],
) -> Result<(Vec<RunRow>, String), String> {
    // A baseline written before run ids is read with its ids recovered (records::migrate).
    let index = records::migrate::LabelIndex::new(all);
    let parse = |bytes: Vec<u8>, name: &str| -> Result<Vec<RunRow>, String> {
        let bytes = match records::migrate::add_ids(&bytes, &index) {
            Ok(Some((migrated, _))) => migrated,
            Ok(None) => bytes,
            Err(e) => return Err(format!("{name}: {e}")),
        };
        let rows: Vec<RunRow> =
            records::table::from_reader(bytes.as_slice()).map_err(|e| format!("{name}: {e}"))?;
        check_rows(&rows).map_err(|e| format!("{name}: {e}"))?;
        Ok(rows)
    };
    let read = |path: &std::path::Path| -> Result<Vec<RunRow>, String> {
        let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
        parse(bytes, &path.display().to_string())
    };
    if let Some(f) = file {
        if f.is_dir() {
            return Err(format!(
                "--baseline {}: is a directory; give a runs.csv file (e.g. {})",
                f.display(),
                f.join("runs.csv").display()
            ));
        }
        let rows = read(f).map_err(|e| format!("--baseline: {e}"))?;
        return Ok((rows, f.display().to_string()));
    }
    let in_tree = results_dir == root.join("results");
    let committed = in_tree
        .then(|| {
            std::process::Command::new("git")
                .args(["show", "HEAD:results/runs.csv"])
                .current_dir(root)
                .output()
                .ok()
                .filter(|o| o.status.success())
        })
        .flatten();
    match committed {
        Some(out) => {
            let name = "git HEAD:results/runs.csv".to_string();
            Ok((parse(out.stdout, &name)?, name))
        }
        None => {
            let path = results_dir.join("runs.csv");
            Ok((read(&path)?, path.display().to_string()))
        }
    }
}

/// Compares `fresh` with the baseline's rows of the same experiments (records::gate).
fn check(
    baseline_rows: Vec<RunRow>,
    baseline_name: &str,
    fresh: &[RunRow],
    exact_only: bool,
) -> ExitCode {
    let experiments: HashSet<&str> = fresh.iter().map(|f| f.experiment.as_str()).collect();
    let committed: Vec<RunRow> = baseline_rows
        .into_iter()
        .filter(|c| experiments.contains(c.experiment.as_str()))
        .filter(|c| !exact_only || c.is_exact())
        .collect();
    let problems = records::gate::compare(&committed, fresh, baseline_name);
    if problems.is_empty() {
        println!(
            "regression gate: {} runs agree with {baseline_name}",
            fresh.len(),
        );
        ExitCode::SUCCESS
    } else {
        println!(
            "regression gate: {} differences\n{}",
            problems.len(),
            problems.join("\n")
        );
        ExitCode::from(1)
    }
}

/// The report is rendered beside the results directory: `<root>/results` -> `<root>/report`.
fn report_root(cli: &Cli) -> Result<PathBuf, String> {
    match cli.results_dir.file_name() {
        Some(name) if name == "results" => {
            Ok(cli.results_dir.parent().map(PathBuf::from).unwrap_or_else(|| PathBuf::from(".")))
        }
        _ => Err(format!(
            "the report needs a results directory named `results` (got {}); use --dry-run for a scratch run",
            cli.results_dir.display()
        )),
    }
}

/// Checks, before anything runs, that `root/report` and its figures directory lie inside the
/// project (no symbolic link leading elsewhere) and that the report can be written there.
fn check_report_dir(root: &Path) -> Result<(), String> {
    let report =
        records::tracked_dir::TrackedDir::open_within(root, "report").map_err(|e| e.to_string())?;
    report
        .resolve(Path::new(presentation::figures::FIGURES))
        .map_err(|e| e.to_string())?;
    records::runs::check_writable(report.path()).map_err(|e| e.to_string())
}

/// Figures first (the report links them), then REPORT.md, then the leaderboard table (recorded
/// in the results directory's manifest).
fn render_report(cli: &Cli, root: &std::path::Path, results: &ResultsDir) -> Result<(), String> {
    let figures = presentation::figures::render_all(root).map_err(|e| e.to_string())?;
    let report = presentation::report::render(root, &cli.project_root.join("papers"))
        .map_err(|e| e.to_string())?;
    presentation::task_card::write_all(root).map_err(|e| e.to_string())?;
    records::leaderboard::write(
        results.path(),
        &results.read_runs().map_err(|e| e.to_string())?,
    )
    .map_err(|e| e.to_string())?;
    results.save().map_err(|e| e.to_string())?;
    eprintln!("wrote {} figures and {}", figures.len(), report.display());
    Ok(())
}

/// The selection flags of the command line (recorded in a shard's manifest).
fn selection(cli: &Cli) -> records::shard::Selection {
    records::shard::Selection {
        paper: cli.paper.clone(),
        experiments: cli.experiment.clone(),
        exact_only: cli.exact_only,
    }
}

/// `--merge`: checks the shard directories (records::shard: manifests, integrity, revision,
/// ownership, traces) before anything is written, then merges their rows and traces into the
/// results directory and renders the report, as a normal run does.
fn merge_shards(
    cli: &Cli,
    files: &[PaperFile],
    all: &[Job],
    git_rev: &str,
) -> Result<ExitCode, String> {
    let edits = if cli.accept_edited {
        Edits::Accept
    } else {
        Edits::Refuse
    };
    let shards = cli
        .merge
        .iter()
        .map(|d| records::shard::read_shard(d, edits))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())?;
    let sel = shards
        .first()
        .map(|s| s.manifest.selection.clone())
        .unwrap_or_default();
    let expected: Vec<String> = select_jobs(all, files, &sel)?
        .iter()
        .map(|j| j.key().to_string())
        .collect();
    let hash = records::shard::experiments_hash(&cli.experiments_dir).map_err(|e| e.to_string())?;
    records::shard::check_shards(&shards, &expected, &hash).map_err(|e| e.to_string())?;
    let results = open_results(cli, git_rev, all)?;
    let described = described_keys(all);
    let (kept, pruned) = results
        .plan_pruning(
            results.read_runs().map_err(|e| e.to_string())?,
            |row| described.contains(&row.key()),
            cli.prune,
            &cli.experiments_dir,
        )
        .map_err(|e| e.to_string())?;
    let traces = records::shard::copy_traces(&shards, &results).map_err(|e| e.to_string())?;
    let rows: Vec<RunRow> = shards.iter().flat_map(|s| s.rows.clone()).collect();
    let unexpected: Vec<String> = rows
        .iter()
        .filter(|r| !r.completed() && !records::gate::expected_to_diverge(r))
        .map(|r| format!("{}: {}", r.key(), r.failure))
        .collect();
    eprintln!(
        "merging {} shard(s): {} runs, {traces} traces",
        shards.len(),
        rows.len()
    );
    write_results(&results, &[], kept, &pruned, rows)?;
    match report_root(cli) {
        Ok(root) => render_report(cli, &root, &results)?,
        Err(why) => eprintln!("report not rendered: {why}"),
    }
    if !unexpected.is_empty() {
        eprintln!("unexpected failures (exit code 1):");
        for line in &unexpected {
            eprintln!("  {line}");
        }
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

fn select_jobs(
    all: &[Job],
    files: &[PaperFile],
    cli: &records::shard::Selection,
) -> Result<Vec<Job>, String> {
    if let Some(p) = &cli.paper {
        if !files.iter().any(|f| &f.paper == p) {
            let known: Vec<&str> = files.iter().map(|f| f.paper.as_str()).collect();
            return Err(format!(
                "unknown paper \"{p}\" (known: {})",
                known.join(", ")
            ));
        }
    }
    let ids: HashSet<&str> = all.iter().map(|j| j.experiment.as_str()).collect();
    for e in &cli.experiments {
        if !ids.contains(e.as_str()) {
            let mut known: Vec<&str> = ids.iter().copied().collect();
            known.sort_unstable();
            return Err(format!(
                "unknown experiment \"{e}\" (known: {})",
                known.join(", ")
            ));
        }
    }
    Ok(all
        .iter()
        .filter(|j| cli.paper.as_ref().is_none_or(|p| &j.paper == p))
        .filter(|j| cli.experiments.is_empty() || cli.experiments.contains(&j.experiment))
        .filter(|j| !cli.exact_only || j.solver == simulation::experiment::SolverChoice::Exact)
        .cloned()
        .collect())
}

/// Prunes the stored rows no experiment file describes (said run by run; their traces only if
/// this program wrote them), merges the fresh rows into the kept ones, writes the traces of
/// `untraced` (the runs the journal could not checkpoint) and runs.csv, and saves the manifest.
fn write_results(
    results: &ResultsDir,
    untraced: &[&RunRecord],
    kept: Vec<RunRow>,
    pruned: &[RunRow],
    rows: Vec<RunRow>,
) -> Result<(), String> {
    for line in results.prune(pruned).map_err(|e| e.to_string())? {
        eprintln!("{line}");
    }
    if !pruned.is_empty() {
        eprintln!(
            "pruned {} stored run(s) that no experiment file describes any more",
            pruned.len()
        );
    }
    let merged = merge(kept, rows);
    for r in untraced {
        results.write_trace(r).map_err(|e| e.to_string())?;
    }
    results.write_runs(&merged).map_err(|e| e.to_string())?;
    results.save().map_err(|e| e.to_string())?;
    eprintln!(
        "wrote {} ({} rows)",
        results.runs_path().display(),
        merged.len()
    );
    Ok(())
}

fn fmt(v: Option<f64>) -> String {
    v.map(|v| format!("{v:.3e}")).unwrap_or_else(|| "-".into())
}

fn print_summary(rows: &[RunRow]) {
    let mut out = String::new();
    let mut current = String::new();
    for r in rows {
        if r.experiment != current {
            current = r.experiment.clone();
            let _ = writeln!(
                out,
                "\n== {current} ({} on {}, T = {} s)",
                r.robot, r.path, r.duration
            );
            let _ = writeln!(
                out,
                "{:<26} {:<28} {:>10} {:>10} {:>10} {:>10} {:>10} {:>7} {:>8}",
                "variant",
                "solver",
                "drift",
                "max err",
                "rms err",
                "|x-x*|max",
                "peak qd",
                "steps",
                "wall s"
            );
        }
        if !r.completed() {
            let _ = writeln!(
                out,
                "{:<26} {:<28} FAILED at t = {} (peak qd {}, max err {}): {}",
                r.variant,
                r.solver,
                fmt(r.failed_at),
                fmt(r.peak_thetadot),
                fmt(r.max_pos_err),
                r.failure
            );
            continue;
        }
        let _ = writeln!(
            out,
            "{:<26} {:<28} {:>10} {:>10} {:>10} {:>10} {:>10} {:>7} {:>8.2}",
            r.variant,
            r.solver,
            fmt(r.drift_norm),
            fmt(r.max_pos_err),
            fmt(r.rms_pos_err),
            fmt(r.score_max_dx),
            fmt(r.peak_thetadot),
            r.steps,
            r.wall_s
        );
    }
    if rows.iter().any(|r| r.solver.starts_with("VP-RNN-PF")) {
        out.push_str(
            "\n|x-x*|max: largest |x_nn - x*|_inf of the joint command against Clarabel along the run. For \
             VP-RNN-PF it measures the exponential-penalty approximation (its equilibrium is the penalised \
             optimum, not x*), not a solver fault.\n",
        );
    }
    emit(&out);
}

fn print_list(files: &[PaperFile], jobs: &[Job]) {
    let mut out = String::new();
    for f in files {
        let _ = writeln!(out, "{} — {}", f.paper, f.title);
        for e in &f.experiments {
            let n = jobs.iter().filter(|j| j.experiment == e.id).count();
            if n == 0 {
                continue;
            }
            let _ = writeln!(
                out,
                "  {:<28} {} on {} (T = {} s), {}: {n} runs",
                e.id, e.robot, e.path.name, e.path.duration, e.paper_output
            );
            // The key (ids: what --task, papers/ and the results use), then the labels.
            for j in jobs.iter().filter(|j| j.experiment == e.id) {
                let k = j.key();
                let _ = writeln!(
                    out,
                    "      {:<48} {} · {}",
                    format!("{} / {}", k.variant, k.solver),
                    j.variant,
                    j.solver.label()
                );
            }
        }
    }
    emit(&out);
}

fn print_robot_check_values() {
    use simulation::robot_registry::{robot_by_name, robot_names};
    for name in robot_names() {
        let robot = robot_by_name(&name).expect("a registry name");
        let theta = robot.stated_pose();
        let (p, sv) = robot
            .check_values(&theta)
            .expect("the stated pose has the robot's joint count");
        println!(
            "{name:<14} {} joints{}, theta = {theta:.4?}\n               f = ({:.6}, {:.6}, {:.6}), sigma(J) = {sv:.6?}",
            robot.dof(),
            if robot.has_dynamics() { ", dynamics" } else { "" },
            p.x,
            p.y,
            p.z,
        );
    }
}

/// Writes to stdout, ending quietly when the reader has gone (e.g. `| head`).
fn emit(text: &str) {
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
}
