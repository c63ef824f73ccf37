//! The experiment files as the orchestrator takes them (`reproduce::experiments`, which this
//! crate's tests do not link): read and validated as data by crate `catalog`, then every run
//! checked by this crate's setup ([`check_job`]), a failure placed at its field.

use catalog::error::{ExperimentError, ExperimentFileError};
use catalog::experiment::PaperFile;
use simulation::check_job;
use std::path::Path;

/// That every run of `file` can be built.
fn check(file: &PaperFile) -> Result<(), ExperimentError> {
    file.declared_runs()
        .try_for_each(|run| check_job(&run.spec).map_err(|e| run.at_fault(e)))
}

/// The file of `text`, its runs checked.
pub fn from_toml(text: &str) -> Result<PaperFile, ExperimentError> {
    let file = PaperFile::from_toml(text)?;
    check(&file)?;
    Ok(file)
}

/// The file at `path`, its runs checked.
pub fn load(path: &Path) -> Result<PaperFile, ExperimentFileError> {
    let file = PaperFile::load(path)?;
    check(&file).map_err(|error| ExperimentFileError::Invalid {
        file: path.to_path_buf(),
        error,
    })?;
    Ok(file)
}

/// Every file of `dir`, their runs checked.
pub fn load_dir(dir: &Path) -> Result<Vec<PaperFile>, ExperimentFileError> {
    let files = catalog::experiment::load_dir(dir)?;
    for file in &files {
        check(file).map_err(|error| ExperimentFileError::Invalid {
            file: dir.join(&file.file_name),
            error,
        })?;
    }
    Ok(files)
}
