//! Why a network could not be built from its parameters ([`NetworkError`]): the neural
//! layer of `solvers`. Each variant names the network and the parameter with its valid range;
//! the simulation layer wraps it (`simulation::SetupError::Network`).

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
