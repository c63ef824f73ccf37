//! The LU factors of a zeroing network's Q = [P A'; A 0] (nx + m unknowns, m = n_eq), bit for
//! bit those of [`super::lu`]'s textbook loop on the assembled matrix, computed without the
//! operations that leave a value unchanged when P is diagonal.
//!
//! # What the textbook loop does with a diagonal P
//!
//! Let P = diag(d) with d_k > 0, every off-diagonal entry of P +0.0, every entry of A finite,
//! and |A_rk| <= d_k for every row r of A and k < nx. At stage k < nx of the LU with partial
//! pivoting, column k is still Q's (an earlier stage k' updates column k only where
//! U_k'k = P_k'k is nonzero), so the pivot is d_k (a row of A replaces it only where
//! |A_rk| > d_k), no rows are swapped, and the multipliers are P_ik / d_k = +0 for i < nx and
//! l_rk = A_rk / d_k for the rows of A. Only the columns nx + c of A' where A_ck is nonzero are
//! updated; their entries in rows i < nx take away +-0 products, so a nonzero A_ci keeps its
//! value (a zero one may change its sign), and their rows of A accumulate the bottom block
//!
//! ```text
//! B_rc = (((0 - l_r0 A_c0) - l_r1 A_c1) - ...) - l_r,nx-1 A_c,nx-1      (k ascending, A_ck != 0)
//! ```
//!
//! The stages k >= nx are the textbook loop on the m x m block B (its row swaps also swap the
//! rows of l). So the factors are d, A (U's upper-right block is A'), l (L's lower-left block)
//! and the LU of B: for kong2019's 5 joints and 3 task rows, 15 divisions and 45 products to
//! factor, where the 8 x 8 loop also searches, divides and updates the zero entries.
//!
//! # Solving
//!
//! The textbook solve's forward substitution takes +0 L_ij b_j away from b_i for i < nx, and its
//! back substitution +0 U_ij b_j for i < j < nx before A' and the division by d_i: neither
//! changes a nonzero finite b_i, nor does a +-0 entry of A' change a nonzero partial sum. So
//! where b is finite with b_i nonzero for i < nx, no partial sum meets a zero entry of A' at
//! zero, and the answer is finite, z is computed as
//!
//! ```text
//! z_B = the LU solve of B for b_B - l b_x     (b_B permuted by B's pivots first)
//! z_i = (b_i - sum_c A_ci z_B,c) / d_i        (i < nx, c ascending)
//! ```
//!
//! in the textbook loop's order. Anywhere else (a zero or non-finite entry, a P or A outside
//! the conditions above), the textbook loop runs on the full matrix (assembled, or its factors
//! written out from the structured ones with the textbook's operations on the zeros), so every
//! answer is the textbook loop's, bit for bit (a test compares them on random systems, with
//! zeros, ties and swaps).

use super::lu::{self, Fixed, Order};
use nalgebra::DMatrix;
use qp::{Qp, QpDims};

/// The factors of Q (module docs), buffers sized once.
#[derive(Clone, Debug)]
pub(crate) struct KktLu {
    dims: QpDims,
    /// Whether the structured factors below hold (else `lu` and `piv` hold the textbook ones).
    structured: bool,
    /// The diagonal d of P.
    d: Vec<f64>,
    /// A, column-major m x nx (A_rk at r + k m).
    a: Vec<f64>,
    /// l = A_rk / d_k, same layout, rows permuted by B's pivots.
    l: Vec<f64>,
    /// B, then its LU factors (m x m), and its pivots.
    b: DMatrix<f64>,
    piv_b: Vec<usize>,
    /// Q, then its LU factors (the textbook path), and its pivots.
    lu: DMatrix<f64>,
    piv: Vec<usize>,
    /// A copy of the right-hand side, for the textbook path when the structured solve declines.
    rhs: Vec<f64>,
}

