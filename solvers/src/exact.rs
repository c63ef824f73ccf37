//! The exact reference solver: Clarabel (an interior-point conic solver) on the QP of
//! [`qp`], plus a direct KKT solve for equality-only QPs as an independent check.
//!
//! # Cone mapping
//!
//! Clarabel solves
//!
//! ```text
//! minimise x'Px/2 + q'x  subject to  A_c x + s = b_c,  s in K,
//! ```
//!
//! with dual variable z in the dual cone K* and stationarity P x + q + A_c' z = 0.
//! The QP is stacked into (A_c, b_c, K) as
//!
//! ```text
//! rows            A_c      b_c     cone            multiplier (qp.rs convention)
//! A x = b         A        b       zero            z = lambda
//! G x <= h        G        h       nonnegative     z = mu
//! x_i <= u_i      e_i'     u_i     nonnegative     z = z_upper[i]
//! -x_i <= -l_i    -e_i'    -l_i    nonnegative     z = z_lower[i]
//! ```
//!
//! Only finite bounds get a row; an absent bound (l_i = -inf, u_i = +inf) and an absent
//! inequality (h_i = +inf) get no row and a zero multiplier: no big-M constant is ever
//! introduced. With this stacking Clarabel's stationarity P x + q + A_c' z = 0 reads
//! P x + q + A'lambda + G'mu + z_u - z_l = 0, exactly the convention of [`qp`], so the
//! multipliers are copied without sign changes. P is passed as its upper triangle in CSC form.
//!
//! # Tolerances
//!
//! Clarabel stops on its own (equilibrated, relative) gap and feasibility tolerances. Its
//! default, 1e-8, leaves x wrong by up to ~1e-5 on these QPs: where a constraint is weakly active
//! (degenerate, as |thetadot_i| = p at a joint-velocity bound) an interior-point x is only
//! accurate to about the square root of the gap. The solver therefore first runs at 1e-12 (x
//! then agrees to ~1e-8 between equivalent formulations, see the tests) and, only if Clarabel
//! cannot get there (AlmostSolved, InsufficientProgress, NumericalError, MaxIterations..., about
//! one QP in 7,000 of the random ones), reruns at 1e-10, which never failed on them: see
//! [`CLARABEL_TOLS`]. The status and the outcome reported are those of the last attempt, the
//! iterations are summed over the attempts. Tighter values (1e-13) fail several times more often.
//!
//! A solution is accepted only if our own residuals ([`Qp::kkt_residuals`]) satisfy
//! `kkt.max() <= kkt_tol * (1 + max(|q|_inf, |b|_inf))`, with `kkt_tol` = [`DEFAULT_KKT_TOL`] =
//! 1e-6 unless changed. The scale uses the cost and the equality right-hand side only: the
//! inequality and bound right-hand sides are left out because the papers fill them with large
//! constants standing for +inf (varpi = 1e3 and more), which would make the check meaningless.

use crate::dense_lu::{Backend, DenseLu};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use nalgebra::{DMatrix, DVector};
use qp::QpError;
use qp::{KktResiduals, Qp, QpDims, QpDuals};
use std::fmt;

/// Clarabel's gap and feasibility tolerances, tried in turn (see the module docs).
pub const CLARABEL_TOLS: [f64; 2] = [1e-12, 1e-10];
/// Default relative tolerance on our own KKT residuals (see the module docs).
pub const DEFAULT_KKT_TOL: f64 = 1e-6;

/// Clarabel's termination status, mirrored so that callers need not depend on Clarabel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ExactStatus {
    /// The solver has not run.
    Unsolved,
    /// Solved to the requested tolerances.
    Solved,
    /// Certificate of primal infeasibility.
    PrimalInfeasible,
    /// Certificate of dual infeasibility (unbounded objective).
    DualInfeasible,
    /// Solved to Clarabel's reduced tolerances only.
    AlmostSolved,
    /// Primal infeasibility certificate to reduced tolerances.
    AlmostPrimalInfeasible,
    /// Dual infeasibility certificate to reduced tolerances.
    AlmostDualInfeasible,
    /// Iteration limit reached.
    MaxIterations,
    /// Time limit reached.
    MaxTime,
    /// Numerical failure (e.g. in the KKT factorisation).
    NumericalError,
    /// Stopped for lack of progress.
    InsufficientProgress,
    /// Stopped by a user callback (none is installed here).
    CallbackTerminated,
}

