//! A hand-written dense active-set solver for the small strictly convex QPs of [`qp`],
//! hot-started from the previous instant's working set and certified by its KKT residuals.
//!
//! # Why hand-written
//!
//! No permissively licensed, maintained Rust crate does dense active-set QP: the `quadprog`
//! crate (Goldfarb–Idnani) is GPL-2.0, and DAQP, qpOASES and ProxQP have no Rust crates. The
//! papers' QPs have at most ~10 variables and ~30 rows, so a dense method that updates the
//! factors of a small KKT matrix by a row at every working-set change is both simple and fast,
//! and its answers are checked here (see *Certification*) and against Clarabel in the tests.
//!
//! # Problem and constraint numbering
//!
//! The QP is that of [`qp`]: minimise x'Px/2 + q'x subject to A x = b, G x <= h,
//! l <= x <= u. Every inequality is written as c_k'x <= d_k and numbered (this is the order
//! used for every tie break):
//!
//! ```text
//! k in [0, m_in)              Constraint::Inequality(i)   c_k = G_i,   d_k =  h_i
//! k in [m_in, m_in + n)       Constraint::Upper(i)        c_k =  e_i,  d_k =  u_i
//! k in [m_in + n, m_in + 2n)  Constraint::Lower(i)        c_k = -e_i,  d_k = -l_i
//! ```
//!
//! Rows with an infinite right-hand side (h_i = +inf, u_i = +inf, l_i = -inf) are absent: they
//! are never violated, never enter a working set and get a zero multiplier.
//!
//! # The KKT system of a working set
//!
//! For a working set W (inequality rows held as equalities) with matrix C = [A; C_W] and
//! right-hand side d = [b; d_W], the minimiser of the objective on {C x = d} and its
//! multipliers solve
//!
//! ```text
//! [ P  C' ] [ x ]   [ -q ]
//! [ C  0  ] [ y ] = [  d ]
//! ```
//!
//! which is nonsingular when C has full row rank and P is positive definite on the null space
//! of C.
//!
//! # Factorisation
//!
//! When P is positive definite (every scheme's QP but MVN's, which [`crate::auxiliary`]
//! reduces to one) the system is solved through the Schur complement C P^-1 C'
//! ([`crate::kkt_schur`]): with P = L L', each row c_r of C has its row y_r = L^-1 c_r, and
//! S = C P^-1 C' = Y Y' its Cholesky factor M, computed row by row. Of that, per solve:
//!
//! - L depends on P alone and is kept while P is unchanged (bit for bit) from one solve to the
//!   next, as along a run; a diagonal P (jia2019's, zhong2021's, kong2019's) makes L diagonal
//!   and its triangular solves n multiplications. u_q = L^-1 (-q), the rows of Y for A and
//!   their rows of M are computed once per solve;
//! - a row joining W costs its y_k (n^2/2, or n for a diagonal P) and one new row of M
//!   (m n + m^2/2); a row leaving W at position s keeps the rows of M before s and recomputes
//!   those after it;
//! - a solve from u_q costs 2 m n + m^2 multiply-adds and a triangular solve with L' (n^2/2,
//!   or n multiplications for a diagonal P).
//!
//! If P is not positive definite, or C not of full row rank (a pivot of M vanishes), the whole
//! matrix (order n + m_eq + |W| <= 2n) is assembled in a buffer sized at construction and
//! factorised by an in-place LU with partial pivoting (our own few lines: nalgebra's `LU` takes
//! an owned matrix of exactly the system's order and allocates its permutation at every
//! factorisation), and each of its solves is followed by one step of iterative refinement.
//! "A KKT factorisation" ([`ActiveSetSolution::kkt_solves`]) below is the factorisation of one
//! working set, whether by a row update or by LU.
//!
//! # Accuracy
//!
//! The Schur complement is formed explicitly, so its rounding errors grow with
//! cond(S) = cond(Y)^2, and x = L^-T (u_q - Y'y) is the difference of two larger vectors: on the
//! jia2019 QPs along a run (cond(S) up to ~300) the solve alone is accurate to ~1e-14. One
//! step of iterative refinement against the unfactorised matrix (the residual
//! [-q; d] - [P C'; C 0] z from P and the rows of C, corrected with the same factors) brings
//! the answer within ~4e-16 of the exact solution (measured against rational arithmetic).
//!
//! The answer is always W's KKT system solved from u_q and refined once, with the operations
//! of revision 7c49228 (which refactorised and refined at every working-set change) in the same
//! order, so the answers are that revision's bit for bit: the exact column's runs integrate
//! them with adaptive steps, which turn a last-bit change of the answer into a different step
//! sequence and drifts that differ at the integration tolerance. The warm start's first solve,
//! usually the answer, is refined at once (so the feasibility check's G x serves the
//! certification); after primal iterations the final solve is refined; after dual steps, which
//! move (x, y) along their directions instead of solving again, the final working set's system
//! is solved and refined. The dual directions and the intermediate iterates only steer the
//! iterations, whose tolerances are 1e-12 (below), and are neither refined nor solved afresh.
//!
//! # Primal iterations (from a feasible point)
//!
//! Given a feasible x that lies on the rows of W, let x* be the KKT solution for W and
//! p = x* - x. If p != 0, the step length is the blocking ratio
//!
//! ```text
//! alpha = min(1, min over k not in W with c_k'p > 0 of (d_k - c_k'x) / c_k'p),
//! ```
//!
//! x <- x + alpha p, and the blocking row (smallest k on ties) joins W. If p = 0, x minimises
//! the objective on W; if every inequality multiplier y_k of W is >= 0 the KKT conditions hold
//! and x is optimal, otherwise the row with the most negative multiplier (smallest k on ties)
//! leaves W: moving off it decreases the objective while keeping the other rows.
//!
//! # Dual iterations (Goldfarb–Idnani; the cold start)
//!
//! A primal method needs a feasible point, which a general QP does not provide (a phase 1
//! would be a linear program, i.e. a second solver). The cold start is therefore the dual
//! active-set method of Goldfarb and Idnani (1983), which starts from the minimiser subject to
//! the equalities only (W empty), keeps every iterate a minimiser on its working set with
//! multipliers >= 0 (dual feasible), and works towards primal feasibility:
//!
//! 1. pick the most violated row p (largest c_p'x - d_p, smallest k on ties); none: optimal;
//! 2. raise p's multiplier t from 0 along the directions (dx, dy) that keep stationarity and
//!    the rows of W: `[P C'; C 0] [dx; dy] = [-c_p; 0]`, so x(t) = x + t dx, y(t) = y + t dy
//!    (with the Schur complement, L^-1 (-c_p) = -y_p is p's row of Y, computed once for the
//!    direction and for p's joining W);
//! 3. full step t2 = (c_p'x - d_p) / (-c_p'dx) makes p active (c_p'dx = -dx'P dx < 0): x and y
//!    move by t2 (dx, dy) and p joins W with multiplier t + t2; partial step
//!    t1 = min over inequality rows j of W with dy_j < 0 of y_j / (-dy_j) (smallest k on ties)
//!    drives y_j to zero: x and y move by t1 (dx, dy), j leaves W and step 2 is repeated for
//!    the same p with the reached t;
//! 4. if dx = 0 (c_p is a combination of the rows of W) and no dy_j < 0, t can grow without
//!    bound: the dual is unbounded, i.e. the QP is **infeasible**
//!    ([`ActiveSetError::Infeasible`]).
//!
//! The dual objective strictly increases at every full step, so no working set repeats.
//!
//! # Hot start
//!
//! [`ActiveSetSolver::solve`] with a warm working set (the previous instant's) first solves the
//! KKT system of that set once. If its x is primal feasible and its inequality multipliers are
//! nonnegative the KKT conditions hold and the answer costs exactly one KKT solve (the usual case
//! along a trajectory). If x is feasible but some multiplier is negative, primal iterations
//! continue from x. If x is infeasible, the rows with negative multipliers are dropped (and
//! the system re-solved) until the multipliers are nonnegative, and dual iterations continue from
//! there. A warm set that is inconsistent (index out of range, infinite right-hand side,
//! duplicate row, more rows than variables, singular KKT matrix), or a warm path that fails,
//! falls back to the cold start.
//!
//! # Why a KKT point is the optimum
//!
//! For a convex QP (P positive semidefinite) the KKT conditions are sufficient. Let x be
//! feasible with P x + q + A'lambda + G'mu + z_u - z_l = 0, mu, z_l, z_u nonnegative and
//! complementary. For every feasible x', by convexity, A x' = A x = b and complementarity
//! (mu'(h - Gx) = 0 and so on):
//!
//! ```text
//! f(x') - f(x) >= (P x + q)'(x' - x)
//!               = -lambda'A(x' - x) - mu'G(x' - x) - z_u'(x' - x) + z_l'(x' - x)
//!               = mu'(h - G x') + z_u'(u - x') + z_l'(x' - l)  >=  0.
//! ```
//!
//! With P positive definite on the null space of the active rows the minimiser is unique.
//!
//! # Certification
//!
//! Every answer (x and the multipliers, in the sign convention of [`qp`]:
//! P x + q + A'lambda + G'mu + z_u - z_l = 0) has its KKT residuals, as [`Qp::kkt_residuals`]
//! defines them, computed by the solver: stationarity, primal feasibility, dual feasibility and
//! complementarity must all be at most `tol * (1 + max(|q|_inf, |b|_inf))`, the scale of
//! [`crate::exact`], with `tol` = [`DEFAULT_CERT_TOL`] = 1e-10 unless changed. The solver sums
//! them in one pass with what it has: G x from the last feasibility check when it was made at
//! the answer, the rows of C (A's and W's) for A x - b and for A'lambda + G'mu + z_u - z_l (the
//! multipliers are zero outside W), so they equal [`Qp::kkt_residuals`] to rounding. A
//! warm-started answer that fails is retried cold; a cold answer that fails is an error
//! ([`ActiveSetError::NotCertified`]), on which the caller should fall back to Clarabel
//! ([`crate::ExactSolver`]).
//!
//! # Validation
//!
//! Malformed data is refused with [`ActiveSetError::InvalidData`] and the error of
//! [`Qp::validate`]. The sizes are checked before anything else. The entries are checked by
//! [`Qp::validate`] before the iterations when certification is off; when it is on, the
//! certificate checks them itself: P when it changes (L is kept while it does not), and every
//! entry of q, A, b, G, h and the bounds enters a residual (P x + q + A'lambda + ...,
//! A x - b, G x, G x - h, l - x, x - u) that is NaN or +inf when the entry is NaN or infinite
//! (on the wrong side, for h and the bounds): a certificate with such a residual, or any error
//! of the iterations, runs [`Qp::validate`] before it is returned.
//!
//! # Tolerances inside the iterations
//!
//! With s = 1 + max(|q|_inf, |b|_inf): a row is violated when c_k'x - d_k > 1e-12 s; a
//! multiplier is negative when y_k < -1e-12 s; a primal step is zero when
//! |p|_inf <= 1e-12 (1 + |x|_inf); a row blocks only when c_k'p > 1e-12 |c_k|_1 |p|_inf; dx is
//! zero when dx'P dx <= 1e-20 |c_p|^2 / max|P_ij|; an LU pivot below 1e-13 max|K_ij| means a
//! singular KKT matrix.
//!
//! # Allocation
//!
//! Every buffer is sized at construction for the largest [`QpDims`] given (and grown, once,
//! if a larger QP comes). [`ActiveSetSolver::solve_into`] writes into a caller-owned
//! [`ActiveSetSolution`] and allocates nothing, certification included (checked by a test);
//! [`ActiveSetSolver::solve`] allocates the returned solution.

