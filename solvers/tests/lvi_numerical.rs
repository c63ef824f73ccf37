//! robio2018's six PLPE methods (94LVI, E47, M3-M6) against Clarabel on random QPs, with what
//! each rule as printed does on every shape recorded as a finding where it does not converge:
//! the equality-plus-bounds shape (M invertible), the equality-only shapes (zhang2018,
//! kong2019) and the shapes with inequality rows (jia2019, zhong2021: M singular). Warm starts,
//! the typed errors, the [`QpSolver`] view of every per-instant method, and OSQP warm-started.

use solvers::{random_feasible, random_qp, ExactSolver, Qp, QpDims, QpShape, QpSolver};
use solvers::{LviError, LviMethod, LviSettings, LviSolver};
#[cfg(feature = "osqp")]
use solvers::{OsqpQp, OsqpSettings};

/// Random QPs per shape and method.
const N_PER_SHAPE: u64 = 50;
/// Stopping tolerance of the tests, on |e|_2.
const TIGHT: f64 = 1e-10;
/// Required agreement with Clarabel in x, relative to max(1, |x|_inf): |x - x*| <= c |e|_2 with
/// c of order 10 on these QPs (the worst seen is 6e-9 at |e|_2 <= 1e-10), plus Clarabel's own
/// error.
const AGREE_TOL: f64 = 1e-7;
/// The equality-plus-bounds shape, robio2018's (M invertible).
const EQ_BOUNDS: QpDims = QpDims {
    nx: 6,
    n_eq: 3,
    n_in: 0,
};

fn settings() -> LviSettings {
    LviSettings {
        tolerance: TIGHT,
        ..LviSettings::default()
    }
}

fn rel_dx(x: &[f64], reference: &[f64]) -> f64 {
    let scale = reference.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    x.iter()
        .zip(reference)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale
}

/// Solves every QP cold with `method`; asserts that each answer agrees with Clarabel and
/// returns the failures (seed, error).
fn run(method: LviMethod, qps: &[Qp]) -> Vec<(usize, LviError)> {
    let mut clarabel = ExactSolver::new();
    let mut failures = Vec::new();
    let mut most = 0;
    for (seed, qp) in qps.iter().enumerate() {
        let mut solver = LviSolver::new(method, qp.dims(), settings());
        match solver.solve(qp) {
            Ok(iterations) => {
                let exact = clarabel.solve(qp).expect("random QPs are feasible");
                let dx = rel_dx(solver.x(), exact.x.as_slice());
                assert!(dx <= AGREE_TOL, "{} seed {seed}: dx {dx:e}", method.name());
                most = most.max(iterations);
            }
            Err(e) => failures.push((seed, e)),
        }
    }
    eprintln!(
        "{}: {} of {} converged, most iterations {most}",
        method.name(),
        qps.len() - failures.len(),
        qps.len()
    );
    failures
}

fn eq_bounds_qps() -> Vec<Qp> {
    (0..N_PER_SHAPE)
        .map(|seed| random_feasible(EQ_BOUNDS, seed))
        .collect()
}

fn shape_qps(shape: QpShape) -> Vec<Qp> {
    (0..N_PER_SHAPE)
        .map(|seed| random_qp(shape, seed))
        .collect()
}

#[test]
fn every_method_but_94lvi_agrees_with_clarabel_on_equality_bounds_qps() {
    let qps = eq_bounds_qps();
    for method in LviMethod::ALL {
        let failures = run(method, &qps);
        if method == LviMethod::Lvi94 {
            // Finding: 94LVI as printed (Q = I, rho = |e|^2 / e'(I + M)e, unprojected) is not
            // convergent here: it fails (diverges or stalls) on part of these QPs.
            assert!(!failures.is_empty());
        } else {
            assert!(failures.is_empty(), "{}: {failures:?}", method.name());
        }
    }
}

#[test]
fn equality_only_qps() {
    for shape in [QpShape::Kong2019, QpShape::Zhang2018] {
        let qps = shape_qps(shape);
        for method in LviMethod::ALL {
            eprint!("{shape:?} ");
            let failures = run(method, &qps);
            match method {
                // Finding: 94LVI as printed diverges on every equality-only QP (with no bound
                // to project on, U - rho (M U + q) with rho in [1/2, 1] is unstable for the
                // skew part of M).
                LviMethod::Lvi94 => assert_eq!(failures.len(), qps.len()),
                // M5 converges, but slowly (up to ~85,000 iterations to |e|_2 <= 1e-10).
                LviMethod::E47 | LviMethod::M4 | LviMethod::M5 | LviMethod::M6 => {
                    assert!(failures.is_empty(), "{}: {failures:?}", method.name())
                }
                // Finding: M3 converges on only part of these QPs (kong2019 48 of 50, zhang2018
                // 25 of 50: it breaks down or diverges on the others).
                LviMethod::M3 => assert!(failures.len() < qps.len()),
            }
        }
    }
}

