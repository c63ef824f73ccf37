//! The papers' group's own network, as its public MATLAB code computes it
//! (`docs/group-code.md`: `ldkong1205/numerical-planning`, `code/EXP1`, `code/EXP2`,
//! `mvn_ZZJLJrebi1_net.m`).
//!
//! On the equality-constrained velocity-level QP min x'Px/2 + q'x s.t. A x = b:
//!
//! ```text
//!   Q ydot = -Qdot y - gamma Phi(E) + udot - nu t E + Delta_s(t),   E = Q y - u,
//!   Q = [ P  A' ],   u = [ -q ],   y = [ thetadot ]
//!       [ A  0  ]        [  b ]        [ lambda   ]
//! ```
//!
//! (the group's code: Q = [I J'; J 0], u = [-k (theta - theta0); rdot*], gamma = 500,
//! nu = 2500). It is the zeroing network of [`super::zeroing`] (W ydot = -Wdot y + vdot
//! - gamma Phi(W y - v), the FP-CDNN / ZNN core) with three of that core's options switched on:
//!
//! - the growing-gain term -nu t E (t the simulation time, from 0);
//! - the injected perturbation Delta_s(t) = a_s [2 sin w, 4 cos 2w, -5 sin 3w, cos 3w,
//!   -sin 3w, 3 cos w, -sin w, -sin 2w, cos w]', w = pi t / T: the vector part of zhang2018's
//!   reference perturbation ([`settings::solver_spec::ReferencePerturbation`], a_s = 1.5 in the group's
//!   code); its matrix part is computed by the code but not used, so the `a_d` of the
//!   perturbation is ignored here;
//! - with `udot_rmp = false`, udot = [0; bdot] instead of [-qdot; bdot]: the group's EXP1 file
//!   has udot = [0; rddot*], missing the -k thetadot term (EXP2 has it).
//!
//! Phi is the group's power-sigmoid with xi = 1, p = 1 by default
//! ([`super::activation::Activation::GroupPowerSigmoid`]); any activation can be given.
//! The Jacobian is analytic (QP data frozen): Q dF/dy = -Qdot - (gamma diag(Phi'(E)) + nu t I) Q.
//! The network is built only for equality-only QPs (n_in = 0, bounds ignored), as the core.

use super::activation::Activation;
use super::zeroing::{Gain, ZeroingNetwork};
use schemes::qp::QpDims;
use settings::error::NetworkError;
use settings::solver_spec::ReferencePerturbation;

/// The group's network (module docs): gain gamma, growing gain nu, activation Phi, optional
/// perturbation (Delta_s only), and `udot_rmp` (false: udot without its -qdot part).
pub fn group_znn(
    gamma: f64,
    nu: f64,
    activation: Activation,
    perturbation: Option<ReferencePerturbation>,
    udot_rmp: bool,
    dims: QpDims,
) -> Result<ZeroingNetwork, NetworkError> {
    let net = ZeroingNetwork::new(
        "group ZNN",
        Gain::Fixed(gamma),
        activation,
        perturbation,
        dims,
    )?
    .with_growing_gain(nu)?
    .with_vector_perturbation_only();
    Ok(if udot_rmp { net } else { net.without_udot_q() })
}
