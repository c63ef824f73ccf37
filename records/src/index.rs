//! The stored runs, indexed the way the report looks them up: by their key (experiment,
//! variant and solver ids), by paper and by experiment; metric access by column name; a run's status in words.

use crate::error::MissingRun;
use crate::runs::RunRow;

/// The solver id of the exact column.
pub use spec::EXACT_ID as EXACT;

/// All rows of `results/runs.csv`, sorted by (experiment, variant, solver).
#[derive(Clone, Debug)]
pub struct Runs {
    rows: Vec<RunRow>,
}

impl Runs {
    /// Indexes `rows` (sorted, so every listing below is deterministic).
    pub fn new(mut rows: Vec<RunRow>) -> Self {
        rows.sort_by_key(|r| r.key());
        Runs { rows }
    }

    /// Every run.
    pub fn all(&self) -> &[RunRow] {
        &self.rows
    }

    /// The run of solver id `solver` on variant id `variant` of `experiment`.
    pub fn find(&self, experiment: &str, variant: &str, solver: &str) -> Option<&RunRow> {
        self.rows.iter().find(|r| {
            r.experiment == experiment && r.variant_id == variant && r.solver_id == solver
        })
    }

    /// Like [`Runs::find`], with the missing run as an error.
    pub fn need(
        &self,
        experiment: &str,
        variant: &str,
        solver: &str,
    ) -> Result<&RunRow, MissingRun> {
        self.find(experiment, variant, solver)
            .ok_or_else(|| MissingRun {
                experiment: experiment.to_string(),
                variant: variant.to_string(),
                solver: solver.to_string(),
            })
    }

    /// The runs of one paper (the `paper` column).
    pub fn of_paper<'a>(&'a self, paper: &'a str) -> impl Iterator<Item = &'a RunRow> + 'a {
        self.rows.iter().filter(move |r| r.paper == paper)
    }

    /// The runs of one experiment.
    pub fn of_experiment<'a>(
        &'a self,
        experiment: &'a str,
    ) -> impl Iterator<Item = &'a RunRow> + 'a {
        self.rows.iter().filter(move |r| r.experiment == experiment)
    }

    /// The experiment ids of one paper, sorted.
    pub fn experiments(&self, paper: &str) -> Vec<String> {
        let mut ids: Vec<String> = self
            .of_paper(paper)
            .map(|r| r.experiment.to_string())
            .collect();
        ids.dedup();
        ids
    }
}

/// True for a run of a neural solver (everything but the exact column).
pub fn is_neural(r: &RunRow) -> bool {
    !r.is_exact()
}

/// True when the run reached the end of its task.
pub fn completed(r: &RunRow) -> bool {
    r.completed()
}

/// `ok`, or `failed at t = ... (reason)`.
pub fn status_text(r: &RunRow) -> String {
    if completed(r) {
        "ok".to_string()
    } else {
        format!("{} ({})", failed_at(r), r.failure)
    }
}

/// `failed at t = ...` without the reason (for narrow cells).
pub fn failed_at(r: &RunRow) -> String {
    match r.failed_at {
        Some(t) => format!("failed at t = {t:.3} s"),
        None => "failed".to_string(),
    }
}

/// A metric's name and how it is read from a row.
pub type Column = (&'static str, fn(&RunRow) -> Option<f64>);

/// Every metric besides the joint drifts: the [`MEASURED`] ones, then the [`TIMINGS`].
pub fn metrics() -> impl Iterator<Item = &'static Column> {
    MEASURED.iter().chain(TIMINGS)
}

/// A numeric column of a run by its `runs.csv` name (`drift_k` for joint k, or one of
/// [`metrics`]); `None` when not measured or unknown.
pub fn metric(r: &RunRow, name: &str) -> Option<f64> {
    if let Some(k) = joint_drift(name) {
        return k.checked_sub(1).and_then(|i| r.drift.get(i).copied());
    }
    metrics()
        .find(|(n, _)| *n == name)
        .and_then(|(_, column)| column(r))
}

/// Whether `name` is a metric [`metric`] knows: `drift_k` (k >= 1) or one of [`metrics`].
pub fn is_metric(name: &str) -> bool {
    joint_drift(name).is_some_and(|k| k >= 1) || metrics().any(|(n, _)| *n == name)
}

/// k of `drift_k`.
fn joint_drift(name: &str) -> Option<usize> {
    name.strip_prefix("drift_")?.parse::<usize>().ok()
}

/// The measured metrics of a run besides the joint drifts `drift_k`, by name, and how each is
/// read: what the simulation computes, identical from run to run (the gate compares them all).
pub const MEASURED: &[Column] = &[
    ("drift_norm", |r| r.drift_norm),
    // The largest |theta_k(T) - theta_k(0)| over the joints ("every joint drift < x").
    ("drift_max_abs", |r| {
        (!r.drift.is_empty()).then(|| r.drift.iter().fold(0.0f64, |m, d| m.max(d.abs())))
    }),
    ("solver_iterations", |r| {
        r.solver_iterations.map(|v| v as f64)
    }),
    ("solver_iterations_max", |r| {
        r.solver_iterations_max.map(|v| v as f64)
    }),
    ("solver_products", |r| r.solver_products.map(|v| v as f64)),
    ("drift_ref_norm", |r| r.drift_ref_norm),
    ("max_pos_err", |r| r.max_pos_err),
    ("rms_pos_err", |r| r.rms_pos_err),
    ("final_pos_err", |r| r.final_pos_err),
    ("theta_margin", |r| r.theta_margin),
    ("thetadot_margin", |r| r.thetadot_margin),
    ("peak_thetadot", |r| r.peak_thetadot),
    ("peak_thetaddot", |r| r.peak_thetaddot),
    ("peak_torque", |r| r.peak_torque),
    ("min_sigma_j", |r| r.min_sigma_j),
    ("net_error_final", |r| r.net_error_final),
    ("net_error_max_after_1s", |r| r.net_error_max_after_1s),
    ("score_max_dx", |r| r.score_max_dx),
    ("score_rms_dx", |r| r.score_rms_dx),
    ("score_rms_dx_after_1s", |r| r.score_rms_dx_after_1s),
    ("score_max_obj_gap", |r| r.score_max_obj_gap),
    ("score_max_violation", |r| r.score_max_violation),
];

/// What the report's tables show of a run besides its metrics, by `runs.csv` name: the
/// integrator's tolerances and step limit, and the effort counts (steps, rejected steps,
/// right-hand-side and Jacobian evaluations, QP solves, score samples, failed exact solves).
/// Identical from run to run as the metrics are (the timings are not): the gate compares them
/// too.
pub const SHOWN: &[Column] = &[
    ("rtol", |r| Some(r.rtol)),
    ("atol", |r| Some(r.atol)),
    ("max_step", |r| r.max_step),
    ("steps", |r| Some(r.steps as f64)),
    ("rejected", |r| Some(r.rejected as f64)),
    ("rhs_evals", |r| Some(r.rhs_evals as f64)),
    ("jac_evals", |r| Some(r.jac_evals as f64)),
    ("qp_solves", |r| Some(r.qp_solves as f64)),
    ("score_samples", |r| r.score_samples.map(|n| n as f64)),
    ("score_failures", |r| Some(r.score_failures as f64)),
];

/// The timings of a run (s): measured on a machine, different from run to run.
pub const TIMINGS: &[Column] = &[("wall_s", |r| Some(r.wall_s)), ("sim_s", |r| Some(r.sim_s))];
