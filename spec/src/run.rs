//! A run's choices as data: its solver ([`SolverChoice`]: the exact optimum, a network or a
//! registered QP solver), where it is scored ([`Scoring`]), where a network starts
//! ([`NetworkInit`]), limits that replace the robot's ([`LimitsSpec`]) and the part of a run
//! that could not be built ([`JobPart`]). Crate `catalog` reads them from experiment files;
//! the engine (crates `simulation`, `control`) builds from them.

use crate::ids::VariantId;
use crate::ids::{ExperimentId, IdError, SolverId};
use crate::mount::{MountError, MountSpec};
use crate::numerical::NumericalSpec;
use crate::path::PathError;
use crate::path::PathSpec;
use crate::run_key::{RunKey, TaskKey};
use crate::scheme::SchemeError;
use crate::scheme::SchemeSpec;
use crate::solver_kind::SolverKind;
use serde::{Deserialize, Serialize};
use settings::IntegratorSettings;
use settings::NetworkError;
use settings::SolverSpec;

/// Elementwise limits `lower <= value <= upper`, one entry per joint (an experiment's
/// `joint_limits` in rad, `velocity_limits` in rad/s), replacing the robot model's.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LimitsSpec {
    /// Lower limits, one per joint (below `upper`; below 0 for velocity limits).
    pub lower: Vec<f64>,
    /// Upper limits, one per joint (above `lower`; above 0 for velocity limits).
    pub upper: Vec<f64>,
}

impl LimitsSpec {
    /// Checks `n` finite entries on each side with lower < upper; velocity limits (`velocity`)
    /// must also hold 0 (lower < 0 < upper: the arm can stop, and the bound conversion of
    /// robio2018 (10) stays feasible at rest).
    pub fn check(&self, n: usize, velocity: bool) -> Result<(), LimitsError> {
        for v in [&self.lower, &self.upper] {
            if v.len() != n {
                return Err(LimitsError::Length {
                    given: v.len(),
                    joints: n,
                });
            }
            if v.iter().any(|x| !x.is_finite()) {
                return Err(LimitsError::NotFinite);
            }
        }
        for (i, (lo, hi)) in self.lower.iter().zip(&self.upper).enumerate() {
            let ok = lo < hi && (!velocity || (*lo < 0.0 && *hi > 0.0));
            if !ok {
                return Err(LimitsError::Order {
                    joint: i + 1,
                    lower: *lo,
                    upper: *hi,
                    requirement: if velocity {
                        "lower < 0 < upper"
                    } else {
                        "lower < upper"
                    },
                });
            }
        }
        Ok(())
    }
}

/// Why a [`LimitsSpec`] does not fit a robot ([`LimitsSpec::check`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LimitsError {
    /// A side has not one entry per joint.
    #[error("has {given} entries, the robot has {joints} joints")]
    Length {
        /// The entries given.
        given: usize,
        /// The robot's joint count.
        joints: usize,
    },
    /// A side has a NaN or infinite entry.
    #[error("entries must be finite")]
    NotFinite,
    /// A joint's limits are out of order.
    #[error("joint {joint}: lower = {lower}, upper = {upper} (must be {requirement})")]
    Order {
        /// The joint, numbered from 1.
        joint: usize,
        /// Its lower limit (rad, or rad/s for velocity limits).
        lower: f64,
        /// Its upper limit (rad, or rad/s for velocity limits).
        upper: f64,
        /// What must hold: `lower < upper` (joint limits) or `lower < 0 < upper` (velocity
        /// limits).
        requirement: &'static str,
    },
}

/// Where a network's state starts: the papers leave it open, the group's code starts from zero.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum NetworkInit {
    /// y(0) = 0 (thetadot = 0 and zero multipliers at the velocity level), as the group's code.
    #[default]
    Zero,
    /// The network's joint command starts at the exact optimum x*(0) of the QP at t = 0 (its
    /// other state entries, multipliers and auxiliary variables, at zero): no start transient.
    Exact,
}

/// The solver id of the exact column (the exact optimum x*(t) in the loop).
pub const EXACT_ID: &str = "exact";

/// Where a network run is compared with the exact optimum (one exact QP solve each).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum Scoring {
    /// At every accepted step of the integrator (the default: the score sees every state the
    /// network reaches).
    #[default]
    EveryStep,
    /// At most this many instants: the first accepted step at or after each point of a uniform
    /// grid of the run's duration (and the last step), so a run of 10^5 steps costs a bounded
    /// number of exact solves; `score_samples` in results says how many were taken.
    MaxInstants(usize),
    /// Not scored (the explanation layer's controlled re-runs need only drift and error).
    Off,
}

/// The solver of one run: the exact optimum or a neural network.
#[derive(Clone, Debug, PartialEq)]
pub enum SolverChoice {
    /// The exact column: the QP solved to optimality at every evaluation.
    Exact,
    /// A neural network, with its parameters.
    Neural(SolverSpec),
    /// A registered QP solver at every instant of a fixed-step loop.
    Numerical(NumericalSpec),
}

