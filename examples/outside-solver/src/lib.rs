//! A QP solver written outside driftbench's `solvers` crate, against the one seam alone
//! ([`qp::QpSolver`]; this crate links `qp` and nothing else of the suite): the proof that an
//! outside solver passes the conformance kit with one call and runs as a run's solver through
//! the registry (its tests do both).
//!
//! [`EqualityKkt`] solves equality-constrained QPs, min x'Px/2 + q'x s.t. A x = b, by one dense
//! solve of their KKT system
//!
//! ```text
//! [ P  A' ] [ x      ]   [ -q ]
//! [ A  0  ] [ lambda ] = [  b ]
//! ```
//!
//! (Gaussian elimination with partial pivoting, in buffers sized once: a solve allocates
//! nothing). Stationarity is then P x + q + A'lambda = 0, the seam's convention with
//! mu = z_l = z_u = 0. A QP with inequality rows or finite bounds is answered only when the
//! equality-constrained optimum satisfies them (to `tolerance`): it is then the QP's optimum,
//! with those multipliers zero; otherwise the solve is refused with [`QpStatus::InvalidInput`]
//! (this method cannot handle active inequalities). A pivot below 1e-12 of the largest entry
//! refuses the QP as [`QpStatus::Singular`] (a repeated or inconsistent equality row).

// A NaN fails `!(pivot > tol)`, which the forms clippy proposes would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use qp::{Qp, QpDims, QpDuals, QpSolve, QpSolver, QpSolverError, QpStatus, SolverId};

/// The id it is registered under.
pub const ID: &str = "equality-kkt";

/// Below this ratio to the largest entry of the KKT matrix a pivot is taken as zero.
const PIVOT_RATIO: f64 = 1e-12;

/// Why a solve failed.
#[derive(Debug, thiserror::Error)]
pub enum KktError {
    /// The QP has other sizes than the solver was built for.
    #[error("built for QPs of sizes {expected:?}, given one of {found:?}")]
    Dimensions {
        /// The sizes it was built for.
        expected: QpDims,
        /// The sizes given.
        found: QpDims,
    },
    /// A NaN or infinite entry in P, q, A or b.
    #[error("the QP's data has a NaN or infinite entry")]
    NotFinite,
    /// The KKT matrix is singular (A has dependent rows, or P is singular on A's null space).
    #[error("the KKT matrix is singular (pivot {pivot:.3e} at column {column})")]
    Singular {
        /// The column of elimination.
        column: usize,
        /// The largest pivot candidate there.
        pivot: f64,
    },
    /// The equality-constrained optimum violates an inequality row or a bound.
    #[error("an inequality or bound is active (violated by {violation:.3e}): equality-constrained QPs only")]
    ActiveInequality {
        /// The largest violation.
        violation: f64,
    },
}

/// The dense KKT solver of the module docs.
#[derive(Clone, Debug)]
pub struct EqualityKkt {
    dims: QpDims,
    tolerance: f64,
    /// The KKT matrix, row-major, (nx + n_eq)^2, overwritten by its elimination.
    k: Vec<f64>,
    /// The right-hand side, then the solution [x; lambda].
    rhs: Vec<f64>,
    /// The answer of the last successful solve (zeros before one).
    x: Vec<f64>,
    lambda: Vec<f64>,
}

impl EqualityKkt {
    /// A solver for QPs of sizes `dims`, checking inequalities and bounds to `tolerance`.
    pub fn new(dims: QpDims, tolerance: f64) -> Self {
        let m = dims.nx + dims.n_eq;
        EqualityKkt {
            dims,
            tolerance,
            k: vec![0.0; m * m],
            rhs: vec![0.0; m],
            x: vec![0.0; dims.nx],
            lambda: vec![0.0; dims.n_eq],
        }
    }

    /// Writes the KKT system of `qp` (module docs).
    fn assemble(&mut self, qp: &Qp) {
        let QpDims { nx, n_eq, .. } = self.dims;
        let m = nx + n_eq;
        self.k.fill(0.0);
        for i in 0..nx {
            for j in 0..nx {
                self.k[i * m + j] = qp.p[(i, j)];
            }
            self.rhs[i] = -qp.q[i];
        }
        for r in 0..n_eq {
            for j in 0..nx {
                self.k[(nx + r) * m + j] = qp.a[(r, j)];
                self.k[j * m + nx + r] = qp.a[(r, j)];
            }
            self.rhs[nx + r] = qp.b[r];
        }
    }

