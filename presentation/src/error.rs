//! The presentation layer's errors: drawing a figure ([`FigureError`], with a trace that cannot
//! be read: [`TraceError`]), rendering the report and the figures ([`ReportError`], wrapping
//! the records layer's errors: every results file is read through it).

use records::table::TableError;
use std::path::PathBuf;
use store::TrackedError;
use store::{ControlFileError, IoError, RunsError};

/// Why a figure could not be drawn or encoded.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// plotters' error (generic over the drawing backend), by its message.
    #[error("drawing a figure: {0}")]
    Draw(String),
    #[error("encoding a PNG: {0}")]
    Png(#[from] png::EncodingError),
    #[error("the embedded font DejaVuSans.ttf does not parse")]
    Font,
    #[error(transparent)]
    Trace(#[from] TraceError),
}

/// A trace CSV that cannot be drawn, naming the file.
#[derive(Debug, thiserror::Error)]
#[error("{}: {problem}", path.display())]
pub struct TraceError {
    pub path: PathBuf,
    pub problem: TraceProblem,
}

/// What is wrong with a trace CSV.
#[derive(Debug, thiserror::Error)]
pub enum TraceProblem {
    #[error(transparent)]
    Read(#[from] std::io::Error),
    #[error(transparent)]
    Csv(#[from] csv::Error),
    #[error("no column `{0}`")]
    NoColumn(&'static str),
    #[error("expected theta_1..n and thetadot_1..n, found {theta} and {thetadot}")]
    Joints { theta: usize, thetadot: usize },
    #[error("row {row}: `{column}` = {} is not a number", settings::shown(text))]
    NotANumber {
        row: usize,
        column: String,
        text: String,
    },
    #[error("row {row}: `{column}` is empty")]
    Empty { row: usize, column: String },
}

/// Why the report or its figures could not be rendered.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    #[error(transparent)]
    Runs(#[from] RunsError),
    /// A table of the explanation, the setup inference or the Python package.
    #[error(transparent)]
    Table(#[from] TableError),
    /// A result file of the control experiments.
    #[error(transparent)]
    ControlFile(#[from] ControlFileError),
    #[error(transparent)]
    Tracked(#[from] TrackedError),
    #[error(transparent)]
    Io(#[from] IoError),
    #[error(transparent)]
    Trace(#[from] TraceError),
    /// The figure `name` could not be drawn.
    #[error("{name}: {error}")]
    Figure { name: String, error: FigureError },
    #[error("two figures would be written to {0}: rename a variant or a solver")]
    SameFigure(String),
    #[error(transparent)]
    Papers(#[from] analysis::papers::PapersError),
    /// `records::dof_cost` could not read its file.
    #[error(transparent)]
    DofCost(#[from] store::DofCostError),
}