use crate::kkt_schur::{dot, SchurKkt};
use nalgebra::DVector;
use qp::QpError;
use qp::{KktResiduals, Qp, QpDims, QpDuals};
use std::fmt;

/// Default relative tolerance of the certification (see the module docs).
pub const DEFAULT_CERT_TOL: f64 = 1e-10;
/// Default cap on working-set changes per solve (adds plus drops, over all phases).
pub const DEFAULT_MAX_ITERATIONS: u32 = 500;

const FEAS_TOL: f64 = 1e-12;
const DUAL_TOL: f64 = 1e-12;
const STEP_TOL: f64 = 1e-12;
const BLOCK_TOL: f64 = 1e-12;
const DX_TOL: f64 = 1e-20;
const PIVOT_TOL: f64 = 1e-13;

/// One inequality row of a QP (see the module docs for the numbering).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Constraint {
    /// Row i of G x <= h.
    Inequality(usize),
    /// The upper bound x_i <= u_i.
    Upper(usize),
    /// The lower bound x_i >= l_i.
    Lower(usize),
}

impl Constraint {
    /// The row's number k (module docs) in a QP with `nx` variables and `n_in` rows of G.
    fn id(self, nx: usize, n_in: usize) -> usize {
        match self {
            Self::Inequality(i) => i,
            Self::Upper(i) => n_in + i,
            Self::Lower(i) => n_in + nx + i,
        }
    }

    fn from_id(k: usize, nx: usize, n_in: usize) -> Self {
        if k < n_in {
            Self::Inequality(k)
        } else if k < n_in + nx {
            Self::Upper(k - n_in)
        } else {
            Self::Lower(k - n_in - nx)
        }
    }
}

/// A set of inequality rows held as equalities (the equality rows are always included and not
/// listed). The solver returns it sorted (Inequality rows, then Upper, then Lower bounds, each by
/// index); as a warm start any order is accepted.
#[derive(Debug, Default, PartialEq, Eq, Hash)]
pub struct WorkingSet {
    constraints: Vec<Constraint>,
}

impl Clone for WorkingSet {
    fn clone(&self) -> Self {
        Self {
            constraints: self.constraints.clone(),
        }
    }

    /// Reuses `self`'s buffer (no allocation when it is large enough), unlike the derived impl.
    fn clone_from(&mut self, source: &Self) {
        self.constraints.clone_from(&source.constraints);
    }
}

impl WorkingSet {
    /// The empty set (only the equalities active).
    pub fn new() -> Self {
        Self::default()
    }

    /// The empty set with room for `capacity` rows.
    pub fn with_capacity(capacity: usize) -> Self {
        Self {
            constraints: Vec::with_capacity(capacity),
        }
    }

    /// The number of inequality rows in the set.
    pub fn len(&self) -> usize {
        self.constraints.len()
    }

    /// Whether no inequality row is held (only the equalities are active).
    pub fn is_empty(&self) -> bool {
        self.constraints.is_empty()
    }

    /// Whether row `c` is in the set.
    pub fn contains(&self, c: Constraint) -> bool {
        self.constraints.contains(&c)
    }

    /// Adds row `c` at the end (no check for duplicates).
    pub fn push(&mut self, c: Constraint) {
        self.constraints.push(c);
    }

    /// Empties the set, keeping its buffer.
    pub fn clear(&mut self) {
        self.constraints.clear();
    }

    /// The rows, in the set's order.
    pub fn as_slice(&self) -> &[Constraint] {
        &self.constraints
    }

    /// The rows, in the set's order.
    pub fn iter(&self) -> impl Iterator<Item = Constraint> + '_ {
        self.constraints.iter().copied()
    }
}

