//! Activation functions of the papers' networks: each unit phi of the processing array
//! Phi(e) = [phi(e_1), ..., phi(e_k)] is odd and monotonically increasing (zhong2021, text after
//! eq. 2.26; zhang2018, eq. 2.10), which is all the Lyapunov proofs (e' phi(e) > 0 for e != 0)
//! need.
//!
//! | variant | phi(e) | source |
//! |---|---|---|
//! | [`Activation::Linear`] | e | zhong2021 eq. 2.27; zhang2018 ("linear unless stated"); the ZNN |
//! | [`Activation::Sinh`] | (exp(e) - exp(-e))/2 | zhong2021 eq. 2.28 |
//! | [`Activation::PowerSigmoid`] | (1+exp(-alpha))(1-exp(-alpha e)) / ((1-exp(-alpha))(1+exp(-alpha e))) for abs(e) <= 1, sgn(e) abs(e)^chi for abs(e) > 1 | zhong2021 eq. 2.29 (alpha >= 2, chi >= 3) |
//! | [`Activation::GroupPowerSigmoid`] | e^p for abs(e) >= 1, ((1+exp(-xi))/(1-exp(-xi))) (1-exp(-xi e))/(1+exp(-xi e)) otherwise | the group's `AFMpowersigmoid(e, xi, p)` (`docs/group-code.md`) |
//! | [`Activation::SignPower`] | abs(e)^r sgn(e) | kong2019 eq. 6 and 20 (r = the paper's alpha, 0 < r < 1) |
//!
//! Power-sigmoid: the paper prints e^chi for abs(e) > 1, which is odd only for odd integer chi;
//! we write sgn(e) abs(e)^chi, identical for odd chi (the paper's range chi >= 3 with the usual
//! choice chi = 3) and odd for every chi. The two branches meet at abs(e) = 1 (both give +-1), so
//! phi is continuous; its derivative jumps there (alpha(1+exp(-alpha))/(... ) vs chi).
//! Defaults (the paper gives only the ranges): alpha = 4, chi = 3.
//!
//! # The group's power-sigmoid, and how it maps onto zhong2021's
//!
//! The papers' group's MATLAB code (`AFMpowersigmoid.m`, see `docs/group-code.md`) computes,
//! elementwise, phi(e) = e^p where abs(e) >= 1 and
//! ((1 + exp(-xi)) / (1 - exp(-xi))) (1 - exp(-xi e)) / (1 + exp(-xi e)) otherwise; called with
//! one argument it uses xi = 1, p = 1, with two p = 3
//! ([`settings::GROUP_POWER_SIGMOID_XI`],
//! [`settings::GROUP_POWER_SIGMOID_P`] are the one-argument defaults, the ones its
//! network uses).
//! This is zhong2021's eq. 2.29 with **alpha = xi and chi = p**: the same sigmoid branch
//! (= coth(xi/2) tanh(xi e/2)) inside, the same power outside. The two differ only at
//! abs(e) = 1 exactly, which the group gives to the power branch (>= 1) and zhong2021 to the
//! sigmoid (<= 1): the values agree there (both branches give +-1, up to rounding of the sigmoid
//! branch), the one-sided derivatives do not (p vs xi / sinh(xi)), so
//! [`Activation::derivative`] returns p at abs(e) = 1 for the group's form and the sigmoid's
//! slope for zhong2021's. What differs in practice is the parameters: zhong2021 asks alpha >= 2,
//! chi >= 3 (we default to 4, 3), the group uses xi = 1, p = 1, i.e. a sigmoid of slope
//! (xi/2) coth(xi/2) = 1.082 at 0 and xi / sinh(xi) = 0.851 at abs(e) = 1, and the identity
//! outside [-1, 1]. Like zhong2021's, the power branch is written sgn(e) abs(e)^p: identical to
//! the code's e.^p for odd integer p (the code's 1 and 3: the sign is preserved), and odd for
//! every p (for even p, e.^p would lose the sign; for non-integer p MATLAB would return complex
//! numbers for e <= -1). Both branches are evaluated on abs(e) and signed, so phi is exactly odd
//! in floating point. Parameters: xi > 0, p >= 1.
//!
//! Sign-power with r < 1 has an infinite slope at e = 0 (that is what makes the convergence
//! finite-time, and what makes every integrator fail once e reaches 0: explicit steps collapse,
//! Newton iterations of implicit ones diverge). [`settings::sign_power()`] therefore takes a smoothing width
//! delta: phi(e) = e (e^2 + delta^2)^((r - 1)/2), which is odd, strictly increasing (slope
//! (e^2 + delta^2)^((r-3)/2) (r e^2 + delta^2) > 0), smooth, equal to abs(e)^r sgn(e) up to a
//! relative (1 + delta^2/e^2)^((r-1)/2) - 1 (< 0.5 % at abs(e) = 10 delta for r = 0.1), and has the
//! finite slope delta^(r-1) at 0: the finite-time phase is kept down to abs(e) ~ delta and then
//! turns into an exponential decay with rate delta^(r-1). delta = 0 gives the exact form (its
//! slope then evaluated at max(abs(e), [`SIGN_POWER_MIN_ABS`](settings::SIGN_POWER_MIN_ABS)) so Jacobians stay finite). The same
//! function is kong2019's c in its finite-time scheme (`schemes::kong2019`).

