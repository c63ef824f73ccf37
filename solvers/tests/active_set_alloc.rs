//! [`ActiveSetSolver::solve_into`] allocates nothing once its buffers and the output are sized,
//! cold or hot-started, certified or not, and neither does a hot-started [`ExactPath`] solve of
//! MVN's QP in reduced form (between its Clarabel checks): counted with a global allocator that
//! counts the current thread's allocations while a flag is set.

use alloc_count::count;
use solvers::{
    random_qp, ActiveSetSolution, ActiveSetSolver, ExactPath, QpShape, WorkingSet, CHECK_EVERY,
};

#[test]
fn solves_do_not_allocate() {
    assert!(count(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
    for certify in [false, true] {
        for shape in QpShape::ALL {
            let qps: Vec<_> = (0..50).map(|seed| random_qp(shape, seed)).collect();
            let dims = qps[0].dims();
            let mut solver = ActiveSetSolver::new(dims).with_certification(certify);
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
                assert_eq!(out.certified, certify);
            }
        }
    }
}

#[test]
fn reduced_mvn_solves_do_not_allocate() {
    let mut qp = random_qp(QpShape::Jia2019, 5);
    let p = qp.q.len() - 1;
    qp.p[(p, p)] = 0.0;
    let mut path = ExactPath::new(&qp);
    path.solve(&qp).unwrap();
    for k in 1..CHECK_EVERY {
        qp.b[0] += 1e-4;
        let n = count(|| {
            path.solve(&qp).unwrap();
        });
        assert_eq!(n, 0, "solve {k}: {n} allocations");
    }
    assert_eq!(path.stats.fallbacks, 0);
}
