//! Serde-readable solver specifications for experiment files: the papers' networks and their
//! parameters as data, with their ids, display names and the defaults of the papers. The
//! networks themselves are built from them by crate `solvers` (`solvers::neural::build_solver`).
//!
//! ```toml
//! solver = { kind = "lvi-pdnn", gamma = 1e7 }
//! solver = { kind = "s-lvi-pdnn", beta = 1e7 }
//! solver = { kind = "vp-rnn-pf", p = 1e-4, sigma = 400, gamma = 2, activation = "power-sigmoid", alpha = 4, chi = 3 }
//! solver = { kind = "fp-cdnn", gamma = 200, perturbation = { a_d = 1.0, a_s = 1.5, task_duration = 8 } }
//! solver = { kind = "vp-cdnn", gamma = 200 }
//! solver = { kind = "finite-time", beta = 1, alpha = 0.1, smoothing = 1e-8 }   # smoothing optional
//! solver = { kind = "znn", gamma = 1 }
//! solver = { kind = "group-znn", gamma = 500, nu = 2500, perturbation = { a_s = 1.5, task_duration = 8 } }
//! solver = { kind = "group-znn", udot_rmp = false, activation = "linear" }
//! solver = { kind = "zeroing", gain = { law = "power", gamma = 1.0, p = 2.0 }, activation = "sign-bi-power", exponent = 0.5 }
//! solver = { kind = "projection", error = { form = "lvi", scaling = "identity" }, gain = { law = "power", gamma = 1e3, p = 2.0 } }
//! ```
//!
//! `zeroing` is the zeroing family as data ([`crate::zeroing`]): `gain` (a table with its `law`:
//! `constant`, `exponential`, `power`, `polynomial`), `activation` with its parameters
//! (`exponent`, `smoothing` for `sign-power` and `sign-bi-power`), `nu` (growing gain, default
//! 0), `perturbation`, `perturbation_matrix` (default true) and `udot_rmp` (default true). The
//! other zeroing kinds (`fp-cdnn`, `vp-cdnn`, `finite-time`, `znn`, `group-znn`) are presets
//! that expand to it ([`SolverSpec::zeroing`]).
//!
//! `projection` is the projection family as data ([`crate::projection`]): `error` (a table with
//! its `form`: `lvi` with its `scaling`, `i-plus-mt` or `identity`; `penalty` with `p` and
//! `sigma`), `gain` (the same gain laws) and `activation` with its parameters. `lvi-pdnn`,
//! `s-lvi-pdnn` and `vp-rnn-pf` are presets that expand to it ([`SolverSpec::projection`]).
//!
//! `activation` is `linear` (default; for `group-znn` the default is `group-power-sigmoid`),
//! `sinh`, `power-sigmoid` or `group-power-sigmoid`; `alpha`/`chi` (defaults 4 and 3) are the
//! power-sigmoid's parameters (zhong2021 (2.29)), `xi`/`power` (defaults 1 and 1) the group's
//! power-sigmoid's xi and p (`power`, since VP-RNN-PF's `p` is its own parameter); each pair is
//! ignored for the other activations. Every network that takes an activation (VP-RNN-PF, the
//! CDNNs, the group's network) takes all four, written beside the network's own fields and held
//! in code as one [`ActivationSpec`]. The CDNNs' runs in the paper are linear.
//!
//! The file form is a flat table: a private mirror of [`SolverSpec`] with the activation's
//! fields inline is what serde reads and writes, converted to and from [`SolverSpec`] without
//! loss. The two vocabularies' kinds (`zeroing`, `projection`), which take all seven fields
//! (`activation`, `alpha`, `chi`, `xi`, `power`, `exponent`, `smoothing`), declare them once: one
//! struct flattened into both (serde checks the keys the two leave over, so a misspelt field
//! stays an error that names it). The presets `vp-rnn-pf`, `fp-cdnn` and `vp-cdnn` take five (no
//! `exponent`, no `smoothing`: a file may not give a preset a field it does not use), one struct
//! of those flattened into the three; `group-znn`, whose default activation is its own, keeps
//! its five inline. The vocabularies' struct repeats the presets' five fields rather than
//! flattening their struct into its own: under `deny_unknown_fields` serde refuses the keys of a
//! struct flattened inside a flattened one as unknown.
//!
//! `group-znn` (the group's network, `docs/networks.md`): `gamma` (default 500), `nu`
//! (default 2500), `activation`, `perturbation` (optional, as the CDNNs; only `a_s` and `task_duration`
//! are used, its DeltaD is not) and `udot_rmp` (default true; false drops the -qdot part of
//! udot, as the group's EXP1 file).

use crate::activation::{
    ActivationKind, ActivationSpec, GROUP_POWER_SIGMOID_P, GROUP_POWER_SIGMOID_XI,
    POWER_SIGMOID_ALPHA, POWER_SIGMOID_CHI, SIGN_POWER_EXPONENT, SIGN_POWER_SMOOTHING,
};
use crate::error::NetworkError;
use crate::network_kind::NetworkKind;
use crate::projection::{ProjectionErrorForm, ProjectionSpec, Scaling};
use crate::zeroing::{GainLaw, ZeroingSpec};
use serde::{Deserialize, Serialize};

