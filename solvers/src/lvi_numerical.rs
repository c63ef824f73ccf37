//! The six numerical methods for the piecewise-linear projection equation (PLPE) compared in
//! robio2018: Z. Zhang, L. Kong, Z. Yan, K. Chen, S. Li, X. Qu and N. Tan, "Comparisons among
//! Six Numerical Methods for Solving Repetitive Motion Planning of Redundant Robot
//! Manipulators", IEEE ROBIO 2018. Two of them, **94LVI** and **E47**, are the numerical methods
//! zhong2021 compares its networks with (its refs. \[26\], \[27\]); robio2018 adds **M3** to **M6**.
//! Every rule below is robio2018's printed one, written here (no crate has them).
//!
//! # The problem they solve
//!
//! A QP (see [`qp::Qp`]) is equivalent to the linear variational inequality of
//! jia2019 (2.21) (built in [`crate::neural::projection`]): find U* in Omega with
//! (U - U*)'(M U* + q) >= 0 for all U in Omega, with U = [x; u; v], the same M, q and box Omega
//! as LVI-PDNN. robio2018 writes it for its QP with M = [I -J'; J 0], q = [C; -rdot] and
//! Omega = [zeta-, zeta+] x [-omega, omega]; the general M, q, Omega of jia2019 (2.21) reduce
//! to that for an equality-plus-bounds QP with P = I. It is the PLPE
//!
//! ```text
//! e(U) := U - P_Omega(U - (M U + q)) = 0,
//! ```
//!
//! whose zeros are the QP's primal-dual solutions (jia2019 (2.22) writes the same residual with
//! the opposite sign; [`LviCore::residual`] returns that form, -e; every rule below is even in
//! e's sign except the update, which is applied as U + rho Q (-e)).
//!
//! # The iterations (k = 0, 1, 2, ...)
//!
//! All six are robio2018 (21),
//!
//! ```text
//! U^{k+1} = U^k - rho(U^k) Q e(U^k),
//! ```
//!
//! with, writing e = e(U^k) and |v|_A^2 = v' A v:
//!
//! | method | Q | rho | equation |
//! |---|---|---|---|
//! | [`LviMethod::Lvi94`] 94LVI | I | \|e\|^2 / (e'(I + M) e) | robio2018 (22) |
//! | [`LviMethod::E47`] E47 | M^{-1} | \|e\|^2 / (e'(I + M^{-1}) e) | robio2018 (23) |
//! | [`LviMethod::M3`] M3 | I + M^{-1} | \|e\|^2 / \|(I + M^{-1}) e\|^2_{I+M} | robio2018 (24) |
//! | [`LviMethod::M4`] M4 | (I + M)^{-1} | 1 | robio2018 (25) |
//! | [`LviMethod::M5`] M5 | M' | \|e\|^2 / \|e\|^2_{M(I+M')} | robio2018 (26) |
//! | [`LviMethod::M6`] M6 | I + M^{-1} | \|e\|^2 / \|e\|^2_{M(I+M')} | robio2018 (27) |
//!
//! The update is not projected (robio2018 (21) as printed). The quadratic forms are evaluated
//! as e'(I + M)e = e'(I + M')e, e'M(I + M')e = e'(M'e) + |M'e|^2 and
//! d'(I + M)d = d'(I + M')d, so every product is one with M' ([`LviCore::i_plus_mt`]).
//! M^{-1} and (I + M)^{-1} are never formed: E47, M3 and M6 factorise M, M4 factorises I + M,
//! once per [`LviSolver::solve`] call (M changes with the QP at every call), by dense LU with
//! partial pivoting on preallocated buffers ([`DenseLu`]), and apply the inverse by the two
//! triangular solves. M is invertible for an equality-plus-bounds QP with A of full row rank
//! and P positive definite, but with inequality rows (jia2019's and zhong2021's shapes: more
//! rows than variables) it is singular; such a call returns [`LviError::SingularMatrix`]
//! (detected as a pivot ratio min|u_kk| / max|u_kk| below [`SINGULAR_PIVOT_RATIO`]). I + M is
//! always invertible, since M + M' = diag(2P, 0) is positive semidefinite.
//!
//! Every denominator is positive for monotone M and e != 0 (e'(I + M)e >= |e|^2, and M^{-1} is
//! monotone when M is), except M5's and M6's |e|^2_{M(I+M')}, which vanishes when M'e = 0 (only
//! for singular M); a zero or non-finite denominator returns [`LviError::Breakdown`].
//!
//! # Convergence (what robio2018 states)
//!
//! robio2018 proves M5's global convergence (its Theorem 4); for 94LVI, E47 and M4 it cites
//! He's 1994 analysis (B. He, "A new method for a class of linear variational inequalities",
//! Math. Programming 66, 1994); M3 and M6 are supported by its simulations only. This module
//! does not rely on any of these: the tests (`tests/lvi_numerical.rs`) check each method
//! against Clarabel and record where a rule as printed does not converge.
//!
//! Before robio2018's rules were adopted, 94LVI here was He's 1994 projection-and-contraction
//! step and E47 a projected variant read from an abstract; both now follow robio2018 (22) and
//! (23) as printed (report/deviations.md).
//!
//! # Stopping rule
//!
//! robio2018's Algorithm 1, step 3: stop at the first k with |e(U^k)|_2 <= `tolerance`
//! ([`LviSettings`]; the paper's value is 1e-3 (`experiments/robio2018.toml`), the suite's default
//! [`DEFAULT_TOLERANCE`] = 1e-10, tight enough to compare with Clarabel), or fail with
//! [`LviError::NotConverged`] after `max_iterations`. Near a non-degenerate solution
//! |U - U*| <= c |e(U)| for a constant c of the QP, so the rule bounds the error in x.
//!
//! # Cost, in products
//!
//! The unit is one product of an n x n matrix with a vector, n = dim U (about n^2
//! multiply-adds dense): a product with M or M' counts 1 (computed blockwise, it costs less,
//! but it is counted 1 whatever the structure, as for the projection networks: one
//! forward-Euler step of S-LVI-PDNN costs one product, one of LVI-PDNN two); a solve with LU
//! factors (forward plus back substitution, n^2 multiply-adds) counts 1; one LU factorisation
//! (about n^3/3 multiply-adds) counts ceil(n/3). Each iteration evaluates e(U^k) (1, for M U^k)
//! and its direction and step ([`LviMethod::products_per_iteration`]: 94LVI 2, E47 2, M3 3,
//! M4 2, M5 2, M6 3), the final residual that confirms convergence counts 1, and the
//! factorising methods add one factorisation per call that iterates ([`LviMethod::products`]).
//!
//! The solver keeps its iterate between calls: a call starts from where the last ended (the
//! previous tick's solution in a control loop: warm start; a call whose start already meets the
//! stopping rule takes 0 iterations and factorises nothing), or from U = 0 after
//! [`LviSolver::reset`]. Solving does not allocate.

