//! The command line: the flags of every mode ([`Cli`], parsed by clap after
//! [`crate::commands::to_flags`] has turned a leading subcommand into its flag), and what is
//! resolved from them before any mode runs ([`crate::resolve`]: the project root, the
//! experiments and results directories, the shard, the thread count's bound).

use crate::commands;
use clap::{CommandFactory, FromArgMatches, Parser};
use records::shard::Selection;
use records::tracked_dir::Edits;
use std::path::PathBuf;

/// Regenerates the tables and error data of the papers on drift-free redundancy resolution
/// in papers/ (jia2019, zhang2018, zhong2021, kong2019, robio2018, and any paper added as
/// data), solving every scheme's QP exactly along every run and scoring each paper's neural
/// or numerical solver against that optimum.
///
/// With no flags (or `run`): runs every experiment in experiments/*.toml (in parallel), writes
/// results/runs.csv (one row per run) and results/traces/, and prints a summary table. Each
/// other mode is a subcommand or, equally, its flag (listed below the options).
#[derive(Parser, Debug)]
#[command(
    version = concat!(env!("CARGO_PKG_VERSION"), " (revision ", env!("DRIFTBENCH_REVISION"), ")"),
    about,
    long_about
)]
pub struct Cli {
    /// Run only this paper's experiments: the `paper` id of an experiment file (jia2019,
    /// zhang2018, zhong2021, kong2019, robio2018, group, or a paper added as data; `cross` is
    /// the suite's own cross experiment: every velocity-level solver on every velocity-level
    /// scheme and path).
    #[arg(long)]
    pub paper: Option<String>,
    /// Run only this experiment (an id of docs/experiments.md, e.g. jia2019-clover). Repeatable.
    #[arg(long)]
    pub experiment: Vec<String>,
    /// Run only the exact column (the QP solved to optimality in the loop: certified active set, Clarabel where it cannot certify), no neural solvers.
    #[arg(long)]
    pub exact_only: bool,
    /// List the experiments and their runs, then exit.
    #[arg(long)]
    pub list: bool,
    /// List the robots experiment files can name (Jaco2 variants, Katana 6M180, Franka Panda,
    /// the n-link family, and every robot file of robots/data/, e.g. puma560) with their joint
    /// counts and check values (tip position and singular values of J at a stated pose), then
    /// exit. Needs no project.
    #[arg(long)]
    pub robots: bool,
    /// The project root: the directory with experiments/, results/ and report/ (default: the
    /// nearest directory at or above the working directory that has an experiments/ folder).
    #[arg(long, value_name = "DIR")]
    pub root: Option<PathBuf>,
    /// Directory of the experiment files (default: ROOT/experiments).
    #[arg(long = "experiments-dir", value_name = "DIR")]
    pub experiments_dir_arg: Option<PathBuf>,
    /// Directory results are written to (default: ROOT/results); the report goes beside it.
    #[arg(long = "results-dir", value_name = "DIR")]
    pub results_dir_arg: Option<PathBuf>,
    /// The resolved project root, experiments and results directories.
    #[arg(skip)]
    pub project_root: PathBuf,
    #[arg(skip)]
    pub experiments_dir: PathBuf,
    #[arg(skip)]
    pub results_dir: PathBuf,
    /// Do not write results/ or report/ (print the summary only).
    #[arg(long)]
    pub dry_run: bool,
    /// The regression gate: run the selected experiments and compare them with the committed
    /// results/runs.csv of git HEAD (or --baseline; status, drifts, max position error); write nothing; exit 1 on any
    /// difference. `cargo test --workspace --release` runs the same gate over everything.
    #[arg(long)]
    pub check: bool,
    /// The gate's baseline (default: git HEAD's committed results/runs.csv, or the results
    /// directory's runs.csv outside a checkout). Read before anything runs.
    #[arg(long, value_name = "FILE", requires = "check")]
    pub baseline: Option<PathBuf>,
    /// Re-render report/REPORT.md and report/figures/ from the stored results/ without running
    /// anything, then exit.
    #[arg(long, conflicts_with_all = ["paper", "experiment", "exact_only", "list", "check", "baseline", "skip_explain", "explain_only", "infer", "dof_cost", "shard", "shards", "merge", "dry_run", "prune"])]
    pub report_only: bool,
    /// Worker threads (default: all cores; at most MAX_THREADS_PER_CORE times the cores).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    pub threads: Option<u64>,
    /// Take result files that differ from results/manifest.toml (edited, truncated, copied in
    /// by hand) as they are, instead of refusing to start. Say it only when the edit is
    /// deliberate; the manifest is then written anew.
    #[arg(long)]
    pub accept_edited: bool,
    /// Allow pruning more than a quarter of the stored runs (those no experiment file
    /// describes any more). Without it such a run stops before anything runs, naming the
    /// experiments directory and the count: an empty or wrong --experiments-dir must not wipe
    /// the results.
    #[arg(long)]
    pub prune: bool,
    /// Skip the explanation runs (tolerance ladders, drift attribution) that a normal run
    /// adds for the selected runs of the papers' solvers and of the group-code experiments.
    #[arg(long, conflicts_with = "explain_only")]
    pub skip_explain: bool,
    /// Run only the explanation runs of the selection (ladders and attribution; writes
    /// results/ladder.csv and results/attribution.csv and the report), not the runs themselves.
    #[arg(long)]
    pub explain_only: bool,
    /// Setup inference: fit the parameters the papers leave open (path pose and plane tilt,
    /// size where it is assumed, direction, RMP reading; robot variant and MATLAB-default
    /// tolerances as discrete hypotheses; experiments/inference/family.toml) to a published
    /// drift table, jointly and column by column; `all`, a paper
    /// (`jia2019`), one table (`jia2019:T2`) or a comma-separated list of these. Writes
    /// results/inference.csv and
    /// results/inference-entries.csv (each table as it finishes), then re-renders the report.
    /// Takes minutes per table.
    #[arg(long, value_name = "TABLE")]
    pub infer: Option<String>,
    /// Cost against the number of joints: time scheme build, network RHS and Jacobian, the
    /// exact solve (active set and Clarabel), the dense KKT floor and whole runs on the n-link
    /// arms (N = 3 ... 30; kong2019 to N = 200 on dynamic-size types, the dense LUs on nalgebra
    /// and faer) with jia2019's and kong2019's schemes (crate cost), write
    /// results/dof-cost.csv (with the fitted growth exponents and the machine), then re-render
    /// the report. Takes about a minute; run it on an otherwise idle machine.
    #[arg(long, conflicts_with_all = ["check", "report_only", "explain_only", "infer", "merge", "shard"])]
    pub dof_cost: bool,
    /// Cluster runs (docs/cluster.md): run only shard K of N of the selected runs (K = 1..N; a
    /// run's shard is a stable hash of its key) into ROOT/results-shard-K-of-N/ (or
    /// --results-dir), bound to this shard and selection at the start (another selection's or
    /// sweep's directory is refused): runs.csv, traces/ and, written last, shard.toml. Implies
    /// --skip-explain and renders no report. A shard started again resumes from its journal.
    /// `--shard auto` (or `--shard` alone) takes K and N from a Slurm job array (K =
    /// SLURM_ARRAY_TASK_ID; N = --shards, else DRIFTBENCH_SHARDS, else SLURM_ARRAY_TASK_COUNT
    /// for an array of exactly 1-N) or a Kubernetes Indexed Job (K = JOB_COMPLETION_INDEX + 1;
    /// N = --shards or DRIFTBENCH_SHARDS). With --list: the shard's runs.
    #[arg(long, value_name = "K/N", num_args = 0..=1, default_missing_value = "auto",
          conflicts_with_all = ["check", "report_only", "explain_only", "infer", "merge"])]
    pub shard: Option<String>,
    /// The number of shards N for `--shard auto`: needed under Kubernetes and for a Slurm task
    /// resubmitted alone (`sbatch --array=K`); with --list and no --shard: print how many of
    /// the selected runs each of N shards gets.
    #[arg(long, value_name = "N")]
    pub shards: Option<usize>,
    /// Merge finished shard directories (of `--shard K/N`) into results/ and render the report:
    /// checks that they agree on N and on the experiment files and that every selected run (the
    /// selection the shards were given) is in exactly one shard; otherwise names the missing
    /// or duplicated runs (and the shard that should have produced them), writes nothing and
    /// exits 2. Does not run the explanation layer: run `reproduce --explain-only` afterwards
    /// if wanted.
    #[arg(long, value_name = "DIR", num_args = 1..,
          conflicts_with_all = ["check", "report_only", "explain_only", "infer", "paper", "experiment", "exact_only", "dry_run", "list", "skip_explain"])]
    pub merge: Vec<PathBuf>,
    /// The resolved shard of `--shard`.
    #[arg(skip)]
    pub shard_resolved: Option<records::shard::Shard>,
    /// Score a trajectory produced elsewhere (CSV: t, theta_1..n, optionally thetadot_1..n) on
    /// the task --task, as a run is scored; writes scores.csv, its trace and figure under
    /// --score-out, then exits (reproduce::score).
    #[arg(long, value_name = "FILE", requires = "task")]
    pub score: Option<PathBuf>,
    /// The task of --score: "<experiment> / <variant>".
    #[arg(long, value_name = "ID", requires = "score")]
    pub task: Option<String>,
    /// Where --score writes (default: scores/ in the working directory).
    #[arg(long = "score-out", value_name = "DIR", default_value = "scores")]
    pub score_out: PathBuf,
}

