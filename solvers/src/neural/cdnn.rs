//! FP-CDNN and VP-CDNN (zhang2018 eq. 2.15 and 2.11) and their perturbed forms (eq. 3.2, 3.1).
//!
//! Both are the zeroing network of [`super::zeroing`] on the Lagrange system of the
//! equality-only QP (zhang2018 eq. 2.8: Q = [W J'; J 0], y = [x; lambda], u = [-eta; b]):
//!
//! ```text
//!   VP-CDNN (2.11):  Q ydot = -Qdot y - gamma exp(t) Phi(Q y - u) + udot
//!   FP-CDNN (2.15):  Q ydot = -Qdot y - gamma        Phi(Q y - u) + udot
//!   perturbed (3.1 / 3.2):
//!                    Q ydot = -(Qdot + DeltaD(t)) y - g(t) Phi(Q y - u) + udot + Delta s(t)
//! ```
//!
//! i.e. DeltaD(t) is added to Qdot where it multiplies y (the "differential errors of matrix
//! Q") and Delta s(t) is added to udot (the "differential errors of vector u as well as external
//! disturbance"); Q itself, u and the activated error term are unperturbed. Activation linear
//! unless stated (the robustness theorem of zhang2018 is for the linear activation).
//!
//! The perturbation's terms (zhang2018's reference perturbation) are [`super::perturbation`]'s.

use super::activation::Activation;
use super::zeroing::{Gain, ZeroingNetwork};
use schemes::qp::QpDims;
use settings::error::NetworkError;
use settings::solver_spec::ReferencePerturbation;

/// FP-CDNN (zhang2018 eq. 2.15; eq. 3.2 with a perturbation): gain gamma.
pub fn fp_cdnn(
    gamma: f64,
    activation: Activation,
    perturbation: Option<ReferencePerturbation>,
    dims: QpDims,
) -> Result<ZeroingNetwork, NetworkError> {
    ZeroingNetwork::new(
        "FP-CDNN",
        Gain::Fixed(gamma),
        activation,
        perturbation,
        dims,
    )
}

/// VP-CDNN (zhang2018 eq. 2.11; eq. 3.1 with a perturbation): gain gamma exp(t).
pub fn vp_cdnn(
    gamma: f64,
    activation: Activation,
    perturbation: Option<ReferencePerturbation>,
    dims: QpDims,
) -> Result<ZeroingNetwork, NetworkError> {
    ZeroingNetwork::new(
        "VP-CDNN",
        Gain::Exponential(gamma),
        activation,
        perturbation,
        dims,
    )
}
