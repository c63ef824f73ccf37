//! The dense LU backends: faer's solution equals nalgebra's (and the in-house elimination's)
//! to rounding on random well-conditioned systems of 1 to 250 unknowns; a singular matrix is
//! reported by both; the KKT solve gives one x on either backend.

use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use solvers::{solve_equality_kkt_with, Backend, DenseLu, Qp, QpDims};

/// A random n x n matrix with entries in [-1, 1] plus n on the diagonal (strictly diagonally
/// dominant, condition number below 3), and a random right-hand side.
fn system(n: usize, seed: u64) -> (DMatrix<f64>, DVector<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut a = DMatrix::from_fn(n, n, |_, _| rng.gen_range(-1.0..1.0));
    for i in 0..n {
        a[(i, i)] += n as f64;
    }
    // Swap two rows so that pivoting has work to do.
    if n > 1 {
        a.swap_rows(0, n - 1);
    }
    let b = DVector::from_fn(n, |_, _| rng.gen_range(-1.0..1.0));
    (a, b)
}

#[test]
fn faer_solves_as_nalgebra_does() {
    for (seed, n) in [1usize, 2, 3, 7, 20, 39, 40, 64, 101, 203, 250]
        .into_iter()
        .enumerate()
    {
        let (a, b) = system(n, seed as u64);
        let reference = a.clone().lu().solve(&b).expect("regular");
        for backend in Backend::ALL {
            let mut lu = DenseLu::new(n, backend);
            assert!(lu.factor(&a), "n = {n}, {backend:?}");
            let mut x = b.clone();
            lu.solve(x.as_mut_slice());
            let err = (&x - &reference).amax() / reference.amax();
            assert!(err < 1e-12, "n = {n}, {backend:?}: relative error {err:e}");
            let residual = (&a * &x - &b).amax();
            assert!(
                residual < 1e-12 * n as f64,
                "n = {n}, {backend:?}: {residual:e}"
            );
            // Refactorising another matrix of the same size reuses the buffers.
            let (a2, b2) = system(n, 1000 + seed as u64);
            assert!(lu.factor(&a2));
            let mut x2 = b2.clone();
            lu.solve(x2.as_mut_slice());
            assert!((&a2 * &x2 - &b2).amax() < 1e-12 * n as f64);
        }
    }
}

#[test]
fn a_singular_matrix_is_reported_by_both_backends() {
    let (mut a, _) = system(50, 9);
    let row = a.row(3).into_owned();
    a.set_row(7, &row);
    a.set_row(3, &(row * 0.0));
    for backend in Backend::ALL {
        assert!(!DenseLu::new(50, backend).factor(&a), "{backend:?}");
    }
}

#[test]
fn backends_are_chosen_by_the_crossover_and_named() {
    assert_eq!(
        Backend::for_size(settings::FAER_CROSSOVER - 1),
        Backend::Nalgebra
    );
    assert_eq!(Backend::for_size(settings::FAER_CROSSOVER), Backend::Faer);
    assert_eq!(DenseLu::for_size(3).backend(), Backend::Nalgebra);
    for backend in Backend::ALL {
        assert_eq!(Backend::from_id(backend.id()), Some(backend));
    }
    assert_eq!(Backend::from_id("lapack"), None);
}

#[test]
fn the_kkt_solve_agrees_across_backends() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for nx in [4, 30, 120] {
        // P = I, random q, a random full-rank 3 x nx A and b, no bounds (kong2019's shape).
        let mut qp = Qp::zeros(QpDims {
            nx,
            n_eq: 3,
            n_in: 0,
        });
        qp.p.fill_with_identity();
        qp.q.iter_mut().for_each(|v| *v = rng.gen_range(-1.0..1.0));
        qp.a.iter_mut().for_each(|v| *v = rng.gen_range(-1.0..1.0));
        qp.b.iter_mut().for_each(|v| *v = rng.gen_range(-1.0..1.0));
        qp.lower.fill(f64::NEG_INFINITY);
        qp.upper.fill(f64::INFINITY);
        let x_nalgebra = solve_equality_kkt_with(&qp, Backend::Nalgebra).expect("regular");
        let x_faer = solve_equality_kkt_with(&qp, Backend::Faer).expect("regular");
        let err = (&x_faer - &x_nalgebra).amax() / x_nalgebra.amax();
        assert!(err < 1e-10, "nx = {nx}: {err:e}");
    }
}
