//! A small in-place LU factorisation with partial pivoting (Doolittle, row interchanges) on a
//! preallocated dense matrix, so the zeroing networks can solve Q ydot = r at every right-hand
//! side evaluation without allocating (nalgebra's `DMatrix::lu` returns a new matrix).
//!
//! The orders the papers' networks use (n = nx + n_eq = 6 to 12, e.g. kong2019's 5 joints and
//! 3 task rows: n = 8) are compiled with n a constant, so the loops
//! have fixed trip counts and no bounds checks (the factorisation holds the matrix as n
//! columns of n entries, `[[f64; N]; N]`, so every index is checked against n when it is
//! compiled); every other order runs the textbook loop with n read at run time. Either way
//! the operations and their order are those of the textbook loop, so the factors and the
//! solution are the same bit for bit (a test compares the compiled orders with the run-time
//! loop, pivots, factors and solutions, on random matrices with ties, zeros and NaN).

use nalgebra::DMatrix;

/// Relative pivot threshold below which the matrix is reported singular.
pub(crate) const SINGULAR_PIVOT: f64 = 1e-300;

/// The order n of the matrix (or a block size): a compile-time constant (`Fixed`) or a
/// run-time `usize`.
pub(crate) trait Order: Copy {
    fn get(self) -> usize;
}

/// An order known at compile time.
#[derive(Clone, Copy)]
pub(crate) struct Fixed<const N: usize>;

impl<const N: usize> Order for Fixed<N> {
    #[inline(always)]
    fn get(self) -> usize {
        N
    }
}

impl Order for usize {
    #[inline(always)]
    fn get(self) -> usize {
        self
    }
}

/// Calls `$f` with the order `$n` as a `Fixed` constant where it is one of the compiled
/// orders, else as a run-time `usize`.
macro_rules! by_order {
    ($n:expr, $f:ident ( $($arg:expr),* )) => {
        match $n {
            6 => $f(Fixed::<6>, $($arg),*),
            7 => $f(Fixed::<7>, $($arg),*),
            8 => $f(Fixed::<8>, $($arg),*),
            9 => $f(Fixed::<9>, $($arg),*),
            10 => $f(Fixed::<10>, $($arg),*),
            11 => $f(Fixed::<11>, $($arg),*),
            12 => $f(Fixed::<12>, $($arg),*),
            n => $f(n, $($arg),*),
        }
    };
}

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
    let s = a.as_mut_slice();
    match n {
        6 => factor_fixed::<6>(s, piv),
        7 => factor_fixed::<7>(s, piv),
        8 => factor_fixed::<8>(s, piv),
        9 => factor_fixed::<9>(s, piv),
        10 => factor_fixed::<10>(s, piv),
        11 => factor_fixed::<11>(s, piv),
        12 => factor_fixed::<12>(s, piv),
        n => factor_in(n, s, piv),
    }
}

/// The textbook loop with n read at run time (see [`factor`]).
fn factor_in(n: usize, s: &mut [f64], piv: &mut [usize]) -> bool {
    let piv = &mut piv[..n];
    let s = &mut s[..n * n];
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

/// [`factor_in`]'s loop for a compiled order N, its operations in the same order, on the
/// matrix held as N columns of N entries (every index below N, so no bounds check is left and
/// every loop has a constant bound).
#[inline(always)]
fn factor_fixed<const N: usize>(s: &mut [f64], piv: &mut [usize]) -> bool {
    let (c, piv) = as_columns::<N>(s, piv);
    let mut ok = true;
    for k in 0..N {
        ok &= stage(c, piv, k);
    }
    ok
}

/// The first N * N entries of `s` as N columns of N, and the first N pivots.
#[inline(always)]
fn as_columns<'a, const N: usize>(
    s: &'a mut [f64],
    piv: &'a mut [usize],
) -> (&'a mut [[f64; N]; N], &'a mut [usize; N]) {
    let (columns, _) = s[..N * N].as_chunks_mut::<N>();
    let c = columns
        .try_into()
        .expect("N * N entries are N columns of N");
    let piv = (&mut piv[..N]).try_into().expect("N pivots");
    (c, piv)
}

/// Stage k of the textbook loop ([`factor_in`]'s loop body): the pivot of column k, the row
/// swap, the multipliers and the update of the columns after k; false (and only `piv[k]`
/// written) when the pivot is zero or not finite.
#[inline(always)]
fn stage<const N: usize>(c: &mut [[f64; N]; N], piv: &mut [usize; N], k: usize) -> bool {
    let mut p = k;
    let mut best = c[k][k].abs();
    for (i, v) in c[k].iter().enumerate().skip(k + 1) {
        if v.abs() > best {
            best = v.abs();
            p = i;
        }
    }
    piv[k] = p;
    if !(best > SINGULAR_PIVOT) || !best.is_finite() {
        return false;
    }
    if p != k {
        for column in c.iter_mut() {
            column.swap(k, p);
        }
    }
    let (left, right) = c.split_at_mut(k + 1);
    let column = &mut left[k];
    let pivot = column[k];
    for v in &mut column[k + 1..] {
        *v /= pivot;
    }
    let l = &column[k + 1..];
    for col in right.iter_mut() {
        let akj = col[k];
        if akj != 0.0 {
            for (v, lik) in col[k + 1..].iter_mut().zip(l) {
                *v -= lik * akj;
            }
        }
    }
    true
}

