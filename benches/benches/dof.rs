//! Cost against the number of joints, with criterion's statistics: the quantities of
//! `simulation::dof_cost` (and of `reproduce --dof-cost`, which writes them to
//! `results/dof-cost.csv` for the report) on the n-link arms `nlink-N` for N = 3, 7, 15, 30,
//! with jia2019's VLTCO scheme (four-leaf clover) and kong2019's ZNN scheme (circle).
//!
//! Groups are `dof/<scheme>/<quantity>`, ids the joint count N, so a full id reads
//! `dof/jia2019/exact-active-set/15` and `cargo bench -p driftbench-benches --bench dof --
//! dof/jia2019` selects one scheme. A per-call quantity (`scheme-build`, `network-rhs`,
//! `network-jacobian`, `exact-active-set`, `exact-clarabel`, `kkt-floor`) cycles through the
//! states sampled from one exact run, so its mean is over a trajectory, not one point; a run
//! quantity (`run-exact`, `run-network`) is one whole `simulate` call (flat sampling, the
//! minimum of 10 samples: the jia2019 runs at N = 30 take seconds each).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};
use driftbench_benches::{fast_config, whole_run_config};
use simulation::dof_cost::{prepare, Case, Quantity, SchemeKind};

/// The joint counts benched (a subset of the registry's `NLINK_SIZES`).
const SIZES: [usize; 4] = [3, 7, 15, 30];
/// States sampled from the exact run of each case.
const STATES: usize = 100;

fn per_call(c: &mut Criterion) {
    for scheme in SchemeKind::ALL {
        let mut cases: Vec<_> = SIZES
            .iter()
            .map(|&n| {
                prepare(&Case::new(scheme, n), STATES)
                    .unwrap_or_else(|e| panic!("{} nlink-{n}: {e}", scheme.id()))
            })
            .collect();
        for quantity in Quantity::ALL.into_iter().filter(|q| !q.is_run()) {
            let mut group = c.benchmark_group(format!("dof/{}/{}", scheme.id(), quantity.id()));
            for (case, n) in cases.iter_mut().zip(SIZES) {
                if !case.supports(quantity) {
                    continue;
                }
                let mut i = 0usize;
                group.bench_function(BenchmarkId::from_parameter(n), |b| {
                    b.iter(|| {
                        i = i.wrapping_add(1);
                        case.call(quantity, i);
                    })
                });
            }
            group.finish();
        }
    }
}

fn whole_runs(c: &mut Criterion) {
    for scheme in SchemeKind::ALL {
        let mut cases: Vec<_> = SIZES
            .iter()
            .map(|&n| {
                prepare(&Case::new(scheme, n), 1)
                    .unwrap_or_else(|e| panic!("{} nlink-{n}: {e}", scheme.id()))
            })
            .collect();
        for quantity in Quantity::ALL.into_iter().filter(|q| q.is_run()) {
            let mut group = c.benchmark_group(format!("dof/{}/{}", scheme.id(), quantity.id()));
            group.sampling_mode(SamplingMode::Flat);
            for (case, n) in cases.iter_mut().zip(SIZES) {
                group.bench_function(BenchmarkId::from_parameter(n), |b| {
                    b.iter(|| case.call(quantity, 0))
                });
            }
            group.finish();
        }
    }
}

criterion_group! {
    name = calls;
    config = fast_config();
    targets = per_call
}
criterion_group! {
    name = runs;
    config = whole_run_config();
    targets = whole_runs
}
criterion_main!(calls, runs);
