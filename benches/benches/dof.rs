//! Cost against the number of joints, with criterion's statistics: the quantities of the cost
//! harness (`reproduce::cost`, which `reproduce cost` writes to `results/dof-cost.csv` for the
//! report) on the n-link arms `nlink-N` for N = 3, 7, 15, 30, with jia2019's VLTCO scheme
//! (four-leaf clover) and kong2019's ZNN scheme (circle), and kong2019 at N = 100 and 200
//! (per-instant quantities only).
//!
//! Groups are `dof/<scheme>/<quantity>/<backend>`, ids the joint count N, so a full id reads
//! `dof/jia2019/exact-active-set/nalgebra/15` and `cargo bench -p driftbench-benches --bench
//! dof -- dof/kong2019/kkt-floor` compares the backends of one quantity. A per-call quantity
//! cycles through the sampled states, so its mean is over a trajectory, not one point; a run
//! quantity (`run-exact`, `run-network`) is one whole `simulate` call (flat sampling, the
//! minimum of 10 samples: the jia2019 runs at N = 30 take seconds each).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};
use driftbench_benches::{fast_config, whole_run_config};
use records::dof_cost::{Quantity, SchemeKind};
use reproduce::cost::{backends, prepare, Case, PreparedCase, LARGE_STATES};
use solvers::Backend;

/// The joint counts benched with both schemes (a subset of the harness's sweep).
const SIZES: [usize; 4] = [3, 7, 15, 30];
/// The joint counts benched with kong2019's scheme alone (a subset of the harness's large sizes).
const LARGE_SIZES: [usize; 2] = [100, 200];
/// States sampled from the exact run of each case.
const STATES: usize = 100;

/// The prepared cases of `scheme`, with their N.
fn cases(scheme: SchemeKind, states: usize) -> Vec<(usize, Box<dyn PreparedCase>)> {
    let sweep = SIZES.iter().map(|&n| {
        let p = prepare(&Case::new(scheme, n), states);
        (n, p.unwrap_or_else(|e| panic!("{e}")))
    });
    let large = LARGE_SIZES
        .iter()
        .filter(|_| scheme == SchemeKind::ZnnRmp)
        .map(|&n| {
            let p = prepare(&Case::new(scheme, n), LARGE_STATES);
            (n, p.unwrap_or_else(|e| panic!("{e}")))
        });
    sweep.chain(large).collect()
}

fn per_call(c: &mut Criterion) {
    for scheme in SchemeKind::ALL {
        let mut cases = cases(scheme, STATES);
        for quantity in Quantity::ALL.into_iter().filter(|q| !q.is_run()) {
            for &backend in backends(quantity) {
                let mut group = c.benchmark_group(format!(
                    "dof/{}/{}/{}",
                    scheme.id(),
                    quantity.id(),
                    backend.id()
                ));
                for (n, case) in cases.iter_mut() {
                    if !case.supports(quantity) {
                        continue;
                    }
                    let mut i = 0usize;
                    group.bench_function(BenchmarkId::from_parameter(*n), |b| {
                        b.iter(|| {
                            i = i.wrapping_add(1);
                            case.call(quantity, backend, i);
                        })
                    });
                }
                group.finish();
            }
        }
    }
}

fn whole_runs(c: &mut Criterion) {
    for scheme in SchemeKind::ALL {
        let mut cases = cases(scheme, 1);
        for quantity in Quantity::ALL.into_iter().filter(|q| q.is_run()) {
            let mut group = c.benchmark_group(format!(
                "dof/{}/{}/{}",
                scheme.id(),
                quantity.id(),
                Backend::Nalgebra.id()
            ));
            group.sampling_mode(SamplingMode::Flat);
            for (n, case) in cases.iter_mut().filter(|(_, c)| c.supports(quantity)) {
                group.bench_function(BenchmarkId::from_parameter(*n), |b| {
                    b.iter(|| case.call(quantity, Backend::Nalgebra, 0))
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