/// The group's gamma (`mvn_ZZJLJrebi1.m`).
pub const GROUP_GAMMA: f64 = 500.0;
/// The group's nu of the growing-gain term -nu t E.
pub const GROUP_NU: f64 = 2500.0;
/// Default half-width of the sign-power's linear zone of the finite-time network (see
/// `docs/networks.md`).
pub const FINITE_TIME_SMOOTHING: f64 = 1e-8;
/// Size of the reference perturbation: n + m = 6 + 3 (Jaco2, position task).
pub const PERTURBATION_DIM: usize = 9;
/// Reference amplitude A_D of DeltaD.
pub const REFERENCE_A_D: f64 = 1.0;
/// Reference amplitude A_s of Delta s.
pub const REFERENCE_A_S: f64 = 1.5;

fn default_a_d() -> f64 {
    REFERENCE_A_D
}
fn default_a_s() -> f64 {
    REFERENCE_A_S
}

/// zhang2018's reference perturbation DeltaD(t), Delta s(t) (its terms: `solvers::neural::perturbation`):
/// amplitudes A_D, A_s and the task duration T.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ReferencePerturbation {
    /// A_D: DeltaD(t) = A_D D0(t) (reference 1.0).
    #[serde(default = "default_a_d")]
    pub a_d: f64,
    /// A_s: the factor in front of Delta s's vector (reference 1.5).
    #[serde(default = "default_a_s")]
    pub a_s: f64,
    /// T in w = pi t / T (the task duration; 8 s in zhang2018).
    pub task_duration: f64,
}

impl ReferencePerturbation {
    /// The reference amplitudes (A_D = 1, A_s = 1.5) for a task of duration T.
    pub fn reference(task_duration: f64) -> Self {
        Self {
            a_d: REFERENCE_A_D,
            a_s: REFERENCE_A_S,
            task_duration,
        }
    }

    /// Checks the perturbation for a network whose state has `state_dim` entries.
    pub fn validate(&self, state_dim: usize) -> Result<(), NetworkError> {
        if state_dim != PERTURBATION_DIM {
            return Err(NetworkError::PerturbationDim {
                expected: PERTURBATION_DIM,
                state_dim,
            });
        }
        if !(self.task_duration > 0.0 && self.task_duration.is_finite()) {
            return Err(NetworkError::PerturbationDuration(self.task_duration));
        }
        if !self.a_d.is_finite() || !self.a_s.is_finite() {
            return Err(NetworkError::PerturbationAmplitudes);
        }
        Ok(())
    }
}

fn default_alpha() -> f64 {
    POWER_SIGMOID_ALPHA
}
fn default_chi() -> f64 {
    POWER_SIGMOID_CHI
}
fn default_smoothing() -> f64 {
    FINITE_TIME_SMOOTHING
}
fn default_xi() -> f64 {
    GROUP_POWER_SIGMOID_XI
}
fn default_power() -> f64 {
    GROUP_POWER_SIGMOID_P
}
fn default_group_gamma() -> f64 {
    GROUP_GAMMA
}
fn default_group_nu() -> f64 {
    GROUP_NU
}
fn default_group_activation() -> ActivationKind {
    ActivationKind::GroupPowerSigmoid
}
fn default_true() -> bool {
    true
}
fn default_exponent() -> f64 {
    SIGN_POWER_EXPONENT
}
fn default_sign_smoothing() -> f64 {
    SIGN_POWER_SMOOTHING
}

/// A network and its parameters, by the papers' names.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(from = "FileSolverSpec", into = "FileSolverSpec")]
pub enum SolverSpec {
    /// jia2019 (2.23) (gamma = 1e7 in the paper).
    LviPdnn {
        /// The gain gamma.
        gamma: f64,
    },
    /// zhong2021 (2.35) (beta = 1e7 in the paper).
    SLviPdnn {
        /// The gain beta.
        beta: f64,
    },
    /// zhong2021 (2.30).
    VpRnnPf {
        /// The penalty parameter p (>= 0).
        p: f64,
        /// sigma (> 0).
        sigma: f64,
        /// The varying parameter's gain gamma.
        gamma: f64,
        /// The activation of the error term.
        activation: ActivationSpec,
    },
    /// zhang2018 (2.15) ((3.2) when perturbed).
    FpCdnn {
        /// The fixed gain gamma.
        gamma: f64,
        /// The activation of the error term.
        activation: ActivationSpec,
        /// zhang2018's reference perturbation, if any.
        perturbation: Option<ReferencePerturbation>,
    },
    /// zhang2018 (2.11) ((3.1) when perturbed).
    VpCdnn {
        /// The gain gamma of the varying parameter.
        gamma: f64,
        /// The activation of the error term.
        activation: ActivationSpec,
        /// zhang2018's reference perturbation, if any.
        perturbation: Option<ReferencePerturbation>,
    },
    /// kong2019 (20) (derived form): gain beta, sign-power exponent alpha (paper: 1 and 0.1),
    /// linear zone |e| < smoothing of the sign-power (ours, see `docs/networks.md`).
    FiniteTime {
        /// The gain beta.
        beta: f64,
        /// The sign-power exponent alpha, 0 < alpha < 1.
        alpha: f64,
        /// Half-width of the sign-power's linear zone (default `FINITE_TIME_SMOOTHING`).
        smoothing: f64,
    },
    /// Linear ZNN (kong2019's comparison solver).
    Znn {
        /// The gain gamma.
        gamma: f64,
    },
    /// The papers' group's own network (`docs/group-code.md`, `docs/networks.md`):
    /// Q ydot = -Qdot y - gamma Phi(E) + udot - nu t E + Delta_s(t).
    GroupZnn {
        /// gamma (default `GROUP_GAMMA`).
        gamma: f64,
        /// nu of the growing-gain term (default `GROUP_NU`).
        nu: f64,
        /// Phi (default: the group's power-sigmoid).
        activation: ActivationSpec,
        /// Only `a_s` and `task_duration` are used (the group's code does not use DeltaD).
        perturbation: Option<ReferencePerturbation>,
        /// false: udot = [0; bdot], without its -qdot part (the group's EXP1 file).
        udot_rmp: bool,
    },
    /// A zeroing network as a point of the vocabulary ([`crate::zeroing`]).
    Zeroing {
        /// g(t).
        gain: GainLaw,
        /// Phi.
        activation: ActivationSpec,
        /// nu of the growing-gain term -nu t E.
        nu: f64,
        /// zhang2018's reference perturbation, if any.
        perturbation: Option<ReferencePerturbation>,
        /// Whether the perturbation's DeltaD(t) is used (else Delta s(t) alone).
        perturbation_matrix: bool,
        /// false: udot = [0; bdot].
        udot_rmp: bool,
    },
    /// A projection-family network as a point of the vocabulary ([`crate::projection`]).
    Projection {
        /// The error driven to zero, with its scaling or penalty.
        error: ProjectionErrorForm,
        /// g(t).
        gain: GainLaw,
        /// Phi.
        activation: ActivationSpec,
    },
}

