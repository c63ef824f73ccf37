//! `reproduce score FILE --task EXPERIMENT/VARIANT` (and `driftbench.score` in Python): a
//! trajectory produced elsewhere, scored on a task of the suite
//! (`simulation::score_trajectory`), written as a run is: its row in `<out>/scores.csv` (the
//! `results/runs.csv` schema, one row per task and name: `--name`, the row's solver id,
//! `trajectory` by default; replaced when the same file is scored again, and refused for
//! another file, whose row and trace it would replace: so one row per task and file), its trace in
//! `<out>/traces/<experiment>/<variant>__<name>.csv` and its figure (the report's run figure)
//! in `<out>/figures/<experiment>__<variant>__<name>.svg` and `.png`; its summary line is printed
//! like a run's, with warnings for what looks wrong ([`Warning`]). `<out>` is a directory of its
//! own: never results/, report/ or another directory this program seals.

use crate::error::{ReproduceError, ScoreError};
use crate::options::ScoreOptions;
use crate::project::Project;
use crate::summary::{emit, summary};
use inputs::trajectory::read;
use inputs::trajectory::Columns;
use presentation::figures::run_figure;
use records::score_row;
use records::trace_csv;
use records::{merge_runs, RunRow};
use simulation::run_row;
use simulation::score_trajectory;
use simulation::RunRecord;
use spec::ids::SolverId;
use spec::RunSpec;
use spec::TaskKey;
use std::path::{Path, PathBuf};
use store::write_atomic;
use store::OwnedDir;
use store::{IoAction, IoError};

/// Scores `options.file` on `options.task` (an id `experiment / variant`) into `options.out`.
pub fn score(
    project: &Project,
    options: &ScoreOptions,
    git_rev: &str,
) -> Result<(), ReproduceError> {
    let task = find_task(&project.experiments_dir, &options.task)?;
    let s = score_file(
        &task,
        &options.file,
        options.columns.as_ref(),
        &options.name,
        &options.out,
        git_rev,
    )?;
    emit(&summary(std::slice::from_ref(&s.row)));
    for w in &s.warnings {
        eprintln!("warning: {}: {w}", options.file.display());
    }
    eprintln!(
        "wrote {}, {} and {}",
        s.scores.display(),
        s.trace.display(),
        s.figure.display()
    );
    Ok(())
}

/// What scoring a file wrote.
#[derive(Clone, Debug)]
pub struct Scored {
    pub record: RunRecord,
    pub row: RunRow,
    pub scores: PathBuf,
    pub trace: PathBuf,
    pub figure: PathBuf,
    /// What looks wrong with the trajectory though it could be scored ([`Warning`]).
    pub warnings: Vec<Warning>,
}

/// A position error above this fraction of the task's path size suggests the trajectory was
/// made for another task (another path, pose or robot).
pub const WRONG_TASK_FRACTION: f64 = 0.1;

/// Samples whose joint angles all carry at most this many significant decimal digits look
/// rounded (an integrator's output carries 15-17): MATLAB's `csvwrite` keeps 5.
pub const ROUNDED_DIGITS: usize = 8;

/// How many joint-angle values [`significant_digits`] inspects at most (the first ones).
const INSPECTED_VALUES: usize = 20_000;

/// What looks wrong with a scored trajectory.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Warning {
    /// The position error is large against the path: the wrong task?
    #[error("its largest position error, {max_pos_err:.3e} m, is over {:.0} % of the task's path size ({path_size} m): is this the right task?", 100.0 * WRONG_TASK_FRACTION)]
    WrongTask { max_pos_err: f64, path_size: f64 },
    /// The samples were rounded before they were written.
    #[error("its joint angles carry at most {digits} significant digits: the samples look rounded (MATLAB's csvwrite keeps 5; write with writematrix, or dlmwrite(..., 'precision', 17)), and the score measures the rounding")]
    Rounded { digits: usize },
}

