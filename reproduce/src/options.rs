//! The options of every mode, one struct per mode ([`Mode`]), and the options every mode shares
//! ([`GlobalOptions`]). They are what the library takes: the command line ([`crate::Cli`])
//! parses into them, and a program calling the library fills them in itself.

use clap::{Args, Subcommand};
use spec::ids::{ExperimentId, PaperId};
use spec::TaskKey;
use std::path::PathBuf;
use store::shard::{Selection, Shard, ShardError};
use store::Edits;

/// The options of every mode, given before or after the subcommand: where the project and its
/// directories are, the worker threads, and how the results store treats edited or pruned files.
#[derive(Args, Clone, Debug, Default, PartialEq, Eq)]
pub struct GlobalOptions {
    /// The project root: the directory with experiments/, results/ and report/ (default: the
    /// nearest directory at or above the working directory that has an experiments/ folder).
    #[arg(long, value_name = "DIR", global = true)]
    pub root: Option<PathBuf>,
    /// Directory of the experiment files (default: ROOT/experiments).
    #[arg(long = "experiments-dir", value_name = "DIR", global = true)]
    pub experiments_dir: Option<PathBuf>,
    /// Directory results are written to (default: ROOT/results, or ROOT/results-shard-K-of-N
    /// for a shard); the report goes beside it.
    #[arg(long = "results-dir", value_name = "DIR", global = true)]
    pub results_dir: Option<PathBuf>,
    /// Worker threads (default: all cores; at most 4 per core, `project::MAX_THREADS_PER_CORE`).
    #[arg(long, global = true, value_parser = clap::value_parser!(u64).range(1..))]
    pub threads: Option<u64>,
    /// Take result files that differ from results/manifest.toml (edited, truncated, copied in
    /// by hand) as they are, instead of refusing to start. Say it only when the edit is
    /// deliberate; the manifest is then written anew.
    #[arg(long, global = true)]
    pub accept_edited: bool,
    /// Allow pruning more than a quarter of the stored runs (those no experiment file
    /// describes any more). Without it such a run stops before anything runs, naming the
    /// experiments directory and the count: an empty or wrong --experiments-dir must not wipe
    /// the results.
    #[arg(long, global = true)]
    pub prune: bool,
}

impl GlobalOptions {
    /// Whether result files edited by hand are taken as they are (`--accept-edited`).
    pub fn edits(&self) -> Edits {
        if self.accept_edited {
            Edits::Accept
        } else {
            Edits::Refuse
        }
    }
}

/// Which runs a mode takes: a paper's, some experiments', and whether only the exact column.
#[derive(Args, Clone, Debug, Default, PartialEq, Eq)]
pub struct SelectionOptions {
    /// Run only this paper's experiments: the `paper` id of an experiment file (the papers of
    /// papers/, group, or a paper added as data; `cross` is the suite's own cross experiment:
    /// every velocity-level solver on every velocity-level scheme and path). `reproduce list`
    /// names them.
    #[arg(long, value_name = "PAPER")]
    pub paper: Option<PaperId>,
    /// Run only this experiment (an id of docs/experiments.md, e.g. jia2019-clover). Repeatable.
    #[arg(long, value_name = "EXPERIMENT")]
    pub experiment: Vec<ExperimentId>,
    /// Run only the exact column (the QP solved to optimality in the loop: certified active
    /// set, Clarabel where it cannot certify), no neural or numerical solvers.
    #[arg(long)]
    pub exact_only: bool,
}

impl SelectionOptions {
    /// The selection (recorded in a shard's manifest).
    pub fn selection(&self) -> Selection {
        Selection {
            paper: self.paper.as_ref().map(|p| p.to_string()),
            experiments: self.experiment.iter().map(|e| e.to_string()).collect(),
            exact_only: self.exact_only,
        }
    }

    /// Whether nothing is selected away: every experiment, every solver.
    pub fn is_whole(&self) -> bool {
        !self.exact_only && self.paper.is_none() && self.experiment.is_empty()
    }
}

