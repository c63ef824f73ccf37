//! The outside solver against the suite: the conformance kit with one call, then a run of an
//! experiment file whose numerical solver is the outside one, registered at run time through
//! the library API (`solvers::registry::register`), next to the same run by Clarabel.

use outside_solver::{EqualityKkt, ID};
use qp::QpSolver;
use reproduce::experiments_from_toml as checked;
use settings::qp_solver::{Limits, QpSolverInfo};
use simulation::run_job;
use simulation::run_row;
use solvers::conformance::{check_qp_solver, AllocationCounter, Conformance};
use solvers::QpShape;
use spec::SolverChoice;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Once};

/// The test binary's counting allocator.
struct Counter;

impl AllocationCounter for Counter {
    fn count(&self, f: &mut dyn FnMut()) -> usize {
        alloc_count::count(f)
    }
}

/// Solvers the registered constructor has built.
static BUILT: AtomicUsize = AtomicUsize::new(0);

/// Registers the outside solver once per test binary (tests share the registry).
fn register() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let info = QpSolverInfo {
            id: ID,
            name: "equality KKT (outside)",
            tolerance: Some(Limits {
                min: 1e-14,
                max: 1e-2,
                default: 1e-9,
            }),
            max_iterations: None,
        };
        solvers::registry::register(
            info,
            Arc::new(|dims, settings| {
                BUILT.fetch_add(1, Ordering::SeqCst);
                let tolerance = settings.tolerance.expect("resolve gives the tolerance");
                Box::new(EqualityKkt::new(dims, tolerance))
            }),
        )
        .expect("the id is new");
    });
}

#[test]
fn the_outside_solver_passes_the_conformance_kit() {
    let violations = check_qp_solver(
        &|dims| Box::new(EqualityKkt::new(dims, 1e-9)),
        &Conformance {
            shapes: &[QpShape::Zhang2018, QpShape::Kong2019],
            random_feasible: false,
            ..Conformance::default()
        },
        Some(&Counter),
    );
    let text: Vec<String> = violations.iter().map(|v| v.to_string()).collect();
    assert!(text.is_empty(), "{}", text.join("\n"));
    // It claims no inequalities: on a shape with active ones it refuses, by status.
    let qp = solvers::random_qp(QpShape::Jia2019, 0);
    let mut solver = EqualityKkt::new(qp.dims(), 1e-9);
    let e = solver.solve(&qp).unwrap_err();
    assert_eq!(e.status, qp::QpStatus::InvalidInput, "{e}");
}

/// kong2019's ZNN scheme (equality-only QPs) on the Katana, 2 s of the circle, solved at every
/// instant by the outside solver and by Clarabel.
const FILE: &str = r#"
paper = "outside"
title = "An outside QP solver as a run's solver"

[[experiment]]
id = "outside-circle"
paper_output = "none"
robot = "katana6m180"
path = { name = "circle", duration = 2.0 }
theta_ref = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.0471975511965976]
theta0 = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.5471975511965976]

[[experiment.variant]]
id = "znn"
label = "ZNN scheme"
scheme = { kind = "znn-rmp", mu = 1.0, k_p = 1.0 }
exact = false
numerical = [{ method = "equality-kkt", tolerance = 1e-8 }, { method = "clarabel" }]
"#;

#[test]
fn a_run_uses_the_registered_outside_solver() {
    // Before registration the file names an unknown solver, at the field.
    if settings::qp_solver::lookup(ID).is_err() {
        let e = checked(FILE).unwrap_err().to_string();
        assert!(e.contains("unknown QP solver \"equality-kkt\""), "{e}");
    }
    register();
    let bad = FILE.replace("tolerance = 1e-8", "tolerance = 1.0");
    let e = checked(&bad).unwrap_err().to_string();
    assert!(
        e.contains("field `numerical[0]`") && e.contains("tolerance = 1e0 must be within"),
        "{e}"
    );
    let file = checked(FILE).unwrap();
    let jobs = file.jobs().unwrap();
    assert_eq!(jobs.len(), 2);
    let before = BUILT.load(Ordering::SeqCst);
    let rows: Vec<_> = jobs.iter().map(|j| run_row(&run_job(j), "test")).collect();
    assert_eq!(
        BUILT.load(Ordering::SeqCst),
        before + 1,
        "built once, for its run"
    );
    let (outside, clarabel) = (&rows[0], &rows[1]);
    let SolverChoice::Numerical(spec) = &jobs[0].solver else {
        panic!("a numerical run");
    };
    assert_eq!(spec.method.id(), ID);
    assert_eq!(outside.solver_kind.to_string(), ID);
    assert_eq!(outside.solver_id.as_str(), "equality-kkt-tol-1e-8");
    assert!(outside.completed(), "{}", outside.failure);
    assert!(clarabel.completed(), "{}", clarabel.failure);
    // One KKT solve per instant: 2 s at h = 1 ms is 2001 instants.
    assert_eq!(outside.solver_iterations, Some(2001));
    // Both solve the same QPs exactly: the same trajectory, to rounding and Clarabel's
    // tolerance.
    for (a, b) in outside.drift.iter().zip(&clarabel.drift) {
        assert!(
            (a - b).abs() < 1e-7,
            "{:?} vs {:?}",
            outside.drift,
            clarabel.drift
        );
    }
    assert!(
        outside.score_max_dx.unwrap() < 1e-7,
        "{:?}",
        outside.score_max_dx
    );
}
