//! Per-evaluation cost of each paper's networks against one exact solve, on a representative QP
//! of the paper's shape ([`RepresentativeQp`]).
//!
//! Groups are named by paper (`jia2019`, `zhong2021`, `zhang2018`, `kong2019`, so
//! `cargo bench -p driftbench-benches --bench solvers -- zhong2021` selects one); ids are
//! `<network>/rhs` (one right-hand-side evaluation, what the integrator calls per stage),
//! `<network>/jacobian` (one analytic dF/dy, what a stiff integrator calls per Newton
//! refresh), `exact-Clarabel/solve` (one `ExactSolver::solve`, what the exact column calls per
//! RHS evaluation before the active-set path), `exact-active-set/hot` and `/cold` (one certified
//! active-set solve, hot-started from the optimum's working set or cold: what the exact column
//! and the scorer call now) and, on the equality-only shapes, `direct-KKT/solve` (one dense KKT
//! solve).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use driftbench_benches::{
    bench_id, experiment_jobs, fast_config, paper_networks, report_allocations, RepresentativeQp,
    EVAL_TIME,
};
use nalgebra::DMatrix;
use solvers::neural::build_solver;
use solvers::{solve_equality_kkt, ActiveSetSolution, ActiveSetSolver, ExactSolver};

fn per_evaluation(c: &mut Criterion) {
    let jobs = experiment_jobs();
    for rep in RepresentativeQp::all() {
        let paper = rep.shape.paper();
        let mut group = c.benchmark_group(paper);
        for (name, spec) in paper_networks(&jobs, rep.shape) {
            let id = bench_id(&name);
            let mut net = build_solver(&spec, rep.qp.dims())
                .unwrap_or_else(|e| panic!("{paper} {name}: {e}"));
            let y = rep.network_state(net.as_ref());
            let n = y.len();
            let mut ydot = vec![0.0; n];
            let mut jac = DMatrix::zeros(n, n);

            let qp_dot = rep.qp_dot_for(net.as_ref());
            report_allocations(&format!("{paper}/{id}/rhs"), || {
                net.rhs(EVAL_TIME, &y, &rep.qp, qp_dot, &mut ydot)
            });
            group.bench_function(format!("{id}/rhs"), |b| {
                b.iter(|| {
                    net.rhs(
                        black_box(EVAL_TIME),
                        black_box(&y),
                        black_box(&rep.qp),
                        qp_dot,
                        &mut ydot,
                    );
                    black_box(&ydot);
                })
            });

            report_allocations(&format!("{paper}/{id}/jacobian"), || {
                assert!(
                    net.jacobian(EVAL_TIME, &y, &rep.qp, qp_dot, &mut jac),
                    "{name}: no analytic Jacobian"
                );
            });
            group.bench_function(format!("{id}/jacobian"), |b| {
                b.iter(|| {
                    black_box(net.jacobian(
                        black_box(EVAL_TIME),
                        black_box(&y),
                        black_box(&rep.qp),
                        qp_dot,
                        &mut jac,
                    ));
                    black_box(&jac);
                })
            });
        }

        let mut exact = ExactSolver::new();
        report_allocations(&format!("{paper}/exact-Clarabel/solve"), || {
            exact
                .solve(&rep.qp)
                .expect("Clarabel solves the representative QP");
        });
        group.bench_function("exact-Clarabel/solve", |b| {
            b.iter(|| exact.solve(black_box(&rep.qp)).map(|s| s.x))
        });

        // The exact path of the loop: the certified active-set solver, hot-started from the
        // previous answer's working set (one KKT solve when the active set has not changed) and
        // cold (the dual method from the equality-constrained minimiser).
        let mut fast = ActiveSetSolver::new(rep.qp.dims());
        let mut out = ActiveSetSolution::zeros(rep.qp.dims());
        fast.solve_into(&rep.qp, None, &mut out)
            .expect("the active-set solver solves the representative QP");
        let warm = out.working_set.clone();
        report_allocations(&format!("{paper}/exact-active-set/hot"), || {
            fast.solve_into(&rep.qp, Some(&warm), &mut out)
                .expect("hot start");
        });
        group.bench_function("exact-active-set/hot", |b| {
            b.iter(|| fast.solve_into(black_box(&rep.qp), Some(&warm), &mut out))
        });
        group.bench_function("exact-active-set/cold", |b| {
            b.iter(|| fast.solve_into(black_box(&rep.qp), None, &mut out))
        });

        if rep.shape.is_equality_only() {
            report_allocations(&format!("{paper}/direct-KKT/solve"), || {
                solve_equality_kkt(&rep.qp).expect("the KKT matrix is regular");
            });
            group.bench_function("direct-KKT/solve", |b| {
                b.iter(|| solve_equality_kkt(black_box(&rep.qp)))
            });
        }
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = fast_config();
    targets = per_evaluation
}
criterion_main!(benches);
