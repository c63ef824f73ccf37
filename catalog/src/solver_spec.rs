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
//! ```
//!
//! `activation` is `linear` (default; for `group-znn` the default is `group-power-sigmoid`),
//! `sinh`, `power-sigmoid` or `group-power-sigmoid`; `alpha`/`chi` (defaults 4 and 3) are the
//! power-sigmoid's parameters (zhong2021 eq. 2.29), `xi`/`power` (defaults 1 and 1) the group's
//! power-sigmoid's xi and p (`power`, since VP-RNN-PF's `p` is its own parameter); each pair is
//! ignored for the other activations. Every network that takes an activation (VP-RNN-PF, the
//! CDNNs, the group's network) takes all four. The CDNNs' runs in the paper are linear.
//!
//! `group-znn` (the group's network, `solvers::neural::group`): `gamma` (default 500), `nu`
//! (default 2500), `activation`, `perturbation` (optional, as the CDNNs; only `a_s` and `task_duration`
//! are used, its DeltaD is not) and `udot_rmp` (default true; false drops the -qdot part of
//! udot, as the group's EXP1 file).

use crate::error::NetworkError;
use crate::network_kind::NetworkKind;
use serde::{Deserialize, Serialize};

/// Default power-sigmoid alpha (zhong2021 eq. 2.29 asks only alpha >= 2).
pub const POWER_SIGMOID_ALPHA: f64 = 4.0;
/// Default power-sigmoid chi (zhong2021 eq. 2.29 asks only chi >= 3).
pub const POWER_SIGMOID_CHI: f64 = 3.0;
/// Default xi of the group's power-sigmoid (`AFMpowersigmoid` called with one argument).
pub const GROUP_POWER_SIGMOID_XI: f64 = 1.0;
/// Default p of the group's power-sigmoid (`AFMpowersigmoid` called with one argument).
pub const GROUP_POWER_SIGMOID_P: f64 = 1.0;

/// The group's gamma (`mvn_ZZJLJrebi1.m`).
pub const GROUP_GAMMA: f64 = 500.0;
/// The group's nu of the growing-gain term -nu t E.
pub const GROUP_NU: f64 = 2500.0;
/// Default half-width of the sign-power's linear zone of the finite-time network (see
/// `solvers::neural::znn`).
pub const FINITE_TIME_SMOOTHING: f64 = 1e-8;
/// Size of the reference perturbation: n + m = 6 + 3 (Jaco2, position task).
pub const PERTURBATION_DIM: usize = 9;
/// Reference amplitude A_D of DeltaD.
pub const REFERENCE_A_D: f64 = 1.0;
/// Reference amplitude A_s of Delta s.
pub const REFERENCE_A_S: f64 = 1.5;

/// The serde name of an activation in experiment files (parameters given beside it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ActivationKind {
    #[default]
    Linear,
    Sinh,
    PowerSigmoid,
    /// The group's power-sigmoid (`group-power-sigmoid`, parameters `xi` and `power`).
    GroupPowerSigmoid,
}

fn default_a_d() -> f64 {
    REFERENCE_A_D
}
fn default_a_s() -> f64 {
    REFERENCE_A_S
}

/// zhang2018's reference perturbation DeltaD(t), Delta s(t) (its terms: `solvers::neural::cdnn`):
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

/// A network and its parameters, by the papers' names.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum SolverSpec {
    /// jia2019 eq. 2.23 (gamma = 1e7 in the paper).
    LviPdnn { gamma: f64 },
    /// zhong2021 eq. 2.35 (beta = 1e7 in the paper).
    SLviPdnn { beta: f64 },
    /// zhong2021 eq. 2.30.
    VpRnnPf {
        p: f64,
        sigma: f64,
        gamma: f64,
        #[serde(default)]
        activation: ActivationKind,
        /// Power-sigmoid alpha (eq. 2.29).
        #[serde(default = "default_alpha")]
        alpha: f64,
        /// Power-sigmoid chi (eq. 2.29).
        #[serde(default = "default_chi")]
        chi: f64,
        /// The group's power-sigmoid xi.
        #[serde(default = "default_xi")]
        xi: f64,
        /// The group's power-sigmoid p.
        #[serde(default = "default_power")]
        power: f64,
    },
    /// zhang2018 eq. 2.15 (eq. 3.2 when perturbed).
    FpCdnn {
        gamma: f64,
        #[serde(default)]
        activation: ActivationKind,
        #[serde(default = "default_alpha")]
        alpha: f64,
        #[serde(default = "default_chi")]
        chi: f64,
        #[serde(default = "default_xi")]
        xi: f64,
        #[serde(default = "default_power")]
        power: f64,
        #[serde(default)]
        perturbation: Option<ReferencePerturbation>,
    },
    /// zhang2018 eq. 2.11 (eq. 3.1 when perturbed).
    VpCdnn {
        gamma: f64,
        #[serde(default)]
        activation: ActivationKind,
        #[serde(default = "default_alpha")]
        alpha: f64,
        #[serde(default = "default_chi")]
        chi: f64,
        #[serde(default = "default_xi")]
        xi: f64,
        #[serde(default = "default_power")]
        power: f64,
        #[serde(default)]
        perturbation: Option<ReferencePerturbation>,
    },
    /// kong2019 eq. 20 (derived form): gain beta, sign-power exponent alpha (paper: 1 and 0.1),
    /// linear zone |e| < smoothing of the sign-power (ours, see `solvers::neural::znn`).
    FiniteTime {
        beta: f64,
        alpha: f64,
        #[serde(default = "default_smoothing")]
        smoothing: f64,
    },
    /// Linear ZNN (kong2019's comparison solver).
    Znn { gamma: f64 },
    /// The papers' group's own network (`docs/group-code.md`, `solvers::neural::group`):
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
}

