//! An activation function and all of its parameters, as one value ([`ActivationSpec`]).
//!
//! The networks' error terms pass through an activation Phi, applied entry by entry:
//!
//! - `linear`: Phi(e) = e;
//! - `sinh`: Phi(e) = sinh(e);
//! - `power-sigmoid` (zhong2021 (2.29)): Phi(e) = (1 + exp(-alpha)) (1 - exp(-alpha e)) /
//!   ((1 - exp(-alpha)) (1 + exp(-alpha e))) for |e| <= 1 and sgn(e) |e|^chi outside, with
//!   alpha >= 2 and chi >= 3 in the paper (defaults [`POWER_SIGMOID_ALPHA`],
//!   [`POWER_SIGMOID_CHI`]);
//! - `group-power-sigmoid`: the group code's `AFMpowersigmoid`, the same two branches with
//!   alpha = xi and chi = p (the power branch from |e| >= 1); defaults
//!   [`GROUP_POWER_SIGMOID_XI`], [`GROUP_POWER_SIGMOID_P`], the function called with one
//!   argument;
//! - `sign-power` (kong2019 (6)): Phi(e) = |e|^r sgn(e), r = `exponent`, with a linear zone of
//!   half-width `smoothing` around 0 (`sign_power`'s smoothed form);
//! - `sign-bi-power`: Phi(e) = (|e|^r sgn(e) + |e|^(1/r) sgn(e)) / 2, the finite-time
//!   activation of the zeroing literature, each half smoothed as the sign-power.
//!
//! Experiment files write the kind and its parameters beside the network's own fields
//! (`activation = "power-sigmoid", alpha = 4, chi = 3`); `alpha`/`chi` are ignored for the other
//! kinds, and so are `xi`/`power` (`power`, since VP-RNN-PF's `p` is a parameter of its own).
//! The functions themselves are crate `solvers`' (`solvers::neural::activation`).

use serde::{Deserialize, Serialize};

/// Default power-sigmoid alpha (zhong2021 (2.29) asks only alpha >= 2).
pub const POWER_SIGMOID_ALPHA: f64 = 4.0;
/// Default power-sigmoid chi (zhong2021 (2.29) asks only chi >= 3).
pub const POWER_SIGMOID_CHI: f64 = 3.0;
/// Default xi of the group's power-sigmoid (`AFMpowersigmoid` called with one argument).
pub const GROUP_POWER_SIGMOID_XI: f64 = 1.0;
/// Default p of the group's power-sigmoid (`AFMpowersigmoid` called with one argument).
pub const GROUP_POWER_SIGMOID_P: f64 = 1.0;
/// Default exponent r of the sign-power activations.
pub const SIGN_POWER_EXPONENT: f64 = 0.5;
/// Default half-width of the sign-power activations' linear zone (the finite-time network's,
/// `solvers::neural::zeroing`).
pub const SIGN_POWER_SMOOTHING: f64 = 1e-8;

/// The serde name of an activation in experiment files (parameters given beside it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ActivationKind {
    /// Phi(e) = e.
    #[default]
    Linear,
    /// Phi(e) = sinh(e).
    Sinh,
    /// zhong2021 (2.29), parameters alpha and chi.
    PowerSigmoid,
    /// The group's power-sigmoid (`group-power-sigmoid`, parameters `xi` and `power`).
    GroupPowerSigmoid,
    /// |e|^r sgn(e) (parameters `exponent` and `smoothing`).
    SignPower,
    /// (|e|^r + |e|^(1/r)) sgn(e) / 2 (parameters `exponent` and `smoothing`).
    SignBiPower,
}

impl ActivationKind {
    /// The kind's name in experiment files.
    pub fn id(self) -> &'static str {
        match self {
            ActivationKind::Linear => "linear",
            ActivationKind::Sinh => "sinh",
            ActivationKind::PowerSigmoid => "power-sigmoid",
            ActivationKind::GroupPowerSigmoid => "group-power-sigmoid",
            ActivationKind::SignPower => "sign-power",
            ActivationKind::SignBiPower => "sign-bi-power",
        }
    }
}

/// An activation's kind with every parameter an activation may take: `alpha`, `chi` for
/// zhong2021's power-sigmoid, `xi`, `power` for the group's (the others ignore them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ActivationSpec {
    /// Which function.
    pub kind: ActivationKind,
    /// Power-sigmoid alpha (zhong2021 (2.29)).
    pub alpha: f64,
    /// Power-sigmoid chi (zhong2021 (2.29)).
    pub chi: f64,
    /// The group's power-sigmoid xi.
    pub xi: f64,
    /// The group's power-sigmoid p.
    pub power: f64,
    /// The sign-power exponent r.
    pub exponent: f64,
    /// The sign-power's linear zone half-width.
    pub smoothing: f64,
}

impl ActivationSpec {
    /// `kind` at the default parameters.
    pub fn of(kind: ActivationKind) -> Self {
        Self {
            kind,
            alpha: POWER_SIGMOID_ALPHA,
            chi: POWER_SIGMOID_CHI,
            xi: GROUP_POWER_SIGMOID_XI,
            power: GROUP_POWER_SIGMOID_P,
            exponent: SIGN_POWER_EXPONENT,
            smoothing: SIGN_POWER_SMOOTHING,
        }
    }

    /// The activation's name in display names and solver ids: the kind's id at the default
    /// parameters, the id with the parameters its kind uses otherwise.
    pub fn name(&self) -> String {
        match self.kind {
            ActivationKind::PowerSigmoid
                if self.alpha != POWER_SIGMOID_ALPHA || self.chi != POWER_SIGMOID_CHI =>
            {
                format!("power-sigmoid(alpha={},chi={})", self.alpha, self.chi)
            }
            ActivationKind::GroupPowerSigmoid
                if self.xi != GROUP_POWER_SIGMOID_XI || self.power != GROUP_POWER_SIGMOID_P =>
            {
                format!("group-power-sigmoid(xi={},p={})", self.xi, self.power)
            }
            ActivationKind::SignPower | ActivationKind::SignBiPower => {
                format!("{}(r={})", self.kind.id(), self.exponent)
            }
            kind => kind.id().to_string(),
        }
    }
}

impl Default for ActivationSpec {
    /// Linear.
    fn default() -> Self {
        Self::of(ActivationKind::Linear)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_carry_only_the_parameters_the_kind_uses() {
        assert_eq!(ActivationSpec::of(ActivationKind::Sinh).name(), "sinh");
        let mut s = ActivationSpec::of(ActivationKind::Sinh);
        s.alpha = 9.0;
        assert_eq!(s.name(), "sinh");
        s.kind = ActivationKind::PowerSigmoid;
        assert_eq!(s.name(), "power-sigmoid(alpha=9,chi=3)");
        s.kind = ActivationKind::GroupPowerSigmoid;
        assert_eq!(s.name(), "group-power-sigmoid");
        s.power = 3.0;
        assert_eq!(s.name(), "group-power-sigmoid(xi=1,p=3)");
    }
}
