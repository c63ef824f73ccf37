//! The per-tick hot paths allocate nothing once built: every numerical method's tick (E47,
//! 94LVI, the hot-started active set, OSQP's Rust side) and every network form's tick, on random
//! QPs of every paper's shape, counted with the suite's counting allocator
//! (crate `alloc-count`). Clarabel is left out: it allocates per solve by design.

use alloc_count::count;
use control::{Discretisation, Method, Numerical};
use settings::SolverSpec;
use solvers::{random_qp, QpShape};

fn methods() -> Vec<Method> {
    let mut out: Vec<Method> = Numerical::all()
        .into_iter()
        .filter(|n| n.solver.id() != "clarabel")
        .map(Method::Numerical)
        .collect();
    for spec in [
        SolverSpec::LviPdnn { gamma: 1e7 },
        SolverSpec::SLviPdnn { beta: 1e7 },
        SolverSpec::Znn { gamma: 1.0 },
    ] {
        for form in [Discretisation::Euler, Discretisation::Taylor] {
            out.push(Method::Network {
                spec: spec.clone(),
                form,
                substeps: 3,
            });
        }
    }
    out
}

#[test]
fn ticks_do_not_allocate() {
    assert!(count(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
    for shape in QpShape::ALL {
        let qps: Vec<_> = (0..20).map(|seed| random_qp(shape, seed)).collect();
        for method in methods() {
            // The zeroing networks take equality-constrained QPs only.
            let Ok(mut solver) = method.build(qps[0].dims()) else {
                assert!(!shape.is_equality_only(), "{} on {shape:?}", method.label());
                continue;
            };
            // The first tick sets up (OSQP's workspace, the active set's buffers).
            let _ = solver.tick(0.0, &qps[0], Some(&qps[0]), 1e-3);
            for (k, qp) in qps.iter().enumerate() {
                let mut result = Ok(qp::QpSolve::default());
                let n = count(|| result = solver.tick(k as f64 * 1e-3, qp, Some(qp), 1e-3));
                // The scaled networks and robio2018's rules as printed may fail on random data;
                // a failed tick carries its error boxed (`qp::QpSolverError`, one allocation on
                // a path that ends the run), so only the ticks that succeed are held to none.
                if result.is_err() {
                    continue;
                }
                assert_eq!(
                    n,
                    0,
                    "{} on {shape:?} QP {k}: {n} allocations",
                    method.label()
                );
            }
        }
    }
}
