//! The KKT system of an equality-constrained QP, Q z = r with Q = [P A'; A 0] (nx + n_eq
//! unknowns), factorised once and solved for one or more right-hand sides without allocating:
//! the zeroing networks' Q ydot = r at every right-hand side ([`crate::neural::zeroing`]) and
//! the exact optimum [x*; lambda*] = Q^-1 [-q; b] of a QP without inequality rows or finite
//! bounds ([`crate::exact_path`]).
//!
//! # Diagonal P: the Schur complement
//!
//! When P = D is diagonal with positive entries (kong2019's and the group's velocity-level
//! schemes: P = I), z = [x; lambda] and r = [r1; r2] give D x + A' lambda = r1, A x = r2, so
//!
//! ```text
//!     x = D^-1 (r1 - A' lambda),    S lambda = A D^-1 r1 - r2,    S = A D^-1 A' = W A',  W = A D^-1,
//! ```
//!
//! S (n_eq x n_eq) symmetric positive definite when A has full row rank, factorised as
//! S = L E L' (L unit lower triangular, E diagonal: the square-root-free Cholesky, so the
//! factor's critical path has no square root and one division per pivot). For kong2019's 5
//! joints and 3 task rows that is 5 divisions, 15 products for W, 6 dot products of length 5
//! for S and a 3 x 3 factor (about 70 flops), and a solve of about 80 (W r1, two unit
//! triangular solves of order 3 and a diagonal one, A' lambda, D^-1), against about 470 for the
//! LU of the 8 x 8 Q. The answer is the same solution of the same system, by a
//! different order of operations: it agrees with the LU's to rounding (a test checks both on
//! random KKT systems), not bit for bit. The runs integrate those last bits; what they move in
//! the results was judged against the results' own rounding noise (`benches/noise/`), cell by
//! cell, and stayed within it.
//!
//! A pivot E_ii = S_ii - sum_k L_ik^2 E_kk at or below [`PIVOT_TOL`] times the largest S_ii
//! (A rank deficient, or nearly) refuses the Schur form, and Q is then factorised by LU.
//!
//! # Any other P: LU
//!
//! An in-place LU with partial pivoting of the assembled Q ([`crate::neural::lu`]): zhang2018's
//! dense P, a P with a zero or negative diagonal entry, or an A whose Schur complement is not
//! numerically positive definite.

use crate::kkt_schur::PIVOT_TOL;
use crate::neural::lu::{self, Fixed, Order};
use nalgebra::DMatrix;
use qp::{Qp, QpDims};

/// Which factorisation [`Kkt`] holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Factors {
    /// The Schur complement of a diagonal P.
    Schur,
    /// The LU factors of Q.
    Lu,
    /// None (Q was singular, or nothing factorised yet).
    None,
}

/// The factors of Q = [P A'; A 0] (module docs), buffers sized once.
#[derive(Clone, Debug)]
pub(crate) struct Kkt {
    dims: QpDims,
    factors: Factors,
    /// 1 / P_ii.
    p_inv: Vec<f64>,
    /// A, column-major n_eq x nx (A[k, j] at k + j n_eq).
    a: Vec<f64>,
    /// W = A D^-1, same layout.
    w: Vec<f64>,
    /// L and E of S = L E L', row-major n_eq x n_eq: L strictly below the diagonal, E on it.
    l: Vec<f64>,
    /// Q, then its LU factors (the general path).
    lu: DMatrix<f64>,
    piv: Vec<usize>,
}

impl Kkt {
    /// Buffers for QPs of sizes `dims` (n_in is not part of Q).
    pub(crate) fn new(dims: QpDims) -> Self {
        let QpDims { nx, n_eq, .. } = dims;
        let n = nx + n_eq;
        Self {
            dims,
            factors: Factors::None,
            p_inv: vec![0.0; nx],
            a: vec![0.0; n_eq * nx],
            w: vec![0.0; n_eq * nx],
            l: vec![0.0; n_eq * n_eq],
            lu: DMatrix::zeros(n, n),
            piv: vec![0; n],
        }
    }

