//! The `penalty` error form of the projection family ([`super::projection`],
//! `settings::projection`): the error of VP-RNN-PF, the varying-parameter recurrent neural
//! network with penalty function of zhong2021 (eq. 2.19-2.30), and the implicit network its
//! zeroing design formula gives, for any gain law g(t) (VP-RNN-PF's: gamma exp(t), eq. 2.26) and
//! activation.
//!
//! # Penalty (eq. 2.19-2.21)
//!
//! The inequalities B x <= h are moved into the objective with the exponential penalty
//! P(x) = p sum_i exp(-sigma N_i(x)), N_i = h_i - B_i x (p >= 0, sigma > 0); the equality
//! A x = b stays a constraint and keeps a Lagrange multiplier lambda as a network state
//! (eq. 2.22), so the state is y = [x; lambda] in R^(nx + n_eq) (Theorem 1).
//!
//! For our [`Qp`] the inequality set is G x <= h followed by one row per finite bound:
//! e_j' x <= upper_j and -e_j' x <= -lower_j (zhong2021's B = [s; E; -E], h = [d; x+; -x-] is
//! exactly this with s = G when the scheme passes the bounds as bounds; the zhong2021-shaped QPs
//! of [`crate::random_qp()`] pass them as G rows already). Infinite bounds contribute no row
//! (exp(-sigma * inf) = 0, as the paper's varpi intends).
//!
//! # Network (eq. 2.23-2.30)
//!
//! With c_i = p sigma exp(-sigma N_i) (the i-th penalty multiplier), the error is the Lagrangian
//! gradient phi = D y - u (eq. 2.24-2.25):
//!
//! ```text
//!   phi_x      = P x + q + A' lambda + sum_i c_i B_i'
//!   phi_lambda = A x - b
//! ```
//!
//! and Edot = -gamma exp(t) Phi(phi) (eq. 2.26) gives eq. 2.30, W ydot = -S y - gamma exp(t) Phi(phi) + mu:
//!
//! ```text
//!   W  = [ P + sigma sum c_i B_i'B_i   A' ]     S y = [ Pdot x + sigma sum c_i B_i' (Bdot_i x) + Adot' lambda ]
//!        [ A                           0  ]           [ Adot x                                              ]
//!   mu = [ -qdot - sum c_i (Bdot_i' - sigma B_i' hdot_i) ]
//!        [ bdot                                          ]
//! ```
//!
//! (W is dphi/dy; pσ² e^{-σN} in the paper = sigma c_i here.) The data derivatives come from
//! `qp_dot` (P, q, A, b, G, h, and the bounds' derivatives for the bound rows); with no `qp_dot`
//! the QP is frozen. ydot is solved for with a preallocated LU (`dense_lu`: the in-place
//! elimination of [`super::lu`] at the papers' sizes, faer's past its measured crossover).
//! Activation: linear (2.27), sinh (2.28) or power-sigmoid (2.29), see [`Activation`].
//!
//! Sparse rows (ours): most rows of B are bounds, sign e_j'. Every sum over rows and columns
//! above runs over the entries where B or Bdot is nonzero only, in the same order as the dense
//! sums, whose other terms are exact zeros: the same numbers (up to the sign of a zero) at
//! O(nx nnz(B)) instead of O(nx^2 rows).
//!
//! Numerical guard (ours): the exponent -sigma N_i is capped at [`EXPONENT_CAP`] so a deep
//! violation (N_i < -700/sigma) gives a huge but finite penalty instead of +inf.
//!
//! # Steady state on a frozen QP
//!
//! On a frozen QP phidot = W ydot = -g Phi(phi), so phi -> 0: x tends to the optimum x_p of the
//! penalised problem min x'Px/2 + q'x + P(x) s.t. A x = b, not to the QP's optimum x*. Comparing
//! the two stationarity conditions (P x + q + A'lambda + B'm = 0 with m = c(x_p) for x_p and
//! m = mu* for x*) and using A(x_p - x*) = 0 and mu*_i N_i(x*) = 0:
//!
//! ```text
//!   (x_p - x*)' P (x_p - x*) = sum_i [ c_i N_i(x_p) - c_i N_i(x*) - mu*_i N_i(x_p) ]
//!                           <= sum_i [ p/e + mu*_i max(0, -N_i(x_p)) ]
//! ```
//!
//! since c_i N_i = p (sigma N_i) exp(-sigma N_i) <= p/e, c_i N_i(x*) >= 0, and mu*_i >= 0. So
//! lambda_min(P) |x_p - x*|_2^2 <= m p / e + sum_i mu*_i viol_i(x_p), where a violation satisfies
//! viol_i = ln(c_i / (p sigma)) / sigma: the error scales like sqrt(p) plus
//! sqrt(mu* ln(mu*/(p sigma))/sigma) for active constraints. This is the bound the tests check.
//!
//! # Jacobian (QP data frozen)
//!
//! With F = ydot, dF/dy = W^{-1} (dr/dy - (dW/dy) F), r the right-hand side of 2.30; collecting
//! terms (dc_i/dx = sigma c_i B_i):
//!
//! ```text
//!   W dF/dy = -[Pdot + sigma sum c_i (B_i'Bdot_i + Bdot_i'B_i) - sigma^2 sum c_i (hdot_i - Bdot_i x - B_i F_x) B_i'B_i,  Adot';  Adot, 0]
//!             - g(t) diag(Phi'(phi)) W
//! ```

