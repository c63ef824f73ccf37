//! kong2019's zeroing networks on W y = v (eq. 17-19): the finite-time network that solves its
//! repeatable-motion scheme (eq. 14, network eq. 20) and the plain ZNN used for the comparison
//! scheme (eq. 22). Both are the zeroing core of [`super::zeroing`] with W = [I J'; J 0] the
//! Q of the QP (P = I, A = J).
//!
//! # Eq. 20 as printed, and the form we use
//!
//! The paper prints
//!
//! ```text
//!   ydot = Wdot y + (W + I) ydot - vdot + beta_theta |W y - v|^alpha sgn(W y - v)      (20, printed)
//! ```
//!
//! which cannot be right: cancelling ydot leaves W ydot = -Wdot y + vdot - beta |E|^alpha sgn(E)
//! only with the signs of (W + I) and of the first, third and fourth terms flipped, and it is
//! the evident garbling of zhang2018's rewriting ydot = (I - Q) ydot - Qdot y - gamma Phi(E) + udot
//! (zhang2018 eq. 2.12). We derive it from the paper's own design formula, eq. 6
//! (Edot = -beta_theta |E|^alpha sgn(E), applied elementwise), with E = W y - v (eq. 19):
//! Edot = Wdot y + W ydot - vdot, hence
//!
//! ```text
//!   W ydot = -Wdot y + vdot - beta |W y - v|^alpha sgn(W y - v)                        (20, derived)
//! ```
//!
//! i.e. the zeroing network with the fixed gain beta and the single sign-power activation
//! Phi(e) = |e|^alpha sgn(e) (no sign-bi-power combination: the paper's eq. 6 and 20 have one
//! term). The paper reuses the scheme's symbols for the network: beta = beta_theta = 1 and
//! alpha = 0.1 in its simulations; here they are the network's own parameters `beta` and
//! `alpha`. By eq. 11 each error component reaches zero at
//! t_s = |E_i(0)|^(1-alpha) / (beta (1-alpha)).
//!
//! # The linear zone of the sign-power (ours)
//!
//! With alpha < 1 the sign-power has an infinite slope at e = 0, so the network is not
//! Lipschitz there. Implicit integrators (BDF, ESDIRK, TR-BDF2) then fail: Newton's method on
//! |e|^alpha sgn(e) overshoots the root by a factor 1/alpha - 1 = 9 and diverges; explicit ones
//! chatter around E = 0 with tiny steps. We therefore make the activation linear with the
//! matching value, phi(e) = e delta^(alpha-1), inside |e| < delta = `smoothing`
//! (default [`settings::solver_spec::FINITE_TIME_SMOOTHING`] = 1e-8: slope 1.6e7 for
//! alpha = 0.1, as stiff as the gamma = 1e7 projection networks). The finite-time phase is
//! untouched down to |E_i| = 1e-8, then E_i decays exponentially with rate beta * 1.6e7; 0 gives
//! the exact form. In our tests BDF fails on every QP with delta = 0 and 1e-10 and succeeds on
//! all with 1e-8.
//!
//! The ZNN of the comparison (eq. 22 is a scheme; kong2019 solves it with "ZNN", the linear
//! zeroing design of its eq. 4) is the same core with the linear activation and gain gamma:
//! W ydot = -Wdot y + vdot - gamma (W y - v).

use super::activation::Activation;
use super::zeroing::{Gain, ZeroingNetwork};
use schemes::qp::QpDims;
use settings::error::NetworkError;

/// kong2019's finite-time network (eq. 20 as derived in the module docs).
/// `smoothing` is the half-width delta of the linear zone of the sign-power (module docs;
/// 0 gives the exact, non-Lipschitz form).
pub fn finite_time(
    beta: f64,
    alpha: f64,
    smoothing: f64,
    dims: QpDims,
) -> Result<ZeroingNetwork, NetworkError> {
    if !(alpha > 0.0 && alpha < 1.0) {
        return Err(NetworkError::FiniteTimeAlpha(alpha));
    }
    ZeroingNetwork::new(
        "FTNN",
        Gain::Fixed(beta),
        Activation::SignPower {
            r: alpha,
            smoothing,
        },
        None,
        dims,
    )
}

/// The linear ZNN (kong2019's comparison solver): W ydot = -Wdot y + vdot - gamma (W y - v).
pub fn znn(gamma: f64, dims: QpDims) -> Result<ZeroingNetwork, NetworkError> {
    ZeroingNetwork::new("ZNN", Gain::Fixed(gamma), Activation::Linear, None, dims)
}
