//! The quadratic program every scheme produces at every instant ([`Qp`]: the form and the KKT
//! conventions are on the type), its sizes, multipliers and KKT residuals.

use crate::error::QpError;
use nalgebra::{DMatrix, DVector};

/// Sizes of a QP: variables, equality rows, inequality rows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QpDims {
    /// Number of variables: the length of x.
    pub nx: usize,
    /// Number of equality rows A x = b.
    pub n_eq: usize,
    /// Number of inequality rows G x <= h.
    pub n_in: usize,
}

/// A dense convex QP, the quadratic program every scheme produces at every instant:
///
/// ```text
/// minimise    x'Px/2 + q'x
/// subject to  A x  = b          (m_eq rows)
///             G x <= h          (m_in rows)
///             l <= x <= u       (elementwise; +-inf where a bound is absent)
/// ```
///
/// P is symmetric positive semidefinite. The storage is dense (the papers' QPs have at most
/// ~10 variables) and allocated once per run: schemes overwrite it in place at every step.
///
/// KKT conditions with multipliers (lambda for A x = b, mu >= 0 for G x <= h,
/// z_l, z_u >= 0 for the bounds):
/// stationarity  P x + q + A'lambda + G'mu - z_l + z_u = 0,
/// primal        A x = b, G x <= h, l <= x <= u,
/// complementarity mu_i (h - Gx)_i = 0, z_l (x - l) = 0, z_u (u - x) = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Qp {
    /// P: the objective's Hessian (nx x nx, symmetric positive semidefinite).
    pub p: DMatrix<f64>,
    /// q: the objective's linear term (length nx).
    pub q: DVector<f64>,
    /// A: the equality matrix (n_eq x nx).
    pub a: DMatrix<f64>,
    /// b: the equality right-hand side (length n_eq).
    pub b: DVector<f64>,
    /// G: the inequality matrix (n_in x nx).
    pub g: DMatrix<f64>,
    /// h: the inequality right-hand side (length n_in; +inf where a row is absent).
    pub h: DVector<f64>,
    /// l: the variables' lower bounds (length nx; -inf where absent).
    pub lower: DVector<f64>,
    /// u: the variables' upper bounds (length nx; +inf where absent).
    pub upper: DVector<f64>,
}

/// Multipliers of a QP solution (sign conventions as in [`Qp`]'s docs).
#[derive(Clone, Debug, PartialEq)]
pub struct QpDuals {
    /// lambda: multipliers of A x = b, one per equality row (either sign).
    pub lambda: DVector<f64>,
    /// mu >= 0: multipliers of G x <= h, one per inequality row.
    pub mu: DVector<f64>,
    /// z_l >= 0: multipliers of the lower bounds l <= x, one per variable.
    pub z_lower: DVector<f64>,
    /// z_u >= 0: multipliers of the upper bounds x <= u, one per variable.
    pub z_upper: DVector<f64>,
}

/// Infinity-norm KKT residuals of a primal-dual pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KktResiduals {
    /// max violation of A x = b, G x <= h and the bounds.
    pub primal: f64,
    /// |P x + q + A'lambda + G'mu - z_l + z_u|_inf, plus any negative multiplier.
    pub dual: f64,
    /// max |mu_i (h - Gx)_i|, |z_l (x - l)|, |z_u (u - x)| over finite bounds.
    pub complementarity: f64,
}

impl KktResiduals {
    /// Largest of the three residuals.
    pub fn max(&self) -> f64 {
        self.primal.max(self.dual).max(self.complementarity)
    }
}

impl QpDuals {
    /// Zero multipliers sized for QPs of `dims`.
    pub fn zeros(dims: QpDims) -> Self {
        QpDuals {
            lambda: DVector::zeros(dims.n_eq),
            mu: DVector::zeros(dims.n_in),
            z_lower: DVector::zeros(dims.nx),
            z_upper: DVector::zeros(dims.nx),
        }
    }
}

