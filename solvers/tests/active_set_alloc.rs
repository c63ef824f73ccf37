//! With certification off, [`ActiveSetSolver::solve_into`] allocates nothing once its buffers and
//! the output are sized, cold or hot-started: counted with a global allocator that counts the
//! current thread's allocations while a flag is set. (Certification calls `Qp::kkt_residuals`,
//! which allocates; that is documented in the module.)

mod common;

use common::count;
use solvers::{random_qp, ActiveSetSolution, ActiveSetSolver, QpDims, QpShape, WorkingSet};

#[test]
fn uncertified_solves_do_not_allocate() {
    assert!(count(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
    for shape in QpShape::ALL {
        let qps: Vec<_> = (0..50).map(|seed| random_qp(shape, seed)).collect();
        let dims = qps[0].dims();
        let mut solver = ActiveSetSolver::new(dims).with_certification(false);
        let mut out = ActiveSetSolution::zeros(dims);
        let mut prev = WorkingSet::with_capacity(dims.nx);
        for (seed, qp) in qps.iter().enumerate() {
            // Warm from the previous QP's set (primal or dual continuation, or cold).
            let n1 = count(|| solver.solve_into(qp, Some(&prev), &mut out).unwrap());
            let n2 = count(|| solver.solve_into(qp, None, &mut out).unwrap());
            let n3 = count(|| prev.clone_from(&out.working_set));
            let n4 = count(|| solver.solve_into(qp, Some(&prev), &mut out).unwrap());
            let n = n1 + n2 + n3 + n4;
            assert_eq!(n, 0, "{shape:?} seed {seed}: {n} allocations");
            assert!(!out.certified);
        }
    }
    // Certified, the only allocations are those of Qp::kkt_residuals.
    let qp = random_qp(QpShape::Jia2019, 1);
    let mut solver = ActiveSetSolver::new(QpDims {
        nx: 7,
        n_eq: 3,
        n_in: 12,
    });
    let mut out = ActiveSetSolution::zeros(qp.dims());
    solver.solve_into(&qp, None, &mut out).unwrap();
    let n = count(|| solver.solve_into(&qp, None, &mut out).unwrap());
    let d = out.duals.clone();
    let x = out.x.clone();
    let m = count(|| {
        std::hint::black_box(qp.kkt_residuals(&x, &d));
    });
    assert_eq!(n, m, "certified solve allocates beyond kkt_residuals");
}
