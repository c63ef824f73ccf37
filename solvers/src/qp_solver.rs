//! The built-in per-instant QP methods behind the one seam, [`QpSolver`] (crate `qp`): the
//! control loop's ticks, the conformance kit ([`crate::conformance`]) and any outside solver go
//! through it. Each method starts from what its previous call left where it can:
//!
//! - robio2018's six PLPE methods ([`LviSolver`], [`crate::lvi_numerical`]): iterated from the
//!   previous call's primal-dual point (warm start); the only ones that count their work in
//!   products ([`QpSolve::products`]);
//! - the dense active-set solver hot-started from the previous call's optimal working set
//!   ([`HotActiveSet`]);
//! - Clarabel ([`ExactSolver`]): an interior-point method, started afresh every call;
//! - OSQP (`OsqpQp`, with the `osqp` feature): data updated in place, warm-started.
//!
//! Each method's failure maps to a [`QpStatus`] (`From` impls below).

use crate::active_set::{ActiveSetError, ActiveSetSolution, ActiveSetSolver, WorkingSet};
use crate::exact::{ExactError, ExactSolver};
use crate::lvi_numerical::{LviError, LviSolver};
#[cfg(feature = "osqp")]
use crate::osqp_qp::{OsqpError, OsqpQp};
use qp::{Qp, QpDims, QpDuals, QpSolve, QpSolver, QpSolverError, QpStatus, SolverId};

/// Bound multipliers from the stationarity residual r = P x + q + A' lambda + G' mu: at a
/// solution r + z_u - z_l = 0 with z_l, z_u >= 0 in the normal cone of the bounds, so
/// z_l = max(r, 0) and z_u = max(-r, 0) (a zero residual leaves both at 0).
fn bound_duals_from_stationarity(qp: &Qp, x: &[f64], duals: &mut QpDuals) {
    let nx = x.len();
    for i in 0..nx {
        let mut r = qp.q[i];
        for j in 0..nx {
            r += qp.p[(i, j)] * x[j];
        }
        for k in 0..duals.lambda.len() {
            r += qp.a[(k, i)] * duals.lambda[k];
        }
        for k in 0..duals.mu.len() {
            r += qp.g[(k, i)] * duals.mu[k];
        }
        duals.z_lower[i] = r.max(0.0);
        duals.z_upper[i] = (-r).max(0.0);
    }
}

impl From<LviError> for QpSolverError {
    fn from(e: LviError) -> Self {
        let status = match e {
            LviError::NotConverged { .. } => QpStatus::IterationLimit,
            LviError::NonFinite { .. } | LviError::Breakdown { .. } => QpStatus::NumericalFailure,
            LviError::SingularMatrix { .. } => QpStatus::Singular,
            LviError::Dimensions { .. } => QpStatus::InvalidInput,
        };
        QpSolverError::new(status, e)
    }
}

impl From<ExactError> for QpSolverError {
    fn from(e: ExactError) -> Self {
        let status = match e {
            ExactError::InvalidData(_) | ExactError::Rejected(_) => QpStatus::InvalidInput,
            ExactError::PrimalInfeasible(_) => QpStatus::Infeasible,
            ExactError::DualInfeasible(_) => QpStatus::Unbounded,
            ExactError::Failed { .. } => QpStatus::NumericalFailure,
            ExactError::Inaccurate { .. } => QpStatus::Inaccurate,
        };
        QpSolverError::new(status, e)
    }
}

impl QpSolver for LviSolver {
    fn id(&self) -> SolverId {
        SolverId::builtin(self.method().id())
    }

    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        let iterations = LviSolver::solve(self, qp)?;
        Ok(QpSolve {
            products: Some(self.method().products(iterations, self.state().len())),
            ..QpSolve::solved(iterations)
        })
    }

    fn x(&self) -> &[f64] {
        LviSolver::x(self)
    }

    /// The LVI's iterate U = [x; u; v] holds lambda = -u and mu = v
    /// ([`crate::neural::projection`]); the bound multipliers follow from stationarity.
    fn duals(&self, qp: &Qp, duals: &mut QpDuals) {
        let QpDims { nx, n_eq, n_in } = qp.dims();
        let u = self.state();
        for k in 0..n_eq {
            duals.lambda[k] = -u[nx + k];
        }
        for k in 0..n_in {
            duals.mu[k] = u[nx + n_eq + k];
        }
        bound_duals_from_stationarity(qp, self.x(), duals);
    }

    fn reset(&mut self) {
        LviSolver::reset(self);
    }
}