impl FromIterator<Constraint> for WorkingSet {
    fn from_iter<I: IntoIterator<Item = Constraint>>(iter: I) -> Self {
        Self {
            constraints: iter.into_iter().collect(),
        }
    }
}

/// How a solve started (and hence how much it cost).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ActiveSetStart {
    /// The warm working set was optimal: one KKT solve.
    Warm,
    /// The warm set's point was feasible; primal iterations followed.
    WarmPrimal,
    /// The warm set's point was infeasible; dual iterations followed.
    WarmDual,
    /// No (usable) warm set: dual iterations from the equality-constrained minimiser.
    Cold,
}

/// A certified solution of [`ActiveSetSolver`].
#[derive(Clone, Debug, PartialEq)]
pub struct ActiveSetSolution {
    /// The primal solution x.
    pub x: DVector<f64>,
    /// Multipliers in the convention of [`qp`] (zero outside the working set).
    pub duals: QpDuals,
    /// x'Px/2 + q'x at `x`.
    pub objective: f64,
    /// The optimal working set, sorted; pass it as the next instant's warm start.
    pub working_set: WorkingSet,
    /// Working-set changes (rows added plus rows dropped), over all phases.
    pub iterations: u32,
    /// KKT factorisations, one per working set (1 for a successful warm start from the
    /// optimal set; module docs, *Factorisation*).
    pub kkt_solves: u32,
    /// Which path found the answer.
    pub start: ActiveSetStart,
    /// [`Qp::kkt_residuals`] of (x, duals); `None` when certification is disabled.
    pub kkt: Option<KktResiduals>,
    /// Whether the answer was certified (always true unless certification is disabled).
    pub certified: bool,
}

impl ActiveSetSolution {
    /// An all-zero solution of the given sizes, to be filled by [`ActiveSetSolver::solve_into`].
    pub fn zeros(dims: QpDims) -> Self {
        let nx = dims.nx;
        Self {
            x: DVector::zeros(nx),
            duals: QpDuals::zeros(dims),
            objective: 0.0,
            working_set: WorkingSet::with_capacity(nx),
            iterations: 0,
            kkt_solves: 0,
            start: ActiveSetStart::Cold,
            kkt: None,
            certified: false,
        }
    }
}

/// Why the active-set solver gave no answer (the caller should fall back to Clarabel).
#[derive(Clone, Debug, PartialEq)]
pub enum ActiveSetError {
    /// Inconsistent sizes, a NaN or infinite entry in P, q, A, b or G, or an infinite bound on
    /// the wrong side.
    InvalidData(QpError),
    /// The dual iterations proved the constraints inconsistent (module docs, step 4).
    Infeasible,
    /// A KKT matrix was singular: A rank deficient, or P not positive definite on the null
    /// space of the active rows.
    Singular,
    /// More than the allowed working-set changes.
    IterationLimit {
        /// The working-set changes made when it stopped (the limit plus one).
        iterations: u32,
    },
    /// The answer's KKT residuals exceed the tolerance.
    NotCertified {
        /// The answer's KKT residuals.
        kkt: KktResiduals,
        /// The absolute tolerance they were held to: the relative certification tolerance
        /// times 1 + max(|q|_inf, |b|_inf).
        tolerance: f64,
    },
}

impl fmt::Display for ActiveSetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidData(msg) => write!(f, "invalid QP data: {msg}"),
            Self::Infeasible => write!(f, "QP is infeasible (dual iterations unbounded)"),
            Self::Singular => write!(f, "singular KKT matrix"),
            Self::IterationLimit { iterations } => {
                write!(f, "active-set iteration limit reached ({iterations})")
            }
            Self::NotCertified { kkt, tolerance } => write!(
                f,
                "answer not certified: KKT residuals (primal {:.3e}, dual {:.3e}, \
                 complementarity {:.3e}) exceed {tolerance:.3e}",
                kkt.primal, kkt.dual, kkt.complementarity
            ),
        }
    }
}

impl std::error::Error for ActiveSetError {}

/// Dense active-set QP solver with hot start and KKT certification (see the module docs).
#[derive(Clone, Debug)]
pub struct ActiveSetSolver {
    max_iterations: u32,
    cert_tol: f64,
    certify: bool,
    /// Dims the buffers are sized for.
    cap: QpDims,
    /// The P of the last solve (as the QP stores it, column-major) and its order, while
    /// `p_known`: an unchanged P keeps its factorisation (module docs, *Factorisation*).
    p_seen: Vec<f64>,
    p_n: usize,
    p_known: bool,
    /// That P row-major (p_row[i n + j] = P_ij), whether it is positive definite (its
    /// Cholesky factor is then in `schur`), and max |P_ij| (1 if P = 0).
    p_row: Vec<f64>,
    p_pd: bool,
    pmax: f64,
    /// The Schur-complement factors (`kkt_schur`), and whether they factorise the
    /// current working set's KKT matrix (else `lu` does).
    schur: SchurKkt,
    schur_ok: bool,
    /// u_q = L^-1 (-q) of the current QP.
    uq: Vec<f64>,
    /// C = [A; C_W], row-major (n_eq + |W|) x n, then the staged row of a dual step, and the
    /// row number staged there (if W has not changed since).
    c: Vec<f64>,
    staged: Option<usize>,
    /// KKT matrix (row-major, order k, packed), overwritten by its LU factors.
    lu: Vec<f64>,
    /// The unfactorised KKT matrix, for the LU solves' iterative refinement.
    kkt: Vec<f64>,
    piv: Vec<usize>,
    /// Right-hand side, solution and scratch of the main system.
    rhs: Vec<f64>,
    z: Vec<f64>,
    /// Direction (dual step) solution.
    dz: Vec<f64>,
    res: Vec<f64>,
    /// Scratch of length n.
    u: Vec<f64>,
    /// The iterate of the primal iterations, and the answer.
    x: Vec<f64>,
    /// G x at z's x part, valid while `gx_valid` (reset by every change of z).
    gx: Vec<f64>,
    gx_valid: bool,
    /// How `z` was obtained (module docs, *Accuracy*).
    z_state: ZState,
    /// P x (at the answer, or scratch).
    px: Vec<f64>,
    /// Working set (row numbers), in KKT order, and membership flags.
    w: Vec<usize>,
    in_w: Vec<bool>,
    // Per-solve state.
    iterations: u32,
    kkt_solves: u32,
    /// Order of the current KKT system.
    k: usize,
}

/// How the solver's `z` was obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ZState {
    /// Solved for the current working set (and `rhs` holds its right-hand side).
    Solved,
    /// Solved and refined.
    Refined,
    /// Moved by dual steps since it was last solved.
    Stepped,
}

/// Problem-wide constants of one solve.
#[derive(Clone, Copy)]
struct Ctx {
    nx: usize,
    n_eq: usize,
    n_in: usize,
    /// 1 + max(|q|_inf, |b|_inf).
    scale: f64,
    /// max |P_ij| (1 if P = 0).
    pmax: f64,
}