impl KktLu {
    /// Buffers for QPs of sizes `dims` (n_in is not part of Q).
    pub(crate) fn new(dims: QpDims) -> Self {
        let QpDims { nx, n_eq: m, .. } = dims;
        let n = nx + m;
        Self {
            dims,
            structured: false,
            d: vec![0.0; nx],
            a: vec![0.0; m * nx],
            l: vec![0.0; m * nx],
            b: DMatrix::zeros(m, m),
            piv_b: vec![0; m],
            lu: DMatrix::zeros(n, n),
            piv: vec![0; n],
            rhs: vec![0.0; n],
        }
    }

    /// Factorises Q of `qp`; false when a pivot is zero or not finite (no usable factors).
    pub(crate) fn factor(&mut self, qp: &Qp) -> bool {
        let QpDims { nx, n_eq, .. } = self.dims;
        let (p, a) = (qp.p.as_slice(), qp.a.as_slice());
        self.structured = match (nx, n_eq) {
            (5, 3) => self.load(Fixed::<5>, Fixed::<3>, p, a),
            (6, 3) => self.load(Fixed::<6>, Fixed::<3>, p, a),
            (7, 3) => self.load(Fixed::<7>, Fixed::<3>, p, a),
            _ => self.load(nx, n_eq, p, a),
        };
        if !self.structured {
            assemble_q(self.dims, qp, &mut self.lu);
            return lu::factor(&mut self.lu, &mut self.piv);
        }
        if !lu::factor(&mut self.b, &mut self.piv_b) {
            return false;
        }
        // B's row swaps, in order, on the rows of l as the full loop swaps whole rows.
        let m = n_eq;
        for (k, &p) in self.piv_b.iter().enumerate() {
            if p != k {
                for column in self.l.chunks_exact_mut(m) {
                    column.swap(k, p);
                }
            }
        }
        true
    }

    /// d, A, l and the unfactorised B (module docs), or false where P or A is outside the
    /// structured form's conditions.
    #[inline(always)]
    fn load(&mut self, nx: impl Order, m: impl Order, p: &[f64], a: &[f64]) -> bool {
        let (nx, m) = (nx.get(), m.get());
        let (p, a) = (&p[..nx * nx], &a[..m * nx]);
        let (d, l) = (&mut self.d[..nx], &mut self.l[..m * nx]);
        for k in 0..nx {
            let column = &p[k * nx..(k + 1) * nx];
            let dk = column[k];
            if !(dk > lu::SINGULAR_PIVOT && dk.is_finite()) {
                return false;
            }
            for (i, v) in column.iter().enumerate() {
                if i != k && v.to_bits() != 0 {
                    return false;
                }
            }
            for (r, v) in a[k * m..(k + 1) * m].iter().enumerate() {
                if !(v.is_finite() && v.abs() <= dk) {
                    return false;
                }
                l[r + k * m] = v / dk;
            }
            d[k] = dk;
        }
        self.a[..m * nx].copy_from_slice(a);
        let b = &mut self.b.as_mut_slice()[..m * m];
        for c in 0..m {
            for r in 0..m {
                let mut s = 0.0;
                for k in 0..nx {
                    let ack = a[c + k * m];
                    if ack != 0.0 {
                        s -= l[r + k * m] * ack;
                    }
                }
                b[r + c * m] = s;
            }
        }
        true
    }

    /// Solves Q z = `z` in place with the factors of the last [`KktLu::factor`], which must
    /// have returned true.
    pub(crate) fn solve(&mut self, z: &mut [f64]) {
        if !self.structured {
            lu::solve(&self.lu, &self.piv, z);
            return;
        }
        let QpDims { nx, n_eq, .. } = self.dims;
        let n = nx + n_eq;
        self.rhs[..n].copy_from_slice(&z[..n]);
        let done = match (nx, n_eq) {
            (5, 3) => self.solve_structured(Fixed::<5>, Fixed::<3>, z),
            (6, 3) => self.solve_structured(Fixed::<6>, Fixed::<3>, z),
            (7, 3) => self.solve_structured(Fixed::<7>, Fixed::<3>, z),
            _ => self.solve_structured(nx, n_eq, z),
        };
        if !done {
            self.assemble_factors();
            z[..n].copy_from_slice(&self.rhs[..n]);
            lu::solve(&self.lu, &self.piv, z);
        }
    }

