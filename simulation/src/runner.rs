//! Running many jobs: in parallel across runs (rayon), longest first, with a progress bar
//! ([`map_costliest_first`]: list scheduling of independent items).
//! Each run is independent and deterministic, so the order of execution never changes a number.

use crate::run::{run_job, RunRecord};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::iter::{ParallelBridge, ParallelIterator};
use settings::NetworkKind;
use spec::RunSpec;
use spec::SolverChoice;
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::Instant;

/// Runs `jobs` and returns their records in the order of `jobs`.
pub fn run_jobs(jobs: &[RunSpec], progress: bool) -> Vec<RunRecord> {
    run_jobs_with(jobs, progress, |_| {})
}

/// [`run_jobs`], calling `finished` with each record as soon as its run ends (from the worker
/// thread: the checkpoint journal).
pub fn run_jobs_with(
    jobs: &[RunSpec],
    progress: bool,
    finished: impl Fn(&RunRecord) + Sync,
) -> Vec<RunRecord> {
    run_jobs_into(jobs, progress, |r| {
        finished(&r);
        r
    })
}

/// Runs `jobs`, handing each record to `finished` as soon as its run ends (from the worker
/// thread), and returns what `finished` made of them, in the order of `jobs`. A caller that
/// writes each record out and keeps nothing of it (a shard) holds no record beyond the runs in
/// flight.
pub fn run_jobs_into<R: Send>(
    jobs: &[RunSpec],
    progress: bool,
    finished: impl Fn(RunRecord) -> R + Sync,
) -> Vec<R> {
    let bar = ProgressBar::new(jobs.len() as u64);
    if progress {
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} runs  {msg}",
            )
            .expect("valid template"),
        );
    } else {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    }
    // Without a terminal (CI logs, redirected output) the bar is hidden: a line per finished
    // experiment shows life instead.
    let log = (progress && !std::io::stderr().is_terminal()).then(|| ExperimentLog::new(jobs));
    let made = map_costliest_first(jobs, expected_cost, |job| {
        let r = finished(run_job(job));
        bar.inc(1);
        bar.set_message(job.key().to_string());
        if let Some(log) = &log {
            log.finished(&job.experiment);
        }
        r
    });
    bar.finish_and_clear();
    made
}

/// `f` of every item of `items`, on rayon's pool, returned in the order of `items`. The items
/// are handed out one at a time, costliest first (by `cost`; ties in their order), each to the
/// next thread that is free, so that a long item never starts last while the other threads
/// idle (an indexed parallel iterator would instead give each thread a contiguous block to run
/// in order, where a long item far down its block can start last). Each item must be
/// independent of the others and deterministic: then the order of execution and the number of
/// threads change no result.
pub fn map_costliest_first<T: Sync, R: Send>(
    items: &[T],
    cost: impl Fn(&T) -> f64,
    f: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by(|&a, &b| cost(&items[b]).total_cmp(&cost(&items[a])));
    let mut done: Vec<(usize, R)> = order
        .iter()
        .par_bridge()
        .map(|&i| (i, f(&items[i])))
        .collect();
    done.sort_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, r)| r).collect()
}

/// Rough relative cost for scheduling: neural runs on long paths first, the finite-time
/// network (hundreds of thousands of steps) before everything.
fn expected_cost(j: &RunSpec) -> f64 {
    let solver = match &j.solver {
        SolverChoice::Exact => 1.0,
        SolverChoice::Neural(s) if s.network_kind() == NetworkKind::FiniteTime => 100.0,
        SolverChoice::Neural(_) => 4.0,
        // Every instant of the fixed-step loop iterates the method (thousands of instants).
        SolverChoice::Numerical(_) => 20.0,
    };
    solver * j.path.duration
}

/// Per experiment id: (runs finished, runs).
type Counts = BTreeMap<String, (usize, usize)>;

/// Progress without a terminal: one line per experiment whose runs have all finished, with the
/// overall count and the elapsed time.
struct ExperimentLog {
    started: Instant,
    total: usize,
    /// Per experiment: (finished, runs); and the runs finished overall.
    state: Mutex<(Counts, usize)>,
}

impl ExperimentLog {
    fn new(jobs: &[RunSpec]) -> Self {
        let mut per: BTreeMap<String, (usize, usize)> = BTreeMap::new();
        for j in jobs {
            per.entry(j.experiment.to_string()).or_default().1 += 1;
        }
        Self {
            started: Instant::now(),
            total: jobs.len(),
            state: Mutex::new((per, 0)),
        }
    }

    fn finished(&self, experiment: &str) {
        let Ok(mut state) = self.state.lock() else {
            return;
        };
        state.1 += 1;
        let overall = state.1;
        if let Some((done, runs)) = state.0.get_mut(experiment) {
            *done += 1;
            if done == runs {
                eprintln!(
                    "[{:>7.1} s] {experiment}: {runs} runs done ({overall}/{} overall)",
                    self.started.elapsed().as_secs_f64(),
                    self.total
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_results_come_in_the_order_of_the_items_whatever_their_costs() {
        let items: Vec<usize> = (0..200).collect();
        // Costs that reorder the execution: every seventh item first.
        let out = map_costliest_first(&items, |&i| (i % 7) as f64, |&i| i * i);
        assert_eq!(out, items.iter().map(|i| i * i).collect::<Vec<_>>());
        assert!(map_costliest_first(&[] as &[usize], |_| 0.0, |&i| i).is_empty());
    }

    #[test]
    fn the_costliest_items_are_handed_out_first() {
        // On one thread the items run in the order they are handed out.
        let started = Mutex::new(Vec::new());
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| {
                map_costliest_first(
                    &[1.0, 5.0, 3.0, 5.0],
                    |&c| c,
                    |&c| {
                        started.lock().unwrap().push(c);
                    },
                )
            });
        assert_eq!(started.into_inner().unwrap(), [5.0, 5.0, 3.0, 1.0]);
    }
}