impl ActiveSetSolver {
    /// A solver with buffers for QPs up to `max_dims`, certification on at [`DEFAULT_CERT_TOL`],
    /// at most `DEFAULT_MAX_ITERATIONS` working-set changes.
    pub fn new(max_dims: QpDims) -> Self {
        let mut s = Self {
            max_iterations: DEFAULT_MAX_ITERATIONS,
            cert_tol: DEFAULT_CERT_TOL,
            certify: true,
            cap: QpDims {
                nx: 0,
                n_eq: 0,
                n_in: 0,
            },
            p_seen: Vec::new(),
            p_n: 0,
            p_known: false,
            p_row: Vec::new(),
            p_pd: false,
            pmax: 1.0,
            schur: SchurKkt::default(),
            schur_ok: false,
            uq: Vec::new(),
            c: Vec::new(),
            staged: None,
            lu: Vec::new(),
            kkt: Vec::new(),
            piv: Vec::new(),
            rhs: Vec::new(),
            z: Vec::new(),
            dz: Vec::new(),
            res: Vec::new(),
            u: Vec::new(),
            x: Vec::new(),
            gx: Vec::new(),
            gx_valid: false,
            z_state: ZState::Stepped,
            px: Vec::new(),
            w: Vec::new(),
            in_w: Vec::new(),
            iterations: 0,
            kkt_solves: 0,
            k: 0,
        };
        s.reserve(max_dims);
        s
    }

    /// Changes the cap on working-set changes per solve.
    pub fn with_max_iterations(mut self, max_iterations: u32) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// Changes the relative certification tolerance (see the module docs).
    pub fn with_certification_tolerance(mut self, tol: f64) -> Self {
        self.cert_tol = tol;
        self
    }

    /// Turns certification off (answers then have `certified == false`, `kkt == None`) or on.
    /// Off, the answers are unchecked.
    pub fn with_certification(mut self, certify: bool) -> Self {
        self.certify = certify;
        self
    }

    /// Grows the buffers to hold QPs up to `dims` (no-op if they already do).
    fn reserve(&mut self, dims: QpDims) {
        let cap = QpDims {
            nx: self.cap.nx.max(dims.nx),
            n_eq: self.cap.n_eq.max(dims.n_eq),
            n_in: self.cap.n_in.max(dims.n_in),
        };
        if cap == self.cap && !self.lu.is_empty() {
            return;
        }
        self.cap = cap;
        // Order of the KKT system: n + m_eq + |W| <= 2n (a larger system has dependent rows and
        // is refused before assembly).
        let n = cap.nx;
        let kmax = 2 * n;
        let m_total = cap.n_in + 2 * n;
        self.p_known = false;
        self.p_seen.resize(n * n, 0.0);
        self.p_row.resize(n * n, 0.0);
        self.lu.resize(kmax * kmax, 0.0);
        self.schur.reserve(n, n);
        self.uq.resize(n, 0.0);
        self.c.resize((n + 1) * n, 0.0);
        self.kkt.resize(kmax * kmax, 0.0);
        self.piv.resize(kmax, 0);
        self.rhs.resize(kmax, 0.0);
        self.z.resize(kmax, 0.0);
        self.dz.resize(kmax, 0.0);
        self.res.resize(kmax, 0.0);
        self.u.resize(n, 0.0);
        self.x.resize(n, 0.0);
        self.gx.resize(cap.n_in, 0.0);
        self.px.resize(n, 0.0);
        self.w.reserve(m_total.max(kmax));
        self.in_w.resize(m_total, false);
    }

    /// Solves `qp`, hot-started from `warm` if given (see the module docs); allocates the
    /// returned solution.
    pub fn solve(
        &mut self,
        qp: &Qp,
        warm: Option<&WorkingSet>,
    ) -> Result<ActiveSetSolution, ActiveSetError> {
        let mut out = ActiveSetSolution::zeros(qp.dims());
        self.solve_into(qp, warm, &mut out)?;
        Ok(out)
    }

    /// As [`Self::solve`], writing into `out` (resized if its sizes differ from the QP's). On
    /// error `out` holds unspecified values. To hot-start from `out` itself, copy its working
    /// set first (`prev.clone_from(&out.working_set)` does not allocate once `prev` is large
    /// enough).
    pub fn solve_into(
        &mut self,
        qp: &Qp,
        warm: Option<&WorkingSet>,
        out: &mut ActiveSetSolution,
    ) -> Result<(), ActiveSetError> {
        // Module docs, *Validation*: the sizes always first; the entries up front only when
        // no certification will read them.
        if !self.certify || !shapes_agree(qp) {
            validate(qp)?;
        }
        let solved = self.solve_valid_shapes(qp, warm, out);
        if solved.is_err() && self.certify {
            validate(qp)?;
        }
        solved
    }

    /// [`Self::solve_into`] for a QP whose sizes agree.
    fn solve_valid_shapes(
        &mut self,
        qp: &Qp,
        warm: Option<&WorkingSet>,
        out: &mut ActiveSetSolution,
    ) -> Result<(), ActiveSetError> {
        let dims = qp.dims();
        self.reserve(dims);
        self.begin(qp)?;
        let ctx = Ctx {
            nx: dims.nx,
            n_eq: dims.n_eq,
            n_in: dims.n_in,
            scale: 1.0 + amax(qp.q.as_slice()).max(amax(qp.b.as_slice())),
            pmax: self.pmax,
        };
        self.iterations = 0;
        self.kkt_solves = 0;
        if let Some(ws) = warm {
            if self.load_warm(qp, &ctx, ws) {
                if let Ok(start) = self.warm_path(qp, &ctx) {
                    if self.finish(qp, &ctx, start, out).is_ok() {
                        return Ok(());
                    }
                }
            }
        }
        self.clear_w(&ctx);
        self.factor_and_solve(qp, &ctx, false)?;
        self.dual_loop(qp, &ctx)?;
        self.finish(qp, &ctx, ActiveSetStart::Cold, out)
    }

    /// The work of a solve that does not depend on the working set: P's factorisation (kept
    /// from the previous solve when P is unchanged), u_q = L^-1 (-q), and C = A with the rows
    /// of Y for A (module docs, *Factorisation*). A P with a non-finite entry is refused.
    fn begin(&mut self, qp: &Qp) -> Result<(), ActiveSetError> {
        let (nx, n_eq) = (qp.q.len(), qp.b.len());
        let p = qp.p.as_slice();
        let seen = &self.p_seen[..nx * nx];
        let same = self.p_known
            && self.p_n == nx
            && p.iter()
                .zip(seen)
                .fold(0u64, |acc, (a, b)| acc | (a.to_bits() ^ b.to_bits()))
                == 0;
        if !same {
            self.p_known = false;
            if p.iter().any(|v| !v.is_finite()) {
                return Err(ActiveSetError::InvalidData(QpError::NonFinite {
                    field: "P",
                }));
            }
            self.p_seen[..nx * nx].copy_from_slice(p);
            self.p_n = nx;
            self.p_known = true;
            for i in 0..nx {
                for j in 0..nx {
                    self.p_row[i * nx + j] = qp.p[(i, j)];
                }
            }
            self.pmax = match amax(p) {
                m if m > 0.0 => m,
                _ => 1.0,
            };
            self.p_pd = self.schur.factor_p(nx, &self.p_row[..nx * nx]);
        }
        self.schur.truncate(0);
        // A is stored column-major: column j holds A_rj, r = 0..n_eq.
        for (j, col) in qp.a.as_slice().chunks_exact(n_eq.max(1)).enumerate() {
            for (r, &v) in col.iter().enumerate() {
                self.c[r * nx + j] = v;
            }
        }
        if self.p_pd {
            for (u, q) in self.uq[..nx].iter_mut().zip(qp.q.as_slice()) {
                *u = -q;
            }
            self.schur.forward(&mut self.uq[..nx]);
            for r in 0..n_eq {
                self.schur.stage(&self.c[r * nx..(r + 1) * nx]);
                self.schur.commit();
            }
        }
        Ok(())
    }

