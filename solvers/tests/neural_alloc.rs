//! The networks' `rhs` and `jacobian` must not allocate (their scratch is preallocated): counted
//! with a global allocator that counts allocations made by the current thread while a flag is
//! set. Every kind of [`SolverSpec`], with every activation where it takes one, and the group's
//! network with each of its options.

use alloc_count::count;
use nalgebra::DMatrix;
use settings::SolverSpec;
use solvers::neural::build_solver;
use solvers::{random_qp, Qp, QpShape};

#[derive(serde::Deserialize)]
struct File {
    solver: SolverSpec,
}

#[test]
fn network_evaluations_do_not_allocate() {
    assert!(count(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
    let pert = "perturbation = { a_s = 1.5, task_duration = 8.0 }";
    let acts = [
        "activation = \"linear\"",
        "activation = \"sinh\"",
        "activation = \"power-sigmoid\"",
        "activation = \"group-power-sigmoid\", xi = 1.0, power = 3.0",
    ];
    let mut cases: Vec<(String, QpShape)> = vec![
        ("kind = \"lvi-pdnn\", gamma = 1e7".into(), QpShape::Jia2019),
        (
            "kind = \"s-lvi-pdnn\", beta = 1e7".into(),
            QpShape::Zhong2021,
        ),
        (
            "kind = \"finite-time\", beta = 1.0, alpha = 0.1".into(),
            QpShape::Kong2019,
        ),
        ("kind = \"znn\", gamma = 1.0".into(), QpShape::Kong2019),
        ("kind = \"group-znn\"".into(), QpShape::Kong2019),
        (
            format!("kind = \"group-znn\", udot_rmp = false, {pert}"),
            QpShape::Zhang2018,
        ),
    ];
    for act in acts {
        cases.push((
            format!("kind = \"vp-rnn-pf\", p = 1e-4, sigma = 400.0, gamma = 2.0, {act}"),
            QpShape::Zhong2021,
        ));
        cases.push((
            format!("kind = \"fp-cdnn\", gamma = 200.0, {act}, {pert}"),
            QpShape::Zhang2018,
        ));
        cases.push((
            format!("kind = \"vp-cdnn\", gamma = 2.0, {act}"),
            QpShape::Zhang2018,
        ));
        cases.push((
            format!("kind = \"group-znn\", {act}, {pert}"),
            QpShape::Zhang2018,
        ));
    }
    for (text, shape) in cases {
        let spec = toml::from_str::<File>(&format!("solver = {{ {text} }}"))
            .unwrap_or_else(|e| panic!("{text}: {e}"))
            .solver;
        let qp = random_qp(shape, 3);
        let dims = qp.dims();
        let mut net = build_solver(&spec, dims).unwrap();
        let n = net.state_dim(dims);
        let y: Vec<f64> = (0..n).map(|i| 0.1 * (i as f64) - 0.3).collect();
        let mut dy = vec![0.0; n];
        let mut jac = DMatrix::zeros(n, n);
        let mut qp_dot = Qp::zeros(dims);
        qp_dot.q.fill(0.2);
        qp_dot.a.fill(0.1);
        let qd = spec.needs_qp_dot().then_some(&qp_dot);
        // Warm up (nothing lazily allocated may hide in the first call either, but the counted
        // calls are the second and third).
        net.rhs(0.5, &y, &qp, qd, &mut dy);
        net.jacobian(0.5, &y, &qp, qd, &mut jac);
        let allocs = count(|| {
            net.rhs(0.7, &y, &qp, qd, &mut dy);
            net.jacobian(0.7, &y, &qp, qd, &mut jac);
        });
        assert_eq!(allocs, 0, "{}: {allocs} allocations", spec.display_name());
    }
}
