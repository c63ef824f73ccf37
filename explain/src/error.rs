//! The explanation layer's errors: reading and writing its results files ([`ExplainError`],
//! wrapping the records layer's [`TableError`] and [`IoError`]) and reading the inference
//! family file ([`FamilyError`], wrapped by [`crate::inference::InferenceError::Family`]).

use records::error::IoError;
use records::table::TableError;

/// Why a results file of the explanation layer could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum ExplainError {
    #[error(transparent)]
    Table(#[from] TableError),
    #[error(transparent)]
    Csv(#[from] csv::Error),
    #[error(transparent)]
    Io(#[from] IoError),
}

/// What is wrong with the inference family file.
#[derive(Debug, thiserror::Error)]
pub enum FamilyError {
    #[error(transparent)]
    Read(#[from] std::io::Error),
    #[error(transparent)]
    Toml(#[from] toml::de::Error),
    #[error("unknown robot \"{0}\"")]
    UnknownRobot(String),
    #[error("robot variant \"{variant}\" has another joint count than \"{declared}\"")]
    JointCount { variant: String, declared: String },
    #[error("`network` lists \"exact\": the exact column is always tried")]
    ExactNetwork,
}
