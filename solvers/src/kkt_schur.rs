//! The KKT system of an equality-constrained QP solved through the Schur complement of a
//! positive definite P, factorised row by row so that a working set that changes by one row
//! costs one row of work: the active-set solver's fast factorisation ([`crate::active_set`]).
//!
//! # The factorisation
//!
//! For P (n x n) symmetric positive definite and C (m x n) of full row rank with rows c_r,
//!
//! ```text
//! [ P  C' ] [ x ]   [ r1 ]            P = L L'            (Cholesky)
//! [ C  0  ] [ y ] = [ r2 ]    with    y_r = L^-1 c_r      (row r of Y, m x n)
//!                                     S = C P^-1 C' = Y Y' = M M'   (Cholesky)
//! ```
//!
//! is solved by u = L^-1 r1, S y = Y u - r2, x = L^-T (u - Y'y): from P x + C'y = r1,
//! x = P^-1 (r1 - C'y), and C x = r2 gives C P^-1 r1 - S y = r2.
//!
//! # Row updates
//!
//! L depends on P only, and y_r on P and c_r only: [`SchurKkt::factor_p`] computes L once per
//! P (the active-set solver keeps it while P is unchanged), and a row's y_r is computed once,
//! when the row joins C ([`SchurKkt::stage`], [`SchurKkt::commit`]). Row i of the Cholesky
//! factor M depends only on rows 0..=i of S, i.e. on y_0, ..., y_i:
//!
//! ```text
//! M_ij = (S_ij - sum_{k<j} M_ik M_jk) / M_jj   (j < i),     M_ii = sqrt(S_ii - sum_{k<i} M_ik^2)
//! ```
//!
//! so appending a row of C adds one row of M (m n + m^2/2 multiply-adds), and removing row s
//! leaves rows 0..s of M as they are and recomputes rows s.. ([`SchurKkt::factor_rows`]
//! computes whatever rows are not yet valid). The factors are the same numbers a
//! factorisation from scratch computes, in the same order of operations, and a solve performs
//! the operations of revision 7c49228's solve with factors from scratch, in the same order, so
//! its answers are that revision's, bit for bit (the exact column's runs integrate them with
//! adaptive steps, which turn a last-bit change into a different step sequence).
//!
//! A pivot of L at or below [`PIVOT_TOL`] times the largest diagonal entry of P refuses P (not
//! positive definite); a pivot sum S_ii - sum M_ik^2 at or below [`PIVOT_TOL`] times the largest
//! S_ii refuses C (rank deficient): the caller then factorises the whole matrix by LU.
//!
//! # Diagonal P
//!
//! When P is diagonal (as in jia2019's, zhong2021's and kong2019's QPs), so is L, and the
//! triangular solves with L reduce to n divisions: skipping the products with the zero entries
//! of L changes no value (x - 0 y = x for finite y).
//!
//! Buffers are sized at construction ([`SchurKkt::reserve`]); factorising and solving allocate
//! nothing.

/// Relative pivot below which P or S counts as singular.
pub const PIVOT_TOL: f64 = 1e-13;

/// The factors of one KKT matrix, updated row by row (see the module docs).
#[derive(Clone, Debug, Default)]
pub struct SchurKkt {
    n: usize,
    /// Whether P, hence L, is diagonal.
    diagonal: bool,
    /// L, row-major n x n (lower triangle).
    l: Vec<f64>,
    /// Y, row-major (m + 1) x n: the rows of C, then the staged row.
    y: Vec<f64>,
    /// |y_r|^2 = S_rr.
    y_sq: Vec<f64>,
    /// M, row-major with row stride `cap` (lower triangle).
    s: Vec<f64>,
    /// The pivot sums S_ii - sum_{k<i} M_ik^2 of the rows of M.
    pivot_sums: Vec<f64>,
    /// Rows M has room for.
    cap: usize,
    /// Rows of C.
    m: usize,
    /// Leading rows of M that are up to date.
    valid: usize,
}

impl SchurKkt {
    /// Grows the buffers to n variables and m rows (no-op if they are large enough).
    pub fn reserve(&mut self, n: usize, m: usize) {
        if self.l.len() < n * n {
            self.l.resize(n * n, 0.0);
        }
        if self.y.len() < (m + 1) * n {
            self.y.resize((m + 1) * n, 0.0);
        }
        if self.cap < m {
            // M's row stride changes: its rows are recomputed.
            self.cap = m;
            self.s.resize(m * m, 0.0);
            self.y_sq.resize(m + 1, 0.0);
            self.pivot_sums.resize(m, 0.0);
            self.valid = 0;
        }
    }

