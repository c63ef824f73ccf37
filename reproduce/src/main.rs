//! `cargo run --release -p reproduce`: runs driftbench's experiments and writes `results/`.

use clap::Parser;
use records::runs::{
    check_writable, merge, read_runs, remove_stale_tmp, runs_csv, trace_csv, trace_file,
    write_atomic, RunRow,
};
use simulation::experiment::{load_dir, Job, PaperFile};
use simulation::naming::run_stem;
use simulation::run::RunRecord;
use simulation::runner::run_jobs_with;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

/// Regenerates the tables and error data of four papers on drift-free redundancy resolution
/// (jia2019, zhang2018, zhong2021, kong2019), solving every scheme's QP exactly with Clarabel
/// along every run and scoring each paper's neural solver against that optimum.
///
/// With no flags: runs every experiment in experiments/*.toml (in parallel), writes
/// results/runs.csv (one row per run) and results/traces/, and prints a summary table.
#[derive(Parser, Debug)]
#[command(version, about, long_about)]
struct Cli {
    /// Run only this paper's experiments (jia2019, zhang2018, zhong2021, kong2019; `cross` is
    /// the suite's own cross experiment: every velocity-level solver on every velocity-level
    /// scheme and path).
    #[arg(long)]
    paper: Option<String>,
    /// Run only this experiment (an id of experiments.md, e.g. jia2019-clover). Repeatable.
    #[arg(long)]
    experiment: Vec<String>,
    /// Run only the exact column (Clarabel in the loop), no neural solvers.
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
    /// directory's runs.csv outside a checkout).
    #[arg(long, value_name = "FILE")]
    baseline: Option<PathBuf>,
    /// Re-render report/REPORT.md and report/figures/ from the stored results/ without running
    /// anything, then exit.
    #[arg(long)]
    report_only: bool,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Skip the explanation runs (tolerance ladders, drift attribution) that a normal run
    /// adds for the selected runs of the papers' solvers and of the group-code experiments.
    #[arg(long)]
    skip_explain: bool,
    /// Run only the explanation runs of the selection (ladders and attribution; writes
    /// results/ladder.csv and results/attribution.csv and the report), not the runs themselves.
    #[arg(long)]
    explain_only: bool,
    /// Setup inference: fit the parameters the papers leave open (path pose, size where it is
    /// assumed, direction, RMP reading) to a published drift table; `all`, a paper
    /// (`jia2019`), one table (`jia2019:T2`) or a comma-separated list of these. Writes
    /// results/inference.csv and
    /// results/inference-entries.csv (each table as it finishes), then re-renders the report.
    /// Takes minutes per table.
    #[arg(long, value_name = "TABLE")]
    infer: Option<String>,
    /// Cost against the number of joints: time scheme build, network RHS and Jacobian, the
    /// exact solve (active set and Clarabel), the dense KKT floor and whole runs on the n-link
    /// arms (N = 3 ... 30) with jia2019's and kong2019's schemes (simulation::dof_cost), write
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
          conflicts_with_all = ["check", "report_only", "explain_only", "infer", "paper", "experiment", "exact_only", "dry_run"])]
    merge: Vec<PathBuf>,
    /// The resolved shard of `--shard`.
    #[arg(skip)]
    shard_resolved: Option<records::shard::Shard>,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match resolve_dirs(cli).and_then(real_main) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// Fills in the project root (`--root`, else found from the working directory) and the
