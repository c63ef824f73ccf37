//! The timing pass: after the parallel reproduction, the runs whose times are compared — the
//! leaderboard's (every non-exact run on a standard task, [`analysis::leaderboard`]) and the
//! runs the report sets beside the papers' MATLAB times ([`Papers::timed_runs`]) — run again
//! [`records::TIMING_REPETITIONS`] times each, one run at a time on this (one) thread, into
//! `results/leaderboard-timing.csv` ([`records::Timings`]), which the leaderboard ranks by and
//! the report's MATLAB comparison shows. No other run is timed: no table shows its time.
//!
//! Only the times are kept: a repetition recomputes the same run, and `results/runs.csv` keeps
//! the reproduction's row.

use analysis::leaderboard::standard_tasks;
use analysis::papers::{Papers, PapersError};
use records::index::Runs;
use records::RunRow;
use records::{TimingRow, Timings, TIMING_REPETITIONS};
use simulation::run_job;
use simulation::run_row;
use spec::RunKey;
use spec::RunSpec;
use std::collections::BTreeSet;
use std::path::Path;
use store::results_dir::{ResultsDir, ResultsError};

/// Why the timing pass could not run or write its table.
#[derive(Debug, thiserror::Error)]
pub enum TimingError {
    #[error(transparent)]
    Results(#[from] ResultsError),
    #[error(transparent)]
    Runs(#[from] store::RunsError),
    #[error(transparent)]
    Papers(#[from] PapersError),
    #[error("{0}: a stored run no experiment file describes cannot be timed")]
    Undescribed(RunKey),
}

/// The keys of the runs to time (sorted): the leaderboard's and those set beside a published
/// MATLAB time.
pub fn timed_keys(runs: &Runs, papers: &Papers) -> BTreeSet<RunKey> {
    let tasks = standard_tasks(runs.all());
    let mut keys: BTreeSet<RunKey> = runs
        .all()
        .iter()
        .filter(|r| {
            !r.is_exact()
                && tasks
                    .iter()
                    .any(|t| t.experiment == r.experiment && t.variant == r.variant_id)
        })
        .map(RunRow::key)
        .collect();
    keys.extend(
        papers
            .timed_runs(runs)
            .filter_map(|t| t.run)
            .map(RunRow::key),
    );
    keys
}

/// Times the compared runs alone (module docs) and writes `results/leaderboard-timing.csv`
/// into `results` (papers read from `papers_dir`); `all` are the experiment files' jobs. Returns
/// how many runs were timed.
pub fn time_alone(
    all: &[RunSpec],
    results: &ResultsDir,
    papers_dir: &Path,
    git_rev: &str,
) -> Result<usize, TimingError> {
    let papers = Papers::load(papers_dir)?;
    let keys = timed_keys(&Runs::new(results.read_runs()?), &papers);
    let (machine, cores) = crate::cost::machine();
    let mut rows = Vec::with_capacity(keys.len());
    eprintln!(
        "timing {} runs alone, {TIMING_REPETITIONS} times each, one at a time",
        keys.len()
    );
    for key in keys {
        let job = all
            .iter()
            .find(|j| j.key() == key)
            .ok_or_else(|| TimingError::Undescribed(key.clone()))?;
        let samples: Vec<(f64, f64)> = (0..TIMING_REPETITIONS)
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
    store::timing::write(results.path(), &Timings::new(rows))?;
    results.save()?;
    Ok(timed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use analysis::papers::{Mapping, PaperValue};
    use settings::NetworkKind;
    use spec::SolverKind;

    fn row(paper: &str, experiment: &str, variant: &str, solver: &str) -> RunRow {
        let kind = if solver == spec::EXACT_ID {
            SolverKind::Exact
        } else {
            SolverKind::Network(NetworkKind::ALL[0])
        };
        RunRow {
            paper: paper.to_string(),
            ..RunRow::blank(
                &RunKey::from_ids(experiment, variant, solver).unwrap(),
                kind,
            )
        }
    }

    /// A paper publishing the time of solver `s1` on its experiment `e`, our `m-e`.
    fn papers() -> Papers {
        Papers {
            values: vec![PaperValue {
                paper: "m".into(),
                table: "T1".into(),
                experiment: "e".into(),
                column: "S1".into(),
                metric: "sim_s".into(),
                value: 2.0,
                note: String::new(),
                inconsistent: None,
            }],
            mappings: vec![Mapping {
                paper: "m".into(),
                published_experiment: "e".into(),
                published_column: "S1".into(),
                run: RunKey::from_ids("m-e", "w", "s1").unwrap(),
                companions: Vec::new(),
            }],
            ..Papers::default()
        }
    }

    #[test]
    fn the_leaderboard_runs_and_those_beside_a_published_time_are_timed() {
        let runs = Runs::new(vec![
            row("cross", "c", "v", "exact"),
            row("cross", "c", "v", "a"),
            row("m", "m-e", "w", "s1"),
            row("m", "m-e", "v", "s1"),
            row("m", "m-e", "v", "s2"),
            row("m", "m-e", "v", "exact"),
        ]);
        let keys: Vec<String> = timed_keys(&runs, &papers())
            .iter()
            .map(RunKey::to_string)
            .collect();
        // The leaderboard's non-exact run, and the first run of the published solver (by key):
        // not the exact column, the other variant or the solver without a published time.
        assert_eq!(keys, ["c / v / a", "m-e / v / s1"]);
    }
}