use settings::NetworkError;
use settings::{sign_power, sign_power_slope};
use settings::{ActivationKind, ActivationSpec, POWER_SIGMOID_ALPHA, POWER_SIGMOID_CHI};

/// The sigmoid branch shared by both power-sigmoids at a = abs(e) <= 1, steepness `s` (zhong2021's
/// alpha, the group's xi): (1 + exp(-s)) (1 - exp(-s a)) / ((1 - exp(-s)) (1 + exp(-s a))).
#[inline]
fn sigmoid_branch(a: f64, s: f64) -> f64 {
    let ea = (-s).exp();
    let ee = (-s * a).exp();
    (1.0 + ea) * (1.0 - ee) / ((1.0 - ea) * (1.0 + ee))
}

/// d/da of [`sigmoid_branch`]: d/da (1-z)/(1+z) with z = exp(-s a) is 2 s z / (1+z)^2.
#[inline]
fn sigmoid_branch_slope(a: f64, s: f64) -> f64 {
    let ea = (-s).exp();
    let z = (-s * a).exp();
    (1.0 + ea) / (1.0 - ea) * 2.0 * s * z / ((1.0 + z) * (1.0 + z))
}

/// One activation unit phi (applied elementwise).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Activation {
    /// phi(e) = e (zhong2021 eq. 2.27).
    Linear,
    /// phi(e) = sinh(e) (zhong2021 eq. 2.28).
    Sinh,
    /// zhong2021 eq. 2.29 (see the module docs).
    PowerSigmoid {
        /// Steepness alpha of the sigmoid branch (> 0; zhong2021 asks alpha >= 2, default 4).
        alpha: f64,
        /// Exponent chi of the power branch sgn(e) abs(e)^chi, abs(e) > 1 (>= 1; zhong2021 asks
        /// chi >= 3, default 3).
        chi: f64,
    },
    /// The group's `AFMpowersigmoid(e, xi, p)` (module docs): zhong2021's eq. 2.29 with
    /// alpha = xi, chi = p, the power branch owning abs(e) = 1.
    GroupPowerSigmoid {
        /// Steepness xi of the sigmoid branch (> 0; the group's code: 1).
        xi: f64,
        /// Exponent p of the power branch sgn(e) abs(e)^p, abs(e) >= 1 (>= 1; the group's code:
        /// 1 or 3).
        p: f64,
    },
    /// phi(e) = abs(e)^r sgn(e) (kong2019 eq. 6, 20), optionally smoothed to
    /// phi(e) = e (e^2 + delta^2)^((r - 1)/2), delta = `smoothing` (0: the exact form; module
    /// docs).
    SignPower {
        /// Exponent r (> 0; kong2019's alpha, 0 < r < 1).
        r: f64,
        /// Smoothing width delta >= 0 (0: the exact form).
        smoothing: f64,
    },
    /// phi(e) = (abs(e)^r sgn(e) + abs(e)^(1/r) sgn(e)) / 2, each half the sign-power above
    /// with the same smoothing (the finite-time activation of the zeroing literature).
    SignBiPower {
        /// Exponent r (> 0).
        r: f64,
        /// Smoothing width delta >= 0 (0: the exact form).
        smoothing: f64,
    },
}