/// `reproduce run` (the default): run the selection, then the explanation layer, the control
/// experiments (of a whole reproduction) and the report.
#[derive(Args, Clone, Debug, Default, PartialEq, Eq)]
pub struct RunOptions {
    #[command(flatten)]
    pub selection: SelectionOptions,
    /// Do not write results/ or report/ (print the summary only).
    #[arg(long)]
    pub dry_run: bool,
    /// Skip the explanation runs (tolerance ladders, drift attribution) that a normal run
    /// adds for the selected runs of the papers' solvers and of the group-code experiments.
    #[arg(long)]
    pub skip_explain: bool,
    /// Also write the run's phase table (the wall time of each phase, printed at the end) as
    /// CSV to FILE: the suite's measurement of itself, kept by the benches
    /// (`benches/results/phases.csv`), never in results/.
    #[arg(long, value_name = "FILE")]
    pub phases: Option<PathBuf>,
}

/// `reproduce check`: the regression gate.
#[derive(Args, Clone, Debug, Default, PartialEq, Eq)]
pub struct CheckOptions {
    #[command(flatten)]
    pub selection: SelectionOptions,
    /// The gate's baseline (default: git HEAD's committed results/runs.csv, or the results
    /// directory's runs.csv outside a checkout). Read before anything runs.
    #[arg(long, value_name = "FILE")]
    pub baseline: Option<PathBuf>,
}

/// `reproduce explain`: only the explanation runs of the selection.
#[derive(Args, Clone, Debug, Default, PartialEq, Eq)]
pub struct ExplainOptions {
    #[command(flatten)]
    pub selection: SelectionOptions,
    /// Write nothing (print what would be explained).
    #[arg(long)]
    pub dry_run: bool,
}

/// One choice of published tables as `infer` takes it: `all`, a paper's (`jia2019`) or one
/// table (`jia2019:T2`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TableChoice {
    /// Every published drift table.
    All,
    /// Every drift table of a paper.
    Paper(PaperId),
    /// One table of a paper, named as its `values.csv` names it.
    Table {
        /// The paper.
        paper: PaperId,
        /// The table (`T2`).
        table: String,
    },
}

impl TableChoice {
    /// Whether this choice takes the table `table` of `paper`.
    pub fn takes(&self, paper: &str, table: &str) -> bool {
        match self {
            TableChoice::All => true,
            TableChoice::Paper(p) => p == paper,
            TableChoice::Table { paper: p, table: t } => p == paper && t == table,
        }
    }
}

impl std::fmt::Display for TableChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TableChoice::All => f.write_str("all"),
            TableChoice::Paper(p) => write!(f, "{p}"),
            TableChoice::Table { paper, table } => write!(f, "{paper}:{table}"),
        }
    }
}

/// The tables `infer` fits: a comma-separated list of [`TableChoice`]s, never empty, parsed at
/// the command line. Whether a well-formed paper or table exists is known only from the papers'
/// files, so that is checked when they are read (`crate::inference::select_tables`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tables(Vec<TableChoice>);

impl Tables {
    /// Whether one of the choices takes the table `table` of `paper`.
    pub fn take(&self, paper: &str, table: &str) -> bool {
        self.0.iter().any(|c| c.takes(paper, table))
    }
}

impl std::fmt::Display for Tables {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, choice) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(",")?;
            }
            write!(f, "{choice}")?;
        }
        Ok(())
    }
}

/// A table choice that is not `all`, a paper id or `paper:table`.
#[derive(Debug, thiserror::Error)]
pub enum TablesError {
    /// The paper part is not a paper id.
    #[error("table {}: {source}", settings::shown(text))]
    Paper {
        /// The choice given.
        text: String,
        /// Why its paper is not an id.
        #[source]
        source: spec::ids::IdError,
    },
    /// An empty choice, or an empty table after `paper:`.
    #[error(
        "table {}: expected `all`, a paper id (`PAPER`) or `PAPER:TABLE`, comma-separated",
        settings::shown(text)
    )]
    Empty {
        /// The choice given.
        text: String,
    },
}

impl std::str::FromStr for Tables {
    type Err = TablesError;

