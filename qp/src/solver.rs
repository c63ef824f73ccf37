//! The solver seam: every per-instant QP method, built-in (crate `solvers`) or outside, is a
//! [`QpSolver`]. A solve either succeeds ([`QpSolve`], status [`QpStatus::Solved`]) or fails
//! with a [`QpSolverError`]: its [`QpStatus`] (iteration limit, infeasible, singular, ...) and
//! the method's own error as an open source (`Box<dyn Error>`), so a solver outside the suite
//! implements the trait with errors of its own. A solver is named by a [`SolverId`] (a slug),
//! not by a display name. After a successful solve the primal answer is [`QpSolver::x`], the
//! multipliers [`QpSolver::duals`] (in the convention of [`crate`]: stationarity
//! P x + q + A'lambda + G'mu - z_l + z_u = 0), and the KKT residuals of the pair
//! [`QpSolver::kkt_residuals`].

use crate::{KktResiduals, Qp, QpDuals};
use nalgebra::DVector;
use std::borrow::Cow;
use std::fmt;

/// A QP solver's id: a slug (lower-case ASCII letters, digits and `-`), e.g. `m4`,
/// `active-set`, `clarabel`, `osqp`, or an outside solver's own.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SolverId(Cow<'static, str>);

impl SolverId {
    /// The id `id`, or `None` when it is empty, longer than 64 characters or not a slug.
    pub fn new(id: impl Into<Cow<'static, str>>) -> Option<Self> {
        let id = id.into();
        let ok = !id.is_empty()
            && id.len() <= 64
            && id
                .bytes()
                .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'-');
        ok.then_some(SolverId(id))
    }

    /// A built-in id, given as a literal slug (checked in debug builds).
    pub fn builtin(id: &'static str) -> Self {
        debug_assert!(SolverId::new(id).is_some(), "not a slug: {id}");
        SolverId(Cow::Borrowed(id))
    }

    /// The id as text.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl fmt::Display for SolverId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// How a solve ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum QpStatus {
    /// Solved to the method's own stopping rule.
    Solved,
    /// The method's iteration limit was reached first.
    IterationLimit,
    /// The constraints were shown inconsistent.
    Infeasible,
    /// The objective was shown unbounded below.
    Unbounded,
    /// A matrix the method factorises or inverts was singular to working precision.
    Singular,
    /// The iterate became NaN or infinite, or a step's denominator vanished.
    NumericalFailure,
    /// The QP had the wrong sizes for the solver, or NaN or infinite data.
    InvalidInput,
    /// The method stopped with an answer that failed its own accuracy check.
    Inaccurate,
}

impl QpStatus {
    /// The status as text (`solved`, `iteration-limit`, ...).
    pub fn as_str(self) -> &'static str {
        match self {
            QpStatus::Solved => "solved",
            QpStatus::IterationLimit => "iteration-limit",
            QpStatus::Infeasible => "infeasible",
            QpStatus::Unbounded => "unbounded",
            QpStatus::Singular => "singular",
            QpStatus::NumericalFailure => "numerical-failure",
            QpStatus::InvalidInput => "invalid-input",
            QpStatus::Inaccurate => "inaccurate",
        }
    }
}

impl fmt::Display for QpStatus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What one successful [`QpSolver::solve`] cost.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QpSolve {
    /// [`QpStatus::Solved`].
    pub status: QpStatus,
    /// The method's own iterations (PLPE steps, working-set changes, interior-point or ADMM
    /// iterations); 0 when the warm start already met the method's stopping rule.
    pub iterations: u32,
    /// Work in products with the LVI matrix M (unit: `solvers::lvi_numerical`'s module docs),
    /// for the methods built on jia2019's LVI; `None` for the others.
    pub products: Option<u64>,
}

impl Default for QpSolve {
    fn default() -> Self {
        QpSolve {
            status: QpStatus::Solved,
            iterations: 0,
            products: None,
        }
    }
}

impl QpSolve {
    /// A successful solve of `iterations` iterations, with no product count.
    pub fn solved(iterations: u32) -> Self {
        QpSolve {
            iterations,
            ..QpSolve::default()
        }
    }
}

/// Why a [`QpSolver::solve`] failed: the status it ended with and the method's own error.
#[derive(Debug, thiserror::Error)]
#[error("{source}")]
pub struct QpSolverError {
    /// How the solve ended (never [`QpStatus::Solved`]).
    pub status: QpStatus,
    /// The method's own error.
    #[source]
    pub source: Box<dyn std::error::Error + Send + Sync + 'static>,
}

impl QpSolverError {
    /// A failure with `status` and the method's error `source`.
    pub fn new(
        status: QpStatus,
        source: impl Into<Box<dyn std::error::Error + Send + Sync + 'static>>,
    ) -> Self {
        QpSolverError {
            status,
            source: source.into(),
        }
    }
}

/// A per-instant QP method (the [`crate`] docs: a solve, its status and its multipliers).
pub trait QpSolver {
    /// The solver's id.
    fn id(&self) -> SolverId;
    /// Solves `qp`, starting from what the previous call left where the method can.
    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError>;
    /// The primal answer x of the last successful solve (its state before any, or after
    /// [`Self::reset`]: zeros, or empty for a method with no state, Clarabel).
    fn x(&self) -> &[f64];
    /// Writes the multipliers of the last successful solve of `qp` into `duals` (sized for
    /// `qp`), in the convention of [`crate`]. Must not allocate.
    fn duals(&self, qp: &Qp, duals: &mut QpDuals);
    /// Forgets what the previous calls left: the next solve is a cold start.
    fn reset(&mut self);
    /// The KKT residuals ([`Qp::kkt_residuals`]) of the last successful solve of `qp`, with
    /// `duals` as scratch (sized for `qp`).
    fn kkt_residuals(&self, qp: &Qp, duals: &mut QpDuals) -> KktResiduals {
        self.duals(qp, duals);
        qp.kkt_residuals(&DVector::from_column_slice(self.x()), duals)
    }
}

/// A boxed solver (e.g. one the registry built) is a solver.
impl<S: QpSolver + ?Sized> QpSolver for Box<S> {
    fn id(&self) -> SolverId {
        (**self).id()
    }
    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        (**self).solve(qp)
    }
    fn x(&self) -> &[f64] {
        (**self).x()
    }
    fn duals(&self, qp: &Qp, duals: &mut QpDuals) {
        (**self).duals(qp, duals)
    }
    fn reset(&mut self) {
        (**self).reset()
    }
    fn kkt_residuals(&self, qp: &Qp, duals: &mut QpDuals) -> KktResiduals {
        (**self).kkt_residuals(qp, duals)
    }
}