    /// Factorises P = L L' (`p` row-major n x n, p[i n + j] = P_ij, its lower triangle read);
    /// false if P is not positive definite (module docs). Forgets every row of C. The buffers
    /// must have been reserved for n.
    pub fn factor_p(&mut self, n: usize, p: &[f64]) -> bool {
        self.n = n;
        self.m = 0;
        self.valid = 0;
        let mut pmax: f64 = 0.0;
        for i in 0..n {
            pmax = pmax.max(p[i * n + i].abs());
        }
        self.diagonal = (0..n).all(|i| (0..n).all(|j| i == j || p[i * n + j] == 0.0));
        pmax > 0.0
            && pmax.is_finite()
            && cholesky(
                &mut self.l[..n * n],
                n,
                &|i, j| p[i * n + j],
                PIVOT_TOL * pmax,
            )
    }

    /// Whether the last P factorised is diagonal.
    pub fn is_diagonal(&self) -> bool {
        self.diagonal
    }

    /// Solves L v = b in place (b of length n).
    pub fn forward(&self, b: &mut [f64]) {
        let n = self.n;
        lower_solve(&self.l[..n * n], n, self.diagonal, &mut b[..n]);
    }

    /// Solves L' v = b in place (b of length n).
    fn backward(&self, b: &mut [f64]) {
        let n = self.n;
        let l = &self.l[..n * n];
        if self.diagonal {
            for (i, v) in b[..n].iter_mut().enumerate() {
                *v /= l[i * n + i];
            }
        } else {
            backward(l, n, &mut b[..n]);
        }
    }

    /// Computes y = L^-1 c for a row `c` (length n) that is about to join C, into the staging
    /// row ([`Self::staged`]); [`Self::commit`] appends it.
    pub fn stage(&mut self, c: &[f64]) {
        let n = self.n;
        let base = self.m * n;
        let row = &mut self.y[base..base + n];
        row.copy_from_slice(&c[..n]);
        lower_solve(&self.l[..n * n], n, self.diagonal, row);
    }

    /// The staged row L^-1 c ([`Self::stage`]).
    pub fn staged(&self) -> &[f64] {
        &self.y[self.m * self.n..(self.m + 1) * self.n]
    }

    /// Appends the staged row to C (its row of M is computed by [`Self::factor_rows`]). The
    /// buffers must have been reserved for the new number of rows.
    pub fn commit(&mut self) {
        let row = self.staged();
        self.y_sq[self.m] = row.iter().map(|v| v * v).sum();
        self.m += 1;
    }

    /// Removes row `r` of C.
    pub fn remove(&mut self, r: usize) {
        let n = self.n;
        self.y.copy_within((r + 1) * n..self.m * n, r * n);
        self.y_sq.copy_within(r + 1..self.m, r);
        self.m -= 1;
        self.valid = self.valid.min(r);
    }

    /// Keeps the first `m` rows of C.
    pub fn truncate(&mut self, m: usize) {
        self.m = self.m.min(m);
        self.valid = self.valid.min(self.m);
    }

    /// Brings M up to date with the rows of C (module docs); false if C is rank deficient.
    pub fn factor_rows(&mut self) -> bool {
        let (n, m, cap) = (self.n, self.m, self.cap);
        if m == 0 {
            return true;
        }
        let smax = self.y_sq[..m].iter().fold(0.0f64, |a, &b| a.max(b));
        if !(smax > 0.0 && smax.is_finite()) {
            return false;
        }
        let y = &self.y[..m * n];
        let s = &mut self.s[..cap * cap];
        for i in self.valid..m {
            let yi = &y[i * n..(i + 1) * n];
            for j in 0..=i {
                let yj = &y[j * n..(j + 1) * n];
                let mut sum: f64 = yi.iter().zip(yj).map(|(u, v)| u * v).sum();
                for k in 0..j {
                    sum -= s[i * cap + k] * s[j * cap + k];
                }
                if j < i {
                    s[i * cap + j] = sum / s[j * cap + j];
                } else if sum > 0.0 {
                    self.pivot_sums[i] = sum;
                    s[i * cap + i] = sum.sqrt();
                } else {
                    // A pivot sum that is not positive ends the factorisation here.
                    self.valid = i;
                    return false;
                }
            }
            self.valid = i + 1;
        }
        let tol = PIVOT_TOL * smax;
        self.pivot_sums[..m].iter().all(|&p| p > tol)
    }

