//! The regression gate's baseline for `reproduce check`: the committed rows, read
//! before anything runs (a given file, or git HEAD's `results/runs.csv`, with the committed
//! explanation, leaderboard and control runs beside it); the comparison itself is crate
//! `analysis`'s (`analysis::gate`), and any difference is exit code 3.

use crate::error::{BaselineError, Exit, ReproduceError};
use analysis::leaderboard::LeaderboardRow;
use records::control::ControlRow;
use records::Timings;
use records::{check_run_rows, RunRow};
use spec::RunSpec;
use std::path::Path;
use std::process::ExitCode;

/// The rows the gate compares with, and a name for its messages (a file, or
/// `git HEAD:results/runs.csv`).
#[derive(Debug)]
pub struct Baseline {
    pub rows: Vec<RunRow>,
    pub name: String,
    /// The committed explanation (ladder and attribution rows) from the same place as `rows`
    /// (empty for a given baseline file, which has none).
    pub explanation: explain::Explained,
    /// The committed leaderboard, from the same place (empty for a given baseline file).
    pub leaderboard: Vec<LeaderboardRow>,
    /// The committed control experiments' runs, from the same place (empty for a given
    /// baseline file).
    pub control: Vec<ControlRow>,
    /// The leaderboard's timings (`results/leaderboard-timing.csv` of the results directory),
    /// with which the leaderboard is derived afresh from the runs.
    timings: Timings,
}

impl Baseline {
    /// The gate's baseline, read before anything runs: `file` when given; otherwise the
    /// committed `results/runs.csv` of git HEAD (so a run followed by `check` compares with
    /// what is committed, not with what the run just wrote); outside a checkout, or for another
    /// results directory, its `runs.csv`. `all`: every run of the experiment files, by which a
    /// baseline written before run ids is read with its ids recovered (store::migrate).
    pub fn read(
        root: &Path,
        results_dir: &Path,
        file: Option<&Path>,
        all: &[RunSpec],
    ) -> Result<Self, ReproduceError> {
        if let Some(f) = file {
            if f.is_dir() {
                return Err(ReproduceError::BaselineIsDirectory(f.to_path_buf()));
            }
            let name = f.display().to_string();
            let rows =
                read(f, inputs::Origin::Named, all).map_err(ReproduceError::GivenBaseline)?;
            return Ok(Self {
                rows,
                name,
                explanation: explain::Explained::default(),
                leaderboard: Vec::new(),
                control: Vec::new(),
                timings: Timings::default(),
            });
        }
        let in_tree = results_dir == root.join(store::results_dir::DIR);
        let show = |file: &str| {
            in_tree
                .then(|| {
                    std::process::Command::new("git")
                        .args(["show", &format!("HEAD:results/{file}")])
                        .current_dir(root)
                        .output()
                        .ok()
                        .filter(|o| o.status.success())
                })
                .flatten()
        };
        let committed = show(store::results_dir::RUNS);
        let explanation = explain::Explained {
            ladder: committed_table(
                show(store::results_dir::LADDER),
                results_dir,
                store::results_dir::LADDER,
            )?,
            attribution: committed_table(
                show(store::results_dir::ATTRIBUTION),
                results_dir,
                store::results_dir::ATTRIBUTION,
            )?,
        };
        let leaderboard = committed_table(
            show(store::results_dir::LEADERBOARD),
            results_dir,
            store::results_dir::LEADERBOARD,
        )?;
        let control = committed_table(
            show(store::results_dir::CONTROL),
            results_dir,
            store::results_dir::CONTROL,
        )?;
        let timings = store::timing::read(results_dir)?;
        let (rows, name) = match committed {
            Some(out) => {
                let name = "git HEAD:results/runs.csv".to_string();
                (parse(out.stdout, &name, all)?, name)
            }
            None => {
                let path = results_dir.join(store::results_dir::RUNS);
                (
                    read(&path, inputs::Origin::Under(results_dir), all)?,
                    path.display().to_string(),
                )
            }
        };
        Ok(Self {
            rows,
            name,
            explanation,
            leaderboard,
            control,
            timings,
        })
    }

