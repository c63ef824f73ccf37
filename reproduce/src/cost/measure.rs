//! How the cases are timed, and the whole measurement of `reproduce cost`.
//!
//! [`std::time::Instant`] around batches: a per-call quantity is timed as `reps` back-to-back
//! calls on one state (`reps` chosen once per quantity and backend so a batch lasts at least
//! [`Budget::min_batch_us`], so the clock's resolution and overhead do not count), the sample
//! being the batch's time over `reps`; every state gives one sample per pass, over
//! [`Budget::passes`] passes. A run is one sample per repetition ([`Budget::runs`]). Reported
//! are the median and the 95th percentile of the samples ([`Summary`], the workspace's
//! percentile), in microseconds. Nothing here asserts a speed: the numbers go to
//! `results/dof-cost.csv` and the report.

use super::case::{backends, Case, PreparedCase};
use super::harness::{LARGE_SIZES, LARGE_STATES, SWEEP_SIZES};
use records::dof_cost::{Measurement, Quantity, SchemeKind, Summary};
use std::time::Instant;

/// How much is measured: the defaults take about a minute for every case on one core of a
/// 2020s server CPU (most of it the jia2019 runs at N = 20 and 30, and the nalgebra LUs at
/// N = 200).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// States sampled from the exact run's trace at the sweep's sizes.
    pub states: usize,
    /// States sampled at the large sizes ([`LARGE_STATES`]).
    pub large_states: usize,
    /// Passes over the states (samples per quantity = states x passes).
    pub passes: usize,
    /// Shortest batch of back-to-back calls (us).
    pub min_batch_us: f64,
    /// Most calls in one batch.
    pub max_reps: usize,
    /// Whole runs per run quantity (one sample each).
    pub runs: usize,
}

impl Default for Budget {
    fn default() -> Self {
        Budget {
            states: 100,
            large_states: LARGE_STATES,
            passes: 3,
            min_batch_us: 20.0,
            max_reps: 200,
            runs: 5,
        }
    }
}

/// The machine measured on: the CPU model of `/proc/cpuinfo` and the logical cores the process
/// may use (`"unknown CPU"` where there is no `/proc/cpuinfo`).
pub fn machine() -> (String, usize) {
    let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = cpuinfo
        .lines()
        .find_map(|l| {
            let (key, value) = l.split_once(':')?;
            (key.trim() == "model name").then(|| value.split_whitespace().collect::<Vec<_>>())
        })
        .map(|words| words.join(" "))
        .unwrap_or_else(|| "unknown CPU".to_string());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    (model, cores)
}

/// Measures every case: both schemes at every N of [`SWEEP_SIZES`], then kong2019 at every N
/// of [`LARGE_SIZES`], calling `progress` after each case.
pub fn measure_all(budget: &Budget, mut progress: impl FnMut(&Case)) -> Vec<Measurement> {
    let mut out = Vec::new();
    for scheme in SchemeKind::ALL {
        for n in SWEEP_SIZES {
            let case = Case::new(scheme, n);
            match super::harness::prepare(&case, budget.states) {
                Ok(mut p) => out.extend(measure(case.scheme, case.n, p.as_mut(), budget)),
                Err(e) => eprintln!("{e}; nothing measured"),
            }
            progress(&case);
        }
    }
    for n in LARGE_SIZES {
        let case = Case::new(SchemeKind::ZnnRmp, n);
        match super::harness::prepare(&case, budget.large_states) {
            Ok(mut p) => out.extend(measure(case.scheme, case.n, p.as_mut(), budget)),
            Err(e) => eprintln!("{e}; nothing measured"),
        }
        progress(&case);
    }
    out
}

/// Times every quantity `prepared` supports on each of its backends (see the module docs).
pub fn measure(
    scheme: SchemeKind,
    n: usize,
    prepared: &mut dyn PreparedCase,
    budget: &Budget,
) -> Vec<Measurement> {
    let timer = Timer { budget };
    let mut out = Vec::new();
    for quantity in Quantity::ALL {
        if !prepared.supports(quantity) {
            continue;
        }
        for &backend in backends(quantity) {
            let (samples, run) = if quantity.is_run() {
                let samples = repeat_runs(budget.runs, || prepared.call(quantity, backend, 0));
                (samples, prepared.last_run())
            } else {
                let states = prepared.states();
                let samples = timer.samples(states, |i| prepared.call(quantity, backend, i));
                (samples, None)
            };
            if let Some(summary) = Summary::of(&samples) {
                let dims = prepared.dims();
                out.push(Measurement {
                    scheme,
                    scheme_name: prepared.scheme_name(),
                    network: prepared.network_name(),
                    n,
                    nx: dims.nx,
                    n_eq: dims.n_eq,
                    n_in: dims.n_in,
                    quantity,
                    backend: backend.id().to_string(),
                    summary,
                    run,
                });
            }
        }
    }
    out
}

/// Wall times (us) of `times` (at least one) calls of `run`.
fn repeat_runs(times: usize, mut run: impl FnMut()) -> Vec<f64> {
    (0..times.max(1))
        .map(|_| {
            let started = Instant::now();
            run();
            started.elapsed().as_secs_f64() * 1e6
        })
        .collect()
}

/// Times per-call quantities (see the module docs).
struct Timer<'a> {
    budget: &'a Budget,
}

impl Timer<'_> {
    /// Per-call times (us) of `op(i)` for every state i = 0..states, over the passes.
    fn samples(&self, states: usize, mut op: impl FnMut(usize)) -> Vec<f64> {
        if states == 0 {
            return Vec::new();
        }
        // Calibration: one call (and a warm-up of caches and lazily grown buffers).
        op(0);
        let started = Instant::now();
        op(0);
        let once_us = started.elapsed().as_secs_f64() * 1e6;
        let reps = ((self.budget.min_batch_us / once_us.max(1e-3)).ceil() as usize)
            .clamp(1, self.budget.max_reps.max(1));
        let mut out = Vec::with_capacity(states * self.budget.passes);
        for _ in 0..self.budget.passes.max(1) {
            for i in 0..states {
                let started = Instant::now();
                for _ in 0..reps {
                    op(std::hint::black_box(i));
                }
                out.push(started.elapsed().as_secs_f64() * 1e6 / reps as f64);
            }
        }
        out
    }
}