    /// Solves the factorised system given u = L^-1 r1: on entry `y` holds r2, on return x is
    /// in `x` and y in `y` (lengths n and m). M must be up to date ([`Self::factor_rows`]).
    pub fn solve_u(&self, u: &[f64], x: &mut [f64], y: &mut [f64]) {
        let (n, m, cap) = (self.n, self.m, self.cap);
        let u = &u[..n];
        let y = &mut y[..m];
        let rows = || self.y[..m * n].chunks_exact(n.max(1));
        // S y = M M' y = Y u - r2.
        for (row, v) in rows().zip(y.iter_mut()) {
            let yu: f64 = row.iter().zip(u).map(|(a, b)| a * b).sum();
            *v = yu - *v;
        }
        let s = &self.s[..m * cap];
        forward(s, cap, y);
        backward(s, cap, y);
        // x = L^-T (u - Y'y).
        let x = &mut x[..n];
        x.copy_from_slice(u);
        for (row, &v) in rows().zip(y.iter()) {
            for (t, a) in x.iter_mut().zip(row) {
                *t -= a * v;
            }
        }
        self.backward(x);
    }

    /// Solves the factorised system for `rhs` = [r1; r2] (length n + m) in place; `u` is
    /// scratch of length n.
    pub fn solve(&self, rhs: &mut [f64], u: &mut [f64]) {
        let n = self.n;
        let (top, bottom) = rhs[..n + self.m].split_at_mut(n);
        let u = &mut u[..n];
        u.copy_from_slice(top);
        self.forward(u);
        self.solve_u(u, top, bottom);
    }
}

/// Cholesky factor (lower, row-major n x n) of the symmetric matrix `a(i, j)` into `l`; false
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

/// Solves L v = b in place for the factor `l` of P (row-major n x n), diagonal or not.
fn lower_solve(l: &[f64], n: usize, diagonal: bool, b: &mut [f64]) {
    if diagonal {
        for (i, v) in b.iter_mut().enumerate() {
            *v /= l[i * n + i];
        }
    } else {
        forward(l, n, b);
    }
}

/// Solves L v = b in place (L lower, row-major with row stride `stride`; the order is `b`'s
/// length): each entry by subtractions in the order of its row of L, then one division.
fn forward(l: &[f64], stride: usize, b: &mut [f64]) {
    for i in 0..b.len() {
        let mut s = b[i];
        for (a, v) in l[i * stride..i * stride + i].iter().zip(&b[..i]) {
            s -= a * v;
        }
        b[i] = s / l[i * stride + i];
    }
}

/// Solves L' v = b in place (L as in [`forward`]): each entry by subtractions in the order of
/// its column of L, then one division.
fn backward(l: &[f64], stride: usize, b: &mut [f64]) {
    let n = b.len();
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[k * stride + i] * b[k];
        }
        b[i] = s / l[i * stride + i];
    }
}