    /// `all`, `PAPER` or `PAPER:TABLE`, comma-separated (blanks around each are ignored).
    fn from_str(text: &str) -> Result<Self, TablesError> {
        let choice = |item: &str| {
            let paper = |p: &str| {
                PaperId::new(p).map_err(|source| TablesError::Paper {
                    text: item.to_string(),
                    source,
                })
            };
            match item.split_once(':') {
                _ if item == "all" => Ok(TableChoice::All),
                None if !item.is_empty() => paper(item).map(TableChoice::Paper),
                Some((p, t)) if !t.trim().is_empty() => Ok(TableChoice::Table {
                    paper: paper(p)?,
                    table: t.trim().to_string(),
                }),
                _ => Err(TablesError::Empty {
                    text: item.to_string(),
                }),
            }
        };
        text.split(',')
            .map(|item| choice(item.trim()))
            .collect::<Result<_, _>>()
            .map(Tables)
    }
}

/// `reproduce infer TABLE`: setup inference.
#[derive(Args, Clone, Debug, PartialEq, Eq)]
pub struct InferOptions {
    /// `all`, a paper (`jia2019`), one table (`jia2019:T2`) or a comma-separated list of these.
    #[arg(value_name = "TABLE")]
    pub table: Tables,
    /// Write nothing (print the fits only).
    #[arg(long)]
    pub dry_run: bool,
}

/// Which shard: `K/N` as given, or `auto` (from the scheduler's environment), parsed at the
/// command line.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ShardSpec {
    /// K and N from a Slurm job array or a Kubernetes Indexed Job (`Shard::from_env`).
    #[default]
    Auto,
    /// Shard K of N.
    Given(Shard),
}

/// A shard that is neither `auto` nor a valid `K/N`.
#[derive(Debug, thiserror::Error)]
#[error("{0}; or `auto` (K and N from a Slurm job array or a Kubernetes Indexed Job)")]
pub struct ShardSpecError(#[source] ShardError);

impl std::str::FromStr for ShardSpec {
    type Err = ShardSpecError;

    /// `auto`, or `K/N` with 1 <= K <= N.
    fn from_str(text: &str) -> Result<Self, ShardSpecError> {
        match text {
            "auto" => Ok(ShardSpec::Auto),
            kn => Shard::parse(kn)
                .map(ShardSpec::Given)
                .map_err(ShardSpecError),
        }
    }
}

/// `reproduce shard [K/N]`: one shard of the selection, for a cluster.
#[derive(Args, Clone, Debug, Default, PartialEq, Eq)]
pub struct ShardOptions {
    /// `K/N` (K = 1..N; a run's shard is a stable hash of its key), or `auto` (the default):
    /// K and N from a Slurm job array (K = SLURM_ARRAY_TASK_ID; N = --shards, else
    /// DRIFTBENCH_SHARDS, else SLURM_ARRAY_TASK_COUNT for an array of exactly 1-N) or a
    /// Kubernetes Indexed Job (K = JOB_COMPLETION_INDEX + 1; N = --shards or DRIFTBENCH_SHARDS).
    #[arg(value_name = "K/N", default_value = "auto")]
    pub shard: ShardSpec,
    /// The number of shards N for `auto`: needed under Kubernetes and for a Slurm task
    /// resubmitted alone (`sbatch --array=K`).
    #[arg(long, value_name = "N")]
    pub shards: Option<usize>,
    #[command(flatten)]
    pub selection: SelectionOptions,
}

/// `reproduce merge DIR...`: finished shard directories into results/.
#[derive(Args, Clone, Debug, Default, PartialEq, Eq)]
pub struct MergeOptions {
    /// The shard directories (of `reproduce shard`).
    #[arg(value_name = "DIR", required = true, num_args = 1..)]
    pub dirs: Vec<PathBuf>,
    /// Do not render the report (render it afterwards with `reproduce report`): the merge
    /// then only checks the shards and writes results/.
    #[arg(long, visible_alias = "skip-report")]
    pub no_report: bool,
}

/// `reproduce list`: the experiments and their runs.
#[derive(Args, Clone, Debug, Default, PartialEq, Eq)]
pub struct ListOptions {
    #[command(flatten)]
    pub selection: SelectionOptions,
    /// List only the runs of this shard (`K/N` or `auto`, as `reproduce shard` takes it).
    #[arg(long, value_name = "K/N", num_args = 0..=1, default_missing_value = "auto")]
    pub shard: Option<ShardSpec>,
    /// With no --shard: how many of the selected runs each of N shards gets; with
    /// `--shard auto`: N.
    #[arg(long, value_name = "N")]
    pub shards: Option<usize>,
}

/// `reproduce cost`: the cost against the number of joints.
#[derive(Args, Clone, Debug, Default, PartialEq, Eq)]
pub struct CostOptions {
    /// Measure and print; write nothing.
    #[arg(long)]
    pub dry_run: bool,
}

/// `reproduce score FILE --task EXPERIMENT/VARIANT`: a trajectory made elsewhere, scored.
#[derive(Args, Clone, Debug, PartialEq, Eq)]
pub struct ScoreOptions {
    /// The trajectory: CSV (t, theta_1..n, optionally thetadot_1..n) or a MAT-file.
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// The task: `"<experiment> / <variant>"` (`reproduce list` names them).
    #[arg(long, value_name = "ID", value_parser = TaskKey::parse)]
    pub task: TaskKey,
    /// Which columns of a MAT-file's `y` hold theta and thetadot, 1-based and inclusive as
    /// MATLAB counts: `theta=1:6,thetadot=7:12` (the rest, e.g. a network's own state, is
    /// ignored). Without it `y` must be n or 2n columns wide.
    #[arg(long, value_name = "SPEC")]
    pub columns: Option<inputs::trajectory::Columns>,
    /// The scored trajectory's solver id, a slug (its row's key is the task and this name, so
    /// trajectories of one task scored under different names keep their own rows).
    #[arg(long, value_name = "ID", default_value = records::TRAJECTORY_KIND)]
    pub name: String,
    /// Where the score, its trace and figure are written (default: scores/ in the working
    /// directory; never a directory this program seals, such as results/ or report/).
    #[arg(
        long,
        alias = "score-out",
        value_name = "DIR",
        default_value = "scores"
    )]
    pub out: PathBuf,
}

