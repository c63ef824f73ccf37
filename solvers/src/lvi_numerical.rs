//! The LVI-based numerical QP methods the papers cite against their networks: **94LVI** and
//! **E47** (zhong2021 refs. [26], [27]: Zhang, Fu, Zhang, Xiao and Li, "On the LVI-based
//! numerical method (E47 algorithm) for solving quadratic programming problems", ICAL 2011;
//! Zhang, Li, Mao, Li and Fu, "Complete theory for E47 and 94LVI algorithms ...", CAC 2015).
//! Both descend from He's projection-and-contraction methods for linear variational
//! inequalities (B. He, Math. Programming 66, 1994: "94"; B. He, Appl. Math. Optim. 35, 1997).
//! Written here from their published definitions.
//!
//! # The problem they solve
//!
//! A QP (see [`schemes::qp::Qp`]) is equivalent to the linear variational inequality of
//! jia2019 (2.21) (built in [`crate::neural::projection`]): find y* in Omega with
//! (y - y*)'(M y* + q) >= 0 for all y in Omega, with y = [x; u; v], the same M, q and box Omega
//! as LVI-PDNN. That is the piecewise-linear projection equation (PLPE)
//!
//! ```text
//! e(y) := y - P_Omega(y - (M y + q)) = 0,
//! ```
//!
//! the zeros of whose residual e are the QP's primal-dual solutions (jia2019 (2.22) writes the
//! same residual with the opposite sign; [`LviCore::residual`] returns that form, -e).
//!
//! # The iterations (k = 0, 1, 2, ...)
//!
//! Both use the step length
//!
//! ```text
//! rho(y) = |e(y)|_2^2 / |(I + M') e(y)|_2^2
//! ```
//!
//! - **94LVI**: y^{k+1} = y^k - rho(y^k) (I + M') e(y^k).
//! - **E47**: y^{k+1} = P_Omega( y^k - rho(y^k) (M' e(y^k) + M y^k + q) ).
//!
//! M is monotone (M + M' = diag(2P, 0) is positive semidefinite), and for such LVIs both
//! sequences converge globally to a solution, with |y^k - y*| decreasing monotonically
//! (94LVI: He 1994; E47: Zhang et al. 2011, with global linear convergence).
//!
//! # Convergence criterion
//!
//! Stop at the first k with |e(y^k)|_inf <= `tolerance` ([`LviSettings`], default
//! [`DEFAULT_TOLERANCE`] = 1e-10), or fail with [`LviError::NotConverged`] after
//! `max_iterations`. Near a non-degenerate solution |y - y*| <= c |e(y)| for a constant c of the
//! QP, so the criterion bounds the error in x.
//!
//! # Cost
//!
//! Each iteration of either method costs two products with M (one for e(y^k), which needs
//! M y^k, and one with M') plus O(dim) work; [`PRODUCTS_PER_ITERATION`]. That is the unit the
//! efficiency claim is decided in, shared with the projection networks (one forward-Euler
//! step of S-LVI-PDNN costs one product, one of LVI-PDNN two).
//!
//! The solver keeps its iterate between calls: a call starts from where the last ended (the
//! previous tick's solution in a control loop: warm start), or from y = 0 after
//! [`LviSolver::reset`]. Solving does not allocate.

use crate::neural::projection::{primal_dual_dim, LviCore};
use schemes::qp::{Qp, QpDims};

/// Default stopping tolerance on |e(y)|_inf.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;
/// Default iteration limit of one solve.
pub const DEFAULT_MAX_ITERATIONS: u32 = 200_000;
/// Products with M (or M') per iteration of either method (see the module docs).
pub const PRODUCTS_PER_ITERATION: u64 = 2;

/// Which of the two methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LviMethod {
    /// He 1994 / Zhang et al.: y <- y - rho (I + M') e(y).
    Lvi94,
    /// Zhang et al. 2011: y <- P_Omega(y - rho (M' e(y) + M y + q)).
    E47,
}

impl LviMethod {
    pub const ALL: [LviMethod; 2] = [LviMethod::E47, LviMethod::Lvi94];

    /// The name the papers use (`E47`, `94LVI`).
    pub fn name(self) -> &'static str {
        match self {
            LviMethod::Lvi94 => "94LVI",
            LviMethod::E47 => "E47",
        }
    }
}