impl Cli {
    /// Parses the program's arguments (`args[0]` is the program), a leading subcommand read as
    /// its flag; `--help` lists the subcommands after the flags. A clap error (a bad flag
    /// combination, `--help`, `--version`) is returned for the caller to print and exit with.
    pub fn parse_from_args(args: Vec<String>) -> Result<Self, clap::Error> {
        let matches = Self::command()
            .after_help(commands::help())
            .try_get_matches_from(commands::to_flags(args))?;
        Self::from_arg_matches(&matches)
    }

    /// Whether result files edited by hand are taken as they are (`--accept-edited`).
    pub fn edits(&self) -> Edits {
        if self.accept_edited {
            Edits::Accept
        } else {
            Edits::Refuse
        }
    }

    /// The selection flags of the command line (recorded in a shard's manifest).
    pub fn selection(&self) -> Selection {
        Selection {
            paper: self.paper.clone(),
            experiments: self.experiment.clone(),
            exact_only: self.exact_only,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::error::ErrorKind;

    fn parse(line: &str) -> Result<Cli, clap::Error> {
        Cli::parse_from_args(line.split_whitespace().map(String::from).collect())
    }

    #[test]
    fn a_subcommand_and_its_flag_parse_alike() {
        let sub = parse("reproduce check --paper kong2019 --exact-only").unwrap();
        let flag = parse("reproduce --check --paper kong2019 --exact-only").unwrap();
        assert!(sub.check && flag.check);
        assert_eq!(sub.selection(), flag.selection());
        assert_eq!(
            sub.selection(),
            Selection {
                paper: Some("kong2019".into()),
                experiments: vec![],
                exact_only: true
            }
        );
        let infer = parse("reproduce infer jia2019:T2").unwrap();
        assert_eq!(infer.infer.as_deref(), Some("jia2019:T2"));
        assert_eq!(
            parse("reproduce shard").unwrap().shard.as_deref(),
            Some("auto")
        );
    }

    #[test]
    fn conflicting_and_incomplete_flags_are_refused_by_kind() {
        let kind = |line: &str| parse(line).err().map(|e| e.kind());
        assert_eq!(
            kind("reproduce report --paper jia2019"),
            Some(ErrorKind::ArgumentConflict)
        );
        assert_eq!(
            kind("reproduce merge a --check"),
            Some(ErrorKind::ArgumentConflict)
        );
        assert_eq!(
            kind("reproduce cost --shard 1/2"),
            Some(ErrorKind::ArgumentConflict)
        );
        assert_eq!(
            kind("reproduce --skip-explain --explain-only"),
            Some(ErrorKind::ArgumentConflict)
        );
        assert_eq!(
            kind("reproduce --baseline b.csv"),
            Some(ErrorKind::MissingRequiredArgument)
        );
        assert_eq!(
            kind("reproduce score f.csv"),
            Some(ErrorKind::MissingRequiredArgument)
        );
        assert_eq!(
            kind("reproduce --threads 0"),
            Some(ErrorKind::ValueValidation)
        );
        assert_eq!(kind("reproduce check --baseline b.csv"), None);
    }
}
