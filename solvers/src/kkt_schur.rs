//! The KKT system of an equality-constrained QP solved through the Schur complement of a
//! positive definite P: the active-set solver's fast factorisation ([`crate::active_set`]).
//!
//! For P (n x n) symmetric positive definite and C (m x n) of full row rank,
//!
//! ```text
//! [ P  C' ] [ x ]   [ r1 ]            P = L L'            (Cholesky)
//! [ C  0  ] [ y ] = [ r2 ]    with    Y = (L^-1 C')'      (m x n: row i = L^-1 c_i)
//!                                     S = C P^-1 C' = Y Y' = M M'   (Cholesky)
//! ```
//!
//! is solved by u = L^-1 r1, S y = Y u - r2, x = L^-T (u - Y'y): from P x + C'y = r1,
//! x = P^-1 (r1 - C'y), and C x = r2 gives C P^-1 r1 - S y = r2. The cost is n^3/6 + m n^2 / 2
//! plus m^2 n / 2 + m^3 / 6 multiply-adds against (n + m)^3 / 3 for an LU of the whole matrix, and
//! both Cholesky factorisations need no pivoting. A pivot of L or M at or below
//! [`PIVOT_TOL`] times the largest diagonal entry of P or S refuses the factorisation (P not
//! positive definite, or C rank deficient): the caller then factorises the whole matrix by LU.
//!
//! Buffers are sized at construction ([`SchurKkt::reserve`]); factorising and solving allocate
//! nothing.

/// Relative pivot below which P or S counts as singular.
pub const PIVOT_TOL: f64 = 1e-13;

/// The factors of one KKT matrix (see the module docs).
#[derive(Clone, Debug, Default)]
pub struct SchurKkt {
    n: usize,
    m: usize,
    /// L, row-major n x n (lower triangle).
    l: Vec<f64>,
    /// Y, row-major m x n.
    y: Vec<f64>,
    /// M, row-major m x m (lower triangle).
    s: Vec<f64>,
    /// Scratch of length n.
    u: Vec<f64>,
}

impl SchurKkt {
    /// Grows the buffers to n variables and m rows (no-op if they are large enough).
    pub fn reserve(&mut self, n: usize, m: usize) {
        if self.l.len() < n * n {
            self.l.resize(n * n, 0.0);
            self.u.resize(n, 0.0);
        }
        if self.y.len() < m * n {
            self.y.resize(m * n, 0.0);
        }
        if self.s.len() < m * m {
            self.s.resize(m * m, 0.0);
        }
    }

    /// Factorises the KKT matrix of `p(i, j)` (n x n) and the rows `c` (row-major m x n);
    /// false if P is not positive definite or C not of full row rank (module docs). The
    /// buffers must have been reserved for (n, m).
    pub fn factor(
        &mut self,
        n: usize,
        m: usize,
        p: impl Fn(usize, usize) -> f64,
        c: &[f64],
    ) -> bool {
        self.n = n;
        self.m = m;
        let l = &mut self.l[..n * n];
        let mut pmax: f64 = 0.0;
        for i in 0..n {
            pmax = pmax.max(p(i, i).abs());
        }
        if !(pmax > 0.0 && pmax.is_finite()) || !cholesky(l, n, &p, PIVOT_TOL * pmax) {
            return false;
        }
        let y = &mut self.y[..m * n];
        for r in 0..m {
            let row = &mut y[r * n..(r + 1) * n];
            row.copy_from_slice(&c[r * n..(r + 1) * n]);
            forward(l, n, row);
        }
        if m == 0 {
            return true;
        }
        let y = &self.y[..m * n];
        let dot = |a: usize, b: usize| -> f64 {
            let (ra, rb) = (&y[a * n..(a + 1) * n], &y[b * n..(b + 1) * n]);
            ra.iter().zip(rb).map(|(u, v)| u * v).sum()
        };
        let mut smax: f64 = 0.0;
        for i in 0..m {
            smax = smax.max(dot(i, i));
        }
        if !(smax > 0.0 && smax.is_finite()) {
            return false;
        }
        cholesky(&mut self.s[..m * m], m, &dot, PIVOT_TOL * smax)
    }

