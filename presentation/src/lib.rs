//! driftbench's presentation layer: `report/REPORT.md` ([`report`]) and every figure
//! ([`figures`]), rendered from what `results/` holds (never from a simulation in memory), so
//! the committed report is always a function of the committed results; [`score`] writes the
//! row, trace and figure of a trajectory scored from a file; [`task_card`] writes a card per
//! task (`report/tasks/`).

pub mod error;
pub mod figures;
pub mod report;
pub mod score;
pub mod task_card;
