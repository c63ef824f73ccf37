//! `results/ladder.csv`: the tolerance ladder's rows (crate `explain`, module `ladder`), one run
//! re-integrated at a sequence of tolerances and methods to tell which published digits could
//! be integration noise. One row per rung: its method and tolerances, whether it is the run's
//! own setting, its drift theta(T) - theta(0) per joint (`drift_1 .. drift_K`), and against the
//! converged drift d* (the finest completed rung, `reference`) the relative change
//! |d - d*| / |d*| and the digits shared with d*, -log10 of that change.
//!
//! A numerical run's rungs are its fixed-step loop stopped at a sequence of tolerances: their
//! `method` is [`LadderMethod::FixedStep`], `rtol` holds the stopping tolerance
//! (|e(U)|_2 <= rtol), `atol` is 0 and `max_step` the loop's step h.

use crate::runs::Status;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use settings::Method;
use spec::ids::{ExperimentId, SolverId, VariantId};

/// How a rung integrated (the `method` column): an integrator, stored by its id (`bdf`,
/// `dopri5`, ...), or a numerical run's fixed-step loop, stored as `fixed-step`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LadderMethod {
    /// An adaptive integrator at the rung's tolerances.
    Integrator(Method),
    /// A numerical run's fixed-step loop, stopped at the rung's tolerance (module docs).
    FixedStep,
}

impl LadderMethod {
    /// The id the column stores.
    pub fn id(self) -> &'static str {
        match self {
            LadderMethod::Integrator(m) => m.label(),
            LadderMethod::FixedStep => "fixed-step",
        }
    }
}

impl std::fmt::Display for LadderMethod {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id())
    }
}

impl Serialize for LadderMethod {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.id())
    }
}

impl<'de> Deserialize<'de> for LadderMethod {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = std::borrow::Cow::<str>::deserialize(d)?;
        if text == LadderMethod::FixedStep.id() {
            return Ok(LadderMethod::FixedStep);
        }
        Method::deserialize(serde::de::value::StrDeserializer::<D::Error>::new(&text))
            .map(LadderMethod::Integrator)
    }
}

/// One rung's result, as stored in `results/ladder.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LadderRow {
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
    /// How the rung integrated: an integrator's id, or `fixed-step`.
    pub method: LadderMethod,
    /// RelTol, or a numerical rung's stopping tolerance.
    pub rtol: f64,
    /// AbsTol (0 for a numerical rung).
    pub atol: f64,
    /// The integrator's MaxStep, or a numerical rung's step h.
    pub max_step: Option<f64>,
    /// The run's own setting (the rung results/runs.csv holds).
    pub as_run: bool,
    /// Whether the rung completed (`ok`) or stopped early (`failed`).
    pub status: Status,
    /// Why the rung failed, in words (empty when it completed).
    pub failure: String,
    /// theta(T) - theta(0) per joint (none for a rung that did not complete): the columns
    /// `drift_1 .. drift_K`.
    #[serde(skip)]
    pub drift: Vec<f64>,
    /// |theta(T) - theta(0)|_2 (rad); empty for a rung that did not complete.
    pub drift_norm: Option<f64>,
    /// Largest position error |r*(t) - f(theta(t))|_2 (m); empty when no step was taken.
    pub max_pos_err: Option<f64>,
    /// |d - d*| / |d*| against the converged drift d* (the finest completed rung).
    pub rel_change: Option<f64>,
    /// -log10(rel_change): significant digits shared with the converged drift.
    pub stable_digits: Option<f64>,
    /// This rung is the converged reference d*.
    pub reference: bool,
    /// Accepted steps (a numerical rung: instants of its loop after the first).
    pub steps: usize,
    /// Steps rejected by the integrator's local error test.
    pub rejected: usize,
    /// Evaluations of the ODE's right-hand side.
    pub rhs_evals: usize,
    /// Wall time of the rung's integration (s).
    pub wall_s: f64,
}

impl LadderRow {
    /// The key of the run the row explains.
    pub fn key(&self) -> spec::RunKey {
        spec::RunKey::new(
            self.experiment.clone(),
            self.variant_id.clone(),
            self.solver_id.clone(),
        )
    }
}

impl LadderRow {
    /// Whether the rung completed.
    pub fn completed(&self) -> bool {
        self.status == Status::Ok
    }
}

crate::drift_columns!(LadderRow, drift, "drift_norm");
