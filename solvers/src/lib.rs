//! The exact reference solver (Clarabel), a hot-started dense active-set solver,
//! the papers' neural solvers and the ODE integration layer (diffsol) they are simulated with.

pub mod active_set;
pub mod exact;
pub mod exact_path;
pub mod neural;
pub mod ode;
pub mod random_qp;

pub use active_set::{
    ActiveSetError, ActiveSetSolution, ActiveSetSolver, ActiveSetStart, Constraint, WorkingSet,
};
pub use exact::{solve_equality_kkt, ExactError, ExactSolution, ExactSolver, ExactStatus};
pub use exact_path::{ExactPath, ExactPathStats};
pub use random_qp::{random_feasible, random_qp, QpShape};
pub use schemes::qp::{KktResiduals, Qp, QpDims, QpDuals};
