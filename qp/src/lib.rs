//! The quadratic program, the bottom of driftbench's engine: every scheme writes one at every
//! instant, every solver reads one. The crate depends on nothing of the suite, so a solver
//! (built-in or outside) compiles without robots, schemes or file formats.
//!
//! - [`Qp`], [`QpDims`], [`QpDuals`], [`KktResiduals`]: the dense convex QP
//!   min x'Px/2 + q'x s.t. A x = b, G x <= h, l <= x <= u, its sizes, its multipliers and the
//!   infinity-norm KKT residuals of a primal-dual pair (the form and the sign conventions are
//!   in [`Qp`]'s docs);
//! - [`QpError`]: why a QP's data is malformed ([`Qp::validate`]);
//! - [`difference_quotient`], [`QpDotScratch`], [`FD_STEP`]: dQP/dt by central difference, for
//!   the networks that need the QP's motion;
//! - the one solver seam, [`QpSolver`], with its [`QpStatus`], [`QpSolve`], open
//!   [`QpSolverError`] and [`SolverId`].

#![deny(missing_docs)]

mod dot;
mod error;
mod problem;
mod solver;

pub use dot::{difference_quotient, QpDotScratch, FD_STEP};
pub use error::QpError;
pub use problem::{KktResiduals, Qp, QpDims, QpDuals};
pub use solver::{QpSolve, QpSolver, QpSolverError, QpStatus, SolverId};
