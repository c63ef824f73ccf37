//! E47 and 94LVI against Clarabel on random QPs of every paper's shape: cold-started (y = 0) and
//! warm-started along slowly varying sequences, as a control loop calls them. And OSQP
//! (warm-started) on the same QPs.

use solvers::lvi_numerical::{LviMethod, LviSettings, LviSolver};
use solvers::osqp_qp::{OsqpQp, OsqpSettings};
use solvers::{random_qp, ExactSolver, Qp, QpShape};

/// Random QPs per paper shape and method (4 shapes: 2,000 QPs per method).
const N_PER_SHAPE: u64 = 500;
/// Required agreement with Clarabel in x, relative to max(1, |x|_inf).
const AGREE_TOL: f64 = 1e-6;

fn rel_dx(x: &[f64], reference: &[f64]) -> f64 {
    let scale = reference.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    x.iter()
        .zip(reference)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale
}

/// The QP of `seed` with its data moved by a small relative perturbation `s` (a sequence of
/// nearby QPs, as consecutive control ticks give).
fn perturbed(qp: &Qp, s: f64) -> Qp {
    let mut next = qp.clone();
    for (i, v) in next.q.iter_mut().enumerate() {
        *v += s * ((i + 1) as f64).sin();
    }
    for (i, v) in next.b.iter_mut().enumerate() {
        *v += s * ((i + 2) as f64).cos();
    }
    next
}

#[test]
fn lvi_methods_agree_with_clarabel_cold() {
    let mut clarabel = ExactSolver::new();
    for method in LviMethod::ALL {
        for shape in QpShape::ALL {
            let mut worst = 0.0f64;
            let mut max_iter = 0;
            for seed in 0..N_PER_SHAPE {
                let qp = random_qp(shape, seed);
                let exact = clarabel.solve(&qp).expect("random QPs are feasible");
                let mut solver = LviSolver::new(method, qp.dims(), LviSettings::default());
                let iterations = solver
                    .solve(&qp)
                    .unwrap_or_else(|e| panic!("{shape:?} seed {seed}: {e}"));
                let dx = rel_dx(solver.x(), exact.x.as_slice());
                assert!(
                    dx <= AGREE_TOL,
                    "{} {shape:?} seed {seed}: |x - x_clarabel| = {dx:e}",
                    method.name()
                );
                worst = worst.max(dx);
                max_iter = max_iter.max(iterations);
            }
            eprintln!(
                "{} {shape:?}: worst |x - x*| {worst:.1e}, most iterations {max_iter}",
                method.name()
            );
        }
    }
}

#[test]
fn lvi_methods_warm_along_sequences() {
    let mut clarabel = ExactSolver::new();
    for method in LviMethod::ALL {
        for shape in QpShape::ALL {
            for seed in 0..20 {
                let mut qp = random_qp(shape, 10_000 + seed);
                let mut solver = LviSolver::new(method, qp.dims(), LviSettings::default());
                let mut cold_iterations = None;
                for step in 0..50 {
                    let iterations = solver.solve(&qp).unwrap();
                    cold_iterations.get_or_insert(iterations);
                    let exact = clarabel.solve(&qp).unwrap();
                    let dx = rel_dx(solver.x(), exact.x.as_slice());
                    assert!(dx <= AGREE_TOL, "{shape:?} seed {seed} step {step}: {dx:e}");
                    qp = perturbed(&qp, 1e-4);
                }
            }
        }
    }
}

#[test]
fn lvi_solve_reports_non_convergence() {
    let qp = random_qp(QpShape::Zhong2021, 3);
    let settings = LviSettings {
        tolerance: 1e-12,
        max_iterations: 2,
    };
    let mut solver = LviSolver::new(LviMethod::E47, qp.dims(), settings);
    let err = solver.solve(&qp).unwrap_err().to_string();
    assert!(err.contains("did not reach"), "{err}");
}

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