    /// Solves the factorised system for `rhs` = [r1; r2] (length n + m), in place.
    pub fn solve(&mut self, rhs: &mut [f64]) {
        let (n, m) = (self.n, self.m);
        let (l, y, s) = (&self.l[..n * n], &self.y[..m * n], &self.s[..m * m]);
        let (top, bottom) = rhs[..n + m].split_at_mut(n);
        let u = &mut self.u[..n];
        u.copy_from_slice(top);
        forward(l, n, u);
        // S y = Y u - r2, into `bottom`.
        for r in 0..m {
            let row = &y[r * n..(r + 1) * n];
            let yu: f64 = row.iter().zip(u.iter()).map(|(a, b)| a * b).sum();
            bottom[r] = yu - bottom[r];
        }
        forward(s, m, bottom);
        backward(s, m, bottom);
        // x = L^-T (u - Y'y), into `top`.
        top.copy_from_slice(u);
        for r in 0..m {
            let row = &y[r * n..(r + 1) * n];
            for (t, a) in top.iter_mut().zip(row) {
                *t -= a * bottom[r];
            }
        }
        backward(l, n, top);
    }
}

/// Cholesky factor (lower, row-major) of the n x n symmetric matrix `a(i, j)` into `l`; false
/// if a pivot is at or below `tol` (or NaN).
fn cholesky(l: &mut [f64], n: usize, a: &impl Fn(usize, usize) -> f64, tol: f64) -> bool {
    for i in 0..n {
        for j in 0..=i {
            let mut sum = a(i, j);
            for k in 0..j {
                sum -= l[i * n + k] * l[j * n + k];
            }
            if i == j {
                if !(sum > tol) {
                    return false;
                }
                l[i * n + i] = sum.sqrt();
            } else {
                l[i * n + j] = sum / l[j * n + j];
            }
        }
    }
    true
}

/// Solves L v = b in place (L lower, row-major n x n).
fn forward(l: &[f64], n: usize, b: &mut [f64]) {
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i * n + k] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
}

/// Solves L' v = b in place.
fn backward(l: &[f64], n: usize, b: &mut [f64]) {
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[k * n + i] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_kkt_system_and_refuses_singular_ones() {
        // P = [[4, 1], [1, 3]] ⊕ 2, C = [1 1 1]: the solution of a system built from it.
        let p = [[4.0, 1.0, 0.0], [1.0, 3.0, 0.0], [0.0, 0.0, 2.0]];
        let c = [1.0, 1.0, 1.0];
        let (x, y) = ([0.5, -0.25, 1.0], 0.75);
        let mut rhs = vec![0.0; 4];
        for i in 0..3 {
            rhs[i] = (0..3).map(|j| p[i][j] * x[j]).sum::<f64>() + c[i] * y;
        }
        rhs[3] = (0..3).map(|j| c[j] * x[j]).sum();
        let mut kkt = SchurKkt::default();
        kkt.reserve(3, 1);
        assert!(kkt.factor(3, 1, |i, j| p[i][j], &c));
        kkt.solve(&mut rhs);
        for (got, want) in rhs.iter().zip([x[0], x[1], x[2], y]) {
            assert!((got - want).abs() < 1e-14, "{rhs:?}");
        }
        // P singular (a zero row), or C with two equal rows: refused.
        assert!(!kkt.factor(
            3,
            1,
            |i, j| if i == 2 || j == 2 { 0.0 } else { p[i][j] },
            &c
        ));
        kkt.reserve(3, 2);
        assert!(!kkt.factor(3, 2, |i, j| p[i][j], &[1.0, 1.0, 1.0, 1.0, 1.0, 1.0]));
    }
}