impl From<ActivationSpec> for Activation {
    /// The activation an experiment file's specification names: `alpha`, `chi` for zhong2021's
    /// power-sigmoid, `xi`, `power` for the group's, the other parameters ignored.
    fn from(spec: ActivationSpec) -> Self {
        match spec.kind {
            ActivationKind::Linear => Activation::Linear,
            ActivationKind::Sinh => Activation::Sinh,
            ActivationKind::PowerSigmoid => Activation::PowerSigmoid {
                alpha: spec.alpha,
                chi: spec.chi,
            },
            ActivationKind::GroupPowerSigmoid => Activation::GroupPowerSigmoid {
                xi: spec.xi,
                p: spec.power,
            },
            ActivationKind::SignPower => Activation::SignPower {
                r: spec.exponent,
                smoothing: spec.smoothing,
            },
            ActivationKind::SignBiPower => Activation::SignBiPower {
                r: spec.exponent,
                smoothing: spec.smoothing,
            },
        }
    }
}

impl Activation {
    /// The zhong2021 power-sigmoid with the default alpha = 4, chi = 3.
    pub fn power_sigmoid_default() -> Self {
        Activation::PowerSigmoid {
            alpha: POWER_SIGMOID_ALPHA,
            chi: POWER_SIGMOID_CHI,
        }
    }

    /// Check the papers' parameter ranges (written `!(x > 0 && finite)` so that NaN fails).
    pub fn validate(&self) -> Result<(), NetworkError> {
        match *self {
            Activation::Linear | Activation::Sinh => Ok(()),
            Activation::PowerSigmoid { alpha, chi } => {
                if !(alpha > 0.0 && alpha.is_finite()) || !(chi >= 1.0 && chi.is_finite()) {
                    Err(NetworkError::PowerSigmoid { alpha, chi })
                } else {
                    Ok(())
                }
            }
            Activation::GroupPowerSigmoid { xi, p } => {
                if !(xi > 0.0 && xi.is_finite() && p >= 1.0 && p.is_finite()) {
                    Err(NetworkError::GroupPowerSigmoid { xi, p })
                } else {
                    Ok(())
                }
            }
            Activation::SignPower { r, smoothing } | Activation::SignBiPower { r, smoothing } => {
                if !(r > 0.0 && r.is_finite()) {
                    Err(NetworkError::SignPowerExponent(r))
                } else if !(smoothing >= 0.0 && smoothing.is_finite()) {
                    Err(NetworkError::SignPowerZone(smoothing))
                } else {
                    Ok(())
                }
            }
        }
    }

    /// phi(e).
    #[inline]
    pub fn value(&self, e: f64) -> f64 {
        match *self {
            Activation::Linear => e,
            Activation::Sinh => e.sinh(),
            Activation::PowerSigmoid { alpha, chi } => {
                // Evaluated on |e| and signed, so that phi is exactly odd in floating point.
                let a = e.abs();
                let v = if a <= 1.0 {
                    sigmoid_branch(a, alpha)
                } else {
                    a.powf(chi)
                };
                e.signum() * v
            }
            Activation::GroupPowerSigmoid { xi, p } => {
                let a = e.abs();
                let v = if a >= 1.0 {
                    a.powf(p)
                } else {
                    sigmoid_branch(a, xi)
                };
                e.signum() * v
            }
            Activation::SignPower { r, smoothing } => sign_power(e, r, smoothing),
            Activation::SignBiPower { r, smoothing } => {
                0.5 * (sign_power(e, r, smoothing) + sign_power(e, 1.0 / r, smoothing))
            }
        }
    }

    /// dphi/de (see the module docs for the sign-power floor).
    #[inline]
    pub fn derivative(&self, e: f64) -> f64 {
        match *self {
            Activation::Linear => 1.0,
            Activation::Sinh => e.cosh(),
            Activation::PowerSigmoid { alpha, chi } => {
                let a = e.abs();
                if a <= 1.0 {
                    sigmoid_branch_slope(a, alpha)
                } else {
                    chi * a.powf(chi - 1.0)
                }
            }
            Activation::GroupPowerSigmoid { xi, p } => {
                let a = e.abs();
                if a >= 1.0 {
                    p * a.powf(p - 1.0)
                } else {
                    sigmoid_branch_slope(a, xi)
                }
            }
            Activation::SignPower { r, smoothing } => sign_power_slope(e, r, smoothing),
            Activation::SignBiPower { r, smoothing } => {
                0.5 * (sign_power_slope(e, r, smoothing) + sign_power_slope(e, 1.0 / r, smoothing))
            }
        }
    }
}
