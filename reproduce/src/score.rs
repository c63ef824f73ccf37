//! `reproduce score FILE --task EXPERIMENT/VARIANT` (and `driftbench.score` in Python): a
//! trajectory produced elsewhere, scored on a task of the suite
//! (`simulation::score_trajectory`), written as a run is: its row in `<out>/scores.csv` (the
//! `results/runs.csv` schema, one row per task and file, replaced when scored again), its trace in
//! `<out>/traces/<experiment>/<variant>__<solver>.csv` and its figure (the report's run figure)
//! in `<out>/figures/<experiment>__<variant>__<solver>.svg`; its summary line is printed like a
//! run's.

use crate::error::{ReproduceError, ScoreError};
use crate::options::ScoreOptions;
use crate::project::Project;
use crate::summary::{emit, summary};
use catalog::experiment::{load_dir, Job, PaperFile};
use catalog::run_key::TaskKey;
use presentation::figures::run_svg;
use records::error::{IoAction, IoError};
use records::runs::{merge, write_atomic, RunRow};
use records::trace::trace_csv;
use records::trajectory::{read, score_row};
use simulation::row::run_row;
use simulation::run::{check_job, RunRecord};
use simulation::score_trajectory::score_trajectory;
use std::path::{Path, PathBuf};

/// Scores `options.file` on `options.task` (an id `experiment / variant`) into `options.out`.
pub fn score(
    project: &Project,
    options: &ScoreOptions,
    git_rev: &str,
) -> Result<(), ReproduceError> {
    let task = find_task(&project.experiments_dir, &options.task)?;
    let s = score_file(&task, &options.file, &options.out, git_rev)?;
    emit(&summary(std::slice::from_ref(&s.row)));
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
}

/// The task `"<experiment> / <variant>"` (ids) of the experiment files in `experiments_dir`, as
/// its first run (a trajectory is scored on its robot, path, scheme and poses only).
pub fn find_task(experiments_dir: &Path, id: &str) -> Result<Job, ScoreError> {
    let key = TaskKey::parse(id);
    load_dir(experiments_dir, check_job)?
        .iter()
        .flat_map(PaperFile::jobs)
        .find(|j| Some(j.task()) == key)
        .ok_or_else(|| ScoreError::NoTask(id.to_string()))
}

/// Scores the trajectory file `file` (CSV, or a MAT-file: `records::trajectory::read`) on
/// `task` and writes the row, trace and figure under `out`.
pub fn score_file(
    task: &Job,
    file: &Path,
    out: &Path,
    git_rev: &str,
) -> Result<Scored, ScoreError> {
    let trajectory = read(file, task.theta0.len())?;
    let record = score_trajectory(task, &trajectory).map_err(|error| ScoreError::Score {
        file: file.to_path_buf(),
        task: task.task().to_string(),
        error: Box::new(error),
    })?;
    let source = file.file_name().map_or_else(
        || file.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let row = score_row(run_row(&record, git_rev), &source);
    let scores = out.join("scores.csv");
    let stored: Vec<RunRow> = if scores.exists() {
        records::table::read(&scores)?
    } else {
        Vec::new()
    };
    let rows = merge(stored, vec![row.clone()]);
    let stem = row.key().stem();
    let trace = out
        .join(records::results_dir::TRACES)
        .join(&row.experiment)
        .join(format!("{stem}.csv"));
    let figure = out
        .join("figures")
        .join(format!("{}__{stem}.svg", row.experiment));
    let io = |path: &Path, bytes: &[u8]| -> Result<(), IoError> {
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(IoError::at(dir, IoAction::Write))?;
        }
        write_atomic(path, bytes).map_err(IoError::at(path, IoAction::Write))
    };
    let csv_error = |path: &Path| {
        let path = path.to_path_buf();
        move |source| ScoreError::Csv { path, source }
    };
    io(
        &scores,
        &records::runs::runs_csv(&rows).map_err(csv_error(&scores))?,
    )?;
    io(
        &trace,
        &trace_csv(&record.run.trace).map_err(csv_error(&trace))?,
    )?;
    io(&figure, run_svg(&row, &trace)?.as_bytes())?;
    Ok(Scored {
        record,
        row,
        scores,
        trace,
        figure,
    })
}
