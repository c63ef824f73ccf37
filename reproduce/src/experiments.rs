//! The experiment files as the modes take them. Crate `catalog` reads and validates a file as
//! data; it links no engine, so it cannot build a run. Here the runs a loaded file checks at
//! load (every run but those of a large sweep's variants off its lines) are then checked with
//! the engine's setup (`simulation::run::check_job`: the robot, the path from
//! f(theta_ref), the scheme and the network built as the run builds them, nothing integrated),
//! after loading and before anything runs, and a failure is placed at the field at fault of
//! the file that declares the run (`catalog::DeclaredRun::at_fault`): a file is
//! rejected for exactly what would make one of its runs fail at t = 0.

use catalog::PaperFile;
use catalog::{ExperimentError, ExperimentFileError};
use simulation::check_job;
use std::path::Path;

/// Every experiment file of `dir` ([`catalog::load_dir`]), each of its runs
/// checked (`check`); the error names the file.
pub fn load_dir(dir: &Path) -> Result<Vec<PaperFile>, ExperimentFileError> {
    let files = catalog::load_dir(dir)?;
    for file in &files {
        check(file).map_err(|error| ExperimentFileError::Invalid {
            file: dir.join(&file.file_name),
            error,
        })?;
    }
    Ok(files)
}

/// The experiment file of `text` ([`PaperFile::from_toml`]), each of its runs checked
/// (`check`).
pub fn from_toml(text: &str) -> Result<PaperFile, ExperimentError> {
    let file = PaperFile::from_toml(text)?;
    check(&file)?;
    Ok(file)
}

/// That every run `file` checks at load can be built (every run of a written variant and of
/// a sweep's checked variants, `catalog::PaperFile::checked_runs`: all of a sweep of at most
/// `catalog::CHECKED_WHOLE` variants, the lines of a larger one): the first that cannot,
/// placed at its field.
pub fn check(file: &PaperFile) -> Result<(), ExperimentError> {
    file.checked_runs().try_for_each(|run| {
        let run = run?;
        check_job(&run.spec).map_err(|e| run.at_fault(e))
    })
}
