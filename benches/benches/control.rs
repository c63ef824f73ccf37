//! One control tick of every method on every task of the control experiments' standard task
//! set (`catalog::load_task_set`) at h = 1 ms: the QPs of the first [`TICKS`] ticks of the exact
//! discrete run are collected once, then each id times one `TickSolver::tick` on them in turn
//! (the solver keeps its state from tick to tick, as in the loop: warm starts, network state).
//!
//! Groups are named by task slug (`cargo bench -p driftbench-benches --bench control -- vltco`);
//! ids are the method labels of `results/control.csv` (`E47`, `active set`, `LVI-PDNN [Euler]`).
//! A network whose one step per tick diverges on the task is timed all the same (a step costs
//! the same whether or not it converges).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use driftbench_benches::fast_config;
use qp::Qp;
use spec::slug;

use control::{
    load_tasks, run_loop, with_task, Discretisation, LoopSettings, Method, Numerical, Observer,
    Rounding, TaskArm,
};

/// Ticks collected per task.
const TICKS: usize = 200;
/// The control period.
const H: f64 = 1e-3;

/// Keeps the QPs (and their time derivatives) of the first ticks.
struct Collect {
    qps: Vec<(Qp, Qp)>,
}

impl Observer for Collect {
    fn needs_qp_dot(&self) -> bool {
        true
    }
    fn observe(&mut self, _k: usize, _t: f64, qp: &Qp, qp_dot: Option<&Qp>, _x: &[f64]) {
        let dot = qp_dot.cloned().unwrap_or_else(|| qp.clone());
        self.qps.push((qp.clone(), dot));
    }
}

/// The QPs of a task's first ticks with the exact optimum in the loop.
fn sample(arm: &TaskArm<'_>) -> Vec<(Qp, Qp)> {
    let mut collect = Collect { qps: Vec::new() };
    let mut solver = solvers::HotActiveSet::new(arm.scheme.dims());
    let settings = LoopSettings {
        h: H,
        period: arm.period,
        cycles: 1,
        max_ticks: Some(TICKS),
        rounding: Rounding::AsComputed,
    };
    run_loop(
        arm.robot,
        arm.path,
        arm.scheme,
        &mut solver,
        arm.theta0,
        &settings,
        Some(&mut collect),
    );
    collect.qps
}

fn per_tick(c: &mut Criterion) {
    let root = catalog::root_from_current_dir().expect("run inside the workspace");
    let experiments = root.join("experiments");
    let set = catalog::load_task_set(&experiments).expect("the standard task set");
    let jobs: Vec<_> = reproduce::load_experiments(&experiments)
        .expect("the experiment files")
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .collect();
    let tasks = load_tasks(&jobs, &set.tasks).expect("the tasks");
    for task in &tasks {
        let qps = with_task(task, 1, sample).expect("the task builds");
        let mut methods: Vec<Method> = Numerical::all()
            .into_iter()
            .map(Method::Numerical)
            .collect();
        for spec in &task.networks {
            methods.push(Method::Network {
                spec: spec.clone(),
                form: Discretisation::Euler,
                substeps: 1,
            });
        }
        let mut group = c.benchmark_group(slug(&task.id()));
        for method in &methods {
            let mut solver = method.build(qps[0].0.dims()).expect("the method builds");
            let mut k = 0usize;
            group.bench_function(method.label(), |b| {
                b.iter(|| {
                    let (qp, dot) = &qps[k % qps.len()];
                    let _ = black_box(solver.tick(k as f64 * H, qp, Some(dot), H));
                    k += 1;
                })
            });
        }
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = fast_config();
    targets = per_tick
}
criterion_main!(benches);