    /// Solves the assembled system in place (partial pivoting); `rhs` becomes [x; lambda].
    fn eliminate(&mut self) -> Result<(), KktError> {
        let m = self.rhs.len();
        let scale = self.k.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1.0);
        for c in 0..m {
            let (p, pivot) = (c..m)
                .map(|r| (r, self.k[r * m + c].abs()))
                .fold((c, -1.0), |a, b| if b.1 > a.1 { b } else { a });
            if !(pivot > PIVOT_RATIO * scale) {
                return Err(KktError::Singular { column: c, pivot });
            }
            if p != c {
                for j in 0..m {
                    self.k.swap(c * m + j, p * m + j);
                }
                self.rhs.swap(c, p);
            }
            for r in c + 1..m {
                let f = self.k[r * m + c] / self.k[c * m + c];
                if f != 0.0 {
                    for j in c..m {
                        self.k[r * m + j] -= f * self.k[c * m + j];
                    }
                    self.rhs[r] -= f * self.rhs[c];
                }
            }
        }
        for c in (0..m).rev() {
            let mut v = self.rhs[c];
            for j in c + 1..m {
                v -= self.k[c * m + j] * self.rhs[j];
            }
            self.rhs[c] = v / self.k[c * m + c];
        }
        Ok(())
    }

    /// The largest violation of G x <= h and l <= x <= u by `x` (0 when none), each relative
    /// to max(1, |bound|).
    fn violation(qp: &Qp, x: &[f64]) -> f64 {
        let mut worst = 0.0f64;
        for r in 0..qp.h.len() {
            let gx: f64 = (0..x.len()).map(|j| qp.g[(r, j)] * x[j]).sum();
            worst = worst.max((gx - qp.h[r]) / qp.h[r].abs().max(1.0));
        }
        for (i, &xi) in x.iter().enumerate() {
            worst = worst.max((qp.lower[i] - xi) / qp.lower[i].abs().max(1.0));
            worst = worst.max((xi - qp.upper[i]) / qp.upper[i].abs().max(1.0));
        }
        worst
    }
}

impl QpSolver for EqualityKkt {
    fn id(&self) -> SolverId {
        SolverId::builtin(ID)
    }

    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        if qp.dims() != self.dims {
            return Err(QpSolverError::new(
                QpStatus::InvalidInput,
                KktError::Dimensions {
                    expected: self.dims,
                    found: qp.dims(),
                },
            ));
        }
        let finite = qp.p.iter().chain(qp.q.iter()).chain(qp.a.iter());
        if !finite.chain(qp.b.iter()).all(|v| v.is_finite()) {
            return Err(QpSolverError::new(
                QpStatus::InvalidInput,
                KktError::NotFinite,
            ));
        }
        self.assemble(qp);
        self.eliminate()
            .map_err(|e| QpSolverError::new(QpStatus::Singular, e))?;
        let nx = self.dims.nx;
        let violation = Self::violation(qp, &self.rhs[..nx]);
        if !(violation <= self.tolerance) {
            return Err(QpSolverError::new(
                QpStatus::InvalidInput,
                KktError::ActiveInequality { violation },
            ));
        }
        self.x.copy_from_slice(&self.rhs[..nx]);
        self.lambda.copy_from_slice(&self.rhs[nx..]);
        Ok(QpSolve::solved(1))
    }

    fn x(&self) -> &[f64] {
        &self.x
    }

    fn duals(&self, _qp: &Qp, duals: &mut QpDuals) {
        duals.lambda.as_mut_slice().copy_from_slice(&self.lambda);
        duals.mu.fill(0.0);
        duals.z_lower.fill(0.0);
        duals.z_upper.fill(0.0);
    }

    fn reset(&mut self) {
        self.x.fill(0.0);
        self.lambda.fill(0.0);
    }
}
