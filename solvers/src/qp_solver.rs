//! One interface, [`QpSolver`], for the per-instant QP methods a controller calls at every
//! tick, each started from what its previous call left where the method can:
//!
//! - robio2018's six PLPE methods ([`LviSolver`], [`crate::lvi_numerical`]): iterated from the
//!   previous call's primal-dual point (warm start); the only ones that count their work in
//!   products ([`QpSolve::products`]);
//! - the dense active-set solver hot-started from the previous call's optimal working set
//!   ([`HotActiveSet`]);
//! - Clarabel ([`ExactSolver`]): an interior-point method, started afresh every call;
//! - OSQP (`OsqpQp`, with the `osqp` feature): data updated in place, warm-started.
//!
//! Each type's inherent `solve` keeps its own richer result; [`QpSolver::solve`] is the common
//! view, and [`QpSolverError`] wraps each method's error.

use crate::active_set::{ActiveSetError, ActiveSetSolution, ActiveSetSolver, WorkingSet};
use crate::exact::{ExactError, ExactSolver};
use crate::lvi_numerical::{LviError, LviSolver};
#[cfg(feature = "osqp")]
use crate::osqp_qp::{OsqpError, OsqpQp};
use schemes::qp::{Qp, QpDims};

/// What one successful [`QpSolver::solve`] cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QpSolve {
    /// The method's own iterations (PLPE steps, working-set changes, interior-point or ADMM
    /// iterations); 0 when the warm start already met the method's stopping rule.
    pub iterations: u32,
    /// Work in products with the LVI matrix M, for the methods built on jia2019's LVI (unit:
    /// [`crate::lvi_numerical`]'s module docs); `None` for the others.
    pub products: Option<u64>,
}

/// Why a [`QpSolver::solve`] failed: the failing method's own error.
#[derive(Debug, thiserror::Error)]
pub enum QpSolverError {
    /// One of robio2018's PLPE methods.
    #[error(transparent)]
    Plpe(#[from] LviError),
    /// The hot-started active set failed, cold-started too, and so did Clarabel after it.
    #[error("active set: {active_set}; its Clarabel fallback: {fallback}")]
    ActiveSet {
        /// Why the active-set solver failed (its cold start's error when a warm start was tried
        /// first).
        active_set: ActiveSetError,
        /// Why Clarabel failed after it.
        #[source]
        fallback: ExactError,
    },
    /// Clarabel.
    #[error("exact solver: {0}")]
    Exact(#[from] ExactError),
    /// OSQP.
    #[cfg(feature = "osqp")]
    #[error(transparent)]
    Osqp(#[from] OsqpError),
}

/// A per-instant QP method (module docs).
pub trait QpSolver {
    /// Solves `qp`, starting from what the previous call left where the method can.
    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError>;
    /// The primal answer x of the last successful solve (its state before any, or after
    /// [`Self::reset`]: zeros, or empty for a method with no state, Clarabel).
    fn x(&self) -> &[f64];
    /// Forgets what the previous calls left: the next solve is a cold start.
    fn reset(&mut self);
    /// Display name (`94LVI`, ..., `active set`, `Clarabel`, `OSQP`).
    fn name(&self) -> &'static str;
}

impl QpSolver for LviSolver {
    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        let iterations = LviSolver::solve(self, qp)?;
        Ok(QpSolve {
            iterations,
            products: Some(self.method().products(iterations, self.state().len())),
        })
    }

    fn x(&self) -> &[f64] {
        LviSolver::x(self)
    }

    fn reset(&mut self) {
        LviSolver::reset(self);
    }

    fn name(&self) -> &'static str {
        self.method().name()
    }
}

impl QpSolver for ExactSolver {
    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        let s = ExactSolver::solve(self, qp)?;
        self.set_last_x(s.x.as_slice());
        Ok(QpSolve {
            iterations: s.iterations,
            products: None,
        })
    }

    fn x(&self) -> &[f64] {
        self.last_x()
    }

    fn reset(&mut self) {
        self.set_last_x(&[]);
    }

    fn name(&self) -> &'static str {
        "Clarabel"
    }
}

#[cfg(feature = "osqp")]
impl QpSolver for OsqpQp {
    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        Ok(QpSolve {
            iterations: OsqpQp::solve(self, qp)?,
            products: None,
        })
    }

    fn x(&self) -> &[f64] {
        OsqpQp::x(self)
    }

    fn reset(&mut self) {
        OsqpQp::reset(self);
    }

    fn name(&self) -> &'static str {
        "OSQP"
    }
}

/// The dense active-set solver hot-started from the previous solve's optimal working set,
/// without its KKT certification (a control loop scores every tick against the certified
/// reference instead); when the hot start fails it is cold-started, and when that
/// fails too (MVN's QP, whose p has no weight, has a singular KKT matrix) Clarabel answers and
/// the next solve starts cold. Solving does not allocate while the active set answers.
#[derive(Clone, Debug)]
pub struct HotActiveSet {
    solver: ActiveSetSolver,
    out: ActiveSetSolution,
    warm: WorkingSet,
    has_warm: bool,
    clarabel: ExactSolver,
    x: Vec<f64>,
}

impl HotActiveSet {
    /// A solver for QPs of at most the sizes `dims`, with no working set yet.
    pub fn new(dims: QpDims) -> Self {
        HotActiveSet {
            solver: ActiveSetSolver::new(dims).with_certification(false),
            out: ActiveSetSolution::zeros(dims),
            warm: WorkingSet::with_capacity(dims.n_in + 2 * dims.nx),
            has_warm: false,
            clarabel: ExactSolver::new(),
            x: vec![0.0; dims.nx],
        }
    }
}

impl QpSolver for HotActiveSet {
    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        let warm = self.has_warm.then_some(&self.warm);
        let solved = match self.solver.solve_into(qp, warm, &mut self.out) {
            Err(_) if warm.is_some() => self.solver.solve_into(qp, None, &mut self.out),
            first => first,
        };
        let iterations = match solved {
            Ok(()) => {
                self.warm.clone_from(&self.out.working_set);
                self.has_warm = true;
                self.x.clear();
                self.x.extend_from_slice(self.out.x.as_slice());
                self.out.iterations
            }
            Err(active_set) => {
                self.has_warm = false;
                let s = self
                    .clarabel
                    .solve(qp)
                    .map_err(|fallback| QpSolverError::ActiveSet {
                        active_set,
                        fallback,
                    })?;
                self.x.clear();
                self.x.extend_from_slice(s.x.as_slice());
                s.iterations
            }
        };
        Ok(QpSolve {
            iterations,
            products: None,
        })
    }

    fn x(&self) -> &[f64] {
        &self.x
    }

    fn reset(&mut self) {
        self.has_warm = false;
        self.x.fill(0.0);
    }

    fn name(&self) -> &'static str {
        "active set"
    }
}
