//! OSQP (the `osqp` crate, the operator-splitting ADMM solver of Stellato et al., Math. Prog.
//! Comp. 2020), as robotics practitioners use it for QP-based inverse kinematics: set up once,
//! then at every control tick the data updated in place and the solve warm-started from the
//! previous tick's primal-dual pair.
//!
//! # The map of our QP to OSQP's form
//!
//! OSQP solves min x'Px/2 + q'x s.t. l <= C x <= u. A [`Qp`] (P, q, A, b, G, h, lower, upper)
//! maps to
//!
//! ```text
//! C = [ A ]   l = [ b     ]   u = [ b     ]
//!     [ G ]       [ -inf  ]       [ h     ]
//!     [ I ]       [ lower ]       [ upper ]
//! ```
//!
//! with every entry of P (upper triangle) and C stored, zeros included, so the sparsity pattern
//! never changes and the data of each tick is an in-place update (`update_P_A`, which
//! refactorises OSQP's KKT matrix, `update_lin_cost`, `update_bounds`). Infinite bounds are
//! passed as +-[`OSQP_INFINITY`] (OSQP's own infinity). With OSQP's multipliers w (stationarity
//! P x + q + C'w = 0) the duals of [`qp::QpDuals`] are lambda = w_A, mu = w_G,
//! z_upper = max(w_I, 0), z_lower = max(-w_I, 0).
//!
//! # Accuracy
//!
//! ADMM stops on primal and dual residuals below eps_abs + eps_rel * scale; with polishing
//! (default here) OSQP then solves the KKT system of the guessed active set, which gives
//! answers to ~1e-9 when the guess is right. [`OsqpSettings`] states the defaults.

use nalgebra::DVector;
use osqp::{CscMatrix, Problem, Settings, Status};
use qp::{Qp, QpDims, QpDuals};
use std::borrow::Cow;

/// OSQP's infinity: bounds at or beyond it are absent.
pub const OSQP_INFINITY: f64 = 1e30;

/// Iterations between OSQP's rho adaptations, fixed (OSQP's own multiple of its termination
/// check): left automatic, OSQP sets it from the measured setup time, so its iterates and
/// iteration counts would change from run to run with the machine's load.
pub const ADAPTIVE_RHO_INTERVAL: u32 = 25;

/// OSQP's stopping rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OsqpSettings {
    /// OSQP's absolute tolerance on the primal and dual residuals.
    pub eps_abs: f64,
    /// OSQP's relative tolerance on the primal and dual residuals.
    pub eps_rel: f64,
    /// OSQP's largest number of ADMM iterations per solve.
    pub max_iter: u32,
    /// Solve the active set's KKT system after ADMM.
    pub polish: bool,
}

impl Default for OsqpSettings {
    /// eps_abs = eps_rel = 1e-7, 10,000 iterations, polishing on.
    fn default() -> Self {
        OsqpSettings {
            eps_abs: 1e-7,
            eps_rel: 1e-7,
            max_iter: 10_000,
            polish: true,
        }
    }
}

/// Why a solve failed.
#[derive(Debug, thiserror::Error)]
pub enum OsqpError {
    /// OSQP refused to set the problem up (its error, as text).
    #[error("OSQP setup failed: {0}")]
    Setup(String),
    /// OSQP stopped without a solution.
    #[error("OSQP stopped with status {status} after {iterations} iterations")]
    NotSolved {
        /// OSQP's status name, e.g. `MaxIterationsReached`.
        status: String,
        /// OSQP's iterations.
        iterations: u32,
    },
}

/// OSQP kept set up across solves (see the module docs).
pub struct OsqpQp {
    dims: QpDims,
    settings: OsqpSettings,
    problem: Option<Problem>,
    p_indptr: Vec<usize>,
    p_indices: Vec<usize>,
    p_data: Vec<f64>,
    c_indptr: Vec<usize>,
    c_indices: Vec<usize>,
    c_data: Vec<f64>,
    l: Vec<f64>,
    u: Vec<f64>,
    /// The last solution x and OSQP's multipliers w.
    x: Vec<f64>,
    w: Vec<f64>,
}

impl OsqpQp {
    /// The sizes it was built for.
    pub fn dims(&self) -> QpDims {
        self.dims
    }

    /// A solver for QPs of sizes `dims`; OSQP itself is set up at the first solve.
    pub fn new(dims: QpDims, settings: OsqpSettings) -> Self {
        let QpDims { nx, n_eq, n_in } = dims;
        let m = n_eq + n_in + nx;
        let mut p_indptr = vec![0];
        let mut p_indices = Vec::with_capacity(nx * (nx + 1) / 2);
        for j in 0..nx {
            p_indices.extend(0..=j);
            p_indptr.push(p_indices.len());
        }
        let c_indptr = (0..=nx).map(|j| j * m).collect();
        let c_indices = (0..nx).flat_map(|_| 0..m).collect();
        OsqpQp {
            dims,
            settings,
            problem: None,
            p_data: vec![0.0; p_indices.len()],
            p_indptr,
            p_indices,
            c_indptr,
            c_indices,
            c_data: vec![0.0; m * nx],
            l: vec![0.0; m],
            u: vec![0.0; m],
            x: vec![0.0; nx],
            w: vec![0.0; m],
        }
    }

