//! The setup inference's profiles of one published table (`results/inference.csv`): one panel
//! per profiled parameter, the best table residual with that parameter held at each value
//! (the others re-fitted there, or held at the optimum for a slice, as the panel says), the
//! best fit of the whole table marked (points where a run of the table failed are left out).

use super::layout::{Area, Body, Figure};
use super::panels::ProfilePanel;
use crate::error::FigureError;
use plotters::prelude::*;
use records::inference::{InferenceRow, BEST, FAILED, PHASE, ROTATION, SCALE, TABLE};
use std::f64::consts::PI;

/// File name of a table's profile figure inside `report/figures/`.
pub fn file_name(paper: &str, table: &str) -> String {
    format!("inference-{paper}-{table}__profiles.svg")
}

/// What a profile figure draws under its title: one panel per parameter, three to a row.
pub struct ProfilesBody {
    panels: Vec<ProfilePanel>,
}

impl Body for ProfilesBody {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        if self.panels.is_empty() {
            return Ok(());
        }
        let cols = self.panels.len().min(3);
        let cells = area.split_evenly((self.panels.len().div_ceil(cols), cols));
        for (panel, cell) in self.panels.iter().zip(&cells) {
            panel.draw(cell)?;
        }
        Ok(())
    }
}

/// The figure of one table's profiles; `rows` are that table's rows of `inference.csv`.
pub fn figure(paper: &str, table: &str, rows: &[&InferenceRow]) -> Figure<ProfilesBody> {
    let mut names: Vec<(&str, bool)> = Vec::new();
    for k in rows.iter().filter_map(|r| r.profile()) {
        if !names.contains(&k) {
            names.push(k);
        }
    }
    let best = rows.iter().find(|r| r.kind == BEST && r.objective == TABLE);
    let panels: Vec<ProfilePanel> = names
        .iter()
        .map(|&(name, refitted)| {
            let points = rows
                .iter()
                .filter(|r| r.profile() == Some((name, refitted)))
                // A point whose run failed carries the penalty residual: not drawn.
                .filter(|r| r.rel_residual < FAILED)
                .map(|r| (r.parameter(name), r.rel_residual))
                .collect();
            let (x_desc, x) = match name {
                ROTATION => ("in-plane rotation (rad)".to_string(), 0.0..2.0 * PI),
                PHASE => ("start phase (cycle fraction)".to_string(), 0.0..1.0),
                SCALE => ("size factor".to_string(), 0.0..4.2),
                tilt => (format!("{tilt} (rad)"), -PI / 2.0..PI / 2.0),
            };
            ProfilePanel {
                caption: format!(
                    "{name} ({})",
                    if refitted {
                        "others re-fitted"
                    } else {
                        "slice"
                    }
                ),
                x_desc,
                x,
                points,
                best: best.map(|b| (b.parameter(name), b.rel_residual)),
            }
        })
        .collect();
    Figure {
        title: format!("{paper} {table}: setup inference profiles, best fit marked"),
        body: ProfilesBody { panels },
    }
}