    /// Whether the baseline holds an explanation of any of `jobs` (then `check` re-explains
    /// them and compares).
    pub fn explains(&self, jobs: &[RunSpec]) -> bool {
        let keys: std::collections::HashSet<_> = jobs.iter().map(RunSpec::key).collect();
        self.explanation
            .ladder
            .iter()
            .any(|r| keys.contains(&r.key()))
    }

    /// Every difference the gate finds between `fresh` and the baseline's rows of the same
    /// experiments (only its exact rows with `exact_only`), one line each.
    pub fn problems(self, fresh: &[RunRow], exact_only: bool) -> Vec<String> {
        analysis::gate::compare_selection(self.rows, fresh, exact_only, &self.name)
    }

    /// The leaderboard derived from the committed runs with `fresh` in place of the same runs
    /// (`analysis::leaderboard`), as a reproduction writing `fresh` would write it.
    fn fresh_leaderboard(&self, fresh: &[RunRow]) -> Vec<LeaderboardRow> {
        let keys: std::collections::HashSet<_> = fresh.iter().map(RunRow::key).collect();
        let rows: Vec<RunRow> = self
            .rows
            .iter()
            .filter(|r| !keys.contains(&r.key()))
            .chain(fresh)
            .cloned()
            .collect();
        analysis::leaderboard::leaderboard(&rows, &self.timings)
    }

    /// Prints the gate's verdict on `fresh` and, when given, the fresh explanation of the same
    /// runs (`analysis::gate::compare_explanations`) and the fresh control runs
    /// (`analysis::gate::compare_control`); the leaderboard derived with `fresh` is compared
    /// with the committed one (`analysis::gate::compare_leaderboard`) where one is committed:
    /// [`Exit::GateDifference`] (exit code 3) on any difference.
    pub fn verdict(
        self,
        fresh: &[RunRow],
        exact_only: bool,
        explained: Option<&explain::Explained>,
        control: Option<&[ControlRow]>,
    ) -> ExitCode {
        let name = self.name.clone();
        let board = (!self.leaderboard.is_empty()).then(|| {
            analysis::gate::compare_leaderboard(
                &self.leaderboard,
                &self.fresh_leaderboard(fresh),
                &name,
            )
        });
        let control = control.map(|c| analysis::gate::compare_control(&self.control, c, &name));
        let committed = (
            self.explanation.ladder.clone(),
            self.explanation.attribution.clone(),
        );
        let mut problems = self.problems(fresh, exact_only);
        if let Some(x) = explained {
            problems.extend(analysis::gate::compare_explanations(
                (&committed.0, &committed.1),
                (&x.ladder, &x.attribution),
                &name,
            ));
        }
        problems.extend(board.into_iter().flatten());
        problems.extend(control.into_iter().flatten());
        if problems.is_empty() {
            println!("regression gate: {} runs agree with {name}", fresh.len());
            ExitCode::SUCCESS
        } else {
            println!(
                "regression gate: {} differences\n{}",
                problems.len(),
                problems.join("\n")
            );
            Exit::GateDifference.into()
        }
    }
}

/// The committed table `file`: git HEAD's (`shown`, the output of `git show`), else the
/// results directory's (empty when absent).
fn committed_table<T: records::table::Row>(
    shown: Option<std::process::Output>,
    results_dir: &Path,
    file: &str,
) -> Result<Vec<T>, ReproduceError> {
    let name = match shown {
        Some(_) => format!("git HEAD:results/{file}"),
        None => results_dir.join(file).display().to_string(),
    };
    match shown {
        Some(out) => records::table::from_reader(out.stdout.as_slice()),
        None => store::table::read_if_present(&results_dir.join(file)),
    }
    .map_err(|source| BaselineError::Table { name, source }.into())
}

