//! The exact reference solver (Clarabel), a hot-started dense active-set solver,
//! the papers' neural solvers and the ODE integration layer (diffsol) they are simulated with.

// The numerical kernels index vectors and matrices by the papers' subscripts (x_i, A_ij, the
// KKT blocks); iterator chains would hide that correspondence, so index loops are kept.
#![allow(clippy::needless_range_loop)]
// Parameter checks are written `!(x > 0.0 && x.is_finite())`, `!(pivot > tol)`: a NaN fails
// them, which the "simplified" forms clippy proposes would let through or obscure.
#![allow(clippy::nonminimal_bool, clippy::neg_cmp_op_on_partial_ord)]
#![deny(missing_docs)]

mod active_set;
mod auxiliary;
pub mod conformance;
mod dense_lu;
mod equality_kkt;
mod exact;
mod exact_path;
mod kkt_schur;
mod lvi_numerical;
pub mod neural;
pub mod ode;
#[cfg(feature = "osqp")]
mod osqp_qp;
mod qp_solver;
pub mod random_qp;
pub mod registry;

pub use active_set::DEFAULT_CERT_TOL;
pub use active_set::{
    ActiveSetError, ActiveSetSolution, ActiveSetSolver, ActiveSetStart, Constraint, WorkingSet,
};
pub use auxiliary::AuxiliaryElimination;
pub use dense_lu::{Backend, DenseLu};
pub use exact::{cone_sizes, ConeSizes};
pub use exact::{
    solve_equality_kkt, solve_equality_kkt_with, ExactError, ExactSolution, ExactSolver,
    ExactStatus,
};
pub use exact_path::{ExactPath, ExactPathStats, CHECK_EVERY};
pub use lvi_numerical::{
    LviError, LviMethod, LviSettings, LviSolver,
    DEFAULT_MAX_ITERATIONS as LVI_DEFAULT_MAX_ITERATIONS,
    DEFAULT_TOLERANCE as LVI_DEFAULT_TOLERANCE,
};
#[cfg(feature = "osqp")]
pub use osqp_qp::{OsqpQp, OsqpSettings};
pub use qp::{KktResiduals, Qp, QpDims, QpDuals};
pub use qp::{QpSolve, QpSolver, QpSolverError, QpStatus, SolverId};
pub use qp_solver::{ActiveSetFailure, HotActiveSet};
pub use random_qp::{random_feasible, random_qp, QpShape};