/// The modes of the binary, each with its options.
#[derive(Subcommand, Clone, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Run the selected experiments, the explanation layer and the report (the default).
    Run(RunOptions),
    /// The regression gate: run the selection and compare it with git HEAD's committed
    /// results/runs.csv (or --baseline; status, drifts, every measured metric and the effort
    /// counts and tolerances the report's tables show, not timings), and with the committed
    /// ladder, attribution, leaderboard and (with no selection flags, re-run) control tables;
    /// write nothing; exit 3 on any difference, each named by table, row and column
    /// (docs/reference/exit-codes.md).
    Check(CheckOptions),
    /// Re-render report/ and its figures from the stored results, running nothing.
    Report,
    /// Only the explanation runs of the selection (tolerance ladders and drift attribution;
    /// results/ladder.csv and results/attribution.csv), then the report.
    Explain(ExplainOptions),
    /// Setup inference: fit the parameters the papers leave open (path pose and plane tilt,
    /// size where it is assumed, direction, RMP reading; robot variant and MATLAB-default
    /// tolerances as discrete hypotheses; experiments/inference/family.toml) to a published
    /// drift table, jointly and column by column. Writes results/inference.csv and
    /// results/inference-entries.csv (each table as it finishes), then the report. Takes
    /// minutes per table.
    Infer(InferOptions),
    /// Run one shard of the selection into ROOT/results-shard-K-of-N/ (docs/cluster.md),
    /// bound to the shard and selection at the start (another selection's or sweep's
    /// directory is refused): runs.csv, traces/ and, written last, shard.toml. No explanation
    /// layer, no report. A shard started again resumes from its journal.
    Shard(ShardOptions),
    /// Merge finished shard directories into results/ and render the report: checks that they
    /// agree on N and on the experiment files and that every selected run is in exactly one
    /// shard; otherwise names the missing or duplicated runs, writes nothing and exits 2.
    Merge(MergeOptions),
    /// List the experiments and their runs (keys and labels), then exit.
    List(ListOptions),
    /// List the robots experiment files can name (built-in models and every robot file of
    /// robots/data/) with their joint counts and check values. Needs no project.
    Robots,
    /// Cost against the number of joints on the n-link arms (results/dof-cost.csv with the
    /// fitted growth exponents and the machine), then the report. About a minute; run it on
    /// an otherwise idle machine.
    Cost(CostOptions),
    /// Score a trajectory produced elsewhere on a task, as a run is scored: scores.csv, its
    /// trace and figure under --out.
    Score(ScoreOptions),
}
