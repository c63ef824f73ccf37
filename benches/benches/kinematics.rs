//! Cost of the arm models and of the schemes' QP assembly at a realistic state ([`ArmState`],
//! [`SchemeCase`]).
//!
//! * group `robots`: Jaco2 (pen) position, Jacobian, Jacobian derivative, inertia matrix H,
//!   Coriolis vector c, gravity g; Katana 6M180 Jacobian.
//! * group `schemes`: `<paper>-<scheme>/build` (one QP, called per RHS evaluation of every run)
//!   and `<paper>-<scheme>/build_dot` (its time derivative, called per RHS evaluation of the
//!   zeroing and penalty networks' runs) for jia2019 VLTCO, zhong2021 CMCO, zhang2018 HL-JDF,
//!   kong2019 finite-time and ZNN, and `<paper>-<scheme>/exact-Clarabel` (one `ExactSolver::solve`
//!   of that QP: what the exact column pays per RHS evaluation and every neural run per accepted
//!   step, for its score against the optimum).

use criterion::measurement::WallTime;
use criterion::{black_box, criterion_group, criterion_main, BenchmarkGroup, Criterion};
use driftbench_benches::{
    experiment_jobs, fast_config, jaco2_model, jaco2_scheme_cases, katana_scheme_cases,
    report_allocations, SchemeCase,
};
use robots::{Dynamics, Katana6m180, Robot};
use solvers::ExactSolver;

fn robots(c: &mut Criterion) {
    let jobs = experiment_jobs();
    let jaco = jaco2_scheme_cases(&jobs);
    let katana = katana_scheme_cases(&jobs);
    let s = jaco[0].state.clone();
    let k = katana[0].state.clone();
    let pen = jaco2_model("jaco2-pen");
    let kat = Katana6m180::new();
    // Output buffers, allocated once as a run allocates them.
    let (mut j, mut jd, mut h) = ([0.0; 18], [0.0; 18], [0.0; 36]);
    let (mut cv, mut gv, mut jk) = ([0.0; 6], [0.0; 6], [0.0; 15]);

    report_allocations("robots/jaco2-pen/all-six-calls", || {
        black_box(pen.position(&s.theta));
        pen.jacobian(&s.theta, &mut j);
        pen.jacobian_dot(&s.theta, &s.thetadot, &mut jd);
        pen.inertia(&s.theta, &mut h);
        pen.coriolis(&s.theta, &s.thetadot, &mut cv);
        pen.gravity(&s.theta, &mut gv);
        black_box((&j, &jd, &h, &cv, &gv));
    });
    report_allocations("robots/katana6m180/jacobian", || {
        kat.jacobian(&k.theta, &mut jk);
        black_box(&jk);
    });
    let mut g = c.benchmark_group("robots");
    g.bench_function("jaco2-pen/position", |b| {
        b.iter(|| pen.position(black_box(&s.theta)))
    });
    g.bench_function("jaco2-pen/jacobian", |b| {
        b.iter(|| pen.jacobian(black_box(&s.theta), black_box(&mut j)))
    });
    g.bench_function("jaco2-pen/jacobian_dot", |b| {
        b.iter(|| {
            pen.jacobian_dot(
                black_box(&s.theta),
                black_box(&s.thetadot),
                black_box(&mut jd),
            )
        })
    });
    g.bench_function("jaco2-pen/inertia", |b| {
        b.iter(|| pen.inertia(black_box(&s.theta), black_box(&mut h)))
    });
    g.bench_function("jaco2-pen/coriolis", |b| {
        b.iter(|| {
            pen.coriolis(
                black_box(&s.theta),
                black_box(&s.thetadot),
                black_box(&mut cv),
            )
        })
    });
    g.bench_function("jaco2-pen/gravity", |b| {
        b.iter(|| pen.gravity(black_box(&s.theta), black_box(&mut gv)))
    });
    g.bench_function("katana6m180/jacobian", |b| {
        b.iter(|| kat.jacobian(black_box(&k.theta), black_box(&mut jk)))
    });
    g.finish();
}

fn bench_scheme(g: &mut BenchmarkGroup<'_, WallTime>, case: &SchemeCase) {
    let mut qp = case.scheme.new_qp();
    let mut qp_dot = case.scheme.new_qp();
    let mut scratch = case.scheme.new_dot_scratch();
    report_allocations(&format!("schemes/{}/build", case.label), || {
        case.build(&mut qp)
    });
    g.bench_function(format!("{}/build", case.label), |b| {
        b.iter(|| {
            case.build(black_box(&mut qp));
            black_box(&qp);
        })
    });
    report_allocations(&format!("schemes/{}/build_dot", case.label), || {
        case.build_dot(&mut qp_dot, &mut scratch)
    });
    g.bench_function(format!("{}/build_dot", case.label), |b| {
        b.iter(|| {
            case.build_dot(black_box(&mut qp_dot), &mut scratch);
            black_box(&qp_dot);
        })
    });
    case.build(&mut qp);
    let mut exact = ExactSolver::new();
    exact
        .solve(&qp)
        .unwrap_or_else(|e| panic!("{}: Clarabel failed on the scheme's QP: {e}", case.label));
    g.bench_function(format!("{}/exact-Clarabel", case.label), |b| {
        b.iter(|| exact.solve(black_box(&qp)).map(|s| s.x))
    });
}

fn schemes(c: &mut Criterion) {
    let jobs = experiment_jobs();
    let mut g = c.benchmark_group("schemes");
    for case in &jaco2_scheme_cases(&jobs) {
        bench_scheme(&mut g, case);
    }
    for case in &katana_scheme_cases(&jobs) {
        bench_scheme(&mut g, case);
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = fast_config();
    targets = robots, schemes
}
criterion_main!(benches);