impl Qp {
    /// A QP of the given sizes with all data zero and no bounds.
    pub fn zeros(dims: QpDims) -> Self {
        let QpDims { nx, n_eq, n_in } = dims;
        Self {
            p: DMatrix::zeros(nx, nx),
            q: DVector::zeros(nx),
            a: DMatrix::zeros(n_eq, nx),
            b: DVector::zeros(n_eq),
            g: DMatrix::zeros(n_in, nx),
            h: DVector::zeros(n_in),
            lower: DVector::from_element(nx, f64::NEG_INFINITY),
            upper: DVector::from_element(nx, f64::INFINITY),
        }
    }

    /// Checks the data: every matrix and vector of the sizes q, b and h imply, P, q, A, b and G
    /// finite, and the one-sided data on its own side (h_i, u_i never -inf, l_i never +inf; no
    /// NaN). The message names the offending field.
    pub fn validate(&self) -> Result<(), QpError> {
        let (nx, n_eq, n_in) = (self.q.len(), self.b.len(), self.h.len());
        let shapes = [
            ("P", self.p.shape(), (nx, nx)),
            ("A", self.a.shape(), (n_eq, nx)),
            ("G", self.g.shape(), (n_in, nx)),
            ("lower", self.lower.shape(), (nx, 1)),
            ("upper", self.upper.shape(), (nx, 1)),
        ];
        for (name, got, want) in shapes {
            if got != want {
                return Err(QpError::Shape {
                    field: name,
                    got,
                    expected: want,
                });
            }
        }
        let finite = [
            ("P", self.p.as_slice()),
            ("q", self.q.as_slice()),
            ("A", self.a.as_slice()),
            ("b", self.b.as_slice()),
            ("G", self.g.as_slice()),
        ];
        for (name, data) in finite {
            if data.iter().any(|v| !v.is_finite()) {
                return Err(QpError::NonFinite { field: name });
            }
        }
        let one_sided = [
            ("h", self.h.as_slice(), f64::NEG_INFINITY),
            ("upper", self.upper.as_slice(), f64::NEG_INFINITY),
            ("lower", self.lower.as_slice(), f64::INFINITY),
        ];
        for (name, data, wrong) in one_sided {
            if data.iter().any(|&v| v.is_nan() || v == wrong) {
                return Err(QpError::WrongSide { field: name, wrong });
            }
        }
        Ok(())
    }

    /// Largest difference over every entry of two QPs of the same shape, relative to
    /// max(1, |self entry|), equal entries (infinite bounds too) counting 0. For comparing a QP
    /// with one built another way (a derivative against its difference quotient, say).
    pub fn max_rel_diff(&self, other: &Qp) -> f64 {
        let pairs: [(&[f64], &[f64]); 8] = [
            (self.p.as_slice(), other.p.as_slice()),
            (self.q.as_slice(), other.q.as_slice()),
            (self.a.as_slice(), other.a.as_slice()),
            (self.b.as_slice(), other.b.as_slice()),
            (self.g.as_slice(), other.g.as_slice()),
            (self.h.as_slice(), other.h.as_slice()),
            (self.lower.as_slice(), other.lower.as_slice()),
            (self.upper.as_slice(), other.upper.as_slice()),
        ];
        let mut d: f64 = 0.0;
        for (x, y) in pairs {
            assert_eq!(x.len(), y.len(), "QPs of different shapes");
            for (&u, &v) in x.iter().zip(y).filter(|(u, v)| u != v) {
                d = d.max((u - v).abs() / u.abs().max(1.0));
            }
        }
        d
    }

    /// The sizes q, b and h imply.
    pub fn dims(&self) -> QpDims {
        QpDims {
            nx: self.q.len(),
            n_eq: self.b.len(),
            n_in: self.h.len(),
        }
    }