impl From<FileSolverSpec> for SolverSpec {
    fn from(f: FileSolverSpec) -> Self {
        let act = |kind, alpha, chi, xi, power| ActivationSpec {
            kind,
            alpha,
            chi,
            xi,
            power,
            exponent: SIGN_POWER_EXPONENT,
            smoothing: SIGN_POWER_SMOOTHING,
        };
        match f {
            FileSolverSpec::LviPdnn { gamma } => SolverSpec::LviPdnn { gamma },
            FileSolverSpec::SLviPdnn { beta } => SolverSpec::SLviPdnn { beta },
            FileSolverSpec::VpRnnPf {
                p,
                sigma,
                gamma,
                activation,
            } => SolverSpec::VpRnnPf {
                p,
                sigma,
                gamma,
                activation: activation.into(),
            },
            FileSolverSpec::FpCdnn {
                gamma,
                activation,
                perturbation,
            } => SolverSpec::FpCdnn {
                gamma,
                activation: activation.into(),
                perturbation,
            },
            FileSolverSpec::VpCdnn {
                gamma,
                activation,
                perturbation,
            } => SolverSpec::VpCdnn {
                gamma,
                activation: activation.into(),
                perturbation,
            },
            FileSolverSpec::FiniteTime {
                beta,
                alpha,
                smoothing,
            } => SolverSpec::FiniteTime {
                beta,
                alpha,
                smoothing,
            },
            FileSolverSpec::Znn { gamma } => SolverSpec::Znn { gamma },
            FileSolverSpec::GroupZnn {
                gamma,
                nu,
                activation,
                alpha,
                chi,
                xi,
                power,
                perturbation,
                udot_rmp,
            } => SolverSpec::GroupZnn {
                gamma,
                nu,
                activation: act(activation, alpha, chi, xi, power),
                perturbation,
                udot_rmp,
            },
            FileSolverSpec::Zeroing {
                gain,
                activation,
                nu,
                perturbation,
                perturbation_matrix,
                udot_rmp,
            } => SolverSpec::Zeroing {
                gain,
                activation: activation.into(),
                nu,
                perturbation,
                perturbation_matrix,
                udot_rmp,
            },
            FileSolverSpec::Projection {
                error,
                gain,
                activation,
            } => SolverSpec::Projection {
                error,
                gain,
                activation: activation.into(),
            },
        }
    }
}

impl From<SolverSpec> for FileSolverSpec {
    fn from(s: SolverSpec) -> Self {
        match s {
            SolverSpec::LviPdnn { gamma } => FileSolverSpec::LviPdnn { gamma },
            SolverSpec::SLviPdnn { beta } => FileSolverSpec::SLviPdnn { beta },
            SolverSpec::VpRnnPf {
                p,
                sigma,
                gamma,
                activation: a,
            } => FileSolverSpec::VpRnnPf {
                p,
                sigma,
                gamma,
                activation: a.into(),
            },
            SolverSpec::FpCdnn {
                gamma,
                activation: a,
                perturbation,
            } => FileSolverSpec::FpCdnn {
                gamma,
                activation: a.into(),
                perturbation,
            },
            SolverSpec::VpCdnn {
                gamma,
                activation: a,
                perturbation,
            } => FileSolverSpec::VpCdnn {
                gamma,
                activation: a.into(),
                perturbation,
            },
            SolverSpec::FiniteTime {
                beta,
                alpha,
                smoothing,
            } => FileSolverSpec::FiniteTime {
                beta,
                alpha,
                smoothing,
            },
            SolverSpec::Znn { gamma } => FileSolverSpec::Znn { gamma },
            SolverSpec::GroupZnn {
                gamma,
                nu,
                activation: a,
                perturbation,
                udot_rmp,
            } => FileSolverSpec::GroupZnn {
                gamma,
                nu,
                activation: a.kind,
                alpha: a.alpha,
                chi: a.chi,
                xi: a.xi,
                power: a.power,
                perturbation,
                udot_rmp,
            },
            SolverSpec::Zeroing {
                gain,
                activation: a,
                nu,
                perturbation,
                perturbation_matrix,
                udot_rmp,
            } => FileSolverSpec::Zeroing {
                gain,
                activation: a.into(),
                nu,
                perturbation,
                perturbation_matrix,
                udot_rmp,
            },
            SolverSpec::Projection {
                error,
                gain,
                activation: a,
            } => FileSolverSpec::Projection {
                error,
                gain,
                activation: a.into(),
            },
        }
    }
}