use super::activation::Activation;
use crate::dense_lu::DenseLu;
use nalgebra::DMatrix;
use qp::{Qp, QpDims};
use settings::NetworkError;

/// Cap on the penalty exponent -sigma N_i (exp(700) ~ 1e304).
pub const EXPONENT_CAP: f64 = 700.0;

/// The penalised Lagrangian's gradient and the implicit network of zhong2021 (2.30) on it
/// (module docs), with its preallocated scratch; the gain g(t) and the activation are the
/// caller's.
#[derive(Clone, Debug)]
pub(super) struct PenaltyCore {
    /// Penalty factor p (eq. 2.19).
    p: f64,
    /// Penalty sharpness sigma (eq. 2.19).
    sigma: f64,
    dims: QpDims,
    /// Inequality rows B (G, then the finite bounds), their derivatives, h and hdot.
    b: DMatrix<f64>,
    bdot: DMatrix<f64>,
    h: Vec<f64>,
    hdot: Vec<f64>,
    rows: usize,
    /// For each joint-command index j, the rows r with B_rj or Bdot_rj nonzero, in increasing
    /// r (module docs, sparse rows); capacity `rows` each, so refilling never allocates.
    rows_of: Vec<Vec<usize>>,
    /// c_i = p sigma exp(-sigma N_i).
    c: Vec<f64>,
    /// Bdot_i x.
    bdot_x: Vec<f64>,
    /// W (eq. 2.30) and its LU factors (nalgebra or faer by size, preallocated).
    w: DMatrix<f64>,
    lu: DenseLu,
    /// phi = D y - u (eq. 2.25).
    phi: Vec<f64>,
    /// F = ydot.
    f: Vec<f64>,
    factored: bool,
}

impl PenaltyCore {
    /// The penalty (p >= 0, sigma > 0) for QPs of sizes `dims`.
    pub(super) fn new(p: f64, sigma: f64, dims: QpDims) -> Result<Self, NetworkError> {
        if !(p >= 0.0 && p.is_finite()) || !(sigma > 0.0 && sigma.is_finite()) {
            return Err(NetworkError::Penalty { p, sigma });
        }
        let rows = dims.n_in + 2 * dims.nx;
        let n = dims.nx + dims.n_eq;
        Ok(Self {
            p,
            sigma,
            dims,
            b: DMatrix::zeros(rows, dims.nx),
            bdot: DMatrix::zeros(rows, dims.nx),
            h: vec![0.0; rows],
            hdot: vec![0.0; rows],
            rows: 0,
            rows_of: vec![Vec::with_capacity(rows); dims.nx],
            c: vec![0.0; rows],
            bdot_x: vec![0.0; rows],
            w: DMatrix::zeros(n, n),
            lu: DenseLu::for_size(n),
            phi: vec![0.0; n],
            f: vec![0.0; n],
            factored: false,
        })
    }