    /// Objective x'Px/2 + q'x, allocating nothing (the score of every observed step calls it),
    /// with the roundings of nalgebra's `0.5 * x.dot(&(&p * x)) + q.dot(x)`: each (P x)_i
    /// summed as `row_times` sums it, x'(P x) in the order of nalgebra's dot product
    /// (`dot_order_sum`).
    pub fn objective(&self, x: &DVector<f64>) -> f64 {
        let (p, nx, xs) = (self.p.as_slice(), self.p.nrows(), x.as_slice());
        0.5 * dot_order_sum(xs.len(), |i| xs[i] * row_times(p, nx, i, xs)) + self.q.dot(x)
    }

    /// Largest violation of any constraint at x (0 when x is feasible), allocating nothing:
    /// |A x - b|_inf (folded from its first entry as nalgebra's `amax` folds, m >= v ? m : v),
    /// then G x - h and the bounds, each product's entries summed as `row_times` sums them.
    pub fn constraint_violation(&self, x: &DVector<f64>) -> f64 {
        let xs = x.as_slice();
        let mut v: f64 = 0.0;
        if !self.b.is_empty() {
            let (a, rows) = (self.a.as_slice(), self.a.nrows());
            let residual = |r: usize| (row_times(a, rows, r, xs) - self.b[r]).abs();
            let amax = (1..self.b.len()).fold(residual(0), |m, r| {
                let v = residual(r);
                if m >= v {
                    m
                } else {
                    v
                }
            });
            v = v.max(amax);
        }
        let (g, rows) = (self.g.as_slice(), self.g.nrows());
        for (i, h) in self.h.iter().enumerate() {
            v = v.max(row_times(g, rows, i, xs) - h);
        }
        for i in 0..x.len() {
            v = v.max(self.lower[i] - x[i]).max(x[i] - self.upper[i]);
        }
        v
    }

    /// KKT residuals of (x, duals) (see [`Qp`]'s docs). Allocates nothing (the certification
    /// of every hot-started exact solve calls it).
    pub fn kkt_residuals(&self, x: &DVector<f64>, d: &QpDuals) -> KktResiduals {
        let xs = x.as_slice();
        let nx = xs.len();
        let (n_eq, n_in) = (self.b.len(), self.h.len());
        let (p, a, g) = (self.p.as_slice(), self.a.as_slice(), self.g.as_slice());
        let (lambda, mu) = (d.lambda.as_slice(), d.mu.as_slice());
        let mut primal: f64 = 0.0;
        let mut comp: f64 = 0.0;
        for (r, b) in self.b.iter().enumerate() {
            primal = primal.max((row_dot(a, n_eq, r, xs) - b).abs());
        }
        for (r, (h, mu)) in self.h.iter().zip(mu).enumerate() {
            let gx = row_dot(g, n_in, r, xs);
            primal = primal.max(gx - h);
            // (An absent row, h = +inf, counts only if its multiplier is not zero.)
            if *mu != 0.0 {
                comp = comp.max((mu * (h - gx)).abs());
            }
        }
        let mut dual: f64 = 0.0;
        for i in 0..nx {
            let (xi, lower, upper) = (xs[i], self.lower[i], self.upper[i]);
            primal = primal.max(lower - xi).max(xi - upper);
            // Row i of P x + q + A'lambda + G'mu - z_l + z_u.
            let a_i = &a[i * n_eq..(i + 1) * n_eq];
            let g_i = &g[i * n_in..(i + 1) * n_in];
            let stat = self.q[i] - d.z_lower[i]
                + d.z_upper[i]
                + row_dot(p, nx, i, xs)
                + dot_order_sum(n_eq, |k| a_i[k] * lambda[k])
                + dot_order_sum(n_in, |k| g_i[k] * mu[k]);
            dual = dual.max(stat.abs());
            if lower.is_finite() {
                comp = comp.max((d.z_lower[i] * (xi - lower)).abs());
            }
            if upper.is_finite() {
                comp = comp.max((d.z_upper[i] * (upper - xi)).abs());
            }
        }
        for m in d.mu.iter().chain(d.z_lower.iter()).chain(d.z_upper.iter()) {
            dual = dual.max(-m);
        }
        KktResiduals {
            primal,
            dual,
            complementarity: comp,
        }
    }
}

