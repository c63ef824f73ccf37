//! Running many jobs: in parallel across runs (rayon), longest first, with a progress bar.
//! Each run is independent and deterministic, so the order of execution never changes a number.

use crate::run::{run_job, RunRecord};
use catalog::experiment::{Job, SolverChoice};
use indicatif::{ParallelProgressIterator, ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use settings::network_kind::NetworkKind;
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::Instant;

/// Runs `jobs` and returns their records in the order of `jobs`.
pub fn run_jobs(jobs: &[Job], progress: bool) -> Vec<RunRecord> {
    run_jobs_with(jobs, progress, |_| {})
}

/// [`run_jobs`], calling `finished` with each record as soon as its run ends (from the worker
/// thread: the checkpoint journal).
pub fn run_jobs_with(
    jobs: &[Job],
    progress: bool,
    finished: impl Fn(&RunRecord) + Sync,
) -> Vec<RunRecord> {
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
    // Longest runs first keeps every core busy to the end.
    let mut order: Vec<usize> = (0..jobs.len()).collect();
    order.sort_by(|&a, &b| expected_cost(&jobs[b]).total_cmp(&expected_cost(&jobs[a])));
    let mut records: Vec<(usize, RunRecord)> = order
        .par_iter()
        .progress_with(bar.clone())
        .map(|&i| {
            let r = run_job(&jobs[i]);
            finished(&r);
            bar.set_message(jobs[i].key().to_string());
            if let Some(log) = &log {
                log.finished(&jobs[i].experiment);
            }
            (i, r)
        })
        .collect();
    bar.finish_and_clear();
    records.sort_by_key(|(i, _)| *i);
    records.into_iter().map(|(_, r)| r).collect()
}

/// Rough relative cost for scheduling: neural runs on long paths first, the finite-time
/// network (hundreds of thousands of steps) before everything.
fn expected_cost(j: &Job) -> f64 {
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
    fn new(jobs: &[Job]) -> Self {
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