    /// Forgets OSQP's workspace and iterate: the next solve sets OSQP up again, cold.
    pub fn reset(&mut self) {
        self.problem = None;
        self.x.fill(0.0);
        self.w.fill(0.0);
    }

    /// The last solution's x.
    pub fn x(&self) -> &[f64] {
        &self.x
    }

    /// The last solution's duals (see the module docs for the map).
    pub fn duals(&self) -> QpDuals {
        let QpDims { nx, n_eq, n_in } = self.dims;
        let w = &self.w;
        let bound = |i: usize| w[n_eq + n_in + i];
        QpDuals {
            lambda: DVector::from_column_slice(&w[..n_eq]),
            mu: DVector::from_column_slice(&w[n_eq..n_eq + n_in]),
            z_lower: DVector::from_fn(nx, |i, _| (-bound(i)).max(0.0)),
            z_upper: DVector::from_fn(nx, |i, _| bound(i).max(0.0)),
        }
    }

    /// Writes the QP's data into the CSC arrays and bounds (module docs).
    fn load(&mut self, qp: &Qp) {
        let QpDims { nx, n_eq, n_in } = self.dims;
        let m = n_eq + n_in + nx;
        let mut k = 0;
        for j in 0..nx {
            for i in 0..=j {
                self.p_data[k] = qp.p[(i, j)];
                k += 1;
            }
        }
        for j in 0..nx {
            let col = &mut self.c_data[j * m..(j + 1) * m];
            for r in 0..n_eq {
                col[r] = qp.a[(r, j)];
            }
            for r in 0..n_in {
                col[n_eq + r] = qp.g[(r, j)];
            }
            for i in 0..nx {
                col[n_eq + n_in + i] = if i == j { 1.0 } else { 0.0 };
            }
        }
        let clamp = |v: f64| v.clamp(-OSQP_INFINITY, OSQP_INFINITY);
        for r in 0..n_eq {
            self.l[r] = qp.b[r];
            self.u[r] = qp.b[r];
        }
        for r in 0..n_in {
            self.l[n_eq + r] = -OSQP_INFINITY;
            self.u[n_eq + r] = clamp(qp.h[r]);
        }
        for i in 0..nx {
            self.l[n_eq + n_in + i] = clamp(qp.lower[i]);
            self.u[n_eq + n_in + i] = clamp(qp.upper[i]);
        }
    }

    fn p_csc(&self) -> CscMatrix<'_> {
        CscMatrix {
            nrows: self.dims.nx,
            ncols: self.dims.nx,
            indptr: Cow::Borrowed(&self.p_indptr),
            indices: Cow::Borrowed(&self.p_indices),
            data: Cow::Borrowed(&self.p_data),
        }
    }

    fn c_csc(&self) -> CscMatrix<'_> {
        CscMatrix {
            nrows: self.l.len(),
            ncols: self.dims.nx,
            indptr: Cow::Borrowed(&self.c_indptr),
            indices: Cow::Borrowed(&self.c_indices),
            data: Cow::Borrowed(&self.c_data),
        }
    }

    /// Solves `qp`, warm-started from the previous solve's primal-dual pair (OSQP keeps its
    /// iterate); returns OSQP's iteration count.
    pub fn solve(&mut self, qp: &Qp) -> Result<u32, OsqpError> {
        self.load(qp);
        match self.problem.take() {
            None => {
                let settings = Settings::default()
                    .eps_abs(self.settings.eps_abs)
                    .eps_rel(self.settings.eps_rel)
                    .max_iter(self.settings.max_iter)
                    .polish(self.settings.polish)
                    .warm_start(true)
                    .adaptive_rho_interval(Some(ADAPTIVE_RHO_INTERVAL))
                    .verbose(false);
                let problem = Problem::new(
                    self.p_csc(),
                    qp.q.as_slice(),
                    self.c_csc(),
                    &self.l,
                    &self.u,
                    &settings,
                )
                .map_err(|e| OsqpError::Setup(format!("{e:?}")))?;
                self.problem = Some(problem);
            }
            Some(mut problem) => {
                problem.update_P_A(self.p_csc(), self.c_csc());
                problem.update_lin_cost(qp.q.as_slice());
                problem.update_bounds(&self.l, &self.u);
                self.problem = Some(problem);
            }
        }
        let problem = self.problem.as_mut().expect("set up above");
        let status = problem.solve();
        let iterations = status.iter();
        match status {
            Status::Solved(sol) => {
                self.x.copy_from_slice(sol.x());
                self.w.copy_from_slice(sol.y());
                Ok(iterations)
            }
            other => Err(OsqpError::NotSolved {
                status: format!("{other:?}")
                    .split('(')
                    .next()
                    .unwrap_or_default()
                    .to_string(),
                iterations,
            }),
        }
    }
}