/// Stopping rule of one solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LviSettings {
    /// Stop when |e(y)|_inf <= tolerance.
    pub tolerance: f64,
    /// Fail after this many iterations.
    pub max_iterations: u32,
}

impl Default for LviSettings {
    fn default() -> Self {
        LviSettings {
            tolerance: DEFAULT_TOLERANCE,
            max_iterations: DEFAULT_MAX_ITERATIONS,
        }
    }
}

/// Why a solve failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LviError {
    #[error("{method} did not reach |e|_inf <= {tolerance:e} in {iterations} iterations (|e|_inf = {residual:e})")]
    NotConverged {
        method: &'static str,
        iterations: u32,
        tolerance: f64,
        residual: f64,
    },
    #[error("{method}: the iterate became non-finite after {iterations} iterations")]
    NonFinite {
        method: &'static str,
        iterations: u32,
    },
}

/// E47 or 94LVI with its iterate and scratch (see the module docs).
#[derive(Clone, Debug)]
pub struct LviSolver {
    method: LviMethod,
    settings: LviSettings,
    core: LviCore,
    /// The iterate y = [x; u; v].
    y: Vec<f64>,
    /// e(y) in jia2019's sign (P_Omega(y - (M y + q)) - y).
    e: Vec<f64>,
    /// (I + M') e in the same sign.
    d: Vec<f64>,
}

impl LviSolver {
    /// A solver for QPs of sizes `dims`, its iterate at y = 0.
    pub fn new(method: LviMethod, dims: QpDims, settings: LviSettings) -> Self {
        let n = primal_dual_dim(dims);
        LviSolver {
            method,
            settings,
            core: LviCore::new(dims),
            y: vec![0.0; n],
            e: vec![0.0; n],
            d: vec![0.0; n],
        }
    }

    pub fn method(&self) -> LviMethod {
        self.method
    }

    pub fn settings(&self) -> LviSettings {
        self.settings
    }

    /// The iterate's primal part x.
    pub fn x(&self) -> &[f64] {
        &self.y[..self.core.dims().nx]
    }

    /// The whole iterate y = [x; u; v].
    pub fn state(&self) -> &[f64] {
        &self.y
    }

    /// Restart from y = 0 (a cold start).
    pub fn reset(&mut self) {
        self.y.fill(0.0);
    }

    /// Iterates from the current y until the criterion holds; returns the iterations taken
    /// (0 when the current y already satisfies it).
    pub fn solve(&mut self, qp: &Qp) -> Result<u32, LviError> {
        let name = self.method.name();
        for k in 0..=self.settings.max_iterations {
            let e = self.core.residual(qp, &self.y);
            let residual = e.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if !residual.is_finite() {
                return Err(LviError::NonFinite {
                    method: name,
                    iterations: k,
                });
            }
            if residual <= self.settings.tolerance {
                return Ok(k);
            }
            if k == self.settings.max_iterations {
                return Err(LviError::NotConverged {
                    method: name,
                    iterations: k,
                    tolerance: self.settings.tolerance,
                    residual,
                });
            }
            self.e.copy_from_slice(e);
            self.core.i_plus_mt_e(qp, 1.0, &mut self.d);
            let ee: f64 = self.e.iter().map(|v| v * v).sum();
            let dd: f64 = self.d.iter().map(|v| v * v).sum();
            let rho = ee / dd;
            // In jia2019's sign e_j = -e, d_j = -(I + M') e, so (module docs)
            // 94LVI: y + rho d_j; E47: P(y + rho (d_j - e_j - (M y + q))), M y + q = y - z.
            match self.method {
                LviMethod::Lvi94 => {
                    for (yi, di) in self.y.iter_mut().zip(&self.d) {
                        *yi += rho * di;
                    }
                }
                LviMethod::E47 => {
                    let z = self.core.z();
                    for i in 0..self.y.len() {
                        let my_q = self.y[i] - z[i];
                        self.y[i] += rho * (self.d[i] - self.e[i] - my_q);
                    }
                    self.core.project(qp, &mut self.y);
                }
            }
        }
        unreachable!("the loop returns at k = max_iterations")
    }
}
