//! `results/attribution.csv`: the drift attribution's rows (crate `explain`, module
//! `attribution`). For each explained run, its drift d_run split exactly, per joint, as
//!
//! ```text
//!   d_run = d_exact + (d_net - d_exact) + (d_run - d_net)
//!         = scheme  + network lag        + integration error
//! ```
//!
//! (d_net, d_exact: the network and the exact column integrated to convergence), one row per
//! component, then one "of which" row per switched ingredient (a controlled re-run without it:
//! the injected perturbation, a path that does not close, the sign-power's smoothing), which
//! overlaps the terms above rather than adding to them.

use serde::{Deserialize, Serialize};

/// One component of one run's drift, as stored in `results/attribution.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AttributionRow {
    pub paper: String,
    pub experiment: String,
    /// The run's variant and solver ids (with `experiment`, its key).
    pub variant_id: String,
    pub solver_id: String,
    /// Labels (display only).
    pub variant: String,
    pub solver: String,
    /// `run`, `scheme (exact, converged)`, `network lag`, `integration error`, or an
    /// `of which: ...` switch effect.
    pub component: String,
    /// The component's drift per joint (none where it could not be formed): the columns
    /// `drift_1 .. drift_K`.
    #[serde(skip)]
    pub drift: Vec<f64>,
    /// 2-norm of the component (of the drift itself for `run` and `scheme`).
    pub drift_norm: Option<f64>,
    /// |component| / |d_run|.
    pub share: Option<f64>,
    /// Max position error of the run (`run`, `scheme`, `network lag` = converged network), or
    /// the change of it the ingredient causes (switch rows).
    pub max_pos_err: Option<f64>,
    /// Why a component is missing (a rung or switch run that did not complete).
    pub note: String,
}

impl AttributionRow {
    /// The key of the run the row explains.
    pub fn key(&self) -> catalog::run_key::RunKey {
        catalog::run_key::RunKey::new(&self.experiment, &self.variant_id, &self.solver_id)
    }
}

crate::drift_columns!(AttributionRow, drift, "drift_norm");
