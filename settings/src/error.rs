//! The settings' errors: a network's parameters out of their range ([`NetworkError`], returned
//! by the specifications' own checks here and by the networks' constructors in crate
//! `solvers`), and integrator settings out of theirs ([`IntegratorError`]). Each message names
//! the parameter and its valid range; the layers above (the experiment format, the engine)
//! wrap them with the file and field.

/// Integrator settings out of their range ([`crate::integrator::IntegratorSettings::validate`]);
/// each message names the setting and its valid range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum IntegratorError {
    #[error("rtol must be in (0, 1), got {0}")]
    Rtol(f64),
    #[error("atol must be positive and finite, got {0}")]
    Atol(f64),
    #[error("max_steps must be at least 1, got 0")]
    NoSteps,
    #[error("max_rhs_evals must be at least 1, got 0")]
    NoRhsEvals,
    #[error(
        "max_wall_s must be positive and finite (a budget that cannot run out is none), got {0}"
    )]
    WallBudget(f64),
    #[error("max_step must be positive and finite, got {0}")]
    MaxStep(f64),
}

/// A network parameter out of its range, or a QP the network cannot solve.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NetworkError {
    /// A gain (gamma or beta) that is not positive and finite.
    #[error("{network}: {symbol} must be positive and finite, got {value}")]
    Gain {
        network: &'static str,
        symbol: &'static str,
        value: f64,
    },
    #[error("power-sigmoid needs alpha > 0 and chi >= 1 (paper: alpha >= 2, chi >= 3), got alpha = {alpha}, chi = {chi}")]
    PowerSigmoid { alpha: f64, chi: f64 },
    #[error("group power-sigmoid needs xi > 0 and p >= 1 (the group's code: xi = 1, p = 1 or 3), got xi = {xi}, p = {p}")]
    GroupPowerSigmoid { xi: f64, p: f64 },
    #[error("sign-power needs an exponent r > 0, got {0}")]
    SignPowerExponent(f64),
    #[error("sign-power linear zone must be >= 0, got {0}")]
    SignPowerZone(f64),
    /// The reference perturbation is 9-dimensional; the network's state is not.
    #[error("the reference perturbation is {expected}-dimensional (n + m = 6 + 3); this network's state has {state_dim} entries")]
    PerturbationDim { expected: usize, state_dim: usize },
    #[error("perturbation task_duration must be positive, got {0}")]
    PerturbationDuration(f64),
    #[error("perturbation amplitudes must be finite")]
    PerturbationAmplitudes,
    /// A zeroing network given a QP with inequality rows.
    #[error("{network} solves equality-constrained QPs only (Q y = u); this QP has {n_in} inequality rows")]
    EqualityOnly { network: String, n_in: usize },
    #[error("{network}: nu must be finite and >= 0, got {nu}")]
    GrowingGain { network: String, nu: f64 },
    #[error("VP-RNN-PF needs p >= 0 and sigma > 0 (eq. 2.19), got p = {p}, sigma = {sigma}")]
    VpRnnPf { p: f64, sigma: f64 },
    #[error("finite-time network needs 0 < alpha < 1 (kong2019 (20)), got {0}")]
    FiniteTimeAlpha(f64),
}
