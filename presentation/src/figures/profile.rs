//! The setup inference's profiles of one published table (`results/inference.csv`): one panel
//! per fitted parameter, the best relative residual with the other parameters re-fitted (points
//! where a run of the table failed are left out).

use super::layout::{Area, Body, Figure};
use super::panels::ProfilePanel;
use explain::inference::{InferenceRow, FAILED};
use plotters::prelude::*;
use std::f64::consts::PI;

/// File name of a table's profile figure inside `report/figures/`.
pub fn file_name(paper: &str, table: &str) -> String {
    format!("inference-{paper}-{table}__profiles.svg")
}

/// What a profile figure draws under its title: one panel per parameter, side by side.
pub struct ProfilesBody {
    panels: Vec<ProfilePanel>,
}

impl Body for ProfilesBody {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), String> {
        if self.panels.is_empty() {
            return Ok(());
        }
        let cells = area.split_evenly((1, self.panels.len()));
        for (panel, cell) in self.panels.iter().zip(&cells) {
            panel.draw(cell)?;
        }
        Ok(())
    }
}

/// The figure of one table's profiles; `rows` are that table's rows of `inference.csv`.
pub fn figure(paper: &str, table: &str, rows: &[&InferenceRow]) -> Figure<ProfilesBody> {
    let mut names: Vec<&str> = rows
        .iter()
        .filter_map(|r| r.kind.strip_prefix("profile: "))
        .collect();
    names.dedup();
    let panels: Vec<ProfilePanel> = names
        .iter()
        .map(|&name| {
            let points = rows
                .iter()
                .filter(|r| r.kind.strip_prefix("profile: ") == Some(name))
                // A point whose run failed carries the penalty residual: not drawn.
                .filter(|r| r.rel_residual < FAILED)
                .map(|r| {
                    let x = match name {
                        "rotation" => r.rotation,
                        "phase" => r.phase,
                        _ => r.scale_factor,
                    };
                    (x, r.rel_residual)
                })
                .collect();
            let (x_desc, x) = match name {
                "rotation" => ("in-plane rotation (rad)", 0.0..2.0 * PI),
                "phase" => ("start phase (cycle fraction)", 0.0..1.0),
                _ => ("size factor", 0.0..2.2),
            };
            ProfilePanel {
                caption: format!("residual against {name}"),
                x_desc: x_desc.to_string(),
                x,
                points,
            }
        })
        .collect();
    Figure {
        title: format!("{paper} {table}: setup inference profiles (others re-fitted)"),
        body: ProfilesBody { panels },
    }
}
