//! `reproduce score FILE --task EXPERIMENT/VARIANT`: a trajectory produced elsewhere scored on a
//! task as a run is scored (presentation::score); its summary line is printed like a run's.

use crate::cli::Cli;
use crate::error::ReproduceError;
use crate::summary::{emit, summary};
use std::path::Path;

/// Scores `file` on `task` (an id `experiment / variant`) into `--score-out`.
pub fn score(cli: &Cli, file: &Path, task: &str, git_rev: &str) -> Result<(), ReproduceError> {
    let task = presentation::score::find_task(&cli.experiments_dir, task)?;
    let s = presentation::score::score_file(&task, file, &cli.score_out, git_rev)?;
    emit(&summary(std::slice::from_ref(&s.row)));
    eprintln!(
        "wrote {}, {} and {}",
        s.scores.display(),
        s.trace.display(),
        s.figure.display()
    );
    Ok(())
}