/// Solve A x = b in place (`b` becomes x) with the factors from [`factor`].
pub fn solve(lu: &DMatrix<f64>, piv: &[usize], b: &mut [f64]) {
    by_order!(lu.nrows(), solve_in(lu.as_slice(), piv, b))
}

#[inline(always)]
fn solve_in(n: impl Order, m: &[f64], piv: &[usize], b: &mut [f64]) {
    let n = n.get();
    let m = &m[..n * n];
    let b = &mut b[..n];
    for (k, &p) in piv[..n].iter().enumerate() {
        if p != k {
            b.swap(k, p);
        }
    }
    // Forward substitution with L (unit diagonal): b_i -= sum_{j < i} L_ij b_j, j ascending.
    for i in 0..n {
        let mut s = b[i];
        for j in 0..i {
            s -= m[i + j * n] * b[j];
        }
        b[i] = s;
    }
    // Back substitution with U: b_i = (b_i - sum_{j > i} U_ij b_j) / U_ii, j ascending.
    for i in (0..n).rev() {
        let mut s = b[i];
        for j in (i + 1)..n {
            s -= m[i + j * n] * b[j];
        }
        b[i] = s / m[i + i * n];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DVector;

    /// A deterministic, well-spread test matrix of order n with a zero block (a KKT matrix's
    /// shape: pivoting is needed).
    fn kkt_like(n: usize, seed: u64) -> DMatrix<f64> {
        let mut state = seed;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let m = n / 3;
        let mut a = DMatrix::from_fn(n, n, |_, _| next());
        for i in n - m..n {
            for j in n - m..n {
                a[(i, j)] = 0.0;
            }
        }
        a
    }

    /// Where pivoting meets ties (entries of equal magnitude), zeros (a zero column: a failed
    /// pivot, after which the loop goes on), a negative zero and NaN, the compiled orders give
    /// the run-time loop's verdict, pivots and factors bit for bit.
    #[test]
    fn compiled_orders_match_on_ties_zeros_and_nan() {
        for n in [3usize, 6, 7, 8, 9, 10, 11, 12] {
            for seed in 0..60u64 {
                let mut a = kkt_like(n, seed);
                if seed % 2 == 0 {
                    // Quarters in [-0.5, 0.5]: many ties and zeros.
                    a.iter_mut().for_each(|v| *v = (*v * 4.0).round() / 4.0);
                }
                let j = (seed as usize / 6) % n;
                match seed % 6 {
                    1 => a.column_mut(j).fill(0.0),
                    3 => a[(n - 1, j)] = f64::NAN,
                    5 => a[(0, 0)] = -0.0,
                    _ => {}
                }
                let (mut fixed, mut dynamic) = (a.clone(), a.clone());
                let (mut pf, mut pd) = (vec![0; n], vec![0; n]);
                let ok_fixed = factor(&mut fixed, &mut pf);
                let ok_dynamic = factor_in(n, dynamic.as_mut_slice(), &mut pd);
                assert_eq!(ok_fixed, ok_dynamic, "n = {n}, seed {seed}: verdict");
                assert_eq!(pf, pd, "n = {n}, seed {seed}: pivots");
                let bits = |m: &DMatrix<f64>| m.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&fixed),
                    bits(&dynamic),
                    "n = {n}, seed {seed}: factors"
                );
            }
        }
    }

    #[test]
    fn compiled_orders_give_the_run_time_orders_bits() {
        for n in 2..=14 {
            for seed in 0..20 {
                let a = kkt_like(n, seed);
                let (mut fixed, mut dynamic) = (a.clone(), a.clone());
                let (mut pf, mut pd) = (vec![0; n], vec![0; n]);
                let ok_fixed = factor(&mut fixed, &mut pf);
                let ok_dynamic = factor_in(n, dynamic.as_mut_slice(), &mut pd);
                assert_eq!(ok_fixed, ok_dynamic);
                assert_eq!(pf, pd, "n = {n}: pivots");
                let bits = |m: &DMatrix<f64>| m.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&fixed), bits(&dynamic), "n = {n}: factors");
                let b: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
                let (mut xf, mut xd) = (b.clone(), b.clone());
                solve(&fixed, &pf, &mut xf);
                solve_in(n, dynamic.as_slice(), &pd, &mut xd);
                assert_eq!(
                    xf.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    xd.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    "n = {n}: solution"
                );
                // And it is the solution: A x = b to rounding.
                let r = &a * DVector::from_column_slice(&xf) - DVector::from_column_slice(&b);
                assert!(
                    r.amax() < 1e-9,
                    "n = {n}, seed {seed}: residual {}",
                    r.amax()
                );
            }
        }
    }
}
