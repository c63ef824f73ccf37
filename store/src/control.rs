//! The control experiments' result files (`results/control*.csv`, `results/cycles*.csv`; their
//! rows are [`records::control`]'s) written and read back.

use crate::error::{ControlFileError, IoAction, IoError};
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::path::Path;

/// Writes `rows` to `dir/name` ([`records::control::to_writer`]).
pub fn write<T: Serialize>(dir: &Path, name: &str, rows: &[T]) -> Result<(), ControlFileError> {
    let path = dir.join(name);
    let file = std::fs::File::create(&path).map_err(IoError::at(&path, IoAction::Open))?;
    records::control::to_writer(file, rows).map_err(|source| ControlFileError::Csv { path, source })
}

/// Reads `dir/name` through the one reader (`owned_dir::open_file`,
/// [`records::control::from_reader`]); empty when the file does not exist.
pub fn read<T: DeserializeOwned>(dir: &Path, name: &str) -> Result<Vec<T>, ControlFileError> {
    let path = dir.join(name);
    if !path.exists() {
        return Ok(Vec::new());
    }
    let file = crate::owned_dir::open_file(&path).map_err(IoError::at(&path, IoAction::Read))?;
    records::control::from_reader(file).map_err(|source| ControlFileError::Csv { path, source })
}