use crate::dense_lu::DenseLu;
use crate::neural::projection::{lvi_matrix_into, primal_dual_dim, LviCore};
use nalgebra::DMatrix;
use qp::{Qp, QpDims};

/// The suite's default stopping tolerance on |e(U)|_2.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;
/// Default iteration limit of one solve.
pub const DEFAULT_MAX_ITERATIONS: u32 = 200_000;
/// Below this pivot ratio min|u_kk| / max|u_kk| the factorised matrix is taken as singular.
pub const SINGULAR_PIVOT_RATIO: f64 = 1e-12;

/// Which of robio2018's six methods (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LviMethod {
    /// robio2018 (22): Q = I, rho = |e|^2 / (e'(I + M)e).
    Lvi94,
    /// robio2018 (23): Q = M^{-1}, rho = |e|^2 / (e'(I + M^{-1})e).
    E47,
    /// robio2018 (24): Q = I + M^{-1}, rho = |e|^2 / |(I + M^{-1})e|^2_{I+M}.
    M3,
    /// robio2018 (25): Q = (I + M)^{-1}, rho = 1.
    M4,
    /// robio2018 (26): Q = M', rho = |e|^2 / |e|^2_{M(I+M')}.
    M5,
    /// robio2018 (27): Q = I + M^{-1}, rho = |e|^2 / |e|^2_{M(I+M')}.
    M6,
}