    /// Loads a warm set into `w`; false if it is inconsistent (module docs, *Hot start*).
    fn load_warm(&mut self, qp: &Qp, ctx: &Ctx, ws: &WorkingSet) -> bool {
        self.clear_w(ctx);
        if ctx.n_eq + ws.len() > ctx.nx {
            return false;
        }
        for c in ws.iter() {
            let in_range = match c {
                Constraint::Inequality(i) => i < ctx.n_in,
                Constraint::Upper(i) | Constraint::Lower(i) => i < ctx.nx,
            };
            if !in_range {
                return false;
            }
            let k = c.id(ctx.nx, ctx.n_in);
            if self.in_w[k] || !rhs(qp, ctx, k).is_finite() || self.add(qp, ctx, k).is_err() {
                return false;
            }
        }
        true
    }

    /// The warm path after the first KKT solve (module docs, *Hot start*).
    fn warm_path(&mut self, qp: &Qp, ctx: &Ctx) -> Result<ActiveSetStart, ActiveSetError> {
        self.factor_and_solve(qp, ctx, true)?;
        let feasible = self.most_violated(qp, ctx).is_none();
        let dual_ok = self.most_negative(ctx).is_none();
        if feasible {
            self.x[..ctx.nx].copy_from_slice(&self.z[..ctx.nx]);
            if dual_ok {
                return Ok(ActiveSetStart::Warm);
            }
            self.primal_loop(qp, ctx)?;
            return Ok(ActiveSetStart::WarmPrimal);
        }
        // Drop every row with a negative multiplier until the rest are >= 0.
        while self.most_negative(ctx).is_some() {
            let tol = DUAL_TOL * ctx.scale;
            let mut s = 0;
            while s < self.w.len() {
                if self.z[ctx.nx + ctx.n_eq + s] < -tol {
                    self.remove_at(ctx, s);
                    self.bump()?;
                    // The multipliers shift with the rows; keep z aligned with w.
                    let base = ctx.nx + ctx.n_eq + s;
                    self.z.copy_within(base + 1..self.k, base);
                    self.k -= 1;
                } else {
                    s += 1;
                }
            }
            self.factor_and_solve(qp, ctx, false)?;
        }
        self.dual_loop(qp, ctx)?;
        Ok(ActiveSetStart::WarmDual)
    }

    /// Primal iterations (module docs). Precondition: `x` feasible, on the rows of W, and `z`
    /// solves the KKT system of W.
    fn primal_loop(&mut self, qp: &Qp, ctx: &Ctx) -> Result<(), ActiveSetError> {
        let nx = ctx.nx;
        loop {
            // p = x* - x
            let mut p_norm: f64 = 0.0;
            let mut x_norm: f64 = 0.0;
            for j in 0..nx {
                p_norm = p_norm.max((self.z[j] - self.x[j]).abs());
                x_norm = x_norm.max(self.x[j].abs());
            }
            let mut blocking = None;
            let mut alpha = 1.0;
            if p_norm > STEP_TOL * (1.0 + x_norm) {
                let m_total = ctx.n_in + 2 * nx;
                for k in 0..m_total {
                    if self.in_w[k] {
                        continue;
                    }
                    let d = rhs(qp, ctx, k);
                    if !d.is_finite() {
                        continue;
                    }
                    let (cp, c1) = row_dot_diff(qp, ctx, k, &self.z, &self.x);
                    if cp <= BLOCK_TOL * c1 * p_norm {
                        continue;
                    }
                    let slack = (d - row_dot(qp, ctx, k, &self.x)).max(0.0);
                    let ratio = slack / cp;
                    // Strict: the smallest k wins ties (k increases).
                    if ratio < alpha {
                        alpha = ratio;
                        blocking = Some(k);
                    }
                }
            }
            match blocking {
                Some(k) => {
                    for j in 0..nx {
                        self.x[j] += alpha * (self.z[j] - self.x[j]);
                    }
                    self.add(qp, ctx, k)?;
                    self.bump()?;
                    self.factor_and_solve(qp, ctx, false)?;
                }
                None => {
                    // x = x*, the minimiser on W: multiplier test.
                    self.x[..nx].copy_from_slice(&self.z[..nx]);
                    match self.most_negative(ctx) {
                        None => return Ok(()),
                        Some(s) => {
                            self.remove_at(ctx, s);
                            self.bump()?;
                            self.factor_and_solve(qp, ctx, false)?;
                        }
                    }
                }
            }
        }
    }

    /// Dual (Goldfarb–Idnani) iterations (module docs). Precondition: `z` solves the KKT system
    /// of W (with t = 0) and W's inequality multipliers are >= 0 (up to the tolerance).
    fn dual_loop(&mut self, qp: &Qp, ctx: &Ctx) -> Result<(), ActiveSetError> {
        let nx = ctx.nx;
        let off = nx + ctx.n_eq;
        let mut entering: Option<usize> = None;
        // p's multiplier, raised along the direction since p was picked.
        let mut t = 0.0;
        loop {
            let p = match entering {
                Some(p) => p,
                None => match self.most_violated(qp, ctx) {
                    None => {
                        self.x[..nx].copy_from_slice(&self.z[..nx]);
                        return Ok(());
                    }
                    Some(p) => {
                        entering = Some(p);
                        t = 0.0;
                        p
                    }
                },
            };
            // Directions: [P C'; C 0][dx; dy] = [-c_p; 0]; c_p is C's staged row.
            self.solve_direction(qp, ctx, p);
            p_times(
                &self.p_row[..nx * nx],
                self.schur.is_diagonal(),
                &self.dz[..nx],
                &mut self.px[..nx],
            );
            let dxpdx: f64 = (0..nx).fold(0.0, |s, i| s + self.dz[i] * self.px[i]);
            let m = off - nx + self.w.len();
            let cp = &self.c[m * nx..(m + 1) * nx];
            let nd = dot(cp, &self.dz[..nx]);
            let n_sq = dot(cp, cp);
            // (NaN counts as zero.)
            let dx_zero =
                dxpdx.is_nan() || dxpdx <= DX_TOL * n_sq / ctx.pmax || nd.is_nan() || nd >= 0.0;
            // Partial (dual) step.
            let mut dy_norm: f64 = 0.0;
            for s in 0..self.w.len() {
                dy_norm = dy_norm.max(self.dz[off + s].abs());
            }
            let mut t1 = f64::INFINITY;
            let mut leaving: Option<(usize, usize)> = None; // (position, row number)
            for s in 0..self.w.len() {
                let dy = self.dz[off + s];
                if dy < -1e-13 * dy_norm {
                    let ratio = self.z[off + s].max(0.0) / -dy;
                    let k = self.w[s];
                    let better = match leaving {
                        None => true,
                        Some((_, kb)) => ratio < t1 || (ratio == t1 && k < kb),
                    };
                    if better {
                        t1 = ratio;
                        leaving = Some((s, k));
                    }
                }
            }
            let violation = dot(cp, &self.z[..nx]) - rhs(qp, ctx, p);
            let t2 = if dx_zero {
                f64::INFINITY
            } else {
                violation.max(0.0) / -nd
            };
            if dx_zero && leaving.is_none() {
                return Err(ActiveSetError::Infeasible);
            }
            if !dx_zero && (leaving.is_none() || t2 <= t1) {
                // Full step: p joins W with multiplier t.
                t += t2;
                self.step(t2);
                self.add(qp, ctx, p)?;
                self.z[self.k] = t;
                entering = None;
                self.bump()?;
                self.factor(ctx)?;
            } else {
                // Partial step: row s's multiplier reaches zero and it leaves W.
                let (s, _) = leaving.expect("checked above");
                t += t1;
                self.step(t1);
                self.remove_at(ctx, s);
                self.z.copy_within(off + s + 1..self.k, off + s);
                self.bump()?;
                self.factor(ctx)?;
            }
        }
    }

