//! Any solver of the registry is a tick's solver, with no adapter: a solver registered from
//! outside at run time (here one that hands each QP to Clarabel through its own box) runs the
//! control loop as a `Method::Numerical` and gives what the built-in Clarabel gives, tick for
//! tick.

use control::{
    load_tasks, run_loop, with_task, LoopOutcome, LoopSettings, Method, Numerical, Rounding,
};
use settings::qp_solver::{QpSolverInfo, QpSolverSettings};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

static BUILT: AtomicUsize = AtomicUsize::new(0);

/// 300 ticks of the first standard task with `method`.
fn run(method: &Method) -> LoopOutcome {
    let experiments = Path::new(env!("CARGO_MANIFEST_DIR")).join("../experiments");
    let set = catalog::load_task_set(&experiments).unwrap();
    let jobs: Vec<_> = catalog::load_dir(&experiments)
        .unwrap()
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .collect();
    let tasks = load_tasks(&jobs, &set.tasks[..1]).unwrap();
    with_task(&tasks[0], 1, |arm| {
        let mut solver = method.build(arm.scheme.dims()).unwrap();
        let settings = LoopSettings {
            h: 1e-3,
            period: arm.period,
            cycles: 1,
            max_ticks: Some(300),
            rounding: Rounding::AsComputed,
        };
        run_loop(
            arm.robot,
            arm.path,
            arm.scheme,
            solver.as_mut(),
            arm.theta0,
            &settings,
            None,
        )
    })
    .unwrap()
}

#[test]
fn a_solver_registered_from_outside_is_a_ticks_solver() {
    let key = solvers::registry::register(
        QpSolverInfo {
            id: "outside-clarabel",
            name: "Clarabel (registered from outside)",
            tolerance: None,
            max_iterations: None,
        },
        Arc::new(|dims, _| {
            BUILT.fetch_add(1, Ordering::SeqCst);
            solvers::registry::build("clarabel", &QpSolverSettings::default(), dims).unwrap()
        }),
    )
    .unwrap();
    let outside = run(&Method::Numerical(Numerical {
        solver: key,
        settings: QpSolverSettings::default(),
    }));
    assert_eq!(BUILT.load(Ordering::SeqCst), 1);
    let clarabel = Numerical::all()
        .into_iter()
        .find(|n| n.solver.id() == "clarabel")
        .unwrap();
    let builtin = run(&Method::Numerical(clarabel));
    assert_eq!(outside.ticks, 300);
    assert_eq!(outside.status, builtin.status);
    assert_eq!(outside.drift, builtin.drift);
    assert_eq!(outside.max_dx, builtin.max_dx);
    assert_eq!(outside.max_track_err, builtin.max_track_err);
    assert_eq!(outside.iterations_mean, builtin.iterations_mean);
    assert!(
        outside.iterations_mean > 0.0,
        "Clarabel's iterations are counted"
    );
    assert!(outside.max_dx < 1e-6, "{}", outside.max_dx);
}
