//! driftbench's presentation layer: `report/REPORT.md` and its pages ([`report`]) and every figure
//! ([`figures`]), rendered from what `results/` holds (never from a simulation in memory), so
//! the committed report is always a function of the committed results. It reads `results/`
//! through `records` only and links no solver: scoring a trajectory from a file is the
//! orchestrator's (`reproduce::score`), and so are the task cards' numbers
//! (`reproduce::task_card` builds each card's model; [`task_card`] renders it).

mod error;
pub mod figures;
pub mod report;
pub mod task_card;
pub use error::{FigureError, ReportError};