impl From<SolverStatus> for ExactStatus {
    fn from(s: SolverStatus) -> Self {
        match s {
            SolverStatus::Unsolved => Self::Unsolved,
            SolverStatus::Solved => Self::Solved,
            SolverStatus::PrimalInfeasible => Self::PrimalInfeasible,
            SolverStatus::DualInfeasible => Self::DualInfeasible,
            SolverStatus::AlmostSolved => Self::AlmostSolved,
            SolverStatus::AlmostPrimalInfeasible => Self::AlmostPrimalInfeasible,
            SolverStatus::AlmostDualInfeasible => Self::AlmostDualInfeasible,
            SolverStatus::MaxIterations => Self::MaxIterations,
            SolverStatus::MaxTime => Self::MaxTime,
            SolverStatus::NumericalError => Self::NumericalError,
            SolverStatus::InsufficientProgress => Self::InsufficientProgress,
            SolverStatus::CallbackTerminated => Self::CallbackTerminated,
        }
    }
}

impl ExactStatus {
    /// Whether Clarabel stopped with neither a solution nor an infeasibility certificate.
    pub fn is_failure(self) -> bool {
        matches!(
            self,
            Self::Unsolved
                | Self::MaxIterations
                | Self::MaxTime
                | Self::NumericalError
                | Self::InsufficientProgress
                | Self::CallbackTerminated
        )
    }
}

impl fmt::Display for ExactStatus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self, f)
    }
}

/// Why the exact solver gave no solution.
#[derive(Clone, Debug, PartialEq)]
pub enum ExactError {
    /// The QP data is malformed: inconsistent sizes, NaN, an infinite entry in P, q, A, b or G,
    /// or an infinite bound on the wrong side (h_i = -inf, l_i = +inf, u_i = -inf).
    InvalidData(QpError),
    /// Clarabel refused to set the problem up (its own message).
    Rejected(String),
    /// Clarabel proved the constraints infeasible (status PrimalInfeasible or
    /// AlmostPrimalInfeasible).
    PrimalInfeasible(ExactStatus),
    /// Clarabel proved the objective unbounded below (DualInfeasible or AlmostDualInfeasible).
    DualInfeasible(ExactStatus),
    /// Clarabel stopped without an answer (MaxIterations, MaxTime, NumericalError,
    /// InsufficientProgress, Unsolved, CallbackTerminated).
    Failed {
        /// Clarabel's status at its last attempt.
        status: ExactStatus,
        /// Clarabel's interior-point iterations, summed over the attempts.
        iterations: u32,
    },
    /// Clarabel reported (almost) solved but our KKT residuals exceed the tolerance.
    Inaccurate {
        /// Clarabel's status (Solved or AlmostSolved).
        status: ExactStatus,
        /// Our KKT residuals of Clarabel's answer.
        kkt: KktResiduals,
        /// The absolute tolerance they were held to: the relative KKT tolerance times
        /// 1 + max(|q|_inf, |b|_inf).
        tolerance: f64,
    },
}

impl fmt::Display for ExactError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidData(e) => write!(f, "invalid QP data: {e}"),
            Self::Rejected(msg) => write!(f, "invalid QP data: {msg}"),
            Self::PrimalInfeasible(s) => write!(f, "QP is primal infeasible (Clarabel status {s})"),
            Self::DualInfeasible(s) => {
                write!(
                    f,
                    "QP is dual infeasible, objective unbounded below (Clarabel status {s})"
                )
            }
            Self::Failed { status, iterations } => {
                write!(
                    f,
                    "Clarabel failed with status {status} after {iterations} iterations"
                )
            }
            Self::Inaccurate {
                status,
                kkt,
                tolerance,
            } => write!(
                f,
                "Clarabel status {status} but KKT residuals (primal {:.3e}, dual {:.3e}, \
                 complementarity {:.3e}) exceed {tolerance:.3e}",
                kkt.primal, kkt.dual, kkt.complementarity
            ),
        }
    }
}

impl std::error::Error for ExactError {}

