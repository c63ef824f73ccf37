//! The settings' errors: a network's parameters out of their range ([`NetworkError`], returned
//! by the specifications' own checks here and by the networks' constructors in crate
//! `solvers`), and integrator settings out of theirs ([`IntegratorError`]). Each message names
//! the parameter and its valid range; the layers above (the experiment format, the engine)
//! wrap them with the file and field.

/// Integrator settings out of their range ([`crate::IntegratorSettings::validate`]);
/// each message names the setting and its valid range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum IntegratorError {
    /// `rtol` outside (0, 1).
    #[error("rtol must be in (0, 1), got {0}")]
    Rtol(f64),
    /// `atol` not positive and finite.
    #[error("atol must be positive and finite, got {0}")]
    Atol(f64),
    /// `max_steps` = 0.
    #[error("max_steps must be at least 1, got 0")]
    NoSteps,
    /// `max_rhs_evals` = 0.
    #[error("max_rhs_evals must be at least 1, got 0")]
    NoRhsEvals,
    /// `max_wall_s` not positive and finite.
    #[error(
        "max_wall_s must be positive and finite (a budget that cannot run out is none), got {0}"
    )]
    WallBudget(f64),
    /// `max_step` given but not positive and finite.
    #[error("max_step must be positive and finite, got {0}")]
    MaxStep(f64),
}

/// A network parameter out of its range, or a QP the network cannot solve.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NetworkError {
    /// A gain (gamma or beta) that is not positive and finite.
    #[error("{network}: {symbol} must be positive and finite, got {value}")]
    Gain {
        /// The network's name.
        network: &'static str,
        /// The gain's symbol (`gamma`, `beta`).
        symbol: &'static str,
        /// The value given.
        value: f64,
    },
    /// zhong2021 (2.29)'s parameters out of range.
    #[error("power-sigmoid needs alpha > 0 and chi >= 1 (paper: alpha >= 2, chi >= 3), got alpha = {alpha}, chi = {chi}")]
    PowerSigmoid {
        /// alpha given.
        alpha: f64,
        /// chi given.
        chi: f64,
    },
    /// The group's power-sigmoid's parameters out of range.
    #[error("group power-sigmoid needs xi > 0 and p >= 1 (the group's code: xi = 1, p = 1 or 3), got xi = {xi}, p = {p}")]
    GroupPowerSigmoid {
        /// xi given.
        xi: f64,
        /// p given.
        p: f64,
    },
    /// A sign-power exponent that is not positive.
    #[error("sign-power needs an exponent r > 0, got {0}")]
    SignPowerExponent(f64),
    /// A negative (or non-finite) linear zone of the sign-power.
    #[error("sign-power linear zone must be >= 0, got {0}")]
    SignPowerZone(f64),
    /// The reference perturbation is 9-dimensional; the network's state is not.
    #[error("the reference perturbation is {expected}-dimensional (n + m = 6 + 3); this network's state has {state_dim} entries")]
    PerturbationDim {
        /// The perturbation's dimension.
        expected: usize,
        /// The network state's.
        state_dim: usize,
    },
    /// A perturbation's task duration T that is not positive and finite.
    #[error("perturbation task_duration must be positive, got {0}")]
    PerturbationDuration(f64),
    /// A perturbation amplitude that is not finite.
    #[error("perturbation amplitudes must be finite")]
    PerturbationAmplitudes,
    /// A zeroing network given a QP with inequality rows.
    #[error("{network} solves equality-constrained QPs only (Q y = u); this QP has {n_in} inequality rows")]
    EqualityOnly {
        /// The network's name.
        network: String,
        /// The QP's inequality rows.
        n_in: usize,
    },
    /// The group network's nu negative or not finite.
    #[error("{network}: nu must be finite and >= 0, got {nu}")]
    GrowingGain {
        /// The network's name.
        network: String,
        /// nu given.
        nu: f64,
    },
    /// The penalty error form's (VP-RNN-PF's) p or sigma out of range (zhong2021 (2.19)).
    #[error("the penalty error form (VP-RNN-PF's) needs p >= 0 and sigma > 0 (zhong2021 (2.19)), got p = {p}, sigma = {sigma}")]
    Penalty {
        /// p given.
        p: f64,
        /// sigma given.
        sigma: f64,
    },
    /// The finite-time network's exponent outside (0, 1).
    #[error("finite-time network needs 0 < alpha < 1 (kong2019 (20)), got {0}")]
    FiniteTimeAlpha(f64),
    /// A zeroing network's gain law that is not positive for t >= 0
    /// ([`crate::zeroing::GainLaw::validate`]).
    #[error("the {law} gain law needs {symbol} > 0 (c_k >= 0 past c_0; at most 8 coefficients), got {value}")]
    GainLaw {
        /// The law: `constant`, `exponential`, `power` or `polynomial`.
        law: &'static str,
        /// The parameter out of range.
        symbol: &'static str,
        /// Its value (the number of coefficients for `coefficients`).
        value: f64,
    },
}
