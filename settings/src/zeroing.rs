//! A zeroing network as a point of a vocabulary ([`ZeroingSpec`]): most recurrent networks of
//! the field are one family, a zeroing design formula on the KKT system of the equality-only
//! QP, told apart by their gain law, their activation and their perturbation
//! (`docs/networks.md` lists every term).
//!
//! # The family
//!
//! For min x'Px/2 + q'x s.t. A x = b the Lagrange conditions are Q y = u with
//! Q = [P A'; A 0], y = [x; lambda], u = [-q; b] (zhang2018 (2.7)-(2.8), kong2019 (15)-(18)).
//! The design formula makes the error E = Q y - u obey
//!
//! ```text
//! Edot = -g(t) Phi(E) - nu t E,
//! ```
//!
//! so that, with Edot = Qdot y + Q ydot - udot, the network is the implicit system
//!
//! ```text
//! Q ydot = -Qdot y + udot - g(t) Phi(Q y - u) - nu t (Q y - u)  [ - DeltaD(t) y + Delta s(t) ]
//! ```
//!
//! (zhang2018 (2.11), (2.15), (3.1)-(3.2); kong2019 (20); the group's network with nu > 0).
//!
//! # Gain laws g(t) ([`GainLaw`])
//!
//! | law | g(t) | where |
//! |---|---|---|
//! | `constant` | gamma | zhang2018 (2.15) FP-CDNN, kong2019 (20) with gamma = beta |
//! | `exponential` | gamma exp(t) | zhang2018 (2.11) VP-CDNN |
//! | `power` | gamma (p + t^p) | the power-type varying parameter of Zhang et al.'s VP networks |
//! | `polynomial` | c_0 + c_1 t + ... + c_k t^k | any polynomial gain (at most [`MAX_POLYNOMIAL_TERMS`] terms) |
//!
//! Every law must be positive for t >= 0 (checked at t = 0 and from its parameters: gamma > 0,
//! p > 0, c_0 > 0 and every c_k >= 0).
//!
//! # The presets
//!
//! The papers' zeroing networks are presets of this vocabulary
//! ([`crate::SolverSpec::zeroing`]): `fp-cdnn` = constant gain, `vp-cdnn` =
//! exponential gain, `znn` = constant gain and linear activation, `finite-time` = constant gain
//! and the sign-power activation, `group-znn` = constant gain, nu > 0, the vector part of the
//! perturbation only.

use crate::activation::ActivationSpec;
use crate::error::NetworkError;
use crate::solver_spec::ReferencePerturbation;
use serde::{Deserialize, Serialize};

/// Most terms a polynomial gain may have.
pub const MAX_POLYNOMIAL_TERMS: usize = 8;

/// The gain law g(t) of a zeroing network (module docs).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "law", rename_all = "kebab-case", deny_unknown_fields)]
pub enum GainLaw {
    /// g(t) = gamma.
    Constant {
        /// gamma > 0.
        gamma: f64,
    },
    /// g(t) = gamma exp(t).
    Exponential {
        /// gamma > 0.
        gamma: f64,
    },
    /// g(t) = gamma (p + t^p).
    Power {
        /// gamma > 0.
        gamma: f64,
        /// p > 0.
        p: f64,
    },
    /// g(t) = c_0 + c_1 t + ... + c_k t^k.
    Polynomial {
        /// c_0 > 0, then c_k >= 0.
        coefficients: Vec<f64>,
    },
}

impl GainLaw {
    /// g(t).
    #[inline]
    pub fn at(&self, t: f64) -> f64 {
        match self {
            GainLaw::Constant { gamma } => *gamma,
            GainLaw::Exponential { gamma } => gamma * t.exp(),
            GainLaw::Power { gamma, p } => gamma * (p + t.powf(*p)),
            GainLaw::Polynomial { coefficients } => {
                coefficients.iter().rev().fold(0.0, |acc, c| acc * t + c)
            }
        }
    }