/// The warnings of a trajectory scored into `row`.
pub fn warnings(row: &RunRow, trajectory: &inputs::trajectory::Trajectory) -> Vec<Warning> {
    let mut out = Vec::new();
    if let (Some(max_pos_err), Some(path_size)) = (row.max_pos_err, row.path_scale) {
        if max_pos_err > WRONG_TASK_FRACTION * path_size {
            out.push(Warning::WrongTask {
                max_pos_err,
                path_size,
            });
        }
    }
    let values = trajectory.theta.iter().flatten().copied();
    let digits = values
        .take(INSPECTED_VALUES)
        .map(significant_digits)
        .max()
        .unwrap_or(0);
    if (1..=ROUNDED_DIGITS).contains(&digits) {
        out.push(Warning::Rounded { digits });
    }
    out
}

/// The fewest significant decimal digits that write `v` exactly (0 for 0 and non-finite
/// values; at most 17, which every double needs at most).
pub fn significant_digits(v: f64) -> usize {
    if v == 0.0 || !v.is_finite() {
        return 0;
    }
    (1..=17)
        .find(|&d| format!("{v:.*e}", d - 1).parse::<f64>() == Ok(v))
        .unwrap_or(17)
}

/// The task `"<experiment> / <variant>"` (ids) of the experiment files in `experiments_dir`, as
/// its first run (a trajectory is scored on its robot, path, scheme and poses only).
pub fn find_task(experiments_dir: &Path, task: &TaskKey) -> Result<RunSpec, ScoreError> {
    for file in crate::experiments::load_dir(experiments_dir)? {
        for j in file.iter_jobs() {
            let j = j?;
            if j.task() == *task {
                return Ok(j);
            }
        }
    }
    Err(ScoreError::NoTask(task.to_string()))
}