    /// Computes G x at z's x part into `gx` (G column by column; each entry is summed in the
    /// order of its row, as [`row_dot`] would).
    fn eval_gx(&mut self, qp: &Qp, ctx: &Ctx) {
        let n_in = ctx.n_in;
        let gx = &mut self.gx[..n_in];
        gx.fill(0.0);
        let g = qp.g.as_slice();
        for (col, &xj) in g.chunks_exact(n_in.max(1)).zip(&self.z[..ctx.nx]) {
            for (a, &gkj) in gx.iter_mut().zip(col) {
                *a += gkj * xj;
            }
        }
        self.gx_valid = true;
    }

    /// Most violated row not in W (largest c_k'x - d_k above the tolerance at x = z's x part,
    /// smallest k on ties).
    fn most_violated(&mut self, qp: &Qp, ctx: &Ctx) -> Option<usize> {
        if !self.gx_valid {
            self.eval_gx(qp, ctx);
        }
        let Ctx { nx, n_in, .. } = *ctx;
        let tol = FEAS_TOL * ctx.scale;
        let mut best: Option<(usize, f64)> = None;
        let mut consider = |k: usize, v: f64| {
            if v > tol && best.is_none_or(|(_, vb)| v > vb) {
                best = Some((k, v));
            }
        };
        for (k, (&gx, &h)) in self.gx[..n_in].iter().zip(qp.h.as_slice()).enumerate() {
            if !self.in_w[k] && h.is_finite() {
                consider(k, gx - h);
            }
        }
        let x = &self.z[..nx];
        for (i, (&xi, &u)) in x.iter().zip(qp.upper.as_slice()).enumerate() {
            if !self.in_w[n_in + i] && u.is_finite() {
                consider(n_in + i, xi - u);
            }
        }
        for (i, (&xi, &l)) in x.iter().zip(qp.lower.as_slice()).enumerate() {
            if !self.in_w[n_in + nx + i] && l.is_finite() {
                consider(n_in + nx + i, -xi - -l);
            }
        }
        best.map(|(k, _)| k)
    }

    /// Position in W of the most negative inequality multiplier below the tolerance (smallest
    /// row number on ties).
    fn most_negative(&self, ctx: &Ctx) -> Option<usize> {
        let tol = DUAL_TOL * ctx.scale;
        let off = ctx.nx + ctx.n_eq;
        let mut best: Option<(usize, f64)> = None;
        for s in 0..self.w.len() {
            let y = self.z[off + s];
            if y < -tol {
                let better = match best {
                    None => true,
                    Some((sb, yb)) => y < yb || (y == yb && self.w[s] < self.w[sb]),
                };
                if better {
                    best = Some((s, y));
                }
            }
        }
        best.map(|(s, _)| s)
    }

    fn bump(&mut self) -> Result<(), ActiveSetError> {
        self.iterations += 1;
        if self.iterations > self.max_iterations {
            return Err(ActiveSetError::IterationLimit {
                iterations: self.iterations,
            });
        }
        Ok(())
    }

    /// Empties W: C = A.
    fn clear_w(&mut self, ctx: &Ctx) {
        self.w.clear();
        self.staged = None;
        self.in_w[..ctx.n_in + 2 * ctx.nx].fill(false);
        self.schur.truncate(ctx.n_eq);
    }

    /// Writes c_k into C's staged row (after the rows of C) and, with the Schur complement,
    /// stages its row of Y.
    fn stage_row(&mut self, qp: &Qp, ctx: &Ctx, k: usize) {
        let nx = ctx.nx;
        let base = (ctx.n_eq + self.w.len()) * nx;
        let row = &mut self.c[base..base + nx];
        row.fill(0.0);
        fill_row(qp, ctx, k, |j, v| row[j] = v);
        if self.p_pd {
            self.schur.stage(&self.c[base..base + nx]);
        }
        self.staged = Some(k);
    }

    /// Appends row k to W and C (and Y); more rows than variables are dependent: singular.
    fn add(&mut self, qp: &Qp, ctx: &Ctx, k: usize) -> Result<(), ActiveSetError> {
        if ctx.n_eq + self.w.len() >= ctx.nx {
            return Err(ActiveSetError::Singular);
        }
        if self.staged != Some(k) {
            self.stage_row(qp, ctx, k);
        }
        if self.p_pd {
            self.schur.commit();
        }
        self.staged = None;
        self.w.push(k);
        self.in_w[k] = true;
        Ok(())
    }

    /// Removes the row at position s of W from W and C (and Y).
    fn remove_at(&mut self, ctx: &Ctx, s: usize) {
        let k = self.w.remove(s);
        self.in_w[k] = false;
        self.staged = None;
        let (nx, r) = (ctx.nx, ctx.n_eq + s);
        let m = ctx.n_eq + self.w.len() + 1;
        self.c.copy_within((r + 1) * nx..m * nx, r * nx);
        if self.p_pd {
            self.schur.remove(r);
        }
    }

    /// Brings the factorisation of W's KKT matrix up to date (one KKT factorisation): the
    /// Schur complement's rows of M that changed, or, if P is not positive definite or C not
    /// of full row rank, an LU factorisation of the whole matrix.
    fn factor(&mut self, ctx: &Ctx) -> Result<(), ActiveSetError> {
        let Ctx { nx, n_eq, .. } = *ctx;
        let m = n_eq + self.w.len();
        if m > nx {
            // More rows than variables: necessarily dependent (and beyond the buffers).
            return Err(ActiveSetError::Singular);
        }
        let k = nx + m;
        self.k = k;
        self.kkt_solves += 1;
        self.schur_ok = self.p_pd && self.schur.factor_rows();
        if !self.schur_ok {
            let kk = &mut self.kkt[..k * k];
            kk.fill(0.0);
            for i in 0..nx {
                kk[i * k..i * k + nx].copy_from_slice(&self.p_row[i * nx..(i + 1) * nx]);
            }
            for r in 0..m {
                for j in 0..nx {
                    let v = self.c[r * nx + j];
                    kk[(nx + r) * k + j] = v;
                    kk[j * k + nx + r] = v;
                }
            }
            self.lu[..k * k].copy_from_slice(&self.kkt[..k * k]);
            if !lu_factor(&mut self.lu[..k * k], k, &mut self.piv[..k]) {
                return Err(ActiveSetError::Singular);
            }
        }
        Ok(())
    }

    /// Factorises W's KKT matrix ([`Self::factor`]) and solves it ([`Self::solve_z`]).
    fn factor_and_solve(&mut self, qp: &Qp, ctx: &Ctx, refine: bool) -> Result<(), ActiveSetError> {
        self.factor(ctx)?;
        self.solve_z(qp, ctx, refine);
        Ok(())
    }

    /// Solves W's factorised KKT system for [-q; b; d_W] into `z`: through the Schur
    /// complement from u_q = L^-1 (-q), refined ([`Self::refine`]) if `refine`, else by the LU
    /// factors with one step of iterative refinement.
    fn solve_z(&mut self, qp: &Qp, ctx: &Ctx, refine: bool) {
        let nx = ctx.nx;
        let k = self.k;
        self.gx_valid = false;
        self.fill_rhs(qp, ctx);
        self.z[..k].copy_from_slice(&self.rhs[..k]);
        if self.schur_ok {
            let (x, y) = self.z[..k].split_at_mut(nx);
            self.schur.solve_u(&self.uq[..nx], x, y);
            self.z_state = ZState::Solved;
            if refine {
                self.refine(qp, nx);
            }
        } else {
            self.lu_refined(false);
            self.z_state = ZState::Refined;
        }
    }

