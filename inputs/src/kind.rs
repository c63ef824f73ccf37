//! The kinds of input file and the size cap of each: a file larger than its cap is refused
//! before it is parsed (and never read past the cap). The caps are stated in
//! `docs/experiments.md` and `docs/papers.md`; each is orders of magnitude above the largest
//! file of its kind the suite ships, and small enough that reading one cannot exhaust memory.

/// What an input file is, which sets its cap and how errors call it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `experiments/*.toml` (the largest shipped is 12 kB).
    Experiment,
    /// `papers/<paper>/paper.toml` (5 kB).
    PaperToml,
    /// `papers/<paper>/values.csv` (7 kB).
    PaperValues,
    /// A trajectory to score, as CSV (a sample per row).
    TrajectoryCsv,
    /// A trajectory to score, as a MAT-file (compressed or not; its decompressed size has its
    /// own bound, in [`crate::trajectory::mat_file`]).
    TrajectoryMat,
    /// The regression gate's `--baseline` runs file.
    Baseline,
    /// A shard's `shard.toml` (it lists the shard's run keys).
    ShardManifest,
    /// A shard's `shard-binding.toml` (its shard, selection and experiments hash).
    ShardBinding,
    /// An integrity manifest, `manifest.toml`, of `results/`, `report/` or a shard directory
    /// (`store::integrity`; the committed report's is 110 kB).
    Manifest,
    /// A table one of the Python package's scripts wrote, to be sealed into `results/`
    /// (`driftbench.into_results`; the committed ones are at most 5 kB).
    ScriptTable,
    /// A URDF an arm is read from (`robots::urdf`; the URDFs of common arms are 10-400 kB).
    Urdf,
    /// The inference's setup family, `experiments/inference/family.toml` (2 kB).
    InferenceFamily,
    /// The control experiments' task set, `experiments/control/tasks.toml` (1 kB).
    TaskSet,
    /// A file of a directory the program writes and seals (`results/`, `report/`, a shard
    /// directory): a table, a trace, the journal and its seal (the largest committed is
    /// `results/runs.csv`, about 200 kB).
    Owned,
    /// A paper's robot file, `papers/<paper>/robots/*.toml` (the suite's own are at most 3 kB;
    /// a 1000-joint arm is about 100 kB).
    RobotFile,
}

const MIB: u64 = 1 << 20;

impl Kind {
    /// The largest file of this kind that is read, in bytes.
    pub fn cap(self) -> u64 {
        match self {
            Kind::Experiment
            | Kind::PaperToml
            | Kind::ShardBinding
            | Kind::RobotFile
            | Kind::InferenceFamily
            | Kind::TaskSet => MIB,
            Kind::PaperValues => 4 * MIB,
            Kind::TrajectoryCsv | Kind::TrajectoryMat | Kind::Baseline | Kind::Owned => 256 * MIB,
            Kind::ShardManifest | Kind::ScriptTable | Kind::Manifest => 64 * MIB,
            Kind::Urdf => 16 * MIB,
        }
    }

    /// What the file is called in messages.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Experiment => "experiment file",
            Kind::PaperToml => "paper.toml",
            Kind::PaperValues => "values.csv",
            Kind::TrajectoryCsv => "trajectory CSV",
            Kind::TrajectoryMat => "trajectory MAT-file",
            Kind::Baseline => "baseline runs file",
            Kind::ShardManifest => "shard manifest",
            Kind::ShardBinding => "shard binding",
            Kind::Manifest => "integrity manifest",
            Kind::ScriptTable => "results table",
            Kind::Urdf => "URDF",
            Kind::RobotFile => "robot file",
            Kind::Owned => "file the program wrote",
            Kind::InferenceFamily => "inference family file",
            Kind::TaskSet => "control task set",
        }
    }
}

impl std::fmt::Display for Kind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
