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
//!
//! A numerical run (robio2018's methods in a fixed-step loop of step h, stopped at
//! |e(U)|_2 <= tol) splits the same way over its own ladder (d*(h): the loop at the same h,
//! stopped at 1e-10):
//!
//! ```text
//!   d_run = d_exact + (d*(h) - d_exact) + (d_run - d*(h))
//!         = scheme  + sampling gap       + stopping rule
//! ```

use serde::{Deserialize, Serialize};
use spec::ids::{ExperimentId, SolverId, VariantId};

/// One component of a run's drift: a term of the telescoping sum, or a switch effect ("of
/// which"). Stored by its label, which is also how the report names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Component {
    /// The run's own drift d_run.
    #[serde(rename = "run")]
    Run,
    /// d_exact: the exact column integrated to convergence.
    #[serde(rename = "scheme (exact, converged)")]
    Scheme,
    /// d_net - d_exact (a network).
    #[serde(rename = "network lag")]
    NetworkLag,
    /// d_run - d_net (a network).
    #[serde(rename = "integration error")]
    IntegrationError,
    /// d*(h) - d_exact (a numerical method): the fixed-step loop's sampling.
    #[serde(rename = "sampling gap")]
    SamplingGap,
    /// d_run - d*(h) (a numerical method): its stopping rule |e(U)|_2 <= tol.
    #[serde(rename = "stopping rule")]
    StoppingRule,
    /// The effect of the injected perturbation.
    #[serde(rename = "of which: injected perturbation")]
    InjectedPerturbation,
    /// The effect of a path that does not close.
    #[serde(rename = "of which: path non-closure")]
    PathNonClosure,
    /// The effect of our regularisation of kong2019's sign-power.
    #[serde(rename = "of which: sign-power smoothing (ours)")]
    SignPowerSmoothing,
}

impl Component {
    /// The three terms of a network run's sum, in order.
    pub const NETWORK_SUM: [Component; 3] = [
        Component::Scheme,
        Component::NetworkLag,
        Component::IntegrationError,
    ];
    /// The three terms of a numerical run's sum, in order.
    pub const NUMERICAL_SUM: [Component; 3] = [
        Component::Scheme,
        Component::SamplingGap,
        Component::StoppingRule,
    ];

    /// The label (the stored value and the report's name).
    pub fn label(self) -> &'static str {
        match self {
            Component::Run => "run",
            Component::Scheme => "scheme (exact, converged)",
            Component::NetworkLag => "network lag",
            Component::IntegrationError => "integration error",
            Component::SamplingGap => "sampling gap",
            Component::StoppingRule => "stopping rule",
            Component::InjectedPerturbation => "of which: injected perturbation",
            Component::PathNonClosure => "of which: path non-closure",
            Component::SignPowerSmoothing => "of which: sign-power smoothing (ours)",
        }
    }

    /// A switch effect ("of which"): part of the terms of the sum, not a further term.
    pub fn is_switch(self) -> bool {
        matches!(
            self,
            Component::InjectedPerturbation
                | Component::PathNonClosure
                | Component::SignPowerSmoothing
        )
    }
}

/// One component of one run's drift, as stored in `results/attribution.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AttributionRow {
    /// The paper id of the run's experiment file.
    pub paper: String,
    /// The run's experiment id.
    pub experiment: ExperimentId,
    /// The run's variant and solver ids (with `experiment`, its key).
    pub variant_id: VariantId,
    /// The run's solver id.
    pub solver_id: SolverId,
    /// Labels (display only).
    pub variant: String,
    /// The solver's label (display only).
    pub solver: String,
    /// Which term or switch effect the row holds.
    pub component: Component,
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
    pub fn key(&self) -> spec::RunKey {
        spec::RunKey::new(
            self.experiment.clone(),
            self.variant_id.clone(),
            self.solver_id.clone(),
        )
    }
}

crate::drift_columns!(AttributionRow, drift, "drift_norm");