    /// The right-hand side [-q; b; d_W] of W's KKT system into `rhs`.
    fn fill_rhs(&mut self, qp: &Qp, ctx: &Ctx) {
        let Ctx { nx, n_eq, .. } = *ctx;
        for (r, q) in self.rhs[..nx].iter_mut().zip(qp.q.as_slice()) {
            *r = -q;
        }
        self.rhs[nx..nx + n_eq].copy_from_slice(qp.b.as_slice());
        for (s, &row) in self.w.iter().enumerate() {
            self.rhs[nx + n_eq + s] = rhs(qp, ctx, row);
        }
    }

    /// Solves the factorised system for [-c_p; 0] into `dz` (c_p written to C's staged row).
    /// With the Schur complement u = L^-1 (-c_p) = -y_p is the staged row of Y, and the
    /// direction is not refined (it only steers the iterations; module docs).
    fn solve_direction(&mut self, qp: &Qp, ctx: &Ctx, p: usize) {
        let nx = ctx.nx;
        self.stage_row(qp, ctx, p);
        let k = self.k;
        if self.schur_ok {
            for (u, y) in self.u[..nx].iter_mut().zip(self.schur.staged()) {
                *u = -y;
            }
            self.dz[..k].fill(0.0);
            let (x, y) = self.dz[..k].split_at_mut(nx);
            self.schur.solve_u(&self.u[..nx], x, y);
        } else {
            self.rhs[..k].fill(0.0);
            fill_row(qp, ctx, p, |j, c| self.rhs[j] = -c);
            self.dz[..k].copy_from_slice(&self.rhs[..k]);
            self.lu_refined(true);
        }
    }

    /// One step of iterative refinement of `z` against W's unfactorised KKT matrix
    /// K = [P C'; C 0] with its Schur-complement factors: res = rhs - K z, z += K^-1 res
    /// (module docs, *Accuracy*; each residual summed as revision 7c49228 did). `rhs` must
    /// hold W's [-q; b; d_W] ([`Self::fill_rhs`]). (The LU solves refine themselves.)
    fn refine(&mut self, qp: &Qp, nx: usize) {
        let k = self.k;
        let m = k - nx;
        let c = &self.c[..m * nx];
        let (x, y) = self.z[..k].split_at(nx);
        let diagonal = self.schur.is_diagonal();
        for i in 0..nx {
            let mut s = self.rhs[i];
            if diagonal {
                s -= qp.p[(i, i)] * x[i];
            } else {
                for (p, xj) in self.p_row[i * nx..(i + 1) * nx].iter().zip(x) {
                    s -= p * xj;
                }
            }
            for r in 0..m {
                s -= c[r * nx + i] * y[r];
            }
            self.res[i] = s;
        }
        for (r, row) in c.chunks_exact(nx).enumerate() {
            let cx: f64 = row.iter().zip(x).map(|(a, b)| a * b).sum();
            self.res[nx + r] = self.rhs[nx + r] - cx;
        }
        self.schur.solve(&mut self.res[..k], &mut self.u);
        for (o, r) in self.z[..k].iter_mut().zip(&self.res[..k]) {
            *o += r;
        }
        self.z_state = ZState::Refined;
        self.gx_valid = false;
    }

    /// z += a dz (a step of the dual iterations along their direction).
    fn step(&mut self, a: f64) {
        let k = self.k;
        for (z, d) in self.z[..k].iter_mut().zip(&self.dz[..k]) {
            *z += a * d;
        }
        self.gx_valid = false;
        self.z_state = ZState::Stepped;
    }

    /// LU solve of `dz` (direction) or `z` in place, plus one step of iterative refinement
    /// against the unfactorised matrix (the right-hand side is in `rhs`).
    fn lu_refined(&mut self, direction: bool) {
        let k = self.k;
        let out = if direction {
            &mut self.dz[..k]
        } else {
            &mut self.z[..k]
        };
        lu_solve(&self.lu[..k * k], k, &self.piv[..k], out);
        for i in 0..k {
            let row = &self.kkt[i * k..(i + 1) * k];
            let mut s = self.rhs[i];
            for j in 0..k {
                s -= row[j] * out[j];
            }
            self.res[i] = s;
        }
        lu_solve(&self.lu[..k * k], k, &self.piv[..k], &mut self.res[..k]);
        for (o, r) in out.iter_mut().zip(&self.res[..k]) {
            *o += r;
        }
    }

    /// Certifies the answer in `z` (refining it first if its KKT system's residual calls for
    /// it; module docs, *Certification*) and writes it (x, multipliers, sorted W) into `out`.
    fn finish(
        &mut self,
        qp: &Qp,
        ctx: &Ctx,
        start: ActiveSetStart,
        out: &mut ActiveSetSolution,
    ) -> Result<(), ActiveSetError> {
        let Ctx { nx, n_eq, n_in, .. } = *ctx;
        // The answer: W's KKT system solved and refined (module docs, *Accuracy*).
        match self.z_state {
            ZState::Refined => {}
            ZState::Solved => self.refine(qp, nx),
            ZState::Stepped => self.solve_z(qp, ctx, true),
        }
        self.x[..nx].copy_from_slice(&self.z[..nx]);
        let certificate = if self.certify {
            let (kkt, finite) = self.certificate(qp, ctx);
            let tolerance = self.cert_tol * ctx.scale;
            if !finite || kkt.max() > tolerance {
                return Err(ActiveSetError::NotCertified { kkt, tolerance });
            }
            Some(kkt)
        } else {
            p_times(
                &self.p_row[..nx * nx],
                self.schur.is_diagonal(),
                &self.x[..nx],
                &mut self.px[..nx],
            );
            None
        };
        if out.x.len() != nx {
            out.x = DVector::zeros(nx);
        }
        if out.duals.lambda.len() != n_eq {
            out.duals.lambda = DVector::zeros(n_eq);
        }
        if out.duals.mu.len() != n_in {
            out.duals.mu = DVector::zeros(n_in);
        }
        if out.duals.z_lower.len() != nx {
            out.duals.z_lower = DVector::zeros(nx);
        }
        if out.duals.z_upper.len() != nx {
            out.duals.z_upper = DVector::zeros(nx);
        }
        out.x.as_mut_slice().copy_from_slice(&self.x[..nx]);
        out.duals
            .lambda
            .as_mut_slice()
            .copy_from_slice(&self.z[nx..nx + n_eq]);
        out.duals.mu.as_mut_slice().fill(0.0);
        out.duals.z_lower.as_mut_slice().fill(0.0);
        out.duals.z_upper.as_mut_slice().fill(0.0);
        out.working_set.clear();
        for (s, &k) in self.w.iter().enumerate() {
            let y = self.z[nx + n_eq + s];
            let c = Constraint::from_id(k, nx, n_in);
            match c {
                Constraint::Inequality(i) => out.duals.mu[i] = y,
                Constraint::Upper(i) => out.duals.z_upper[i] = y,
                Constraint::Lower(i) => out.duals.z_lower[i] = y,
            }
            out.working_set.push(c);
        }
        out.working_set.constraints.sort_unstable();
        // x'Px/2 + q'x with `px` = P x.
        let mut obj = 0.0;
        for ((x, px), q) in self.x[..nx].iter().zip(&self.px[..nx]).zip(qp.q.as_slice()) {
            obj += x * (0.5 * px + q);
        }
        out.objective = obj;
        out.iterations = self.iterations;
        out.kkt_solves = self.kkt_solves;
        out.start = start;
        out.certified = certificate.is_some();
        out.kkt = certificate;
        Ok(())
    }

