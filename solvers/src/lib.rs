//! The QP type, the exact reference solver (Clarabel), the papers' neural solvers and the
//! ODE integration layer (diffsol) they are simulated with.

pub mod neural;
pub mod qp;

pub use qp::{KktResiduals, Qp, QpDims, QpDuals};