    /// The QP sizes the buffers are for.
    pub(crate) fn dims(&self) -> QpDims {
        self.dims
    }

    /// Factorises Q of `qp`: through the Schur complement where P is diagonal and positive and
    /// S positive definite, else by LU. False when Q is singular (no factors held).
    pub(crate) fn factor(&mut self, qp: &Qp) -> bool {
        let QpDims { nx, n_eq, .. } = self.dims;
        let (p, a) = (qp.p.as_slice(), qp.a.as_slice());
        let schur = match (nx, n_eq) {
            (5, 3) => self.factor_schur(Fixed::<5>, Fixed::<3>, p, a),
            (6, 3) => self.factor_schur(Fixed::<6>, Fixed::<3>, p, a),
            (7, 3) => self.factor_schur(Fixed::<7>, Fixed::<3>, p, a),
            _ => self.factor_schur(nx, n_eq, p, a),
        };
        self.factors = if schur {
            Factors::Schur
        } else {
            assemble_q(self.dims, qp, &mut self.lu);
            if lu::factor(&mut self.lu, &mut self.piv) {
                Factors::Lu
            } else {
                Factors::None
            }
        };
        self.factors != Factors::None
    }

    /// The Schur factors of the module docs, or false (nothing usable) when P is not diagonal
    /// with positive finite entries or S is not numerically positive definite.
    #[inline(always)]
    fn factor_schur(&mut self, nx: impl Order, n_eq: impl Order, p: &[f64], a: &[f64]) -> bool {
        let (nx, m) = (nx.get(), n_eq.get());
        let p = &p[..nx * nx];
        let a = &a[..m * nx];
        let (p_inv, w, l) = (
            &mut self.p_inv[..nx],
            &mut self.w[..m * nx],
            &mut self.l[..m * m],
        );
        // Column-major P and A: P[i, j] at i + j nx, A[k, j] at k + j m.
        for j in 0..nx {
            let column = &p[j * nx..(j + 1) * nx];
            let d = column[j];
            if !(d > 0.0 && d.is_finite()) {
                return false;
            }
            for (i, v) in column.iter().enumerate() {
                if i != j && *v != 0.0 {
                    return false;
                }
            }
            p_inv[j] = 1.0 / d;
        }
        self.a[..m * nx].copy_from_slice(a);
        for j in 0..nx {
            for k in 0..m {
                w[k + j * m] = a[k + j * m] * p_inv[j];
            }
        }
        // S[i, k] = sum_j W[i, j] A[k, j] (j ascending) for k <= i, into L's lower triangle
        // (row-major), then factorised in place row by row.
        let mut smax = 0.0f64;
        for i in 0..m {
            for k in 0..=i {
                let mut s = 0.0;
                for j in 0..nx {
                    s += w[i + j * m] * a[k + j * m];
                }
                l[i * m + k] = s;
            }
            smax = smax.max(l[i * m + i]);
        }
        let tol = PIVOT_TOL * smax;
        // Row i: L_ik = (S_ik - sum_{c<k} L_ic L_kc E_cc) / E_kk for k < i (c ascending), then
        // the pivot E_ii = S_ii - sum_{k<i} L_ik^2 E_kk.
        for i in 0..m {
            for k in 0..i {
                let mut s = l[i * m + k];
                for c in 0..k {
                    s -= l[i * m + c] * l[k * m + c] * l[c * m + c];
                }
                l[i * m + k] = s / l[k * m + k];
            }
            let mut d = l[i * m + i];
            for k in 0..i {
                let lik = l[i * m + k];
                d -= lik * lik * l[k * m + k];
            }
            if !(d > tol) || !d.is_finite() {
                return false;
            }
            l[i * m + i] = d;
        }
        true
    }

