//! driftbench's presentation layer: `report/REPORT.md` and its pages ([`report`]) and every figure
//! ([`figures`]), rendered from what `results/` holds (never from a simulation in memory), so
//! the committed report is always a function of the committed results. It reads `results/`
//! through `records` only and links no solver: scoring a trajectory from a file and the task
//! cards, which compute, are the orchestrator's (`reproduce::score`, `reproduce::task_card`).

pub mod error;
pub mod figures;
pub mod report;