/// An accepted solution of the exact solver.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactSolution {
    /// The primal solution x (Clarabel's, at its last attempt).
    pub x: DVector<f64>,
    /// Multipliers in the convention of [`qp`] (zero for absent constraints).
    pub duals: QpDuals,
    /// x'Px/2 + q'x evaluated at `x` by [`Qp::objective`].
    pub objective: f64,
    /// Clarabel's interior-point iterations, summed over the attempts (see the module docs).
    pub iterations: u32,
    /// [`ExactStatus::Solved`] or [`ExactStatus::AlmostSolved`] (reduced accuracy, but the
    /// KKT check passed).
    pub status: ExactStatus,
    /// Our own KKT residuals of (x, duals).
    pub kkt: KktResiduals,
}

impl ExactSolution {
    /// Whether Clarabel only reached its reduced tolerances.
    pub fn is_almost(&self) -> bool {
        self.status == ExactStatus::AlmostSolved
    }
}

/// Number of rows of each cone in the conic form handed to Clarabel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConeSizes {
    /// Equality rows (zero cone).
    pub zero: usize,
    /// Inequality rows with finite h plus one row per finite bound (nonnegative cone).
    pub nonnegative: usize,
}

/// The exact reference solver (Clarabel with tight tolerances, see the module docs).
#[derive(Clone, Debug)]
pub struct ExactSolver {
    settings: DefaultSettings<f64>,
    kkt_tol: f64,
    /// x of the last solve through [`crate::qp_solver::QpSolver`] (empty before one).
    last_x: Vec<f64>,
    /// The multipliers of that solve.
    last_duals: QpDuals,
}

impl Default for ExactSolver {
    fn default() -> Self {
        Self::new()
    }
}

impl ExactSolver {
    /// Clarabel silent, tolerances `CLARABEL_TOLS`, KKT acceptance tolerance `DEFAULT_KKT_TOL`.
    pub fn new() -> Self {
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .build()
            .expect("valid Clarabel settings");
        Self {
            settings,
            kkt_tol: DEFAULT_KKT_TOL,
            last_x: Vec::new(),
            last_duals: QpDuals::zeros(QpDims {
                nx: 0,
                n_eq: 0,
                n_in: 0,
            }),
        }
    }

    /// x of the last solve through [`crate::qp_solver::QpSolver`] (empty before one).
    pub(crate) fn last_x(&self) -> &[f64] {
        &self.last_x
    }

    /// The multipliers of the last solve through [`crate::qp_solver::QpSolver`].
    pub(crate) fn last_duals(&self) -> &QpDuals {
        &self.last_duals
    }

    pub(crate) fn set_last(&mut self, x: &[f64], duals: &QpDuals) {
        self.last_x.clear();
        self.last_x.extend_from_slice(x);
        self.last_duals.clone_from(duals);
    }

    /// Changes the relative KKT acceptance tolerance (see the module docs).
    pub fn with_kkt_tolerance(mut self, kkt_tol: f64) -> Self {
        self.kkt_tol = kkt_tol;
        self
    }

    /// Changes Clarabel's iteration limit (per attempt; default 200).
    pub fn with_max_iterations(mut self, max_iter: u32) -> Self {
        self.settings.max_iter = max_iter;
        self
    }