    /// Solves Q z = b in place (`b` becomes z) with the factors of the last [`Kkt::factor`],
    /// which must have returned true.
    pub(crate) fn solve(&self, b: &mut [f64]) {
        let QpDims { nx, n_eq, .. } = self.dims;
        match self.factors {
            Factors::Schur => match (nx, n_eq) {
                (5, 3) => self.solve_schur(Fixed::<5>, Fixed::<3>, b),
                (6, 3) => self.solve_schur(Fixed::<6>, Fixed::<3>, b),
                (7, 3) => self.solve_schur(Fixed::<7>, Fixed::<3>, b),
                _ => self.solve_schur(nx, n_eq, b),
            },
            Factors::Lu => lu::solve(&self.lu, &self.piv, b),
            Factors::None => b.fill(f64::NAN),
        }
    }

    /// Solves Q Z = B in place for every column of `b`.
    pub(crate) fn solve_columns(&self, b: &mut DMatrix<f64>) {
        let n = b.nrows();
        for column in b.as_mut_slice().chunks_exact_mut(n) {
            self.solve(column);
        }
    }

    #[inline(always)]
    fn solve_schur(&self, nx: impl Order, n_eq: impl Order, b: &mut [f64]) {
        let (nx, m) = (nx.get(), n_eq.get());
        let (a, w, l, p_inv) = (
            &self.a[..m * nx],
            &self.w[..m * nx],
            &self.l[..m * m],
            &self.p_inv[..nx],
        );
        let (r1, r2) = b[..nx + m].split_at_mut(nx);
        // t = W r1 - r2 (W r1 summed over ascending j), into r2; then L E L' lambda = t,
        // lambda into r2.
        for (k, t) in r2.iter_mut().enumerate() {
            let mut s = 0.0;
            for j in 0..nx {
                s += w[k + j * m] * r1[j];
            }
            *t = s - *t;
        }
        for i in 0..m {
            let mut s = r2[i];
            for k in 0..i {
                s -= l[i * m + k] * r2[k];
            }
            r2[i] = s;
        }
        for i in 0..m {
            r2[i] /= l[i * m + i];
        }
        for i in (0..m).rev() {
            let mut s = r2[i];
            for k in i + 1..m {
                s -= l[k * m + i] * r2[k];
            }
            r2[i] = s;
        }
        // x = D^-1 (r1 - A' lambda).
        for j in 0..nx {
            let mut s = r1[j];
            for k in 0..m {
                s -= a[k + j * m] * r2[k];
            }
            r1[j] = s * p_inv[j];
        }
    }
}

