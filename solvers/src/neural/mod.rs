//! The papers' recurrent neural networks as continuous-time systems solving a QP
//! (see [`crate::qp::Qp`]). Each network has a state y whose first `nx` entries are the
//! current estimate of the decision variable x (the joint velocity or acceleration that
//! drives the arm); the rest are dual (multiplier) states where the network has them.

use crate::qp::{Qp, QpDims};
use nalgebra::DMatrix;

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
    /// dF/dy with the QP data frozen, written into `jac` (state_dim x state_dim).
    /// Returns false when the network gives no analytic Jacobian.
    fn jacobian(&mut self, _t: f64, _y: &[f64], _qp: &Qp, _qp_dot: Option<&Qp>, _jac: &mut DMatrix<f64>) -> bool {
        false
    }
}