/// Name of an activation in display names: the kind's label at default parameters (so the
/// existing names are unchanged), the label with its parameters otherwise.
fn activation_name(kind: ActivationKind, alpha: f64, chi: f64, xi: f64, power: f64) -> String {
    match kind {
        ActivationKind::PowerSigmoid
            if alpha != POWER_SIGMOID_ALPHA || chi != POWER_SIGMOID_CHI =>
        {
            format!("power-sigmoid(alpha={alpha},chi={chi})")
        }
        ActivationKind::GroupPowerSigmoid
            if xi != GROUP_POWER_SIGMOID_XI || power != GROUP_POWER_SIGMOID_P =>
        {
            format!("group-power-sigmoid(xi={xi},p={power})")
        }
        _ => kind_label(kind).to_string(),
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
        }
    }

    /// The network's stable id in run keys, results rows and file names: its kind, followed by
    /// the parameters that tell two networks of one kind apart in the experiment files
    /// (`Distinguishing`). Lower-case ASCII, digits, `.` and `-` only. Derived from the
    /// specification, never from [`SolverSpec::display_name`], so display names can change
    /// without orphaning results.
    pub fn id(&self) -> String {
        let d = self.distinguishing();
        let mut parts: Vec<String> = vec![self.kind().to_string()];
        if let Some((gamma, nu)) = d.gains {
            parts.push(format!("gamma-{gamma}-nu-{nu}"));
        }
        if let Some(a) = &d.activation {
            parts.push(schemes::slug::slug(a));
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
            SolverSpec::VpRnnPf {
                activation,
                alpha,
                chi,
                xi,
                power,
                ..
            } => d.activation = Some(activation_name(*activation, *alpha, *chi, *xi, *power)),
            SolverSpec::FpCdnn {
                activation,
                alpha,
                chi,
                xi,
                power,
                perturbation,
                ..
            }
            | SolverSpec::VpCdnn {
                activation,
                alpha,
                chi,
                xi,
                power,
                perturbation,
                ..
            } => {
                d.activation = (*activation != ActivationKind::Linear)
                    .then(|| activation_name(*activation, *alpha, *chi, *xi, *power));
                d.perturbation = perturbation.as_ref().map(|p| (Some(p.a_d), p.a_s));
            }
            SolverSpec::GroupZnn {
                gamma,
                nu,
                activation,
                alpha,
                chi,
                xi,
                power,
                perturbation,
                udot_rmp,
            } => {
                let a = activation_name(*activation, *alpha, *chi, *xi, *power);
                d.activation = (a != kind_label(default_group_activation())).then_some(a);
                d.perturbation = perturbation.as_ref().map(|p| (None, p.a_s));
                d.gains = Some((*gamma, *nu));
                d.udot_without_qdot = !udot_rmp;
            }
        }
        d
    }

    /// Whether the network needs dQP/dt (zeroing networks).
    pub fn needs_qp_dot(&self) -> bool {
        !matches!(
            self,
            SolverSpec::LviPdnn { .. } | SolverSpec::SLviPdnn { .. }
        )
    }

    /// Whether the network handles inequality rows and bounds (only the equality part otherwise).
    pub fn handles_inequalities(&self) -> bool {
        matches!(
            self,
            SolverSpec::LviPdnn { .. } | SolverSpec::SLviPdnn { .. } | SolverSpec::VpRnnPf { .. }
        )
    }
}

/// What tells two networks of one kind apart in the experiment files.
#[derive(Default)]
struct Distinguishing {
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

fn kind_label(k: ActivationKind) -> &'static str {
    match k {
        ActivationKind::Linear => "linear",
        ActivationKind::Sinh => "sinh",
        ActivationKind::PowerSigmoid => "power-sigmoid",
        ActivationKind::GroupPowerSigmoid => "group-power-sigmoid",
    }
}
