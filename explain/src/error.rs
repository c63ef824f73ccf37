//! The explanation layer's errors: reading and writing its results files ([`ExplainError`],
//! wrapping the records layer's [`TableError`] and [`IoError`]), building or reading an
//! inference ([`InferenceError`]) and reading the inference family file (the reader's
//! [`inputs::InputError`], wrapped by [`InferenceError::FamilyFile`]; what its content gets
//! wrong, [`FamilyError`], wrapped by [`InferenceError::Family`]).

use records::table::TableError;
use store::IoError;

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
    /// Its TOML (line and column; the file is never quoted).
    #[error(transparent)]
    Toml(#[from] inputs::TomlError),
    /// The registry's error: an unknown robot (with the valid choices) or its invalid file.
    #[error("{0}")]
    UnknownRobot(String),
    #[error(
        "robot variant {} has another joint count than {}",
        settings::shown(variant),
        settings::shown(declared)
    )]
    JointCount { variant: String, declared: String },
    #[error("`network` lists \"exact\": the exact column is always tried")]
    ExactNetwork,
}

/// What can go wrong in building or reading an inference.
#[derive(Debug, thiserror::Error)]
pub enum InferenceError {
    /// No column of the table has published per-joint drifts mapped onto a run.
    #[error("{paper} {table}: no published per-joint drifts map onto a run")]
    NoColumns { paper: String, table: String },
    /// A mapped column's run (`what`: its exact column or its network) is not among the jobs.
    #[error("{paper} {table}: no {what} run of {experiment} / {variant}")]
    NoRun {
        paper: String,
        table: String,
        what: &'static str,
        experiment: String,
        variant: String,
    },
    /// The family file is refused by the input reader (a link out of the experiments
    /// directory, not a regular file, over its cap, not UTF-8; the error names the path).
    #[error(transparent)]
    FamilyFile(#[from] inputs::InputError),
    /// The family file is not valid TOML or names what does not exist.
    #[error("inference family {}: {error}", file.display())]
    Family {
        file: std::path::PathBuf,
        error: FamilyError,
    },
}
