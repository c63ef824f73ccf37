//! Whole runs through `simulation::run_job`, exactly as `reproduce` runs them (the ODE
//! integration of arm + solver, the metrics, the score against the exact optimum along the run),
//! for the runs `benches/cases.toml` lists (`runs`): the exact column and the neural runs of one
//! experiment per velocity-level paper. Group `runs`, ids `<experiment>/<solver>`.
//!
//! Each job is run once before timing and must complete, so a bench never times a failure; that
//! run's counts (steps, RHS and Jacobian evaluations, Clarabel solves, allocations) go to stderr.
//! A neural run's Clarabel solves are the score against the exact optimum at every accepted
//! step, which `run_job` always computes: they are part of the time measured here.

use criterion::{black_box, criterion_group, criterion_main, Criterion, SamplingMode};
use driftbench_benches::{bench_cases, bench_id, experiment_jobs, find_run, whole_run_config};
use simulation::run_job;
use simulation::Outcome;

fn whole_runs(c: &mut Criterion) {
    let jobs = experiment_jobs();
    let mut g = c.benchmark_group("runs");
    g.sampling_mode(SamplingMode::Flat);
    for key in bench_cases().runs {
        let job = find_run(&jobs, &key);
        let (record, allocations) = alloc_count::count_with(|| run_job(&job));
        if let Outcome::Failed { t, error, .. } = &record.run.outcome {
            panic!("{}: failed at t = {t}: {error}", job.key());
        }
        eprintln!(
            "run {}: {} steps, {} rhs, {} jacobians, {} LU, {} Clarabel solves, {} allocations",
            job.key(),
            record.run.stats.steps,
            record.run.stats.rhs_evals,
            record.run.stats.jac_evals,
            record.run.stats.lu_factorisations,
            record.run.qp.solves,
            allocations
        );
        let key = job.key();
        g.bench_function(
            format!("{}/{}", key.experiment, bench_id(&key.solver)),
            |b| b.iter(|| black_box(run_job(black_box(&job)))),
        );
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = whole_run_config();
    targets = whole_runs
}
criterion_main!(benches);