/// The matrix a method factorises once per solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Factored {
    /// M (E47, M3, M6: Q contains M^{-1}).
    M,
    /// I + M (M4).
    IPlusM,
}

impl Factored {
    /// `M` or `I + M`.
    pub fn name(self) -> &'static str {
        match self {
            Factored::M => "M",
            Factored::IPlusM => "I + M",
        }
    }
}

impl LviMethod {
    /// The six, in robio2018's order (22)-(27).
    pub const ALL: [LviMethod; 6] = [
        LviMethod::Lvi94,
        LviMethod::E47,
        LviMethod::M3,
        LviMethod::M4,
        LviMethod::M5,
        LviMethod::M6,
    ];

    /// Identifier in files: `94lvi`, `e47`, `m3`, `m4`, `m5`, `m6`.
    pub fn id(self) -> &'static str {
        match self {
            LviMethod::Lvi94 => "94lvi",
            LviMethod::E47 => "e47",
            LviMethod::M3 => "m3",
            LviMethod::M4 => "m4",
            LviMethod::M5 => "m5",
            LviMethod::M6 => "m6",
        }
    }

    /// The method whose [`LviMethod::id`] is `id`.
    pub fn from_id(id: &str) -> Option<LviMethod> {
        LviMethod::ALL.into_iter().find(|m| m.id() == id)
    }

    /// The name robio2018 uses: `94LVI`, `E47`, `M3`, `M4`, `M5`, `M6`.
    pub fn name(self) -> &'static str {
        match self {
            LviMethod::Lvi94 => "94LVI",
            LviMethod::E47 => "E47",
            LviMethod::M3 => "M3",
            LviMethod::M4 => "M4",
            LviMethod::M5 => "M5",
            LviMethod::M6 => "M6",
        }
    }

    /// The matrix the method factorises once per solve, if any (module docs).
    pub fn factorises(self) -> Option<Factored> {
        match self {
            LviMethod::E47 | LviMethod::M3 | LviMethod::M6 => Some(Factored::M),
            LviMethod::M4 => Some(Factored::IPlusM),
            LviMethod::Lvi94 | LviMethod::M5 => None,
        }
    }

    /// Products per iteration in the module docs' unit: 1 for e(U^k), plus 94LVI (I + M')e;
    /// E47 M^{-1}e; M3 M^{-1}e and (I + M')d; M4 (I + M)^{-1}e; M5 M'e; M6 M^{-1}e and M'e.
    pub fn products_per_iteration(self) -> u64 {
        match self {
            LviMethod::Lvi94 | LviMethod::E47 | LviMethod::M4 | LviMethod::M5 => 2,
            LviMethod::M3 | LviMethod::M6 => 3,
        }
    }

    /// Products of one successful solve of `iterations` iterations on a primal-dual vector of
    /// size `n` (module docs): the iterations, the confirming residual, and one LU
    /// factorisation (ceil(n/3)) when the method factorises and the call iterated.
    pub fn products(self, iterations: u32, n: usize) -> u64 {
        let factorisation = match self.factorises() {
            Some(_) if iterations > 0 => n.div_ceil(3) as u64,
            _ => 0,
        };
        self.products_per_iteration() * u64::from(iterations) + 1 + factorisation
    }
}