/// Scores the trajectory file `file` (CSV, or a MAT-file: `inputs::trajectory::read`) on
/// `task` (a MAT-file's `columns` when given) under the solver id `name` (a slug), and writes
/// the row, trace and figure (SVG and PNG) under `out`: a directory of its own, never one this
/// program seals (`check_out`), every path inside it checked (`store::owned_dir`: a
/// `traces/<experiment>` that is a symbolic link elsewhere is refused).
pub fn score_file(
    task: &RunSpec,
    file: &Path,
    columns: Option<&Columns>,
    name: &str,
    out: &Path,
    git_rev: &str,
) -> Result<Scored, ScoreError> {
    let name = check_name(name)?;
    check_out(out)?;
    let trajectory = read(file, task.theta0.len(), columns)?;
    let record = score_trajectory(task, &trajectory).map_err(|error| ScoreError::Score {
        file: file.to_path_buf(),
        task: task.task().to_string(),
        error: Box::new(error),
    })?;
    let source = file.file_name().map_or_else(
        || file.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let row = score_row(run_row(&record, git_rev), &source, &name);
    let warnings = warnings(&row, &trajectory);
    let dir = OwnedDir::open(out)?;
    let scores = dir.resolve(Path::new(SCORES))?;
    let stored: Vec<RunRow> = if scores.exists() {
        store::table::read(&scores)?
    } else {
        Vec::new()
    };
    // One row per task and file: the row of this task and name may be replaced by the same
    // file scored again, never by another file's.
    if let Some(other) = stored
        .iter()
        .find(|r| r.key() == row.key() && r.solver != row.solver)
    {
        return Err(ScoreError::Taken {
            scores,
            task: task.task().to_string(),
            name: name.to_string(),
            holder: other.solver.clone(),
        });
    }
    let rows = merge_runs(stored, vec![row.clone()]);
    let stem = row.key().stem();
    let rel_trace = Path::new(store::results_dir::TRACES)
        .join(&row.experiment)
        .join(format!("{stem}.csv"));
    let rel_figure = Path::new("figures").join(presentation::figures::run_figure_name(&row.key()));
    // Every file's place checked before the first is written: a `figures` or
    // `traces/<experiment>` that leads elsewhere leaves the directory as it was.
    for rel in [&rel_trace, &rel_figure] {
        dir.resolve(rel)?;
    }
    let io = |rel: &Path, bytes: &[u8]| -> Result<PathBuf, ScoreError> {
        if let Some(parent) = rel.parent().filter(|p| !p.as_os_str().is_empty()) {
            let parent = dir.resolve(parent)?;
            std::fs::create_dir_all(&parent).map_err(IoError::at(&parent, IoAction::Write))?;
        }
        // Resolved again once the directories exist: none of them may lead elsewhere.
        let path = dir.resolve(rel)?;
        write_atomic(&path, bytes).map_err(IoError::at(&path, IoAction::Write))?;
        Ok(path)
    };
    let csv_error = |path: &Path| {
        let path = path.to_path_buf();
        move |source| ScoreError::Csv { path, source }
    };
    let scores = io(
        Path::new(SCORES),
        &records::runs_csv(&rows).map_err(csv_error(&scores))?,
    )?;
    let trace = io(
        &rel_trace,
        &trace_csv(&record.run.trace).map_err(csv_error(&rel_trace))?,
    )?;
    let (svg, png) = run_figure(&row, &trace)?;
    let figure = io(&rel_figure, svg.as_bytes())?;
    io(&rel_figure.with_extension("png"), &png)?;
    Ok(Scored {
        record,
        row,
        scores,
        trace,
        figure,
        warnings,
    })
}

/// The table of scores in an out directory.
pub const SCORES: &str = "scores.csv";

/// A scored trajectory's name: a slug that can name its files, and not the exact column's id.
fn check_name(name: &str) -> Result<SolverId, ScoreError> {
    if name == spec::EXACT_ID {
        return Err(ScoreError::ReservedName {
            name: name.to_string(),
        });
    }
    let max = spec::MAX_SOLVER_LABEL;
    if let Ok(id) = SolverId::new(name) {
        return Ok(id);
    }
    let mut suggestion = settings::slug(name);
    suggestion.truncate(max);
    Err(ScoreError::Name {
        name: name.to_string(),
        suggestion: if suggestion.is_empty() {
            records::TRAJECTORY_KIND.to_string()
        } else {
            suggestion
        },
        max,
    })
}

/// Refuses an out directory that is, or lies inside, a directory this program seals with a
/// manifest (results/, report/, a shard directory; `store::integrity::sealed_by`): scores
/// written there would pass for runs.
pub fn check_out(out: &Path) -> Result<(), ScoreError> {
    match store::integrity::sealed_by(out) {
        Some(sealed) => Err(ScoreError::Sealed {
            out: out.to_path_buf(),
            sealed,
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use inputs::trajectory::Trajectory;

    #[test]
    fn significant_digits_are_the_fewest_that_write_the_value() {
        assert_eq!(significant_digits(0.5), 1);
        assert_eq!(significant_digits(-1.2346), 5);
        assert_eq!(significant_digits(0.0), 0);
        assert_eq!(significant_digits(f64::NAN), 0);
        assert!(significant_digits(std::f64::consts::PI) >= 16);
        assert!(significant_digits(0.1 + 0.2) == 17);
    }

    #[test]
    fn a_far_trajectory_and_rounded_samples_are_warned() {
        let trajectory = |theta: Vec<Vec<f64>>| Trajectory {
            t: (0..theta.len()).map(|k| k as f64).collect(),
            theta,
            thetadot: None,
        };
        let row = |max_pos_err: f64| RunRow {
            max_pos_err: Some(max_pos_err),
            path_scale: Some(0.2),
            ..RunRow::blank(
                &spec::RunKey::from_ids("e", "v", "trajectory").unwrap(),
                spec::SolverKind::Trajectory,
            )
        };
        let exact = trajectory(vec![vec![std::f64::consts::PI, 0.0], vec![1.0 / 3.0, 0.5]]);
        assert_eq!(warnings(&row(1e-6), &exact), []);
        assert_eq!(
            warnings(&row(0.186), &exact),
            [Warning::WrongTask {
                max_pos_err: 0.186,
                path_size: 0.2
            }]
        );
        let rounded = trajectory(vec![vec![1.2346, 0.0], vec![0.33333, 0.5]]);
        assert_eq!(
            warnings(&row(1e-6), &rounded),
            [Warning::Rounded { digits: 5 }]
        );
        // A still arm (every angle 0) is not "rounded".
        assert_eq!(warnings(&row(1e-6), &trajectory(vec![vec![0.0]; 3])), []);
    }
}