    /// The KKT residuals ([`Qp::kkt_residuals`]) of the answer x = `x` with the multipliers of
    /// `z` on the rows of W (zero elsewhere), and whether every quantity they are made of is
    /// finite, which reads every entry of the data (module docs, *Certification*). Leaves P x
    /// in `px`.
    fn certificate(&mut self, qp: &Qp, ctx: &Ctx) -> (KktResiduals, bool) {
        let Ctx { nx, n_eq, n_in, .. } = *ctx;
        if !self.gx_valid {
            self.eval_gx(qp, ctx);
        }
        let x = &self.x[..nx];
        p_times(
            &self.p_row[..nx * nx],
            self.schur.is_diagonal(),
            x,
            &mut self.px[..nx],
        );
        let m = self.k - nx;
        let rows = self.c[..m * nx].chunks_exact(nx);
        let (lambda, y) = self.z[nx..self.k].split_at(n_eq);
        // Stationarity P x + q + A'lambda + sum_W y_k c_k, into `u`, the rows of C being those
        // of A and W.
        let st = &mut self.u[..nx];
        for ((s, px), q) in st.iter_mut().zip(&self.px[..nx]).zip(qp.q.as_slice()) {
            *s = px + q;
        }
        for (row, &v) in rows.clone().zip(self.z[nx..self.k].iter()) {
            for (s, c) in st.iter_mut().zip(row) {
                *s += c * v;
            }
        }
        let mut primal: f64 = 0.0;
        let mut dual: f64 = 0.0;
        let mut comp: f64 = 0.0;
        // `below_inf` is false for NaN and +inf: a residual made of non-finite data.
        let mut finite = lambda.iter().all(|v| v.is_finite());
        let below_inf = |v: f64| v < f64::INFINITY;
        for (row, &b) in rows.zip(qp.b.as_slice()) {
            let v = (dot(row, x) - b).abs();
            finite &= below_inf(v);
            primal = primal.max(v);
        }
        for (&gx, &h) in self.gx[..n_in].iter().zip(qp.h.as_slice()) {
            let v = gx - h;
            finite &= gx.is_finite() && below_inf(v);
            primal = primal.max(v);
        }
        let (lower, upper) = (qp.lower.as_slice(), qp.upper.as_slice());
        for ((&xi, &l), &u) in x.iter().zip(lower).zip(upper) {
            let (lo, hi) = (l - xi, xi - u);
            finite &= below_inf(lo) && below_inf(hi);
            primal = primal.max(lo).max(hi);
        }
        for (&k, &yk) in self.w.iter().zip(y) {
            dual = dual.max(-yk);
            let slack = if k < n_in {
                qp.h[k] - self.gx[k]
            } else if k < n_in + nx {
                upper[k - n_in] - x[k - n_in]
            } else {
                x[k - n_in - nx] - lower[k - n_in - nx]
            };
            comp = comp.max((yk * slack).abs());
        }
        for &s in st.iter() {
            finite &= s.is_finite();
            dual = dual.max(s.abs());
        }
        (
            KktResiduals {
                primal,
                dual,
                complementarity: comp,
            },
            finite,
        )
    }
}

/// P v into `out` (`p` row-major n x n; only its diagonal is read when `diagonal`), each entry
/// summed from 0 in the order of its row.
fn p_times(p: &[f64], diagonal: bool, v: &[f64], out: &mut [f64]) {
    let n = v.len();
    for (i, o) in out.iter_mut().enumerate() {
        *o = if diagonal {
            p[i * n + i] * v[i]
        } else {
            p[i * n..(i + 1) * n]
                .iter()
                .zip(v)
                .fold(0.0, |s, (a, b)| s + a * b)
        };
    }
}

/// max |v_i| (0 for an empty v; NaN entries ignored).
fn amax(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// Whether the sizes of P, A, G and the bounds agree with those of q, b and h (what
/// [`Qp::validate`] checks first).
fn shapes_agree(qp: &Qp) -> bool {
    let (nx, n_eq, n_in) = (qp.q.len(), qp.b.len(), qp.h.len());
    qp.p.shape() == (nx, nx)
        && qp.a.shape() == (n_eq, nx)
        && qp.g.shape() == (n_in, nx)
        && qp.lower.len() == nx
        && qp.upper.len() == nx
}

/// Right-hand side d_k of row k (may be +inf: the row is absent).
fn rhs(qp: &Qp, ctx: &Ctx, k: usize) -> f64 {
    if k < ctx.n_in {
        qp.h[k]
    } else if k < ctx.n_in + ctx.nx {
        qp.upper[k - ctx.n_in]
    } else {
        -qp.lower[k - ctx.n_in - ctx.nx]
    }
}

/// Calls `f(j, c_kj)` for the nonzero entries of row k (all entries for a row of G).
fn fill_row<F: FnMut(usize, f64)>(qp: &Qp, ctx: &Ctx, k: usize, mut f: F) {
    if k < ctx.n_in {
        for j in 0..ctx.nx {
            f(j, qp.g[(k, j)]);
        }
    } else if k < ctx.n_in + ctx.nx {
        f(k - ctx.n_in, 1.0);
    } else {
        f(k - ctx.n_in - ctx.nx, -1.0);
    }
}

/// c_k'v (v's first n entries).
fn row_dot(qp: &Qp, ctx: &Ctx, k: usize, v: &[f64]) -> f64 {
    let mut s = 0.0;
    fill_row(qp, ctx, k, |j, c| s += c * v[j]);
    s
}

/// (c_k'(a - b), |c_k|_1).
fn row_dot_diff(qp: &Qp, ctx: &Ctx, k: usize, a: &[f64], b: &[f64]) -> (f64, f64) {
    let mut s = 0.0;
    let mut n1 = 0.0;
    fill_row(qp, ctx, k, |j, c| {
        s += c * (a[j] - b[j]);
        n1 += c.abs();
    });
    (s, n1)
}

/// In-place LU with partial pivoting of the row-major n x n matrix `a` (LAPACK getrf layout:
/// unit-lower L below the diagonal, U on and above, `piv[i]` the row swapped with row i at
/// step i). False if a pivot is below [`PIVOT_TOL`] times the largest entry.
fn lu_factor(a: &mut [f64], n: usize, piv: &mut [usize]) -> bool {
    let amax = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if n > 0 && (amax.is_nan() || amax <= 0.0 || amax.is_infinite()) {
        return false;
    }
    let tol = PIVOT_TOL * amax;
    for k in 0..n {
        let mut p = k;
        let mut best = a[k * n + k].abs();
        for r in k + 1..n {
            let v = a[r * n + k].abs();
            if v > best {
                best = v;
                p = r;
            }
        }
        if best.is_nan() || best <= tol {
            return false;
        }
        piv[k] = p;
        if p != k {
            for c in 0..n {
                a.swap(k * n + c, p * n + c);
            }
        }
        let pivot = a[k * n + k];
        for r in k + 1..n {
            let f = a[r * n + k] / pivot;
            a[r * n + k] = f;
            if f != 0.0 {
                for c in k + 1..n {
                    a[r * n + c] -= f * a[k * n + c];
                }
            }
        }
    }
    true
}

/// Solves with the factors of [`lu_factor`], overwriting `b` with the solution.
fn lu_solve(a: &[f64], n: usize, piv: &[usize], b: &mut [f64]) {
    for (k, &p) in piv[..n].iter().enumerate() {
        b.swap(k, p);
    }
    for r in 0..n {
        let mut s = b[r];
        for c in 0..r {
            s -= a[r * n + c] * b[c];
        }
        b[r] = s;
    }
    for r in (0..n).rev() {
        let mut s = b[r];
        for c in r + 1..n {
            s -= a[r * n + c] * b[c];
        }
        b[r] = s / a[r * n + r];
    }
}

/// Rejects malformed data (see [`ActiveSetError::InvalidData`] and [`Qp::validate`]).
fn validate(qp: &Qp) -> Result<(), ActiveSetError> {
    qp.validate().map_err(ActiveSetError::InvalidData)
}