    /// Solves Q Z = `z` in place for every column.
    pub(crate) fn solve_columns(&mut self, z: &mut DMatrix<f64>) {
        let n = z.nrows();
        for column in z.as_mut_slice().chunks_exact_mut(n) {
            self.solve(column);
        }
    }

    /// The structured solve (module docs) into `z`, or false (`z` spoilt) where it would not
    /// give the textbook loop's bits.
    #[inline(always)]
    fn solve_structured(&self, nx: impl Order, m: impl Order, z: &mut [f64]) -> bool {
        let (nx, m) = (nx.get(), m.get());
        let (zx, zb) = z[..nx + m].split_at_mut(nx);
        if zx.iter().any(|v| *v == 0.0 || !v.is_finite()) || zb.iter().any(|v| !v.is_finite()) {
            return false;
        }
        let (a, l, d) = (&self.a[..m * nx], &self.l[..m * nx], &self.d[..nx]);
        let (b, piv) = (&self.b.as_slice()[..m * m], &self.piv_b[..m]);
        for (k, &p) in piv.iter().enumerate() {
            if p != k {
                zb.swap(k, p);
            }
        }
        // Forward: the rows of A take away l b_x, then B's unit lower triangle.
        for r in 0..m {
            let mut s = zb[r];
            for (k, x) in zx.iter().enumerate() {
                s -= l[r + k * m] * x;
            }
            for c in 0..r {
                s -= b[r + c * m] * zb[c];
            }
            zb[r] = s;
        }
        // Back: B's upper triangle, then z_i = (b_i - sum_c A_ci z_B,c) / d_i.
        for r in (0..m).rev() {
            let mut s = zb[r];
            for c in r + 1..m {
                s -= b[r + c * m] * zb[c];
            }
            zb[r] = s / b[r + r * m];
        }
        for (i, x) in zx.iter_mut().enumerate() {
            let mut s = *x;
            for (c, v) in zb.iter().enumerate() {
                let aci = a[c + i * m];
                if aci == 0.0 && s == 0.0 {
                    // The sign of U's zero entry would decide the sign of s.
                    return false;
                }
                s -= aci * v;
            }
            *x = s / d[i];
        }
        // Two plain loops (a chained iterator cost some 90 instructions a call here).
        zx.iter().all(|v| v.is_finite()) && zb.iter().all(|v| v.is_finite())
    }

