//! The QP type, the exact reference solver (Clarabel), the papers' neural solvers and the
//! ODE integration layer (diffsol) they are simulated with.

pub mod exact;
pub mod neural;
pub mod ode;
pub mod qp;
pub mod random_qp;

pub use exact::{solve_equality_kkt, ExactError, ExactSolution, ExactSolver, ExactStatus};
pub use qp::{KktResiduals, Qp, QpDims, QpDuals};
pub use random_qp::{random_feasible, random_qp, QpShape};
