//! [`LviSolver::solve`] allocates nothing, for every one of robio2018's six methods, whether it
//! converges, fails to, or finds M singular; nor does the [`QpSolver`] view of it when it
//! converges (a failure there carries its error boxed, `qp::QpSolverError`: one allocation on a
//! path that ends the run).

use alloc_count::count;
use solvers::{random_feasible, random_qp, QpDims, QpShape, QpSolver};
use solvers::{LviMethod, LviSettings, LviSolver};

#[test]
fn plpe_solves_do_not_allocate() {
    assert!(count(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
    let dims = QpDims {
        nx: 6,
        n_eq: 3,
        n_in: 0,
    };
    let qps: Vec<_> = (0..10)
        .map(|seed| random_feasible(dims, seed))
        .chain((0..5).map(|seed| random_qp(QpShape::Jia2019, seed)))
        .collect();
    let settings = LviSettings {
        max_iterations: 5_000,
        ..LviSettings::default()
    };
    for method in LviMethod::ALL {
        for (k, qp) in qps.iter().enumerate() {
            let mut solver = LviSolver::new(method, qp.dims(), settings);
            let mut converged = false;
            let n = count(|| {
                converged = solver.solve(qp).is_ok();
            });
            assert_eq!(n, 0, "{} QP {k}: {n} allocations", method.name());
            if !converged {
                continue;
            }
            let n = count(|| {
                let _ = QpSolver::solve(&mut solver, qp);
                solver.reset();
                let _ = QpSolver::solve(&mut solver, qp);
            });
            assert_eq!(n, 0, "{} QP {k}: {n} allocations", method.name());
        }
    }
}