/// The exact column's label: x*(t) from the certified active set, Clarabel where it cannot
/// certify (`qp_fallbacks` in results counts those instants).
pub const EXACT_LABEL: &str = "exact (active set + Clarabel)";

impl SolverChoice {
    /// The solver's kind: the exact column, the network's kind or the numerical method.
    pub fn kind(&self) -> SolverKind {
        match self {
            SolverChoice::Exact => SolverKind::Exact,
            SolverChoice::Neural(s) => SolverKind::Network(s.network_kind()),
            SolverChoice::Numerical(s) => SolverKind::Numerical(s.method),
        }
    }

    /// The solver's id in run keys: [`EXACT_ID`], or the network's [`SolverSpec::id`].
    pub fn id(&self) -> String {
        match self {
            SolverChoice::Exact => EXACT_ID.to_string(),
            SolverChoice::Neural(s) => s.id(),
            SolverChoice::Numerical(s) => s.id(),
        }
    }

    /// The solver's label in tables (display only): the network with its parameters.
    pub fn label(&self) -> String {
        match self {
            SolverChoice::Exact => EXACT_LABEL.to_string(),
            SolverChoice::Neural(s) => s.display_name(),
            SolverChoice::Numerical(s) => s.display_name(),
        }
    }
}

/// Which part of a run could not be built (the engine's setup errors name it, and the
/// experiment files' reader turns it into the field the part comes from).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JobPart {
    /// The robot (`robot`).
    Robot,
    /// The initial joint vector (`theta0`).
    Theta0,
    /// The scheme's joint reference (`theta_ref`).
    ThetaRef,
    /// The path (`path`).
    Path,
    /// The scheme (`scheme`).
    Scheme,
    /// The network or numerical method (`solvers`, `numerical`).
    Solver,
    /// The `joint_limits` / `velocity_limits` override.
    Limits,
    /// The tool offset (`tool`).
    Tool,
    /// The base transform (`base`).
    Base,
}

impl JobPart {
    /// The experiment-file field the part comes from.
    pub fn field(&self) -> &'static str {
        match self {
            JobPart::Robot => "robot",
            JobPart::Theta0 => "theta0",
            JobPart::ThetaRef => "theta_ref",
            JobPart::Path => "path",
            JobPart::Scheme => "scheme",
            JobPart::Solver => "solvers",
            JobPart::Limits => "joint_limits",
            JobPart::Tool => "tool",
            JobPart::Base => "base",
        }
    }
}

