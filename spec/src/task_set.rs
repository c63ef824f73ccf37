//! The control experiments' standard task set as data: which runs of the experiment files
//! they take (an experiment and one of its variants each, [`TaskRef`]) and how much they run
//! on them ([`Budget`]). Crate `catalog` reads it from `experiments/control/tasks.toml`; the
//! engine (crate `control`) takes it as it is and reads no file.

/// The control period of the control experiments' verdicts (s): the period every method runs
/// at, beside the sweep of the networks and the active set over other periods. The rows carry
/// each run's period (`h_ms`) but not which period is the main one, so the standard task set's
/// budget and the report take it from here.
pub const MAIN_H: f64 = 1e-3;

/// A task: an experiment and one of its variants (ids).
#[derive(Clone, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskRef {
    /// The experiment's id.
    pub experiment: crate::ids::ExperimentId,
    /// The variant's id.
    pub variant: crate::ids::VariantId,
}

/// How much the control experiments run.
#[derive(Clone, Debug, PartialEq)]
pub struct Budget {
    /// The control period every method runs at (s); [`MAIN_H`], the period of the report's
    /// verdicts, for the standard task set.
    pub h: f64,
    /// The other periods of the sweep (s): networks and the active set only.
    pub sweep: Vec<f64>,
    /// Cycles of the many-cycles runs.
    pub cycles: usize,
    /// Ticks of a network's check run for the efficiency claim.
    pub check_ticks: usize,
    /// A check run's Euler steps per tick over the steps the network needs
    /// (`records::control::steps_needed`).
    pub check_steps_factor: u64,
}

/// The standard task set: its tasks, in the file's order, and their budget.
#[derive(Clone, Debug, PartialEq)]
pub struct TaskSet {
    /// Every paper's scheme once.
    pub tasks: Vec<TaskRef>,
    /// How much is run on them.
    pub budget: Budget,
}