impl QpSolver for ExactSolver {
    fn id(&self) -> SolverId {
        SolverId::builtin("clarabel")
    }

    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        let s = ExactSolver::solve(self, qp)?;
        self.set_last(s.x.as_slice(), &s.duals);
        Ok(QpSolve::solved(s.iterations))
    }

    fn x(&self) -> &[f64] {
        self.last_x()
    }

    fn duals(&self, _qp: &Qp, duals: &mut QpDuals) {
        copy_duals(self.last_duals(), duals);
    }

    fn reset(&mut self) {
        self.set_last(
            &[],
            &QpDuals::zeros(QpDims {
                nx: 0,
                n_eq: 0,
                n_in: 0,
            }),
        );
    }
}

/// Copies `from` into `to` (same sizes).
fn copy_duals(from: &QpDuals, to: &mut QpDuals) {
    to.lambda.copy_from(&from.lambda);
    to.mu.copy_from(&from.mu);
    to.z_lower.copy_from(&from.z_lower);
    to.z_upper.copy_from(&from.z_upper);
}

#[cfg(feature = "osqp")]
impl From<OsqpError> for QpSolverError {
    fn from(e: OsqpError) -> Self {
        QpSolverError::new(QpStatus::NumericalFailure, e)
    }
}

#[cfg(feature = "osqp")]
impl QpSolver for OsqpQp {
    fn id(&self) -> SolverId {
        SolverId::builtin("osqp")
    }

    /// The QP is checked first (sizes, then [`Qp::validate`]): OSQP itself would answer a QP
    /// with a NaN in q (found by the conformance kit).
    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        if qp.dims() != self.dims() {
            return Err(QpSolverError::new(
                QpStatus::InvalidInput,
                DimensionsError {
                    expected: self.dims(),
                    found: qp.dims(),
                },
            ));
        }
        qp.validate()
            .map_err(|e| QpSolverError::new(QpStatus::InvalidInput, e))?;
        Ok(QpSolve::solved(OsqpQp::solve(self, qp)?))
    }

    fn x(&self) -> &[f64] {
        OsqpQp::x(self)
    }

    fn duals(&self, _qp: &Qp, duals: &mut QpDuals) {
        copy_duals(&OsqpQp::duals(self), duals);
    }

    fn reset(&mut self) {
        OsqpQp::reset(self);
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
    /// The multipliers of the last answer (the active set's or its Clarabel fallback's).
    duals: QpDuals,
    /// The sizes it was built for.
    dims: QpDims,
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
            duals: QpDuals::zeros(dims),
            dims,
        }
    }
}

impl QpSolver for HotActiveSet {
    fn id(&self) -> SolverId {
        SolverId::builtin("active-set")
    }

    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        if qp.dims() != self.dims {
            return Err(QpSolverError::new(
                QpStatus::InvalidInput,
                DimensionsError {
                    expected: self.dims,
                    found: qp.dims(),
                },
            ));
        }
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
                copy_duals(&self.out.duals, &mut self.duals);
                self.out.iterations
            }
            Err(active_set) => {
                self.has_warm = false;
                let s = self.clarabel.solve(qp).map_err(|fallback| {
                    let status = QpSolverError::from(fallback.clone()).status;
                    QpSolverError::new(
                        status,
                        ActiveSetFailure {
                            active_set,
                            fallback,
                        },
                    )
                })?;
                self.x.clear();
                self.x.extend_from_slice(s.x.as_slice());
                copy_duals(&s.duals, &mut self.duals);
                s.iterations
            }
        };
        Ok(QpSolve::solved(iterations))
    }

    fn x(&self) -> &[f64] {
        &self.x
    }

    fn duals(&self, _qp: &Qp, duals: &mut QpDuals) {
        copy_duals(&self.duals, duals);
    }

    fn reset(&mut self) {
        self.has_warm = false;
        self.x.fill(0.0);
    }
}

/// A QP of other sizes than the solver was built for.
#[derive(Debug, thiserror::Error)]
#[error("built for QPs of sizes {expected:?}, given one of {found:?}")]
pub struct DimensionsError {
    /// The sizes the solver was built for.
    pub expected: QpDims,
    /// The sizes of the QP given.
    pub found: QpDims,
}

/// The hot-started active set failed, cold-started too, and so did Clarabel after it.
#[derive(Debug, thiserror::Error)]
#[error("active set: {active_set}; its Clarabel fallback: {fallback}")]
pub struct ActiveSetFailure {
    /// Why the active-set solver failed (its cold start's error when a warm start was tried
    /// first).
    pub active_set: ActiveSetError,
    /// Why Clarabel failed after it.
    #[source]
    pub fallback: ExactError,
}