/// Stopping rule of one solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LviSettings {
    /// Stop when |e(U)|_2 <= tolerance.
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
    /// `max_iterations` iterations did not bring |e(U)|_2 down to the tolerance.
    #[error("{method} did not reach |e|_2 <= {tolerance:e} in {iterations} iterations (|e|_2 = {residual:e})")]
    NotConverged {
        /// The method's name as robio2018 writes it.
        method: &'static str,
        /// The iterations made: `max_iterations`.
        iterations: u32,
        /// The stopping tolerance on |e(U)|_2.
        tolerance: f64,
        /// |e(U)|_2 at the last iterate.
        residual: f64,
    },
    /// The iterate became NaN or infinite.
    #[error("{method}: the iterate became non-finite after {iterations} iterations")]
    NonFinite {
        /// The method's name as robio2018 writes it.
        method: &'static str,
        /// The iterations completed (the k of the non-finite U^k).
        iterations: u32,
    },
    /// The matrix the method inverts is singular to working precision (module docs).
    #[error(
        "{method}: {matrix} is singular (pivot ratio {pivot_ratio:e}), so its inverse is undefined"
    )]
    SingularMatrix {
        /// The method's name as robio2018 writes it.
        method: &'static str,
        /// The matrix: `M` or `I + M`.
        matrix: &'static str,
        /// Its LU pivot ratio min|u_kk| / max|u_kk| (0 when a pivot was zero or not finite).
        pivot_ratio: f64,
    },
    /// The step length's denominator was zero or not finite (module docs).
    #[error("{method}: the step length's denominator vanished at iteration {iterations}")]
    Breakdown {
        /// The method's name as robio2018 writes it.
        method: &'static str,
        /// The iterations completed before it vanished (the k of U^k).
        iterations: u32,
    },
    /// The QP's sizes are not those the solver was built for.
    #[error("{method}: built for QPs of sizes {expected:?}, given one of {found:?}")]
    Dimensions {
        /// The method's name as robio2018 writes it.
        method: &'static str,
        /// The sizes the solver was built for.
        expected: QpDims,
        /// The sizes of the QP given.
        found: QpDims,
    },
}

/// One of the six methods with its iterate, scratch and factors (see the module docs).
#[derive(Clone, Debug)]
pub struct LviSolver {
    method: LviMethod,
    settings: LviSettings,
    core: LviCore,
    /// The iterate U = [x; u; v].
    y: Vec<f64>,
    /// -e(U) (jia2019's sign, [`LviCore::residual`]).
    e: Vec<f64>,
    /// The direction Q (-e).
    d: Vec<f64>,
    /// Scratch for M'e or (I + M')d.
    w: Vec<f64>,
    /// M or I + M, assembled for the factorisation (empty when the method factorises nothing).
    m: DMatrix<f64>,
    /// Its LU factors (size 0 when the method factorises nothing).
    lu: DenseLu,
}

impl LviSolver {
    /// A solver for QPs of sizes `dims`, its iterate at U = 0.
    pub fn new(method: LviMethod, dims: QpDims, settings: LviSettings) -> Self {
        let n = primal_dual_dim(dims);
        let nf = if method.factorises().is_some() { n } else { 0 };
        LviSolver {
            method,
            settings,
            core: LviCore::new(dims),
            y: vec![0.0; n],
            e: vec![0.0; n],
            d: vec![0.0; n],
            w: vec![0.0; n],
            m: DMatrix::zeros(nf, nf),
            lu: DenseLu::for_size(nf),
        }
    }

    /// The method this solver iterates.
    pub fn method(&self) -> LviMethod {
        self.method
    }

    /// Its stopping rule.
    pub fn settings(&self) -> LviSettings {
        self.settings
    }

    /// The iterate's primal part x.
    pub fn x(&self) -> &[f64] {
        &self.y[..self.core.dims().nx]
    }

    /// The whole iterate U = [x; u; v].
    pub fn state(&self) -> &[f64] {
        &self.y
    }

    /// Restart from U = 0 (a cold start).
    pub fn reset(&mut self) {
        self.y.fill(0.0);
    }