/// Row i of M x for a column-major M with `rows` rows, rounded as nalgebra's `tr_dot` of the
/// row with x rounds it: 0 + M_i0 x_0, then + M_ij x_j for j = 1, 2, ....
fn row_dot(m: &[f64], rows: usize, i: usize, x: &[f64]) -> f64 {
    let mut s = 0.0;
    for (j, xj) in x.iter().enumerate() {
        s += m[i + j * rows] * xj;
    }
    s
}

/// Row i of M x for a column-major M with `rows` rows and x's length columns, rounded as
/// nalgebra's matrix-vector product (`gemv`, column by column) rounds it: M_i0 x_0, then
/// M_ij x_j + the sum so far for j = 1, 2, ... (0 for an empty x).
fn row_times(m: &[f64], rows: usize, i: usize, x: &[f64]) -> f64 {
    let mut terms = x.iter().enumerate().map(|(j, xj)| m[i + j * rows] * xj);
    let first = terms.next().unwrap_or(0.0);
    terms.fold(first, |s, v| v + s)
}

/// The sum of `term(i)` for i < n in the order nalgebra's dot product of two dynamic vectors
/// adds its products: eight running sums (from 0) over each whole block of eight, added to
/// the result (from 0) in the pairs (0, 4), (1, 5), (2, 6), (3, 7), then the rest one by one.
fn dot_order_sum(n: usize, term: impl Fn(usize) -> f64) -> f64 {
    let mut acc = [0.0f64; 8];
    let mut i = 0;
    while n - i >= 8 {
        for (k, a) in acc.iter_mut().enumerate() {
            *a += term(i + k);
        }
        i += 8;
    }
    let mut res = 0.0;
    for k in 0..4 {
        res += acc[k] + acc[k + 4];
    }
    for k in i..n {
        res += term(k);
    }
    res
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniform in [-1, 1), with a zero of either sign, a tie and a NaN now and then.
    fn entries(state: &mut u64, n: usize) -> Vec<f64> {
        (0..n)
            .map(|_| {
                *state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let u = (*state >> 11) as f64 / (1u64 << 53) as f64;
                match *state % 41 {
                    0 => 0.0,
                    1 => -0.0,
                    2 => 0.5,
                    3 => f64::NAN,
                    _ => 2.0 * u - 1.0,
                }
            })
            .collect()
    }

    /// A QP of sizes `dims` with every entry of P, q, A, b, G and h from [`entries`] (bounds
    /// infinite).
    fn random_qp(state: &mut u64, dims: QpDims) -> Qp {
        let QpDims { nx, n_eq, n_in } = dims;
        let mut qp = Qp::zeros(dims);
        qp.p.copy_from_slice(&entries(state, nx * nx));
        qp.q.copy_from_slice(&entries(state, nx));
        qp.a.copy_from_slice(&entries(state, n_eq * nx));
        qp.b.copy_from_slice(&entries(state, n_eq));
        qp.g.copy_from_slice(&entries(state, n_in * nx));
        qp.h.copy_from_slice(&entries(state, n_in));
        qp
    }

    /// The objective and the violation carry the bits of the nalgebra expressions they
    /// replace (which allocate), for every size up to 20 variables and 19 rows (the dot
    /// product's blocks of eight included), zeros of either sign and NaN among the data.
    #[test]
    fn objective_and_violation_round_as_nalgebra_does() {
        let mut state = 3u64;
        for nx in 0usize..=20 {
            for (n_eq, n_in) in [(0, 0), (1, 2), (3, 0), (nx.saturating_sub(1), 19)] {
                for _ in 0..20 {
                    let mut qp = random_qp(&mut state, QpDims { nx, n_eq, n_in });
                    qp.lower.fill(-0.75);
                    let x = DVector::from_vec(entries(&mut state, nx));
                    let objective = 0.5 * x.dot(&(&qp.p * &x)) + qp.q.dot(&x);
                    assert_eq!(qp.objective(&x).to_bits(), objective.to_bits(), "nx {nx}");
                    let mut v: f64 = 0.0;
                    if n_eq > 0 {
                        v = v.max((&qp.a * &x - &qp.b).amax());
                    }
                    if n_in > 0 {
                        let gx = &qp.g * &x;
                        for i in 0..n_in {
                            v = v.max(gx[i] - qp.h[i]);
                        }
                    }
                    for i in 0..nx {
                        v = v.max(qp.lower[i] - x[i]).max(x[i] - qp.upper[i]);
                    }
                    assert_eq!(qp.constraint_violation(&x).to_bits(), v.to_bits());
                }
            }
        }
    }

    /// The KKT residuals carry the bits of the nalgebra expressions they replace (row views'
    /// `tr_dot`, columns' `dot`), for every size up to 20 variables and 19 rows, zeros of
    /// either sign and NaN among the data and the multipliers, finite and infinite bounds.
    #[test]
    fn kkt_residuals_round_as_nalgebra_does() {
        let mut state = 5u64;
        for nx in 0usize..=20 {
            for (n_eq, n_in) in [(0, 0), (1, 2), (3, 0), (nx.saturating_sub(1), 19)] {
                for case in 0..20 {
                    let dims = QpDims { nx, n_eq, n_in };
                    let mut qp = random_qp(&mut state, dims);
                    if case % 2 == 0 {
                        qp.lower.fill(-0.75);
                        qp.upper.fill(0.5);
                    }
                    let x = DVector::from_vec(entries(&mut state, nx));
                    let mut d = QpDuals::zeros(dims);
                    d.lambda.copy_from_slice(&entries(&mut state, n_eq));
                    d.mu.copy_from_slice(&entries(&mut state, n_in));
                    d.z_lower.copy_from_slice(&entries(&mut state, nx));
                    d.z_upper.copy_from_slice(&entries(&mut state, nx));
                    let (mut primal, mut comp, mut dual) = (0.0f64, 0.0f64, 0.0f64);
                    for (r, b) in qp.b.iter().enumerate() {
                        primal = primal.max((qp.a.row(r).tr_dot(&x) - b).abs());
                    }
                    for (r, (h, mu)) in qp.h.iter().zip(d.mu.iter()).enumerate() {
                        let gx = qp.g.row(r).tr_dot(&x);
                        primal = primal.max(gx - h);
                        if *mu != 0.0 {
                            comp = comp.max((mu * (h - gx)).abs());
                        }
                    }
                    for i in 0..nx {
                        let (xi, lower, upper) = (x[i], qp.lower[i], qp.upper[i]);
                        primal = primal.max(lower - xi).max(xi - upper);
                        let stat = qp.q[i] - d.z_lower[i]
                            + d.z_upper[i]
                            + qp.p.row(i).tr_dot(&x)
                            + qp.a.column(i).dot(&d.lambda)
                            + qp.g.column(i).dot(&d.mu);
                        dual = dual.max(stat.abs());
                        if lower.is_finite() {
                            comp = comp.max((d.z_lower[i] * (xi - lower)).abs());
                        }
                        if upper.is_finite() {
                            comp = comp.max((d.z_upper[i] * (upper - xi)).abs());
                        }
                    }
                    for m in d.mu.iter().chain(d.z_lower.iter()).chain(d.z_upper.iter()) {
                        dual = dual.max(-m);
                    }
                    let ours = qp.kkt_residuals(&x, &d);
                    let bits =
                        |k: &KktResiduals| [k.primal, k.dual, k.complementarity].map(f64::to_bits);
                    let expected = KktResiduals {
                        primal,
                        dual,
                        complementarity: comp,
                    };
                    assert_eq!(bits(&ours), bits(&expected), "nx {nx}, case {case}");
                }
            }
        }
    }
}