    /// Solves `qp`; success means Clarabel reports Solved or AlmostSolved (at the tightest
    /// tolerance of `CLARABEL_TOLS` it reaches) and our KKT residuals are within tolerance
    /// (see the module docs).
    pub fn solve(&mut self, qp: &Qp) -> Result<ExactSolution, ExactError> {
        let form = ConicForm::new(qp)?;
        let mut iterations = 0;
        let mut attempt = None;
        for tol in CLARABEL_TOLS {
            self.settings.tol_gap_abs = tol;
            self.settings.tol_gap_rel = tol;
            self.settings.tol_feas = tol;
            let mut solver = DefaultSolver::new(
                &form.p,
                qp.q.as_slice(),
                &form.a,
                &form.b,
                &form.cones,
                self.settings.clone(),
            )
            .map_err(|e| ExactError::Rejected(e.to_string()))?;
            solver.solve();
            iterations += solver.solution.iterations;
            let status = ExactStatus::from(solver.solution.status);
            attempt = Some(solver);
            if status != ExactStatus::AlmostSolved && !status.is_failure() {
                break;
            }
        }
        let sol = &attempt.expect("CLARABEL_TOLS is not empty").solution;
        let status = ExactStatus::from(sol.status);
        match status {
            ExactStatus::Solved | ExactStatus::AlmostSolved => {}
            ExactStatus::PrimalInfeasible | ExactStatus::AlmostPrimalInfeasible => {
                return Err(ExactError::PrimalInfeasible(status))
            }
            ExactStatus::DualInfeasible | ExactStatus::AlmostDualInfeasible => {
                return Err(ExactError::DualInfeasible(status))
            }
            ExactStatus::Unsolved
            | ExactStatus::MaxIterations
            | ExactStatus::MaxTime
            | ExactStatus::NumericalError
            | ExactStatus::InsufficientProgress
            | ExactStatus::CallbackTerminated => {
                return Err(ExactError::Failed { status, iterations })
            }
        }
        let x = DVector::from_column_slice(&sol.x);
        let duals = form.duals(qp, &sol.z);
        let kkt = qp.kkt_residuals(&x, &duals);
        let tolerance = self.kkt_tol * (1.0 + qp.q.amax().max(qp.b.amax()));
        if kkt.max().is_nan() || kkt.max() > tolerance {
            return Err(ExactError::Inaccurate {
                status,
                kkt,
                tolerance,
            });
        }
        Ok(ExactSolution {
            objective: qp.objective(&x),
            x,
            duals,
            iterations,
            status,
            kkt,
        })
    }
}

/// Row counts of the conic form [`ExactSolver::solve`] hands to Clarabel for `qp`.
pub fn cone_sizes(qp: &Qp) -> Result<ConeSizes, ExactError> {
    let form = ConicForm::new(qp)?;
    Ok(ConeSizes {
        zero: form.n_eq,
        nonnegative: form.b.len() - form.n_eq,
    })
}

/// Solves an equality-only QP (no inequality rows, every bound infinite) through its KKT system
/// `[[P, A'], [A, 0]] [x; lambda] = [-q; b]` by LU with partial pivoting, and returns x.
///
/// On nalgebra at every size: the matrix's zero blocks (and P's, identity or diagonal in the
/// papers' schemes) are skipped by the in-place elimination, and faer's dense LU was slower at
/// every measured size up to nx + n_eq = 203 (`kkt-floor` of `results/dof-cost.csv`;
/// `dense_lu`).
///
/// Independent of Clarabel, as a check. `None` when the QP has inequalities or finite bounds,
/// or when the KKT matrix is singular (P not positive definite on the null space of A, or A
/// rank deficient).
pub fn solve_equality_kkt(qp: &Qp) -> Option<DVector<f64>> {
    solve_equality_kkt_with(qp, Backend::Nalgebra)
}

/// [`solve_equality_kkt`] on a given backend (assembly, factorisation and solve allocate).
pub fn solve_equality_kkt_with(qp: &Qp, backend: Backend) -> Option<DVector<f64>> {
    let nx = qp.q.len();
    let n_eq = qp.b.len();
    let has_bounds =
        qp.lower.iter().any(|l| l.is_finite()) || qp.upper.iter().any(|u| u.is_finite());
    if !qp.h.is_empty() || has_bounds {
        return None;
    }
    let mut kkt = DMatrix::zeros(nx + n_eq, nx + n_eq);
    kkt.view_mut((0, 0), (nx, nx)).copy_from(&qp.p);
    kkt.view_mut((0, nx), (nx, n_eq)).tr_copy_from(&qp.a);
    kkt.view_mut((nx, 0), (n_eq, nx)).copy_from(&qp.a);
    let mut rhs = DVector::zeros(nx + n_eq);
    rhs.rows_mut(0, nx).copy_from(&(-&qp.q));
    rhs.rows_mut(nx, n_eq).copy_from(&qp.b);
    let mut lu = DenseLu::new(nx + n_eq, backend);
    if !lu.factor(&kkt) {
        return None;
    }
    lu.solve(rhs.as_mut_slice());
    Some(rhs.rows(0, nx).into_owned())
}