    /// Iterates robio2018 (21) from the current U until |e(U)|_2 <= tolerance; returns the
    /// iterations taken (0 when the current U already satisfies it). Its work in products is
    /// [`LviMethod::products`] of the returned count.
    pub fn solve(&mut self, qp: &Qp) -> Result<u32, LviError> {
        let method = self.method.name();
        if qp.dims() != self.core.dims() {
            return Err(LviError::Dimensions {
                method,
                expected: self.core.dims(),
                found: qp.dims(),
            });
        }
        let mut factored = false;
        let mut k = 0;
        loop {
            self.e.copy_from_slice(self.core.residual(qp, &self.y));
            let residual = dot(&self.e, &self.e).sqrt();
            if !residual.is_finite() {
                return Err(LviError::NonFinite {
                    method,
                    iterations: k,
                });
            }
            if residual <= self.settings.tolerance {
                return Ok(k);
            }
            if k == self.settings.max_iterations {
                return Err(LviError::NotConverged {
                    method,
                    iterations: k,
                    tolerance: self.settings.tolerance,
                    residual,
                });
            }
            if !factored {
                self.factorise(qp)?;
                factored = true;
            }
            let rho = self.direction(qp);
            if !(rho.is_finite() && rho > 0.0) {
                return Err(LviError::Breakdown {
                    method,
                    iterations: k,
                });
            }
            for (yi, di) in self.y.iter_mut().zip(&self.d) {
                *yi += rho * di;
            }
            k += 1;
        }
    }

    /// Assembles and factorises M or I + M, if the method needs either.
    fn factorise(&mut self, qp: &Qp) -> Result<(), LviError> {
        let Some(which) = self.method.factorises() else {
            return Ok(());
        };
        lvi_matrix_into(qp, &mut self.m);
        if which == Factored::IPlusM {
            for i in 0..self.m.nrows() {
                self.m[(i, i)] += 1.0;
            }
        }
        let ok = self.lu.factor(&self.m);
        let pivot_ratio = if ok { self.lu.pivot_ratio() } else { 0.0 };
        if ok && pivot_ratio >= SINGULAR_PIVOT_RATIO {
            Ok(())
        } else {
            Err(LviError::SingularMatrix {
                method: self.method.name(),
                matrix: which.name(),
                pivot_ratio,
            })
        }
    }

    /// Writes d = Q (-e) for `self.e` = -e and returns rho (module docs; every quadratic form is
    /// even in e's sign).
    fn direction(&mut self, qp: &Qp) -> f64 {
        let ee = dot(&self.e, &self.e);
        let den = match self.method {
            LviMethod::Lvi94 => {
                self.core.i_plus_mt(qp, 1.0, &self.e, &mut self.w);
                self.d.copy_from_slice(&self.e);
                dot(&self.e, &self.w)
            }
            LviMethod::E47 => {
                self.d.copy_from_slice(&self.e);
                self.lu.solve(&mut self.d);
                ee + dot(&self.e, &self.d)
            }
            LviMethod::M3 => {
                self.i_plus_m_inverse_e();
                self.core.i_plus_mt(qp, 1.0, &self.d, &mut self.w);
                dot(&self.d, &self.w)
            }
            LviMethod::M4 => {
                self.d.copy_from_slice(&self.e);
                self.lu.solve(&mut self.d);
                return 1.0;
            }
            LviMethod::M5 => {
                let den = self.mt_e_form(qp);
                self.d.copy_from_slice(&self.w);
                den
            }
            LviMethod::M6 => {
                self.i_plus_m_inverse_e();
                self.mt_e_form(qp)
            }
        };
        ee / den
    }

    /// d = (I + M^{-1}) e with the factors of M.
    fn i_plus_m_inverse_e(&mut self) {
        self.d.copy_from_slice(&self.e);
        self.lu.solve(&mut self.d);
        for (di, ei) in self.d.iter_mut().zip(&self.e) {
            *di += ei;
        }
    }

    /// w = M'e; returns |e|^2_{M(I+M')} = e'(M'e) + |M'e|^2.
    fn mt_e_form(&mut self, qp: &Qp) -> f64 {
        self.core.i_plus_mt(qp, 1.0, &self.e, &mut self.w);
        for (wi, ei) in self.w.iter_mut().zip(&self.e) {
            *wi -= ei;
        }
        dot(&self.e, &self.w) + dot(&self.w, &self.w)
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