    /// The law's id in names (`constant`, `exponential`, `power`, `polynomial`).
    pub fn law(&self) -> &'static str {
        match self {
            GainLaw::Constant { .. } => "constant",
            GainLaw::Exponential { .. } => "exponential",
            GainLaw::Power { .. } => "power",
            GainLaw::Polynomial { .. } => "polynomial",
        }
    }

    /// The law with its parameters, e.g. `power(gamma=1,p=2)`.
    pub fn name(&self) -> String {
        match self {
            GainLaw::Constant { gamma } => format!("constant(gamma={gamma})"),
            GainLaw::Exponential { gamma } => format!("exponential(gamma={gamma})"),
            GainLaw::Power { gamma, p } => format!("power(gamma={gamma},p={p})"),
            GainLaw::Polynomial { coefficients } => {
                let c: Vec<String> = coefficients.iter().map(f64::to_string).collect();
                format!("polynomial({})", c.join(","))
            }
        }
    }

    /// Checks that g(t) > 0 for every t >= 0 (module docs).
    pub fn validate(&self) -> Result<(), NetworkError> {
        let bad = |symbol: &'static str, value: f64| NetworkError::GainLaw {
            law: self.law(),
            symbol,
            value,
        };
        let positive = |v: f64| v > 0.0 && v.is_finite();
        match self {
            GainLaw::Constant { gamma } | GainLaw::Exponential { gamma } => {
                if !positive(*gamma) {
                    return Err(bad("gamma", *gamma));
                }
            }
            GainLaw::Power { gamma, p } => {
                if !positive(*gamma) {
                    return Err(bad("gamma", *gamma));
                }
                if !positive(*p) {
                    return Err(bad("p", *p));
                }
            }
            GainLaw::Polynomial { coefficients } => {
                if coefficients.is_empty() || coefficients.len() > MAX_POLYNOMIAL_TERMS {
                    return Err(bad("coefficients", coefficients.len() as f64));
                }
                if !positive(coefficients[0]) {
                    return Err(bad("c_0", coefficients[0]));
                }
                if let Some(&c) = coefficients
                    .iter()
                    .skip(1)
                    .find(|c| !(**c >= 0.0 && c.is_finite()))
                {
                    return Err(bad("c_k", c));
                }
            }
        }
        Ok(())
    }
}

/// A zeroing network of the family of the module docs, every part named.
#[derive(Clone, Debug, PartialEq)]
pub struct ZeroingSpec {
    /// The name errors and labels use (a preset's paper name, e.g. `FP-CDNN`, or `zeroing`).
    pub name: &'static str,
    /// g(t).
    pub gain: GainLaw,
    /// Phi.
    pub activation: ActivationSpec,
    /// nu of the growing-gain term -nu t E (0: none; >= 0).
    pub nu: f64,
    /// zhang2018's reference perturbation, if any.
    pub perturbation: Option<ReferencePerturbation>,
    /// Whether the perturbation's matrix part DeltaD(t) is used (else Delta s(t) alone, as the
    /// group's code).
    pub matrix_perturbation: bool,
    /// Whether udot includes its -qdot part (else udot = [0; bdot], the group's EXP1 file).
    pub udot_q: bool,
}

impl ZeroingSpec {
    /// A network named `name` with gain law `gain` and activation `activation`, no growing gain,
    /// no perturbation, the full udot.
    pub fn new(name: &'static str, gain: GainLaw, activation: ActivationSpec) -> Self {
        ZeroingSpec {
            name,
            gain,
            activation,
            nu: 0.0,
            perturbation: None,
            matrix_perturbation: true,
            udot_q: true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_laws_are_their_formulas() {
        let t: f64 = 1.7;
        assert_eq!(GainLaw::Constant { gamma: 3.0 }.at(t), 3.0);
        assert_eq!(GainLaw::Exponential { gamma: 3.0 }.at(t), 3.0 * t.exp());
        assert_eq!(
            GainLaw::Power { gamma: 3.0, p: 2.0 }.at(t),
            3.0 * (2.0 + t * t)
        );
        let poly = GainLaw::Polynomial {
            coefficients: vec![1.0, 2.0, 0.5],
        };
        assert!((poly.at(t) - (1.0 + 2.0 * t + 0.5 * t * t)).abs() < 1e-15);
    }

    #[test]
    fn a_law_that_is_not_positive_is_refused_naming_the_parameter() {
        for (law, symbol) in [
            (GainLaw::Constant { gamma: 0.0 }, "gamma"),
            (
                GainLaw::Power {
                    gamma: 1.0,
                    p: -1.0,
                },
                "p",
            ),
            (
                GainLaw::Polynomial {
                    coefficients: vec![1.0, -2.0],
                },
                "c_k",
            ),
            (
                GainLaw::Polynomial {
                    coefficients: vec![],
                },
                "coefficients",
            ),
        ] {
            let e = law.validate().unwrap_err().to_string();
            assert!(e.contains(symbol), "{e}");
        }
        assert!(GainLaw::Power { gamma: 1.0, p: 2.0 }.validate().is_ok());
    }
}