    /// The error phi = D y - u of eq. 2.25 (the penalised Lagrangian's gradient) at the last
    /// evaluation.
    pub(super) fn error(&self) -> &[f64] {
        &self.phi
    }

    /// ydot of the last evaluation (NaN where W was singular).
    pub(super) fn ydot(&self) -> &[f64] {
        &self.f
    }

    /// Gather the inequality rows (module docs) of `qp` and their derivatives.
    fn gather_rows(&mut self, qp: &Qp, qp_dot: Option<&Qp>) {
        let QpDims { nx, n_in, .. } = self.dims;
        let fin = |v: f64| if v.is_finite() { v } else { 0.0 };
        let mut r = 0;
        for k in 0..n_in {
            for j in 0..nx {
                self.b[(r, j)] = qp.g[(k, j)];
                self.bdot[(r, j)] = qp_dot.map_or(0.0, |d| d.g[(k, j)]);
            }
            self.h[r] = qp.h[k];
            self.hdot[r] = qp_dot.map_or(0.0, |d| d.h[k]);
            r += 1;
        }
        for j in 0..nx {
            for (bound, sign, dot) in [
                (qp.upper[j], 1.0, qp_dot.map_or(0.0, |d| fin(d.upper[j]))),
                (-qp.lower[j], -1.0, qp_dot.map_or(0.0, |d| -fin(d.lower[j]))),
            ] {
                if bound.is_finite() {
                    for l in 0..nx {
                        self.b[(r, l)] = 0.0;
                        self.bdot[(r, l)] = 0.0;
                    }
                    self.b[(r, j)] = sign;
                    self.h[r] = bound;
                    self.hdot[r] = dot;
                    r += 1;
                }
            }
        }
        self.rows = r;
        for (j, rows) in self.rows_of.iter_mut().enumerate() {
            rows.clear();
            rows.extend((0..r).filter(|&k| self.b[(k, j)] != 0.0 || self.bdot[(k, j)] != 0.0));
        }
    }

    /// Evaluate phi, W, the right-hand side of eq. 2.30 with gain `g` = g(t) and activation
    /// `activation`, and solve for F = ydot.
    pub(super) fn evaluate(
        &mut self,
        g: f64,
        activation: &Activation,
        y: &[f64],
        qp: &Qp,
        qp_dot: Option<&Qp>,
    ) {
        let QpDims { nx, n_eq, .. } = self.dims;
        debug_assert_eq!(
            qp.dims(),
            self.dims,
            "QP sizes differ from the sizes the network was built for"
        );
        debug_assert_eq!(y.len(), nx + n_eq);
        self.gather_rows(qp, qp_dot);
        let (x, lambda) = y.split_at(nx);
        let (p, sigma) = (self.p, self.sigma);
        // B x and Bdot x over each row's nonzeros (c holds B x until it is overwritten).
        self.c[..self.rows].fill(0.0);
        self.bdot_x[..self.rows].fill(0.0);
        for (j, rows) in self.rows_of.iter().enumerate() {
            for &r in rows {
                self.c[r] += self.b[(r, j)] * x[j];
                self.bdot_x[r] += self.bdot[(r, j)] * x[j];
            }
        }
        for i in 0..self.rows {
            let n_i = self.h[i] - self.c[i];
            self.c[i] = p * sigma * (-sigma * n_i).min(EXPONENT_CAP).exp();
        }
        // W and phi.
        for i in 0..nx {
            for j in 0..nx {
                let mut s = qp.p[(i, j)];
                for &r in &self.rows_of[i] {
                    s += sigma * self.c[r] * self.b[(r, i)] * self.b[(r, j)];
                }
                self.w[(i, j)] = s;
            }
            for k in 0..n_eq {
                self.w[(i, nx + k)] = qp.a[(k, i)];
                self.w[(nx + k, i)] = qp.a[(k, i)];
            }
        }
        for k in 0..n_eq {
            for l in 0..n_eq {
                self.w[(nx + k, nx + l)] = 0.0;
            }
        }
        for i in 0..nx {
            let mut s = qp.q[i];
            for j in 0..nx {
                s += qp.p[(i, j)] * x[j];
            }
            for k in 0..n_eq {
                s += qp.a[(k, i)] * lambda[k];
            }
            for &r in &self.rows_of[i] {
                s += self.c[r] * self.b[(r, i)];
            }
            self.phi[i] = s;
        }
        for k in 0..n_eq {
            let mut s = -qp.b[k];
            for j in 0..nx {
                s += qp.a[(k, j)] * x[j];
            }
            self.phi[nx + k] = s;
        }
        // r = -S y - g Phi(phi) + mu.
        for i in 0..(nx + n_eq) {
            self.f[i] = -g * activation.value(self.phi[i]);
        }
        if let Some(d) = qp_dot {
            for i in 0..nx {
                let mut s = -d.q[i];
                for j in 0..nx {
                    s -= d.p[(i, j)] * x[j];
                }
                for k in 0..n_eq {
                    s -= d.a[(k, i)] * lambda[k];
                }
                for &r in &self.rows_of[i] {
                    let c = self.c[r];
                    s -= sigma * c * self.b[(r, i)] * self.bdot_x[r];
                    s -= c * (self.bdot[(r, i)] - sigma * self.b[(r, i)] * self.hdot[r]);
                }
                self.f[i] += s;
            }
            for k in 0..n_eq {
                let mut s = d.b[k];
                for j in 0..nx {
                    s -= d.a[(k, j)] * x[j];
                }
                self.f[nx + k] += s;
            }
        }
        self.factored = self.lu.factor(&self.w);
        if self.factored {
            self.lu.solve(&mut self.f);
        } else {
            self.f.fill(f64::NAN);
        }
    }