/// experiments and results directories under it, unless given.
fn resolve_dirs(mut cli: Cli) -> Result<Cli, String> {
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
        Some("auto") => Some(records::shard::Shard::from_env(
            |v| std::env::var(v).ok(),
            cli.shards,
        )?),
        Some(kn) => Some(records::shard::Shard::parse(kn)?),
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

fn real_main(cli: Cli) -> Result<ExitCode, String> {
    if cli.robots {
        print_robot_check_values();
        return Ok(ExitCode::SUCCESS);
    }
    if cli.report_only {
        let root = report_root(&cli)?;
        let report = root.join("report");
        check_writable(&report)?;
        remove_stale_tmp(&report)
            .map_err(|e| format!("{}: cannot clean: {e}", report.display()))?;
        render_report(&root)?;
        return Ok(ExitCode::SUCCESS);
    }
    if cli.dof_cost {
        dof_cost(&cli)?;
        return Ok(ExitCode::SUCCESS);
    }
    let files = load_dir(&cli.experiments_dir).map_err(|e| e.to_string())?;
    if !cli.merge.is_empty() {
        return merge_shards(&cli, &files);
    }
    let mut jobs = select_jobs(&files, &selection(&cli))?;
    let selected = jobs.len();
    if let Some(shard) = cli.shard_resolved {
        jobs.retain(|j| shard.owns(&j.key()));
        eprintln!(
            "shard {shard}: {} of the {selected} selected runs, into {}",
            jobs.len(),
            cli.results_dir.display()
        );
    }
    if cli.list {
        print_list(&files, &jobs);
        if let (Some(n), None) = (cli.shards, cli.shard_resolved) {
            let keys: Vec<String> = jobs.iter().map(Job::key).collect();
            let counts = records::shard::plan(keys.iter().map(String::as_str), n);
            for (k, c) in counts.iter().enumerate() {
                println!("shard {}/{n}: {c} runs", k + 1);
            }
        }
        return Ok(ExitCode::SUCCESS);
    }
    // Before anything runs: the stored results must be readable (they are merged with the new
    // rows, never dropped), and results/ and report/ writable; stale temporary files of killed
    // runs are removed.
    // One writer at a time: held until the process ends.
    let _lock = if cli.check || cli.dry_run {
        None
    } else {
        Some(lock_results(&cli.results_dir)?)
    };
    let stored = if cli.check || cli.dry_run {
        None
    } else {
        Some(prepare_output(&cli)?)
    };
    // A shard directory is finished only once its manifest is written again, at the end.
    if cli.shard_resolved.is_some() && stored.is_some() {
        records::shard::Manifest::remove(&cli.results_dir)?;
    }
    if let Some(t) = cli.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build_global()
            .map_err(|e| e.to_string())?;
    }
    let git_rev = simulation::root::git_revision(&cli.project_root);
    if let Some(which) = &cli.infer {
        infer(
            &cli,
            which,
            &files.iter().flat_map(|f| f.jobs()).collect::<Vec<_>>(),
        )?;
        return Ok(ExitCode::SUCCESS);
    }
    let all: Vec<Job> = files.iter().flat_map(|f| f.jobs()).collect();
    if cli.explain_only {
        explain(&cli, &jobs, &all, &git_rev)?;
        return Ok(ExitCode::SUCCESS);
    }
    // Resume: fold the journal of an interrupted run into runs.csv; the runs it holds from this
    // code revision are not run again (reproduce::journal).
    let mut stored = stored;
    let mut to_run: Vec<Job> = jobs.clone();
    if let Some(rows) = stored.as_mut() {
        let recovered = records::journal::recover(&cli.results_dir)?;
        if !recovered.is_empty() {
            let done: Vec<(String, String, String)> = recovered
                .iter()
                .filter(|r| r.git_rev == git_rev)
                .map(RunRow::key)
                .collect();
            *rows = merge(std::mem::take(rows), recovered.clone());
            let path = cli.results_dir.join("runs.csv");
            let bytes = runs_csv(rows).map_err(|e| e.to_string())?;
            write_atomic(&path, &bytes).map_err(|e| format!("{}: {e}", path.display()))?;
            records::journal::remove(&cli.results_dir)?;
            let before = to_run.len();
            to_run.retain(|j| {
                !done.contains(&(j.experiment.clone(), j.variant.clone(), j.solver.label()))
            });
            eprintln!(
                "folded {} run(s) of an interrupted run into {}; resuming: {} of the selected runs already done",
                recovered.len(),
                path.display(),
                before - to_run.len()
            );
        }
    }
    let journal = stored
        .is_some()
        .then(|| {
            let joints = jobs
                .iter()
                .filter_map(|j| {
                    simulation::robot_registry::robot_by_name(&j.robot).map(|r| r.dof())
                })
                .max();
            records::journal::Journal::open(&cli.results_dir, &git_rev, joints.unwrap_or(0))
        })
        .transpose()?;
    let records = run_jobs_with(&to_run, true, |r| {
        if let Some(j) = &journal {
            if let Err(e) = j.record(r) {
                eprintln!("warning: run not checkpointed: {e}");
            }
        }
    });
    let rows: Vec<RunRow> = records
        .iter()
        .map(|r| RunRow::from_record(r, &git_rev))
        .collect();
    print_summary(&rows);
    // Failed runs, and whether the experiment files' findings expect them (reproduce::gate).
    let failed: Vec<(String, bool)> = rows
        .iter()
        .filter(|r| !r.completed())
        .map(|r| {
            (
                format!(
                    "{} / {} / {}: {}",
                    r.experiment, r.variant, r.solver, r.failure
                ),
                records::gate::expected_to_diverge(r),
            )
        })
        .collect();
    if cli.check {
        return check(
            &cli.project_root,
            &cli.results_dir,
            cli.baseline.as_deref(),
            &rows,
            cli.exact_only,
        );
    }
    if let Some(stored) = stored {
        write_results(&cli.results_dir, &records, stored, rows, &all)?;
        records::journal::remove(&cli.results_dir)?;
        if let Some(shard) = cli.shard_resolved {
            records::shard::Manifest {
                shard: shard.k,
                shards: shard.n,
                git_rev: git_rev.clone(),
                experiments_hash: records::shard::experiments_hash(&cli.experiments_dir)?,
                runs: jobs.iter().map(Job::key).collect(),
                selection: selection(&cli),
            }
            .write(&cli.results_dir)?;
            eprintln!(
                "shard {shard} done: merge with `reproduce --merge {}...`",
                cli.results_dir.display()
            );
        } else {
            if !cli.skip_explain && !cli.exact_only {
                explain(&cli, &jobs, &all, &git_rev)?;
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
            }
            match report_root(&cli) {
                Ok(root) => render_report(&root)?,
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

/// The ladders and attributions of the selected runs of the papers' solvers (see
/// `explain`), written to results/ and rendered into the report.
fn explain(cli: &Cli, jobs: &[Job], all: &[Job], git_rev: &str) -> Result<(), String> {
    let targets = explain::targets(jobs);
    if targets.is_empty() {
        return Ok(());
    }
    eprintln!(
        "explaining {} runs of the papers' solvers (tolerance ladders, attribution)",
        targets.len()
    );
    let explained = explain::explain(&targets, all, true, git_rev);
    if cli.dry_run {
        return Ok(());
    }
    explain::write(&cli.results_dir, &explained, all)?;
    eprintln!(
        "wrote {} ladder rows and {} attribution rows",
        explained.ladder.len(),
        explained.attribution.len()
    );
    if cli.explain_only {
        render_report(&report_root(cli)?)?;
    }
    Ok(())
}

/// `--infer`: fits the selected published tables (see `explain::inference`).
fn infer(cli: &Cli, which: &str, jobs: &[Job]) -> Result<(), String> {
    use explain::inference::{fit, problem, rows, table_ids, Budget};
    let root = report_root(cli)?;
    let values =
        records::paper_values::read_paper_values(&root.join("report").join("paper-values.csv"))?;
    let ids = table_ids(&values);
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
        let p = problem(paper, table, &values, jobs)?;
        eprintln!(
            "inferring the setup of {paper} {table}: {} columns, {} exact runs per evaluation",
            p.columns.len(),
            p.runs.len()
        );
        let f = fit(&p, Budget::default());
        let best = f.best();
        eprintln!(
            "  declared: residual {:.3}; best fit: residual {:.3} ({:?}), {} evaluations in {:.0} s",
            f.declared.rel_residual, best.rel_residual, best.setup, f.evaluations, f.wall_s
        );
        // Each table is written as soon as it is fitted: an interrupted --infer all keeps the
        // tables it finished.
        let (r, e) = rows(&p, &f);
        if !cli.dry_run {
            explain::write_inference(&cli.results_dir, &r, &e)?;
        }
    }
    if cli.dry_run {
        return Ok(());
    }
    render_report(&root)
}

/// `--dof-cost`: measures the cost against the number of joints (`simulation::dof_cost`),
/// writes results/dof-cost.csv and re-renders the report.
fn dof_cost(cli: &Cli) -> Result<(), String> {
    use simulation::dof_cost::{machine, measure_all, Budget};
    let (cpu, cores) = machine();
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
    let git_rev = simulation::root::git_revision(&cli.project_root);
    let rows = records::dof_cost::rows(&measurements, &cpu, cores, &git_rev);
    for fit in rows.iter().filter(|r| r.is_fit()) {
        eprintln!(
            "  {} {}: cost ~ N^{:.2}",
            fit.scheme,
            fit.quantity,
            fit.exponent.unwrap_or(f64::NAN)
        );
    }
    if cli.dry_run {
        return Ok(());
    }
    let root = report_root(cli)?;
    let _lock = lock_results(&cli.results_dir)?;
    let path = records::dof_cost::write(&cli.results_dir, &rows)?;
    eprintln!("wrote {} ({} rows)", path.display(), rows.len());
    render_report(&root)
}

/// Compares `fresh` with the committed rows of the same runs (see `reproduce::gate`).
/// The gate's baseline: `file` when given; otherwise the committed `results/runs.csv` of git
/// HEAD (so a run followed by `--check` compares with what is committed, not with what the run
/// just wrote); outside a checkout, or for another results directory, its `runs.csv`. Returns
/// the rows and a name for messages.
fn baseline(
    root: &std::path::Path,
    results_dir: &std::path::Path,
    file: Option<&std::path::Path>,
) -> Result<(Vec<RunRow>, String), String> {
    if let Some(f) = file {
        return Ok((read_runs(f)?, f.display().to_string()));
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
            let tmp = std::env::temp_dir()
                .join(format!("driftbench-baseline-{}.csv", std::process::id()));
            std::fs::write(&tmp, &out.stdout).map_err(|e| format!("{}: {e}", tmp.display()))?;
            let rows = read_runs(&tmp).map_err(|e| format!("HEAD:results/runs.csv ({e})"));
            let _ = std::fs::remove_file(&tmp);
            Ok((rows?, "git HEAD:results/runs.csv".to_string()))
        }
        None => {
            let path = results_dir.join("runs.csv");
            Ok((read_runs(&path)?, path.display().to_string()))
        }
    }
}

fn check(
    root: &std::path::Path,
    results_dir: &std::path::Path,
    baseline_file: Option<&std::path::Path>,
    fresh: &[RunRow],
    exact_only: bool,
) -> Result<ExitCode, String> {
    let (baseline_rows, baseline_name) = baseline(root, results_dir, baseline_file)?;
    let committed: Vec<RunRow> = baseline_rows
        .into_iter()
        .filter(|c| fresh.iter().any(|f| f.experiment == c.experiment))
        .filter(|c| !exact_only || c.is_exact())
        .collect();
    let problems = records::gate::compare(&committed, fresh);
    if problems.is_empty() {
        println!(
            "regression gate: {} runs agree with {baseline_name}",
            fresh.len(),
        );
        Ok(ExitCode::SUCCESS)
    } else {
        println!(
            "regression gate: {} differences\n{}",
            problems.len(),
            problems.join("\n")
        );
        Ok(ExitCode::from(1))
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

/// Figures first (the report links them), then REPORT.md.
fn render_report(root: &std::path::Path) -> Result<(), String> {
    let figures = presentation::figures::render_all(root)?;
    let report = presentation::report::render(root)?;
    records::leaderboard::write(
        &root.join("results"),
        &read_runs(&root.join("results/runs.csv"))?,
    )?;
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

/// `--merge`: checks the shard directories (records::shard), then merges their rows and traces
/// into the results directory and renders the report, as a normal run does.
fn merge_shards(cli: &Cli, files: &[PaperFile]) -> Result<ExitCode, String> {
    let shards = cli
        .merge
        .iter()
        .map(|d| records::shard::read_shard(d))
        .collect::<Result<Vec<_>, _>>()?;
    let sel = shards
        .first()
        .map(|s| s.manifest.selection.clone())
        .unwrap_or_default();
    let expected: Vec<String> = select_jobs(files, &sel)?.iter().map(Job::key).collect();
    let hash = records::shard::experiments_hash(&cli.experiments_dir)?;
    records::shard::check_shards(&shards, &expected, &hash)?;
    let _lock = lock_results(&cli.results_dir)?;
    let stored = prepare_output(cli)?;
    let traces = records::shard::copy_traces(&shards, &cli.results_dir)?;
    let rows: Vec<RunRow> = shards.iter().flat_map(|s| s.rows.clone()).collect();
    let unexpected: Vec<String> = rows
        .iter()
        .filter(|r| !r.completed() && !records::gate::expected_to_diverge(r))
        .map(|r| format!("{}: {}", records::shard::row_key(r), r.failure))
        .collect();
    let all: Vec<Job> = files.iter().flat_map(|f| f.jobs()).collect();
    eprintln!(
        "merging {} shard(s): {} runs, {traces} traces",
        shards.len(),
        rows.len()
    );
    write_results(&cli.results_dir, &[], stored, rows, &all)?;
    match report_root(cli) {
        Ok(root) => render_report(&root)?,
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

fn select_jobs(files: &[PaperFile], cli: &records::shard::Selection) -> Result<Vec<Job>, String> {
    let all: Vec<Job> = files.iter().flat_map(|f| f.jobs()).collect();
    if let Some(p) = &cli.paper {
        if !files.iter().any(|f| &f.paper == p) {
            let known: Vec<&str> = files.iter().map(|f| f.paper.as_str()).collect();
            return Err(format!(
                "unknown paper \"{p}\" (known: {})",
                known.join(", ")
            ));
        }
    }
    for e in &cli.experiments {
        if !all.iter().any(|j| &j.experiment == e) {
            let mut ids: Vec<&str> = all.iter().map(|j| j.experiment.as_str()).collect();
            ids.dedup();
            return Err(format!(
                "unknown experiment \"{e}\" (known: {})",
                ids.join(", ")
            ));
        }
    }
    Ok(all
        .into_iter()
        .filter(|j| cli.paper.as_ref().is_none_or(|p| &j.paper == p))
        .filter(|j| cli.experiments.is_empty() || cli.experiments.contains(&j.experiment))
        .filter(|j| !cli.exact_only || j.solver == simulation::experiment::SolverChoice::Exact)
        .collect())
}

/// Checks, before any run, that results can be written without losing anything: reads the
/// stored results/runs.csv (an unreadable or old-schema file is an error naming the file, the
/// An advisory lock on the results directory (`<dir>/.lock`, the operating system's file lock
/// through `std::fs::File::try_lock`): a second writer refuses at once, naming the directory,
/// instead of overwriting the first one's results with its own. The lock ends with the process.
fn lock_results(dir: &std::path::Path) -> Result<std::fs::File, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create: {e}", dir.display()))?;
    let path = dir.join(".lock");
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(|e| format!("{}: cannot open the lock file: {e}", path.display()))?;
    match file.try_lock() {
        Ok(()) => Ok(file),
        Err(std::fs::TryLockError::WouldBlock) => Err(format!(
            "another reproduce is writing to {} (lock {}): wait for it to finish, or give this run another --results-dir",
            dir.display(),
            path.display()
        )),
        Err(std::fs::TryLockError::Error(e)) => {
            Err(format!("{}: cannot lock: {e}", path.display()))
        }
    }
}

/// line and how to recover), checks that results/ and report/ are writable, and removes the
/// temporary files killed runs left there. Returns the stored rows.
fn prepare_output(cli: &Cli) -> Result<Vec<RunRow>, String> {
    let runs_path = cli.results_dir.join("runs.csv");
    let stored = if runs_path.exists() {
        read_runs(&runs_path)?
    } else {
        Vec::new()
    };
    let mut dirs = vec![cli.results_dir.clone()];
    match report_root(cli) {
        Ok(root) => dirs.push(root.join("report")),
        // A shard renders no report.
        Err(_) if cli.shard_resolved.is_some() => {}
        // Said before anything runs, not after.
        Err(why) => eprintln!(
            "note: results go to {}, but {why}",
            cli.results_dir.display()
        ),
    }
    for dir in &dirs {
        check_writable(dir)?;
        let removed =
            remove_stale_tmp(dir).map_err(|e| format!("{}: cannot clean: {e}", dir.display()))?;
        if !removed.is_empty() {
            eprintln!(
                "removed {} stale temporary file(s) of interrupted runs under {}",
                removed.len(),
                dir.display()
            );
        }
    }
    Ok(stored)
}

/// Merges the fresh rows into the stored ones and writes runs.csv and the fresh traces. Stored
/// rows of runs the experiment files no longer describe (`all`: every job of the files) are
/// pruned with their traces, and said so: results reflect the experiment files.
fn write_results(
    dir: &std::path::Path,
    records: &[RunRecord],
    stored: Vec<RunRow>,
    rows: Vec<RunRow>,
    all: &[Job],
) -> Result<(), String> {
    let runs_path = dir.join("runs.csv");
    let exists = |r: &RunRow| {
        all.iter().any(|j| {
            j.experiment == r.experiment && j.variant == r.variant && j.solver.label() == r.solver
        })
    };
    let (kept, pruned): (Vec<RunRow>, Vec<RunRow>) = stored.into_iter().partition(exists);
    for r in &pruned {
        let trace = dir
            .join("traces")
            .join(&r.experiment)
            .join(format!("{}.csv", run_stem(&r.variant, &r.solver)));
        if trace.exists() {
            std::fs::remove_file(&trace).map_err(|e| format!("{}: {e}", trace.display()))?;
        }
        let _ = std::fs::remove_dir(dir.join("traces").join(&r.experiment));
    }
    if !pruned.is_empty() {
        eprintln!(
            "pruned {} stored run(s) that no experiment file describes any more: {}",
            pruned.len(),
            pruned
                .iter()
                .map(|r| format!("{} / {} / {}", r.experiment, r.variant, r.solver))
                .collect::<Vec<_>>()
                .join("; ")
        );
    }
    let merged = merge(kept, rows);
    for r in records {
        let bytes = trace_csv(r).map_err(|e| e.to_string())?;
        let path = dir.join("traces").join(trace_file(r));
        write_atomic(&path, &bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let bytes = runs_csv(&merged).map_err(|e| e.to_string())?;
    write_atomic(&runs_path, &bytes).map_err(|e| format!("{}: {e}", runs_path.display()))?;
    eprintln!(
        "wrote {} ({} rows) and {} traces",
        runs_path.display(),
        merged.len(),
        records.len()
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
            for j in jobs.iter().filter(|j| j.experiment == e.id) {
                let _ = writeln!(out, "      {:<30} {}", j.variant, j.solver.label());
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