/// [`SolverSpec`] as experiment files write it: the activation's fields inline (module docs).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
enum FileSolverSpec {
    /// jia2019 eq. 2.23 (gamma = 1e7 in the paper).
    LviPdnn { gamma: f64 },
    /// zhong2021 eq. 2.35 (beta = 1e7 in the paper).
    SLviPdnn { beta: f64 },
    /// zhong2021 eq. 2.30.
    VpRnnPf {
        p: f64,
        sigma: f64,
        gamma: f64,
        #[serde(flatten)]
        activation: FilePresetActivation,
    },
    /// zhang2018 eq. 2.15 (eq. 3.2 when perturbed).
    FpCdnn {
        gamma: f64,
        #[serde(flatten)]
        activation: FilePresetActivation,
        #[serde(default)]
        perturbation: Option<ReferencePerturbation>,
    },
    /// zhang2018 eq. 2.11 (eq. 3.1 when perturbed).
    VpCdnn {
        gamma: f64,
        #[serde(flatten)]
        activation: FilePresetActivation,
        #[serde(default)]
        perturbation: Option<ReferencePerturbation>,
    },
    /// kong2019 eq. 20 (derived form): gain beta, sign-power exponent alpha (paper: 1 and 0.1),
    /// linear zone |e| < smoothing of the sign-power (ours, see `docs/networks.md`).
    FiniteTime {
        beta: f64,
        alpha: f64,
        #[serde(default = "default_smoothing")]
        smoothing: f64,
    },
    /// Linear ZNN (kong2019's comparison solver).
    Znn { gamma: f64 },
    /// The papers' group's own network (`docs/group-code.md`, `docs/networks.md`):
    /// Q ydot = -Qdot y - gamma Phi(E) + udot - nu t E + Delta_s(t).
    GroupZnn {
        #[serde(default = "default_group_gamma")]
        gamma: f64,
        #[serde(default = "default_group_nu")]
        nu: f64,
        #[serde(default = "default_group_activation")]
        activation: ActivationKind,
        #[serde(default = "default_alpha")]
        alpha: f64,
        #[serde(default = "default_chi")]
        chi: f64,
        #[serde(default = "default_xi")]
        xi: f64,
        #[serde(default = "default_power")]
        power: f64,
        /// Only `a_s` and `task_duration` are used (the group's code does not use DeltaD).
        #[serde(default)]
        perturbation: Option<ReferencePerturbation>,
        /// false: udot = [0; bdot], without its -qdot part (the group's EXP1 file).
        #[serde(default = "default_true")]
        udot_rmp: bool,
    },
    /// The zeroing family as data ([`crate::zeroing`]).
    Zeroing {
        gain: GainLaw,
        #[serde(flatten)]
        activation: FileActivation,
        #[serde(default)]
        nu: f64,
        #[serde(default)]
        perturbation: Option<ReferencePerturbation>,
        #[serde(default = "default_true")]
        perturbation_matrix: bool,
        #[serde(default = "default_true")]
        udot_rmp: bool,
    },
    /// The projection family as data ([`crate::projection`]).
    Projection {
        error: ProjectionErrorForm,
        gain: GainLaw,
        #[serde(flatten)]
        activation: FileActivation,
    },
}

/// The activation of the two vocabularies' networks (`zeroing`, `projection`) as their files
/// write it: every [`ActivationSpec`] field inline, each with its default, flattened into both
/// variants of [`FileSolverSpec`] so that they declare it once (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
struct FileActivation {
    #[serde(default)]
    activation: ActivationKind,
    /// Power-sigmoid alpha (zhong2021 eq. 2.29).
    #[serde(default = "default_alpha")]
    alpha: f64,
    /// Power-sigmoid chi (zhong2021 eq. 2.29).
    #[serde(default = "default_chi")]
    chi: f64,
    /// The group's power-sigmoid xi.
    #[serde(default = "default_xi")]
    xi: f64,
    /// The group's power-sigmoid p.
    #[serde(default = "default_power")]
    power: f64,
    /// The sign-power's exponent.
    #[serde(default = "default_exponent")]
    exponent: f64,
    /// Half-width of the sign-power's linear zone.
    #[serde(default = "default_sign_smoothing")]
    smoothing: f64,
}

/// The activation of the presets that take one (`vp-rnn-pf`, `fp-cdnn`, `vp-cdnn`) as their
/// files write it: the power-sigmoids' four parameters beside the kind (default linear), no
/// sign-power parameters, flattened into each of their variants of [`FileSolverSpec`].
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
struct FilePresetActivation {
    #[serde(default)]
    activation: ActivationKind,
    /// Power-sigmoid alpha (zhong2021 eq. 2.29).
    #[serde(default = "default_alpha")]
    alpha: f64,
    /// Power-sigmoid chi (zhong2021 eq. 2.29).
    #[serde(default = "default_chi")]
    chi: f64,
    /// The group's power-sigmoid xi.
    #[serde(default = "default_xi")]
    xi: f64,
    /// The group's power-sigmoid p.
    #[serde(default = "default_power")]
    power: f64,
}

impl From<FilePresetActivation> for ActivationSpec {
    fn from(f: FilePresetActivation) -> Self {
        ActivationSpec {
            alpha: f.alpha,
            chi: f.chi,
            xi: f.xi,
            power: f.power,
            ..ActivationSpec::of(f.activation)
        }
    }
}

