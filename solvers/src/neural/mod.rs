//! The papers' recurrent neural networks as continuous-time systems solving a QP
//! (see [`qp::Qp`]). Each network has a state y whose first `nx` entries are the
//! current estimate of the decision variable x (the joint velocity or acceleration that
//! drives the arm); the rest are dual (multiplier) states where the network has them.
//!
//! | network | paper, equation | state y | file |
//! |---|---|---|---|
//! | LVI-PDNN | jia2019 eq. 2.21-2.23 | [x; u; v] (nx + n_eq + n_in) | [`projection`] |
//! | S-LVI-PDNN | zhong2021 eq. 2.35 | [x; u; v] | [`projection`] |
//! | VP-RNN-PF | zhong2021 eq. 2.19-2.30 | [x; lambda] (nx + n_eq) | [`projection`] (its penalty form) |
//! | any projection network | a point of `settings::projection`'s vocabulary | by its error form | [`projection`] |
//! | FP-CDNN / VP-CDNN | zhang2018 eq. 2.15 / 2.11, perturbed 3.2 / 3.1 | [x; lambda] | [`zeroing`], [`perturbation`] |
//! | FTNN (finite-time) / ZNN | kong2019 eq. 17-20 / its eq. 22 comparison | [x; lambda] | [`zeroing`] |
//! | group ZNN | the group's MATLAB code (`docs/group-code.md`) | [x; lambda] | [`zeroing`] |
//! | any zeroing network | a point of `settings::zeroing`'s vocabulary | [x; lambda] | [`zeroing`] |
//!
//! The networks are two families, each the presets of one vocabulary: the zeroing family (gain
//! law, activation, growing gain, perturbation) and the projection family (error form with its
//! scaling or penalty, gain law, activation), one engine each ([`ZeroingNetwork`],
//! [`ProjectionNetwork`]); `docs/networks.md` derives each preset from its paper.
//!
//! Activation functions: [`activation`]. The factory that builds a network from its
//! experiment-file specification (`settings::solver_spec`): [`spec`]. A network's parameter
//! errors: `settings::NetworkError`. Every network starts from y = 0 (none of the papers
//! says otherwise).

pub mod activation;
pub mod lu;
mod penalty;
pub mod perturbation;
pub mod projection;
pub mod spec;
pub mod zeroing;

pub use activation::Activation;
pub use perturbation::PerturbationTerms;
pub use projection::ProjectionNetwork;
pub use spec::build_solver;
pub use zeroing::ZeroingNetwork;

use nalgebra::DMatrix;
use qp::{Qp, QpDims};

/// A recurrent network that solves a (possibly time-varying) QP.
///
/// Implementations keep their scratch buffers inside `self` so that [`NeuralSolver::rhs`]
/// does not allocate.
pub trait NeuralSolver: Send {
    /// Display name, as the papers write it (e.g. `LVI-PDNN`).
    fn name(&self) -> String;
    /// Dimension of the network state y for a QP of these sizes.
    fn state_dim(&self, dims: QpDims) -> usize;
    /// Whether [`NeuralSolver::rhs`] needs the time derivative of the QP data (zeroing networks).
    fn needs_qp_dot(&self) -> bool {
        false
    }
    /// Network dynamics ydot = F(t, y; QP(t)). `qp_dot` holds dQP/dt (every field
    /// differentiated; bounds and shapes as in `qp`) when [`NeuralSolver::needs_qp_dot`].
    fn rhs(&mut self, t: f64, y: &[f64], qp: &Qp, qp_dot: Option<&Qp>, ydot: &mut [f64]);
    /// The norm of the network's own error at state y (for the zeroing networks |Q y - u|_2,
    /// kong2019's J_E; for the projection networks |P_Omega(y - (M y + q)) - y|_2), or `None`
    /// where the network has no state-only error (VP-RNN-PF's depends on the last evaluation).
    fn error_norm(&mut self, _qp: &Qp, _y: &[f64]) -> Option<f64> {
        None
    }
    /// dF/dy with the QP data frozen, written into `jac` (state_dim x state_dim).
    /// Returns false when the network gives no analytic Jacobian.
    fn jacobian(
        &mut self,
        _t: f64,
        _y: &[f64],
        _qp: &Qp,
        _qp_dot: Option<&Qp>,
        _jac: &mut DMatrix<f64>,
    ) -> bool {
        false
    }
    /// The derivative of F(t, y; QP) with respect to the QP data along a direction: `out` =
    /// d/ds F(t, y; qp + s dqp, qp_dot + s dqp_dot) at s = 0 (`dqp_dot` only where
    /// [`NeuralSolver::needs_qp_dot`]; `None` there: qp_dot held fixed). The coupled arm +
    /// network ODE chains it with the derivative of the QP data along the arm's state, which
    /// keeps the network's own nonlinearity (e.g. a sign-power of width 1e-6) out of a finite
    /// difference. Returns false when the network does not give it (the caller then differences
    /// F as a whole).
    #[allow(clippy::too_many_arguments)]
    fn data_derivative(
        &mut self,
        _t: f64,
        _y: &[f64],
        _qp: &Qp,
        _qp_dot: Option<&Qp>,
        _dqp: &Qp,
        _dqp_dot: Option<&Qp>,
        _out: &mut [f64],
    ) -> bool {
        false
    }
    /// The network's initial state y(0) for QPs of sizes `dims` (zero: no paper says otherwise).
    fn initial_state(&self, _dims: QpDims, y0: &mut [f64]) {
        y0.fill(0.0);
    }
}

/// |v|_2.
pub(crate) fn euclidean_norm(v: &[f64]) -> f64 {
    v.iter().map(|e| e * e).sum::<f64>().sqrt()
}