/// Writes Q = [P A'; A 0] of `qp` (sizes `dims`) into the (nx + n_eq)-square `q`.
pub(crate) fn assemble_q(dims: QpDims, qp: &Qp, q: &mut DMatrix<f64>) {
    let QpDims { nx, n_eq, .. } = dims;
    debug_assert_eq!(
        qp.dims(),
        dims,
        "QP sizes differ from the sizes the network was built for"
    );
    // Column-major storage: Q's column j is `q[j n..(j + 1) n]`, A's column j is
    // `a[j n_eq..(j + 1) n_eq]`.
    let n = nx + n_eq;
    let q = q.as_mut_slice();
    let (p, a) = (qp.p.as_slice(), qp.a.as_slice());
    for j in 0..nx {
        let column = &mut q[j * n..(j + 1) * n];
        column[..nx].copy_from_slice(&p[j * nx..(j + 1) * nx]);
        column[nx..].copy_from_slice(&a[j * n_eq..(j + 1) * n_eq]);
    }
    for k in 0..n_eq {
        let column = &mut q[(nx + k) * n..(nx + k + 1) * n];
        for (j, v) in column[..nx].iter_mut().enumerate() {
            *v = a[k + j * n_eq];
        }
        column[nx..].fill(0.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DVector;

    /// A deterministic generator of numbers in [-0.5, 0.5).
    fn numbers(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        }
    }

    /// A QP of sizes (nx, n_eq) with a positive diagonal P (plus small random off-diagonal
    /// entries when `dense`) and a random A.
    fn kkt_qp(nx: usize, n_eq: usize, dense: bool, seed: u64) -> Qp {
        let mut next = numbers(seed);
        let mut qp = Qp::zeros(QpDims { nx, n_eq, n_in: 0 });
        for j in 0..nx {
            // P = I on every other seed (the papers' schemes), a positive diagonal otherwise.
            qp.p[(j, j)] = if seed.is_multiple_of(2) {
                1.0
            } else {
                0.5 + next().abs() * 4.0
            };
            if dense {
                for i in 0..j {
                    let v = 0.1 * next();
                    qp.p[(i, j)] = v;
                    qp.p[(j, i)] = v;
                }
            }
        }
        for k in 0..n_eq {
            for j in 0..nx {
                qp.a[(k, j)] = next();
            }
        }
        qp
    }

    #[test]
    fn schur_and_lu_solve_the_same_system() {
        for (nx, n_eq) in [(5, 3), (6, 3), (7, 3), (4, 2), (9, 4), (3, 0)] {
            for seed in 0..25 {
                let qp = kkt_qp(nx, n_eq, false, seed);
                let dims = qp.dims();
                let n = nx + n_eq;
                let mut kkt = Kkt::new(dims);
                assert!(kkt.factor(&qp));
                assert_eq!(
                    kkt.factors,
                    Factors::Schur,
                    "diagonal P takes the Schur form"
                );
                let b: Vec<f64> = (0..n).map(|i| 1.0 + i as f64 * 0.37).collect();
                let mut z = b.clone();
                kkt.solve(&mut z);
                let mut q = DMatrix::zeros(n, n);
                assemble_q(dims, &qp, &mut q);
                let mut piv = vec![0; n];
                let mut lu_z = b.clone();
                let mut lu_q = q.clone();
                assert!(lu::factor(&mut lu_q, &mut piv));
                lu::solve(&lu_q, &piv, &mut lu_z);
                let residual = &q * DVector::from_column_slice(&z) - DVector::from_column_slice(&b);
                assert!(
                    residual.amax() < 1e-12,
                    "({nx}, {n_eq}) seed {seed}: residual {}",
                    residual.amax()
                );
                let scale = lu_z.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                let gap = z
                    .iter()
                    .zip(&lu_z)
                    .fold(0.0f64, |m, (s, l)| m.max((s - l).abs()));
                assert!(
                    gap < 1e-13 * scale * 100.0,
                    "({nx}, {n_eq}) seed {seed}: Schur - LU {gap}"
                );
            }
        }
    }

    #[test]
    fn dense_p_and_rank_deficient_a_take_the_lu() {
        let qp = kkt_qp(5, 3, true, 7);
        let mut kkt = Kkt::new(qp.dims());
        assert!(kkt.factor(&qp));
        assert_eq!(kkt.factors, Factors::Lu);
        // A zero row of A: S singular, refused; Q has a zero row, so the LU fails too.
        let mut qp = kkt_qp(5, 3, false, 8);
        for j in 0..5 {
            qp.a[(2, j)] = 0.0;
        }
        let mut kkt = Kkt::new(qp.dims());
        assert!(!kkt.factor(&qp));
        let mut b = vec![1.0; 8];
        kkt.solve(&mut b);
        assert!(b.iter().all(|v| v.is_nan()));
        // A non-positive diagonal entry of P refuses the Schur form.
        let mut qp = kkt_qp(5, 3, false, 9);
        qp.p[(0, 0)] = -1.0;
        let mut kkt = Kkt::new(qp.dims());
        assert!(kkt.factor(&qp));
        assert_eq!(kkt.factors, Factors::Lu);
    }

    #[test]
    fn solve_columns_solves_each_column() {
        let qp = kkt_qp(5, 3, false, 3);
        let mut kkt = Kkt::new(qp.dims());
        assert!(kkt.factor(&qp));
        let mut b = DMatrix::from_fn(8, 4, |i, j| (i * 4 + j) as f64 * 0.1 - 1.0);
        let original = b.clone();
        kkt.solve_columns(&mut b);
        for j in 0..4 {
            let mut column: Vec<f64> = original.column(j).iter().copied().collect();
            kkt.solve(&mut column);
            assert_eq!(column.as_slice(), b.column(j).as_slice());
        }
    }
}