    /// Writes the structured factors as the textbook loop's factors of the full matrix into
    /// `lu` and `piv` (module docs).
    fn assemble_factors(&mut self) {
        let QpDims { nx, n_eq: m, .. } = self.dims;
        let n = nx + m;
        let q = self.lu.as_mut_slice();
        q.fill(0.0);
        for k in 0..nx {
            q[k + k * n] = self.d[k];
            for r in 0..m {
                q[nx + r + k * n] = self.l[r + k * m];
            }
        }
        // U's upper-right block as the stages k < i leave it: A_ci less L_ik U_k,nx+c
        // (L_ik = +0) where U_k,nx+c is nonzero.
        for c in 0..m {
            for i in 0..nx {
                let mut v = self.a[c + i * m];
                for k in 0..i {
                    let u = q[k + (nx + c) * n];
                    if u != 0.0 {
                        v -= q[i + k * n] * u;
                    }
                }
                q[i + (nx + c) * n] = v;
            }
        }
        for c in 0..m {
            for r in 0..m {
                q[nx + r + (nx + c) * n] = self.b[(r, c)];
            }
        }
        for (k, p) in self.piv.iter_mut().enumerate() {
            *p = if k < nx { k } else { nx + self.piv_b[k - nx] };
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

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    /// The textbook loop's answer: Q assembled, factorised and solved by [`super::lu`].
    fn textbook(qp: &Qp, rhs: &[f64]) -> Option<Vec<f64>> {
        let dims = qp.dims();
        let n = dims.nx + dims.n_eq;
        let mut q = DMatrix::zeros(n, n);
        assemble_q(dims, qp, &mut q);
        let mut piv = vec![0; n];
        if !lu::factor(&mut q, &mut piv) {
            return None;
        }
        let mut z = rhs.to_vec();
        lu::solve(&q, &piv, &mut z);
        Some(z)
    }

    #[test]
    fn the_answers_are_the_textbook_loops_bit_for_bit() {
        let mut structured = 0;
        for (nx, n_eq) in [(5, 3), (6, 3), (7, 3), (4, 2), (9, 4)] {
            for seed in 0..400u64 {
                let mut next = numbers(seed * 31 + nx as u64);
                let mut qp = Qp::zeros(QpDims { nx, n_eq, n_in: 0 });
                let case = seed % 8;
                for j in 0..nx {
                    // P = I mostly (kong2019's), a positive diagonal, or a dense P.
                    qp.p[(j, j)] = if case == 1 { 0.5 + next().abs() } else { 1.0 };
                    if case == 2 && j > 0 {
                        qp.p[(j - 1, j)] = 0.1 * next();
                        qp.p[(j, j - 1)] = qp.p[(j - 1, j)];
                    }
                }
                for k in 0..n_eq {
                    for j in 0..nx {
                        qp.a[(k, j)] = next();
                    }
                }
                match case {
                    // An entry of A above its pivot (a swap), equal to it (a tie), zero.
                    3 => qp.a[(0, 1)] = 1.5,
                    4 => qp.a[(1, 0)] = -1.0,
                    5 => {
                        // Zeros of either sign (the Katana's base joint has dz/dtheta_1 = 0).
                        qp.a[(n_eq - 1, 0)] = 0.0;
                        qp.a[(0, 2)] = -0.0;
                        qp.a[(1, 1)] = -0.0;
                    }
                    6 => qp.p[(0, 1)] = -0.0,
                    _ => {}
                }
                let n = nx + n_eq;
                let mut rhs: Vec<f64> = (0..n).map(|_| next()).collect();
                if seed % 5 == 0 {
                    rhs[seed as usize % n] = if seed % 10 == 0 { 0.0 } else { -0.0 };
                }
                if seed % 13 == 0 {
                    rhs[0] = f64::NAN;
                }
                let expected = textbook(&qp, &rhs);
                let mut kkt = KktLu::new(qp.dims());
                let ok = kkt.factor(&qp);
                assert_eq!(ok, expected.is_some(), "({nx}, {n_eq}) seed {seed}");
                structured += usize::from(kkt.structured);
                if let Some(expected) = expected {
                    let mut z = rhs.clone();
                    kkt.solve(&mut z);
                    assert_eq!(bits(&z), bits(&expected), "({nx}, {n_eq}) seed {seed}");
                    let mut columns = DMatrix::from_fn(n, 2, |i, j| rhs[i] * (j + 1) as f64);
                    let original = columns.clone();
                    kkt.solve_columns(&mut columns);
                    for j in 0..2 {
                        let expected = textbook(&qp, original.column(j).as_slice()).unwrap();
                        assert_eq!(bits(columns.column(j).as_slice()), bits(&expected));
                    }
                }
            }
        }
        // Most systems take the structured form; the others check the textbook path.
        assert!(structured >= 900, "{structured} structured");
    }

    #[test]
    fn a_singular_system_has_no_factors() {
        let mut qp = Qp::zeros(QpDims {
            nx: 5,
            n_eq: 3,
            n_in: 0,
        });
        for j in 0..5 {
            qp.p[(j, j)] = 1.0;
            // Two equal rows of A: B is singular.
            qp.a[(0, j)] = 0.1 * (j + 1) as f64;
            qp.a[(1, j)] = 0.1 * (j + 1) as f64;
            qp.a[(2, j)] = 0.05 * (5 - j) as f64;
        }
        let mut kkt = KktLu::new(qp.dims());
        assert!(!kkt.factor(&qp));
        assert!(kkt.structured, "B is singular, not Q's conditions unmet");
        assert_eq!(textbook(&qp, &[1.0; 8]), None);
    }
}