#[test]
fn qps_with_inequality_rows_have_a_singular_m() {
    for shape in [QpShape::Jia2019, QpShape::Zhong2021] {
        let qps = shape_qps(shape);
        for method in LviMethod::ALL {
            eprint!("{shape:?} ");
            let failures = run(method, &qps);
            match method {
                // More rows than variables: M is singular, and the methods that invert it
                // say so.
                LviMethod::E47 | LviMethod::M3 | LviMethod::M6 => {
                    assert_eq!(failures.len(), qps.len());
                    for (_, e) in &failures {
                        assert!(
                            matches!(e, LviError::SingularMatrix { matrix: "M", .. }),
                            "{e}"
                        );
                    }
                }
                // I + M is always invertible: M4 solves them all.
                LviMethod::M4 => assert!(failures.is_empty(), "{failures:?}"),
                // Finding: neither 94LVI (diverges or stalls) nor M5 (stalls: not even
                // |e|_2 <= 1e-3 in 200,000 iterations) converges on these shapes.
                LviMethod::Lvi94 | LviMethod::M5 => assert_eq!(failures.len(), qps.len()),
            }
        }
    }
}

#[test]
fn a_second_solve_of_the_same_qp_takes_no_iteration() {
    let qp = random_feasible(EQ_BOUNDS, 7);
    let n = qp.dims().nx + qp.dims().n_eq;
    for method in LviMethod::ALL {
        let mut solver = LviSolver::new(method, qp.dims(), settings());
        let Ok(first) = solver.solve(&qp) else {
            assert_eq!(method, LviMethod::Lvi94, "only 94LVI fails here");
            continue;
        };
        assert!(first > 0);
        let again = QpSolver::solve(&mut solver, &qp).unwrap();
        assert_eq!(again.iterations, 0, "{}", method.name());
        // Only the confirming residual: no iteration, no factorisation.
        assert_eq!(again.products, Some(1));
        assert_eq!(method.products(0, n), 1);
        solver.reset();
        assert_eq!(solver.solve(&qp).unwrap(), first, "reset is a cold start");
    }
}

#[test]
fn typed_errors() {
    let qp = random_qp(QpShape::Zhong2021, 3);
    let settings = LviSettings {
        tolerance: 1e-12,
        max_iterations: 2,
    };
    let mut solver = LviSolver::new(LviMethod::M4, qp.dims(), settings);
    let err = solver.solve(&qp).unwrap_err().to_string();
    assert!(err.contains("did not reach"), "{err}");
    let other = random_qp(QpShape::Kong2019, 0);
    assert!(matches!(
        solver.solve(&other),
        Err(LviError::Dimensions { .. })
    ));
}

#[cfg(feature = "osqp")]
#[test]
fn osqp_agrees_with_clarabel_warm() {
    let mut clarabel = ExactSolver::new();
    for shape in QpShape::ALL {
        let dims = random_qp(shape, 0).dims();
        let mut osqp = OsqpQp::new(dims, OsqpSettings::default());
        let mut worst = 0.0f64;
        for seed in 0..N_PER_SHAPE {
            // One solver for the whole family: every solve after the first is warm-started
            // from the previous QP's answer, and its data updated in place.
            let qp = random_qp(shape, seed);
            let exact = clarabel.solve(&qp).unwrap();
            osqp.solve(&qp)
                .unwrap_or_else(|e| panic!("{shape:?} seed {seed}: {e}"));
            let dx = rel_dx(osqp.x(), exact.x.as_slice());
            assert!(
                dx <= AGREE_TOL,
                "OSQP {shape:?} seed {seed}: |x - x_clarabel| = {dx:e}"
            );
            let kkt = qp.kkt_residuals(
                &nalgebra::DVector::from_column_slice(osqp.x()),
                &osqp.duals(),
            );
            assert!(kkt.max() <= 1e-5, "OSQP {shape:?} seed {seed}: {kkt:?}");
            worst = worst.max(dx);
        }
        eprintln!("OSQP {shape:?}: worst |x - x*| {worst:.1e}");
    }
}
