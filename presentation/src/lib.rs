//! driftbench's presentation layer: `report/REPORT.md` ([`report`]) and every figure
//! ([`figures`]), rendered from what `results/` holds (never from a simulation in memory), so
//! the committed report is always a function of the committed results.

pub mod figures;
pub mod report;