    /// dF/dy (module docs) with gain `g` = g(t) and activation `activation`; false where W is
    /// singular.
    pub(super) fn jacobian(
        &mut self,
        g: f64,
        activation: &Activation,
        y: &[f64],
        qp: &Qp,
        qp_dot: Option<&Qp>,
        jac: &mut DMatrix<f64>,
    ) -> bool {
        self.evaluate(g, activation, y, qp, qp_dot);
        if !self.factored {
            return false;
        }
        let QpDims { nx, n_eq, .. } = self.dims;
        let n = nx + n_eq;
        let sigma = self.sigma;
        // -g diag(Phi'(phi)) W.
        for i in 0..n {
            let s = g * activation.derivative(self.phi[i]);
            for j in 0..n {
                jac[(i, j)] = -s * self.w[(i, j)];
            }
        }
        // sigma^2 sum c_i (hdot_i - Bdot_i x - B_i F_x) B_i'B_i (the F_x part is -(dW/dy) F).
        for r in 0..self.rows {
            let mut bf = 0.0;
            for j in 0..nx {
                bf += self.b[(r, j)] * self.f[j];
            }
            let hd = self.hdot[r] - self.bdot_x[r];
            let coef = sigma * sigma * self.c[r] * (hd - bf);
            if coef == 0.0 {
                continue;
            }
            for i in 0..nx {
                let bi = self.b[(r, i)];
                if bi == 0.0 {
                    continue;
                }
                for j in 0..nx {
                    jac[(i, j)] += coef * bi * self.b[(r, j)];
                }
            }
        }
        if let Some(d) = qp_dot {
            for i in 0..nx {
                for j in 0..nx {
                    let mut s = d.p[(i, j)];
                    for r in 0..self.rows {
                        s += sigma
                            * self.c[r]
                            * (self.b[(r, i)] * self.bdot[(r, j)]
                                + self.bdot[(r, i)] * self.b[(r, j)]);
                    }
                    jac[(i, j)] -= s;
                }
            }
            for k in 0..n_eq {
                for j in 0..nx {
                    jac[(j, nx + k)] -= d.a[(k, j)];
                    jac[(nx + k, j)] -= d.a[(k, j)];
                }
            }
        }
        self.lu.solve_columns(jac);
        true
    }
}
