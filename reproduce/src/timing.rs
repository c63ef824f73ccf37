//! The timing pass: after the parallel reproduction, the runs whose times are compared — the
//! leaderboard's (every non-exact run on a standard task, [`analysis::leaderboard`]) and every
//! run of the experiments the papers publish a MATLAB time for — run again
//! [`records::timing::REPETITIONS`] times each, one run at a time on this (one) thread, into
//! `results/leaderboard-timing.csv` ([`records::timing`]), which the leaderboard ranks by and
//! the report's MATLAB comparison shows.
//!
//! Only the times are kept: a repetition recomputes the same run, and `results/runs.csv` keeps
//! the reproduction's row.

use analysis::leaderboard::standard_tasks;
use analysis::papers::{Papers, PapersError};
use catalog::experiment::Job;
use catalog::run_key::RunKey;
use records::results_dir::{ResultsDir, ResultsError};
use records::runs::RunRow;
use records::timing::{TimingRow, Timings, REPETITIONS};
use simulation::row::run_row;
use simulation::run::run_job;
use std::collections::BTreeSet;
use std::path::Path;

/// Why the timing pass could not run or write its table.
#[derive(Debug, thiserror::Error)]
pub enum TimingError {
    #[error(transparent)]
    Results(#[from] ResultsError),
    #[error(transparent)]
    Runs(#[from] records::error::RunsError),
    #[error(transparent)]
    Papers(#[from] PapersError),
    #[error("{0}: a stored run no experiment file describes cannot be timed")]
    Undescribed(RunKey),
}

/// The keys of the runs to time (sorted): the leaderboard's and the MATLAB experiments'.
pub fn timed_keys(rows: &[RunRow], papers: &Papers) -> BTreeSet<RunKey> {
    let tasks = standard_tasks(rows);
    let matlab = papers.timed_experiments();
    rows.iter()
        .filter(|r| {
            let standard = !r.is_exact()
                && tasks
                    .iter()
                    .any(|t| t.experiment == r.experiment && t.variant == r.variant_id);
            standard || matlab.contains(&r.experiment.as_str())
        })
        .map(RunRow::key)
        .collect()
}

/// Times the compared runs alone (module docs) and writes `results/leaderboard-timing.csv`
/// into `results` (papers read from `papers_dir`); `all` are the experiment files' jobs. Returns
/// how many runs were timed.
pub fn time_alone(
    all: &[Job],
    results: &ResultsDir,
    papers_dir: &Path,
    git_rev: &str,
) -> Result<usize, TimingError> {
    let papers = Papers::load(papers_dir)?;
    let keys = timed_keys(&results.read_runs()?, &papers);
    let (machine, cores) = cost::machine();
    let mut rows = Vec::with_capacity(keys.len());
    eprintln!(
        "timing {} runs alone, {REPETITIONS} times each, one at a time",
        keys.len()
    );
    for key in keys {
        let job = all
            .iter()
            .find(|j| j.key() == key)
            .ok_or_else(|| TimingError::Undescribed(key.clone()))?;
        let samples: Vec<(f64, f64)> = (0..REPETITIONS)
            .map(|_| {
                let row = run_row(&run_job(job), git_rev);
                (row.sim_s, row.wall_s)
            })
            .collect();
        rows.push(TimingRow::from_samples(
            &key, &samples, &machine, cores, git_rev,
        ));
    }
    let timed = rows.len();
    records::timing::write(results.path(), &Timings::new(rows))?;
    results.save()?;
    Ok(timed)
}