/// The preset's file form keeps the four parameters; the sign-power's, which a preset's file
/// cannot set, are their defaults.
impl From<ActivationSpec> for FilePresetActivation {
    fn from(a: ActivationSpec) -> Self {
        FilePresetActivation {
            activation: a.kind,
            alpha: a.alpha,
            chi: a.chi,
            xi: a.xi,
            power: a.power,
        }
    }
}

impl From<FileActivation> for ActivationSpec {
    fn from(f: FileActivation) -> Self {
        ActivationSpec {
            kind: f.activation,
            alpha: f.alpha,
            chi: f.chi,
            xi: f.xi,
            power: f.power,
            exponent: f.exponent,
            smoothing: f.smoothing,
        }
    }
}

impl From<ActivationSpec> for FileActivation {
    fn from(a: ActivationSpec) -> Self {
        FileActivation {
            activation: a.kind,
            alpha: a.alpha,
            chi: a.chi,
            xi: a.xi,
            power: a.power,
            exponent: a.exponent,
            smoothing: a.smoothing,
        }
    }
}

impl SolverSpec {
    /// The network's kind as experiment files name it (`kind = "lvi-pdnn"`): its identity, where
    /// [`SolverSpec::display_name`] is a label with its parameters.
    pub fn kind(&self) -> &'static str {
        self.network_kind().id()
    }

    /// The network's kind as an enum ([`NetworkKind`]).
    pub fn network_kind(&self) -> NetworkKind {
        match self {
            SolverSpec::LviPdnn { .. } => NetworkKind::LviPdnn,
            SolverSpec::SLviPdnn { .. } => NetworkKind::SLviPdnn,
            SolverSpec::VpRnnPf { .. } => NetworkKind::VpRnnPf,
            SolverSpec::FpCdnn { .. } => NetworkKind::FpCdnn,
            SolverSpec::VpCdnn { .. } => NetworkKind::VpCdnn,
            SolverSpec::FiniteTime { .. } => NetworkKind::FiniteTime,
            SolverSpec::Znn { .. } => NetworkKind::Znn,
            SolverSpec::GroupZnn { .. } => NetworkKind::GroupZnn,
            SolverSpec::Zeroing { .. } => NetworkKind::Zeroing,
            SolverSpec::Projection { .. } => NetworkKind::Projection,
        }
    }

    /// The projection-family network this spec is a preset of (module docs;
    /// [`crate::projection`]), or `None` for the zeroing family ([`SolverSpec::zeroing`]).
    pub fn projection(&self) -> Option<ProjectionSpec> {
        let linear = ActivationSpec::of(ActivationKind::Linear);
        let lvi = |scaling| ProjectionErrorForm::Lvi { scaling };
        Some(match self {
            SolverSpec::LviPdnn { gamma } => ProjectionSpec {
                name: "LVI-PDNN",
                error: lvi(Scaling::IPlusMt),
                gain: GainLaw::Constant { gamma: *gamma },
                activation: linear,
            },
            SolverSpec::SLviPdnn { beta } => ProjectionSpec {
                name: "S-LVI-PDNN",
                error: lvi(Scaling::Identity),
                gain: GainLaw::Constant { gamma: *beta },
                activation: linear,
            },
            SolverSpec::VpRnnPf {
                p,
                sigma,
                gamma,
                activation,
            } => ProjectionSpec {
                name: "VP-RNN-PF",
                error: ProjectionErrorForm::Penalty {
                    p: *p,
                    sigma: *sigma,
                },
                gain: GainLaw::Exponential { gamma: *gamma },
                activation: *activation,
            },
            SolverSpec::Projection {
                error,
                gain,
                activation,
            } => ProjectionSpec {
                name: "projection",
                error: *error,
                gain: gain.clone(),
                activation: *activation,
            },
            SolverSpec::FpCdnn { .. }
            | SolverSpec::VpCdnn { .. }
            | SolverSpec::FiniteTime { .. }
            | SolverSpec::Znn { .. }
            | SolverSpec::GroupZnn { .. }
            | SolverSpec::Zeroing { .. } => return None,
        })
    }

    /// The zeroing network this spec is a preset of (module docs; [`crate::zeroing`]), or
    /// `None` for the projection family ([`SolverSpec::projection`]).
    pub fn zeroing(&self) -> Option<ZeroingSpec> {
        let linear = ActivationSpec::of(ActivationKind::Linear);
        Some(match self {
            SolverSpec::LviPdnn { .. }
            | SolverSpec::SLviPdnn { .. }
            | SolverSpec::VpRnnPf { .. }
            | SolverSpec::Projection { .. } => return None,
            SolverSpec::FpCdnn {
                gamma,
                activation,
                perturbation,
            } => ZeroingSpec {
                perturbation: *perturbation,
                ..ZeroingSpec::new("FP-CDNN", GainLaw::Constant { gamma: *gamma }, *activation)
            },
            SolverSpec::VpCdnn {
                gamma,
                activation,
                perturbation,
            } => ZeroingSpec {
                perturbation: *perturbation,
                ..ZeroingSpec::new(
                    "VP-CDNN",
                    GainLaw::Exponential { gamma: *gamma },
                    *activation,
                )
            },
            SolverSpec::FiniteTime {
                beta,
                alpha,
                smoothing,
            } => ZeroingSpec::new(
                "FTNN",
                GainLaw::Constant { gamma: *beta },
                ActivationSpec {
                    exponent: *alpha,
                    smoothing: *smoothing,
                    ..ActivationSpec::of(ActivationKind::SignPower)
                },
            ),
            SolverSpec::Znn { gamma } => {
                ZeroingSpec::new("ZNN", GainLaw::Constant { gamma: *gamma }, linear)
            }
            SolverSpec::GroupZnn {
                gamma,
                nu,
                activation,
                perturbation,
                udot_rmp,
            } => ZeroingSpec {
                nu: *nu,
                perturbation: *perturbation,
                matrix_perturbation: false,
                udot_q: *udot_rmp,
                ..ZeroingSpec::new(
                    "group ZNN",
                    GainLaw::Constant { gamma: *gamma },
                    *activation,
                )
            },
            SolverSpec::Zeroing {
                gain,
                activation,
                nu,
                perturbation,
                perturbation_matrix,
                udot_rmp,
            } => ZeroingSpec {
                nu: *nu,
                perturbation: *perturbation,
                matrix_perturbation: *perturbation_matrix,
                udot_q: *udot_rmp,
                ..ZeroingSpec::new("zeroing", gain.clone(), *activation)
            },
        })
    }

    /// The network's stable id in run keys, results rows and file names: its kind, followed by
    /// the parameters that tell two networks of one kind apart in the experiment files
    /// (`Distinguishing`). Lower-case ASCII, digits, `.` and `-` only. Derived from the
    /// specification, never from [`SolverSpec::display_name`], so display names can change
    /// without orphaning results.
    pub fn id(&self) -> String {
        let d = self.distinguishing();
        let mut parts: Vec<String> = vec![self.kind().to_string()];
        if let Some(error) = &d.error {
            parts.push(crate::slug::slug(error));
        }
        if let Some(law) = &d.law {
            parts.push(crate::slug::slug(law));
        }
        if let Some((gamma, nu)) = d.gains {
            parts.push(format!("gamma-{gamma}-nu-{nu}"));
        }
        if let Some(a) = &d.activation {
            parts.push(crate::slug::slug(a));
        }
        match d.perturbation {
            Some((Some(a_d), a_s)) => parts.push(format!("perturbed-ad-{a_d}-as-{a_s}")),
            Some((None, a_s)) => parts.push(format!("perturbed-as-{a_s}")),
            None => {}
        }
        if d.udot_without_qdot {
            parts.push("udot-without-qdot".into());
        }
        parts.join("-")
    }

    /// The network's name as the papers write it, with the variant where it matters,
    /// e.g. `VP-RNN-PF (sinh)`, `FP-CDNN (perturbed A_D=1, A_s=1.5)`.
    pub fn display_name(&self) -> String {
        let d = self.distinguishing();
        let mut parts: Vec<String> = Vec::new();
        parts.extend(d.error.clone());
        parts.extend(d.law.clone());
        if let Some((gamma, nu)) = d.gains {
            parts.push(format!("gamma={gamma}"));
            parts.push(format!("nu={nu}"));
        }
        parts.extend(d.activation);
        match d.perturbation {
            Some((Some(a_d), a_s)) => parts.push(format!("perturbed A_D={a_d}, A_s={a_s}")),
            Some((None, a_s)) => parts.push(format!("perturbed A_s={a_s}")),
            None => {}
        }
        if d.udot_without_qdot {
            parts.push("udot without -qdot".into());
        }
        let base = match self {
            SolverSpec::LviPdnn { .. } => "LVI-PDNN",
            SolverSpec::SLviPdnn { .. } => "S-LVI-PDNN",
            SolverSpec::VpRnnPf { .. } => "VP-RNN-PF",
            SolverSpec::FpCdnn { .. } => "FP-CDNN",
            SolverSpec::VpCdnn { .. } => "VP-CDNN",
            SolverSpec::FiniteTime { .. } => "FTNN",
            SolverSpec::Znn { .. } => "ZNN",
            SolverSpec::GroupZnn { .. } => "group ZNN",
            SolverSpec::Zeroing { .. } => "ZNN",
            SolverSpec::Projection { .. } => "projection network",
        };
        if parts.is_empty() {
            base.to_string()
        } else {
            format!("{base} ({})", parts.join(", "))
        }
    }

    /// What tells this network apart from others of its kind, for [`SolverSpec::id`] and
    /// [`SolverSpec::display_name`] (which only format it).
    fn distinguishing(&self) -> Distinguishing {
        let mut d = Distinguishing::default();
        match self {
            SolverSpec::LviPdnn { .. }
            | SolverSpec::SLviPdnn { .. }
            | SolverSpec::FiniteTime { .. }
            | SolverSpec::Znn { .. } => {}
            SolverSpec::VpRnnPf { activation, .. } => d.activation = Some(activation.name()),
            SolverSpec::FpCdnn {
                activation,
                perturbation,
                ..
            }
            | SolverSpec::VpCdnn {
                activation,
                perturbation,
                ..
            } => {
                d.activation =
                    (activation.kind != ActivationKind::Linear).then(|| activation.name());
                d.perturbation = perturbation.as_ref().map(|p| (Some(p.a_d), p.a_s));
            }
            SolverSpec::GroupZnn {
                gamma,
                nu,
                activation,
                perturbation,
                udot_rmp,
            } => {
                let a = activation.name();
                d.activation = (a != default_group_activation().id()).then_some(a);
                d.perturbation = perturbation.as_ref().map(|p| (None, p.a_s));
                d.gains = Some((*gamma, *nu));
                d.udot_without_qdot = !udot_rmp;
            }
            SolverSpec::Zeroing {
                gain,
                activation,
                nu,
                perturbation,
                perturbation_matrix,
                udot_rmp,
            } => {
                d.law = Some(if *nu > 0.0 {
                    format!("{} nu={nu}", gain.name())
                } else {
                    gain.name()
                });
                d.activation = Some(activation.name());
                d.perturbation = perturbation
                    .as_ref()
                    .map(|p| (perturbation_matrix.then_some(p.a_d), p.a_s));
                d.udot_without_qdot = !udot_rmp;
            }
            SolverSpec::Projection {
                error,
                gain,
                activation,
            } => {
                d.error = Some(error.name());
                d.law = Some(gain.name());
                d.activation = Some(activation.name());
            }
        }
        d
    }

    /// Whether the network needs dQP/dt (the zeroing family and the projection family's
    /// `penalty` form, [`ProjectionSpec::needs_qp_dot`]).
    pub fn needs_qp_dot(&self) -> bool {
        self.projection().is_none_or(|p| p.needs_qp_dot())
    }

    /// Whether the network handles inequality rows and bounds: the projection family does, the
    /// zeroing family solves the equality part only.
    pub fn handles_inequalities(&self) -> bool {
        self.projection().is_some()
    }
}