/// The QP stacked into Clarabel's form (see the module docs for the row order).
struct ConicForm {
    /// Upper triangle of P.
    p: CscMatrix<f64>,
    a: CscMatrix<f64>,
    b: Vec<f64>,
    cones: Vec<SupportedConeT<f64>>,
    n_eq: usize,
    /// Indices of the inequality rows with finite h, in row order.
    ineq_rows: Vec<usize>,
    /// Variables with a finite upper bound, in row order.
    upper_rows: Vec<usize>,
    /// Variables with a finite lower bound, in row order.
    lower_rows: Vec<usize>,
}

impl ConicForm {
    fn new(qp: &Qp) -> Result<Self, ExactError> {
        validate(qp)?;
        let nx = qp.q.len();
        let n_eq = qp.b.len();
        let ineq_rows: Vec<usize> = (0..qp.h.len())
            .filter(|&i| qp.h[i] < f64::INFINITY)
            .collect();
        let upper_rows: Vec<usize> = (0..nx).filter(|&i| qp.upper[i] < f64::INFINITY).collect();
        let lower_rows: Vec<usize> = (0..nx)
            .filter(|&i| qp.lower[i] > f64::NEG_INFINITY)
            .collect();

        // Constraint matrix, stacked densely (the papers' QPs are tiny), then compressed.
        let m = n_eq + ineq_rows.len() + upper_rows.len() + lower_rows.len();
        let mut dense = DMatrix::zeros(m, nx);
        let mut b = Vec::with_capacity(m);
        dense.rows_mut(0, n_eq).copy_from(&qp.a);
        b.extend(qp.b.iter());
        let mut row = n_eq;
        for &i in &ineq_rows {
            dense.row_mut(row).copy_from(&qp.g.row(i));
            b.push(qp.h[i]);
            row += 1;
        }
        for &i in &upper_rows {
            dense[(row, i)] = 1.0;
            b.push(qp.upper[i]);
            row += 1;
        }
        for &i in &lower_rows {
            dense[(row, i)] = -1.0;
            b.push(-qp.lower[i]);
            row += 1;
        }

        let mut cones = Vec::with_capacity(2);
        if n_eq > 0 {
            cones.push(SupportedConeT::ZeroConeT(n_eq));
        }
        if m > n_eq {
            cones.push(SupportedConeT::NonnegativeConeT(m - n_eq));
        }
        Ok(Self {
            p: to_csc(&qp.p, true),
            a: to_csc(&dense, false),
            b,
            cones,
            n_eq,
            ineq_rows,
            upper_rows,
            lower_rows,
        })
    }

    /// Maps Clarabel's dual vector z (one entry per row) to the multipliers of `qp`.
    fn duals(&self, qp: &Qp, z: &[f64]) -> QpDuals {
        let nx = qp.q.len();
        let mut d = QpDuals {
            lambda: DVector::from_column_slice(&z[..self.n_eq]),
            mu: DVector::zeros(qp.h.len()),
            z_lower: DVector::zeros(nx),
            z_upper: DVector::zeros(nx),
        };
        let mut rows = z[self.n_eq..].iter();
        for (&i, &zi) in self.ineq_rows.iter().zip(rows.by_ref()) {
            d.mu[i] = zi;
        }
        for (&i, &zi) in self.upper_rows.iter().zip(rows.by_ref()) {
            d.z_upper[i] = zi;
        }
        for (&i, &zi) in self.lower_rows.iter().zip(rows) {
            d.z_lower[i] = zi;
        }
        d
    }
}

/// Rejects malformed data (see [`ExactError::InvalidData`] and [`Qp::validate`]).
fn validate(qp: &Qp) -> Result<(), ExactError> {
    qp.validate().map_err(ExactError::InvalidData)
}

/// Compressed sparse column copy of `m` without its exact zeros; with `upper_only`, only the
/// entries on or above the diagonal.
fn to_csc(m: &DMatrix<f64>, upper_only: bool) -> CscMatrix<f64> {
    let (rows, cols) = m.shape();
    let mut colptr = Vec::with_capacity(cols + 1);
    let mut rowval = Vec::new();
    let mut nzval = Vec::new();
    colptr.push(0);
    for j in 0..cols {
        let last = if upper_only { (j + 1).min(rows) } else { rows };
        for i in 0..last {
            if m[(i, j)] != 0.0 {
                rowval.push(i);
                nzval.push(m[(i, j)]);
            }
        }
        colptr.push(rowval.len());
    }
    CscMatrix::new(rows, cols, colptr, rowval, nzval)
}