/// Why a run's parts could not be built from its specification (robot, pose, path, scheme,
/// network), each wrapping its layer's own error.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SetupError {
    /// The robot is not one of the registry's, or its robot file is invalid: the registry's
    /// error (the valid choices, or the file and field at fault).
    #[error("{0}")]
    UnknownRobot(String),
    /// theta0, theta_ref or a limits override does not have the robot's joint count.
    #[error("has {given} entries, the robot has {joints} joints")]
    PoseLength {
        /// The part: [`JobPart::Theta0`], [`JobPart::ThetaRef`] or [`JobPart::Limits`].
        part: JobPart,
        /// The entries given (for limits, the longer of `lower` and `upper`).
        given: usize,
        /// The robot's joint count.
        joints: usize,
    },
    /// theta0 or theta_ref has a NaN or infinite entry.
    #[error("entries must be finite")]
    PoseNotFinite {
        /// The part: [`JobPart::Theta0`] or [`JobPart::ThetaRef`].
        part: JobPart,
    },
    /// The path cannot be built (built from f(theta_ref)).
    #[error(transparent)]
    Path(#[from] PathError),
    /// The scheme's error, with a hint naming what would fit (e.g. the robots with dynamics).
    #[error("{error}{hint}")]
    Scheme {
        /// The scheme's own error.
        error: SchemeError,
        /// Text appended to its message (empty when there is nothing to suggest).
        hint: String,
    },
    /// The suite's network could not be built for the scheme's QP.
    #[error("{network}: {error} (scheme {scheme})")]
    Network {
        /// The network's display name, e.g. `VP-RNN-PF (sinh)`.
        network: String,
        /// The scheme's name as its paper writes it.
        scheme: String,
        /// The network's own error.
        error: NetworkError,
    },
    /// A network that solves only a QP's equality part given a scheme whose QP has
    /// inequality rows or finite bounds (its answer would not be the scheme's QP's).
    #[error("network {network} solves equality-constrained QPs only, but scheme {scheme} (field `scheme`) poses {rows} inequality rows and {bounds} finite bounds (its joint-limit or bound terms); choose a network that handles inequalities (lvi-pdnn, s-lvi-pdnn, vp-rnn-pf) or a scheme without them")]
    ConstraintsIgnored {
        /// The network's display name.
        network: String,
        /// The scheme's display name.
        scheme: String,
        /// The QP's inequality rows.
        rows: usize,
        /// Its finite bounds (lower and upper counted apart).
        bounds: usize,
    },
    /// The run's QP solver cannot be built: the registry's error (an unknown id with the
    /// registered ones, a setting not taken or out of range, a solver not built in).
    #[error("{0}")]
    QpSolver(String),
    /// A network given by the caller (e.g. a Python network) could not be built: its message.
    #[error("{0}")]
    CustomNetwork(String),
    /// The experiment's tool offset or base transform is invalid, or does not fit the robot
    /// (a tool offset on a robot without a tool frame, a tilted base under dynamics).
    #[error(transparent)]
    Mount(#[from] MountError),
    /// Limits were given for a robot whose dynamics model the scheme reads its limits from.
    #[error("joint_limits / velocity_limits cannot replace the limits of {} for the acceleration-level scheme, which reads them from the robot's dynamics model", settings::shown(robot))]
    LimitsWithDynamics {
        /// The robot's name.
        robot: String,
    },
}

impl SetupError {
    /// The part of the job (and so the experiment-file field) at fault.
    pub fn part(&self) -> JobPart {
        match self {
            SetupError::UnknownRobot(_) => JobPart::Robot,
            SetupError::PoseLength { part, .. } | SetupError::PoseNotFinite { part } => *part,
            SetupError::Path(_) => JobPart::Path,
            SetupError::Scheme { .. } => JobPart::Scheme,
            SetupError::Network { .. }
            | SetupError::CustomNetwork(_)
            | SetupError::QpSolver(_)
            | SetupError::ConstraintsIgnored { .. } => JobPart::Solver,
            SetupError::LimitsWithDynamics { .. } => JobPart::Limits,
            SetupError::Mount(e) if e.field() == "tool" => JobPart::Tool,
            SetupError::Mount(_) => JobPart::Base,
        }
    }
}

/// One run: everything needed to simulate it (crate `catalog` resolves it from an experiment
/// file; the engine builds the run from it and never reads a file).
#[derive(Clone, Debug)]
pub struct RunSpec {
    /// The paper id of the run's file.
    pub paper: String,
    /// The experiment's id.
    pub experiment: ExperimentId,
    /// The variant's id (the variant's declared `id`, or its label's slug).
    pub variant_id: VariantId,
    /// The variant's label (display only).
    pub variant: String,
    /// The robot's model name (the variant's or the experiment's).
    pub robot: String,
    /// The desired path (the variant's or the experiment's).
    pub path: PathSpec,
    /// Initial joint angles theta(0) (rad; the variant's or the experiment's).
    pub theta0: Vec<f64>,
    /// The scheme's joint reference (rad): the variant's or the experiment's `theta_ref`, else
    /// theta0.
    pub theta_ref: Vec<f64>,
    /// Joint-angle limits replacing the robot's (the variant's or experiment's `joint_limits`).
    pub joint_limits: Option<LimitsSpec>,
    /// Joint-velocity limits replacing the robot's.
    pub velocity_limits: Option<LimitsSpec>,
    /// The robot's tool offset and base (the variant's or the experiment's `tool` and `base`,
    /// each field on its own); `None`: the robot as it is.
    pub mount: Option<MountSpec>,
    /// The scheme and its parameters.
    pub scheme: SchemeSpec,
    /// The run's solver.
    pub solver: SolverChoice,
    /// Integrator settings: the experiment's `exact_integrator` for the exact run, the variant's or
    /// the experiment's `integrator` for a neural run (a numerical run, which steps at its own
    /// fixed gap, carries the exact one and does not use it).
    pub integrator: IntegratorSettings,
    /// Where a neural run is scored against the exact optimum (the experiment's `scoring`;
    /// the controlled re-runs of the `explain` crate need only drift and position error and
    /// switch it off).
    pub scoring: Scoring,
    /// Initial state of a neural run's network.
    pub network_init: NetworkInit,
    /// Why this run is expected to fail, if it is (the variant's `expected_failure`).
    pub expected_failure: Option<String>,
    /// The variant's `explain` flag.
    pub explain: bool,
    /// Whether the run keeps its trace (its sweep's `traces` choice in the experiment file);
    /// a run that does not still writes its row.
    pub keep_trace: bool,
}

impl RunSpec {
    /// The run's task (what every solver of a variant shares).
    pub fn task(&self) -> TaskKey {
        TaskKey {
            experiment: self.experiment.clone(),
            variant: self.variant_id.clone(),
        }
    }

    /// The solver's id ([`SolverChoice::id`]), checked.
    pub fn solver_id(&self) -> Result<SolverId, IdError> {
        SolverId::new(self.solver.id())
    }

    /// The run's identity: experiment / variant / solver ids.
    ///
    /// Every run of an experiment file that was read (`catalog::PaperFile::from_toml`) has a valid
    /// solver id: the file's check refuses a solver whose id is not one (a parameter that
    /// prints as no slug, or too long an id). A key asked of a job whose solver was changed
    /// to such a specification in code panics; [`RunSpec::solver_id`] is the checked form.
    pub fn key(&self) -> RunKey {
        let solver = self
            .solver_id()
            .unwrap_or_else(|e| panic!("{}: {e}", self.task()));
        RunKey::new(self.experiment.clone(), self.variant_id.clone(), solver)
    }
}
