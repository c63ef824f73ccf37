//! A small in-place LU factorisation with partial pivoting (Doolittle, row interchanges) on a
//! preallocated dense matrix, so the zeroing networks can solve Q ydot = r at every right-hand
//! side evaluation without allocating (nalgebra's `DMatrix::lu` returns a new matrix).

use nalgebra::DMatrix;

/// Relative pivot threshold below which the matrix is reported singular.
const SINGULAR_PIVOT: f64 = 1e-300;

/// Factor the square matrix `a` in place: on return its strict lower triangle holds L (unit
/// diagonal implied) and its upper triangle U, with P a = L U where P swaps row k with
/// `piv[k]` for k = 0, 1, ... in order. Returns false when a pivot is exactly zero (or not finite).
///
/// Works on the column-major storage directly (entry (i, j) at `i + j n`), column against
/// column, with the operations of the textbook loop in the same order (the factors are the
/// same bit for bit).
pub fn factor(a: &mut DMatrix<f64>, piv: &mut [usize]) -> bool {
    let n = a.nrows();
    debug_assert_eq!(a.ncols(), n);
    let piv = &mut piv[..n];
    let s = a.as_mut_slice();
    let mut ok = true;
    for k in 0..n {
        let column = &s[k * n..(k + 1) * n];
        let mut p = k;
        let mut best = column[k].abs();
        for (i, v) in column.iter().enumerate().skip(k + 1) {
            if v.abs() > best {
                best = v.abs();
                p = i;
            }
        }
        piv[k] = p;
        if !(best > SINGULAR_PIVOT) || !best.is_finite() {
            ok = false;
            continue;
        }
        if p != k {
            for col in s.chunks_exact_mut(n) {
                col.swap(k, p);
            }
        }
        let (left, right) = s.split_at_mut((k + 1) * n);
        let column = &mut left[k * n..];
        let pivot = column[k];
        for v in &mut column[k + 1..] {
            *v /= pivot;
        }
        let l = &column[k + 1..];
        for col in right.chunks_exact_mut(n) {
            let akj = col[k];
            if akj != 0.0 {
                for (v, lik) in col[k + 1..].iter_mut().zip(l) {
                    *v -= lik * akj;
                }
            }
        }
    }
    ok
}

/// Solve A x = b in place (`b` becomes x) with the factors from [`factor`].
pub fn solve(lu: &DMatrix<f64>, piv: &[usize], b: &mut [f64]) {
    let n = lu.nrows();
    let m = lu.as_slice();
    let b = &mut b[..n];
    for (k, &p) in piv[..n].iter().enumerate() {
        if p != k {
            b.swap(k, p);
        }
    }
    for i in 0..n {
        let mut s = b[i];
        for j in 0..i {
            s -= m[i + j * n] * b[j];
        }
        b[i] = s;
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for j in (i + 1)..n {
            s -= m[i + j * n] * b[j];
        }
        b[i] = s / m[i + i * n];
    }
}

/// Solve A X = B in place for every column of `b` (same factors).
pub fn solve_columns(lu: &DMatrix<f64>, piv: &[usize], b: &mut DMatrix<f64>) {
    let n = b.nrows();
    for j in 0..b.ncols() {
        // A DMatrix is stored column-major: column j is one contiguous slice.
        solve(lu, piv, &mut b.as_mut_slice()[j * n..(j + 1) * n]);
    }
}