/// The rows of the runs file `path` (from `origin`), read with the input reader (a regular
/// file, at most [`inputs::Kind::Baseline`]'s cap, never blocking).
fn read(
    path: &Path,
    origin: inputs::Origin,
    all: &[RunSpec],
) -> Result<Vec<RunRow>, BaselineError> {
    let bytes = inputs::read(path, inputs::Kind::Baseline, origin)?;
    parse(bytes, &path.display().to_string(), all)
}

/// The rows of a runs file's `bytes` (called `name`), with ids recovered if it predates them
/// (by the labels of `all`, every run of the experiment files).
fn parse(bytes: Vec<u8>, name: &str, all: &[RunSpec]) -> Result<Vec<RunRow>, BaselineError> {
    let name = || name.to_string();
    let bytes = match store::add_ids(&bytes, || store::LabelIndex::new(all)) {
        Ok(Some((migrated, _))) => migrated,
        Ok(None) => bytes,
        Err(source) => {
            return Err(BaselineError::Migrate {
                name: name(),
                source,
            })
        }
    };
    let rows: Vec<RunRow> =
        records::table::from_reader(bytes.as_slice()).map_err(|source| BaselineError::Table {
            name: name(),
            source,
        })?;
    check_run_rows(&rows).map_err(|source| BaselineError::Rows {
        name: name(),
        source,
    })?;
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn root() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
    }

    /// The committed results/runs.csv, read as a given baseline.
    fn committed() -> Baseline {
        let file = root().join("results").join("runs.csv");
        Baseline::read(&root(), Path::new("elsewhere"), Some(&file), &[]).unwrap()
    }

    #[test]
    fn the_baseline_agrees_with_itself_and_sees_a_doctored_drift() {
        let fresh: Vec<RunRow> = committed().rows;
        let experiment = fresh[0].experiment.clone();
        let fresh: Vec<RunRow> = fresh
            .into_iter()
            .filter(|r| r.experiment == experiment)
            .collect();
        assert!(committed().problems(&fresh, false).is_empty());
        let mut doctored = fresh.clone();
        let row = doctored
            .iter_mut()
            .find(|r| r.drift_norm.is_some())
            .expect("a completed run");
        row.drift_norm = row.drift_norm.map(|d| d * 1.1 + 1e-9);
        let key = row.key().to_string();
        let problems = committed().problems(&doctored, false);
        assert_eq!(problems.len(), 1, "{problems:?}");
        assert!(
            problems[0].starts_with(&format!("{key}: drift_norm ")),
            "{problems:?}"
        );
    }

    #[test]
    fn only_the_fresh_experiments_and_with_exact_only_only_exact_rows_are_compared() {
        let rows = committed().rows;
        let experiment = rows[0].experiment.clone();
        let exact: Vec<RunRow> = rows
            .iter()
            .filter(|r| r.experiment == experiment && r.is_exact())
            .cloned()
            .collect();
        assert!(
            !exact.is_empty()
                && exact.len() < rows.iter().filter(|r| r.experiment == experiment).count()
        );
        assert!(committed().problems(&exact, true).is_empty());
        // Without --exact-only the experiment's network runs are missing from the fresh rows.
        let missing = committed().problems(&exact, false);
        let networks = rows
            .iter()
            .filter(|r| r.experiment == experiment && !r.is_exact())
            .count();
        assert_eq!(missing.len(), networks, "{missing:?}");
    }

    #[test]
    fn a_baseline_that_is_a_directory_or_missing_is_refused_by_name() {
        let dir = root().join("results");
        let err = Baseline::read(&root(), &dir, Some(&dir), &[]).unwrap_err();
        assert!(
            matches!(&err, ReproduceError::BaselineIsDirectory(d) if d == &dir),
            "{err:?}"
        );
        let missing = root().join("no-such-baseline.csv");
        let err = Baseline::read(&root(), &dir, Some(&missing), &[]).unwrap_err();
        assert!(
            matches!(&err, ReproduceError::GivenBaseline(BaselineError::Read(inputs::InputError::Open { path, .. })) if path == &missing),
            "{err:?}"
        );
        assert!(
            err.to_string()
                .starts_with(&format!("--baseline: {}: ", missing.display())),
            "{err}"
        );
    }
}
