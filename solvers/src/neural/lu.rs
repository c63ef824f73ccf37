//! A small in-place LU factorisation with partial pivoting (Doolittle, row interchanges) on a
//! preallocated dense matrix, so the zeroing networks can solve Q ydot = r at every right-hand
//! side evaluation without allocating (nalgebra's `DMatrix::lu` returns a new matrix).

use nalgebra::DMatrix;

/// Relative pivot threshold below which the matrix is reported singular.
const SINGULAR_PIVOT: f64 = 1e-300;

/// Factor the square matrix `a` in place: on return its strict lower triangle holds L (unit
/// diagonal implied) and its upper triangle U, with P a = L U where P swaps row k with
/// `piv[k]` for k = 0, 1, ... in order. Returns false when a pivot is exactly zero (or not finite).
pub fn factor(a: &mut DMatrix<f64>, piv: &mut [usize]) -> bool {
    let n = a.nrows();
    debug_assert_eq!(a.ncols(), n);
    debug_assert!(piv.len() >= n);
    let mut ok = true;
    for k in 0..n {
        let mut p = k;
        let mut best = a[(k, k)].abs();
        for i in (k + 1)..n {
            let v = a[(i, k)].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        piv[k] = p;
        if !(best > SINGULAR_PIVOT) || !best.is_finite() {
            ok = false;
            continue;
        }
        if p != k {
            a.swap_rows(k, p);
        }
        let pivot = a[(k, k)];
        for i in (k + 1)..n {
            a[(i, k)] /= pivot;
        }
        for j in (k + 1)..n {
            let akj = a[(k, j)];
            if akj != 0.0 {
                for i in (k + 1)..n {
                    a[(i, j)] -= a[(i, k)] * akj;
                }
            }
        }
    }
    ok
}

/// Solve A x = b in place (`b` becomes x) with the factors from [`factor`].
pub fn solve(lu: &DMatrix<f64>, piv: &[usize], b: &mut [f64]) {
    let n = lu.nrows();
    for k in 0..n {
        let p = piv[k];
        if p != k {
            b.swap(k, p);
        }
    }
    for i in 0..n {
        let mut s = b[i];
        for j in 0..i {
            s -= lu[(i, j)] * b[j];
        }
        b[i] = s;
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for j in (i + 1)..n {
            s -= lu[(i, j)] * b[j];
        }
        b[i] = s / lu[(i, i)];
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