/// What tells two networks of one kind apart in the experiment files.
#[derive(Default)]
struct Distinguishing {
    /// A projection point's error form with its parameters.
    error: Option<String>,
    /// A vocabulary network's gain law with its parameters (and its growing gain).
    law: Option<String>,
    /// The activation's name where it is named: always for VP-RNN-PF, when not linear for the
    /// CDNNs, when not the group's power-sigmoid for the group ZNN.
    activation: Option<String>,
    /// A reference perturbation: (A_D, A_s) for the CDNNs, A_s alone for the group ZNN (the
    /// group's code uses no A_D).
    perturbation: Option<(Option<f64>, f64)>,
    /// The group ZNN's gamma and nu.
    gains: Option<(f64, f64)>,
    /// The group ZNN's udot without its -k thetadot term.
    udot_without_qdot: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize, Serialize)]
    struct Holder {
        solver: SolverSpec,
    }

    fn parse(text: &str) -> Result<SolverSpec, toml::de::Error> {
        toml::from_str::<Holder>(text).map(|h| h.solver)
    }

    const EVERY_KIND: [&str; 11] = [
        "solver = { kind = \"lvi-pdnn\", gamma = 1e7 }",
        "solver = { kind = \"s-lvi-pdnn\", beta = 1e7 }",
        "solver = { kind = \"vp-rnn-pf\", p = 1e-4, sigma = 400.0, gamma = 2.0, activation = \"power-sigmoid\", alpha = 5.0, chi = 3.0 }",
        "solver = { kind = \"fp-cdnn\", gamma = 200.0, activation = \"sinh\", perturbation = { a_d = 1.0, a_s = 1.5, task_duration = 8.0 } }",
        "solver = { kind = \"vp-cdnn\", gamma = 200.0 }",
        "solver = { kind = \"finite-time\", beta = 1.0, alpha = 0.1 }",
        "solver = { kind = \"znn\", gamma = 1.0 }",
        "solver = { kind = \"group-znn\", gamma = 500.0, nu = 2500.0, perturbation = { a_s = 1.5, task_duration = 8.0 } }",
        "solver = { kind = \"group-znn\", udot_rmp = false, activation = \"linear\", power = 3.0 }",
        "solver = { kind = \"projection\", error = { form = \"lvi\", scaling = \"i-plus-mt\" }, gain = { law = \"power\", gamma = 1e3, p = 2.0 } }",
        "solver = { kind = \"projection\", error = { form = \"penalty\", p = 1e-4, sigma = 400.0 }, gain = { law = \"constant\", gamma = 2.0 }, activation = \"sinh\" }",
    ];

    #[test]
    fn the_flat_file_form_reads_back_to_the_same_spec() {
        for text in EVERY_KIND {
            let spec = parse(text).unwrap_or_else(|e| panic!("{text}: {e}"));
            let written = toml::to_string(&Holder {
                solver: spec.clone(),
            })
            .unwrap();
            assert_eq!(parse(&written).unwrap(), spec, "{text} -> {written}");
        }
    }

    #[test]
    fn the_activation_is_one_value_with_the_files_defaults() {
        let spec = parse(EVERY_KIND[2]).unwrap();
        let SolverSpec::VpRnnPf { activation, .. } = spec else {
            panic!("{spec:?}")
        };
        assert_eq!(activation.kind, ActivationKind::PowerSigmoid);
        assert_eq!((activation.alpha, activation.chi), (5.0, 3.0));
        assert_eq!((activation.xi, activation.power), (1.0, 1.0));
        let group = parse("solver = { kind = \"group-znn\" }").unwrap();
        let SolverSpec::GroupZnn { activation, .. } = group else {
            panic!("{group:?}")
        };
        assert_eq!(
            activation,
            ActivationSpec::of(ActivationKind::GroupPowerSigmoid)
        );
        assert_eq!(group.id(), "group-znn-gamma-500-nu-2500");
    }

    #[test]
    fn ids_and_names_name_the_activation_where_it_matters() {
        let ids: Vec<String> = EVERY_KIND.iter().map(|t| parse(t).unwrap().id()).collect();
        assert_eq!(
            ids,
            [
                "lvi-pdnn",
                "s-lvi-pdnn",
                "vp-rnn-pf-power-sigmoid-alpha-5-chi-3",
                "fp-cdnn-sinh-perturbed-ad-1-as-1.5",
                "vp-cdnn",
                "finite-time",
                "znn",
                "group-znn-gamma-500-nu-2500-perturbed-as-1.5",
                "group-znn-gamma-500-nu-2500-linear-udot-without-qdot",
                "projection-lvi-i-plus-mt-power-gamma-1000-p-2-linear",
                "projection-penalty-p-0.0001-sigma-400-constant-gamma-2-sinh",
            ]
        );
        assert_eq!(
            parse(EVERY_KIND[3]).unwrap().display_name(),
            "FP-CDNN (sinh, perturbed A_D=1, A_s=1.5)"
        );
    }

    #[test]
    fn misspelt_or_misplaced_fields_are_errors() {
        for bad in [
            "solver = { kind = \"lvi-pdnn\", gama = 1e7 }",
            "solver = { kind = \"vp-cdnn\", gamma = 1.0, alfa = 4.0 }",
            "solver = { kind = \"lvi-pdnn\", gamma = 1e7, activation = \"sinh\" }",
            "solver = { kind = \"znn\", gamma = 1.0, chi = 3.0 }",
            "solver = { kind = \"vp-rnn-pf\", p = 1e-4, sigma = 400.0, gamma = 2.0, activation = \"tanh\" }",
            "solver = { kind = \"projection\", error = { form = \"lvi\", scaling = \"identity\" } }",
            "solver = { kind = \"projection\", error = { form = \"lvi\", scaling = \"identity\" }, gain = { law = \"constant\", gamma = 1.0 }, nu = 1.0 }",
        ] {
            assert!(parse(bad).is_err(), "accepted: {bad}");
        }
    }

    #[test]
    fn flattened_activations_are_written_inline_and_a_misspelt_field_is_refused() {
        let zeroing = "solver = { kind = \"zeroing\", gain = { law = \"power\", gamma = 1.0, p = 2.0 }, activation = \"sign-bi-power\", exponent = 0.5, nu = 3.0 }";
        let spec = parse(zeroing).unwrap();
        let SolverSpec::Zeroing { activation, nu, .. } = &spec else {
            panic!("{spec:?}")
        };
        assert_eq!(activation.kind, ActivationKind::SignBiPower);
        assert_eq!((activation.exponent, *nu), (0.5, 3.0));
        assert_eq!(activation.smoothing, SIGN_POWER_SMOOTHING);
        for (text, keys) in [
            (
                zeroing,
                &[
                    "activation",
                    "alpha",
                    "chi",
                    "exponent",
                    "gain",
                    "kind",
                    "nu",
                    "perturbation_matrix",
                    "power",
                    "smoothing",
                    "udot_rmp",
                    "xi",
                ][..],
            ),
            (
                EVERY_KIND[10],
                &[
                    "activation",
                    "alpha",
                    "chi",
                    "error",
                    "exponent",
                    "gain",
                    "kind",
                    "power",
                    "smoothing",
                    "xi",
                ][..],
            ),
        ] {
            let spec = parse(text).unwrap();
            let written = toml::to_string(&Holder {
                solver: spec.clone(),
            })
            .unwrap();
            let table: toml::Table = toml::from_str(&written).unwrap();
            let mut got: Vec<&str> = table["solver"]
                .as_table()
                .unwrap()
                .keys()
                .map(String::as_str)
                .collect();
            got.sort_unstable();
            assert_eq!(got, keys, "{written}");
            assert_eq!(parse(&written).unwrap(), spec, "{written}");
        }
        for (bad, field) in [
            (zeroing.replace("exponent", "exponnent"), "exponnent"),
            (
                EVERY_KIND[10].replace("activation", "activaton"),
                "activaton",
            ),
            (
                EVERY_KIND[9].replace("gain =", "sigma = 1.0, gain ="),
                "sigma",
            ),
            (
                EVERY_KIND[3].replace("gamma", "exponent = 0.5, gamma"),
                "exponent",
            ),
            (EVERY_KIND[2].replace("chi", "chii"), "chii"),
        ] {
            let e = parse(&bad).unwrap_err().to_string();
            assert!(
                e.contains(&format!("unknown field `{field}`")),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn the_projection_presets_expand_to_their_points() {
        use crate::projection::{ProjectionErrorForm, Scaling};
        let expand = |text: &str| parse(text).unwrap().projection().unwrap();
        let lvi = expand(EVERY_KIND[0]);
        assert_eq!(
            (lvi.error, lvi.gain, lvi.activation.kind),
            (
                ProjectionErrorForm::Lvi {
                    scaling: Scaling::IPlusMt
                },
                GainLaw::Constant { gamma: 1e7 },
                ActivationKind::Linear
            )
        );
        let s_lvi = expand(EVERY_KIND[1]);
        assert_eq!(
            s_lvi.error,
            ProjectionErrorForm::Lvi {
                scaling: Scaling::Identity
            }
        );
        let vp = expand(EVERY_KIND[2]);
        assert_eq!(
            (vp.error, vp.gain, vp.activation.kind),
            (
                ProjectionErrorForm::Penalty {
                    p: 1e-4,
                    sigma: 400.0
                },
                GainLaw::Exponential { gamma: 2.0 },
                ActivationKind::PowerSigmoid
            )
        );
        for text in EVERY_KIND {
            let spec = parse(text).unwrap();
            assert_ne!(
                spec.projection().is_some(),
                spec.zeroing().is_some(),
                "{text}: one family exactly"
            );
            assert_eq!(spec.handles_inequalities(), spec.projection().is_some());
        }
        assert!(!parse(EVERY_KIND[0]).unwrap().needs_qp_dot());
        assert!(parse(EVERY_KIND[2]).unwrap().needs_qp_dot());
    }
}