/// a'b over a's length (b at least as long), summed from 0 in order.
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let b = &b[..a.len()];
    a.iter().zip(b).fold(0.0, |s, (x, y)| s + x * y)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [P C'; C 0] z for row-major P (n x n) and C (m x n).
    fn kkt_times(p: &[f64], c: &[f64], n: usize, m: usize, z: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; n + m];
        for i in 0..n {
            out[i] = (0..n).map(|j| p[i * n + j] * z[j]).sum::<f64>()
                + (0..m).map(|r| c[r * n + i] * z[n + r]).sum::<f64>();
        }
        for r in 0..m {
            out[n + r] = (0..n).map(|j| c[r * n + j] * z[j]).sum();
        }
        out
    }

    fn factor_rows_of(kkt: &mut SchurKkt, c: &[f64], n: usize, m: usize) -> bool {
        kkt.truncate(0);
        for r in 0..m {
            kkt.stage(&c[r * n..(r + 1) * n]);
            kkt.commit();
        }
        kkt.factor_rows()
    }

    #[test]
    fn solves_a_kkt_system_and_refuses_singular_ones() {
        // P = [[4, 1], [1, 3]] ⊕ 2, C = [1 1 1]: the solution of a system built from it.
        let p = [4.0, 1.0, 0.0, 1.0, 3.0, 0.0, 0.0, 0.0, 2.0];
        let c = [1.0, 1.0, 1.0];
        let z = [0.5, -0.25, 1.0, 0.75];
        let mut rhs = kkt_times(&p, &c, 3, 1, &z);
        let mut kkt = SchurKkt::default();
        kkt.reserve(3, 2);
        assert!(kkt.factor_p(3, &p));
        assert!(!kkt.is_diagonal());
        assert!(factor_rows_of(&mut kkt, &c, 3, 1));
        kkt.solve(&mut rhs, &mut [0.0; 3]);
        for (got, want) in rhs.iter().zip(z) {
            assert!((got - want).abs() < 1e-14, "{rhs:?}");
        }
        // C with two equal rows: refused; P singular (a zero row): refused.
        assert!(!factor_rows_of(&mut kkt, &[1.0; 6], 3, 2));
        let mut singular = p;
        singular[8] = 0.0;
        assert!(!kkt.factor_p(3, &singular));
    }

    #[test]
    fn row_updates_match_a_factorisation_from_scratch() {
        // A dense P and five rows, added and removed in an active-set order: after every
        // change the factors equal those of the same rows factorised from scratch, bit for bit.
        let n = 5;
        let mut p = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                p[i * n + j] = 1.0 / (1.0 + (i + j) as f64) + if i == j { 2.0 } else { 0.0 };
            }
        }
        let rows: Vec<Vec<f64>> = (0..5)
            .map(|r| {
                (0..n)
                    .map(|j| ((r * 7 + j * 3) % 5) as f64 - 2.0 + 0.1 * r as f64)
                    .collect()
            })
            .collect();
        let mut kkt = SchurKkt::default();
        kkt.reserve(n, n);
        assert!(kkt.factor_p(n, &p));
        let mut scratch = kkt.clone();
        let mut held: Vec<usize> = Vec::new();
        let changes: [(bool, usize); 8] = [
            (true, 0),
            (true, 3),
            (true, 1),
            (false, 1),
            (true, 4),
            (false, 0),
            (true, 2),
            (false, 2),
        ];
        for (add, what) in changes {
            if add {
                kkt.stage(&rows[what]);
                kkt.commit();
                held.push(what);
            } else {
                kkt.remove(what);
                held.remove(what);
            }
            assert!(kkt.factor_rows());
            let c: Vec<f64> = held.iter().flat_map(|&r| rows[r].clone()).collect();
            assert!(factor_rows_of(&mut scratch, &c, n, held.len()));
            let m = held.len();
            let mut z: Vec<f64> = (0..n + m).map(|i| 0.3 * i as f64 - 1.0).collect();
            let mut z2 = z.clone();
            kkt.solve(&mut z, &mut [0.0; 5]);
            scratch.solve(&mut z2, &mut [0.0; 5]);
            assert_eq!(z, z2, "after {held:?}");
            let back = kkt_times(&p, &c, n, m, &z);
            let want: Vec<f64> = (0..n + m).map(|i| 0.3 * i as f64 - 1.0).collect();
            for (a, b) in back.iter().zip(&want) {
                assert!((a - b).abs() < 1e-12, "after {held:?}: {back:?}");
            }
        }
    }

    #[test]
    fn a_diagonal_p_gives_the_dense_answer() {
        let n = 4;
        let mut p = vec![0.0; n * n];
        for i in 0..n {
            p[i * n + i] = 0.5 + i as f64;
        }
        let c = [1.0, -2.0, 0.5, 0.0, 0.0, 1.0, 1.0, -1.0];
        let mut kkt = SchurKkt::default();
        kkt.reserve(n, 2);
        assert!(kkt.factor_p(n, &p));
        assert!(kkt.is_diagonal());
        assert!(factor_rows_of(&mut kkt, &c, n, 2));
        let want = [0.1, 0.2, -0.3, 0.4, 1.5, -0.5];
        let mut z = kkt_times(&p, &c, n, 2, &want);
        kkt.solve(&mut z, &mut [0.0; 4]);
        for (a, b) in z.iter().zip(want) {
            assert!((a - b).abs() < 1e-14, "{z:?}");
        }
    }
}
