//! The setup inference's profiles of one published table (`results/inference.csv`): one panel
//! per fitted parameter, the best relative residual with the other parameters re-fitted (points
//! where a run of the table failed are left out).

use super::layout::figure;
use super::panels::ProfilePanel;
use explain::inference::{InferenceRow, FAILED};
use std::f64::consts::PI;

/// File name of a table's profile figure inside `report/figures/`.
pub fn file_name(paper: &str, table: &str) -> String {
    format!("inference-{paper}-{table}__profiles.svg")
}

/// The SVG of one table's profiles; `rows` are that table's rows of `inference.csv`.
pub fn render(paper: &str, table: &str, rows: &[&InferenceRow]) -> Result<String, String> {
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
    figure(
        &format!("{paper} {table}: setup inference profiles (others re-fitted)"),
        |area| {
            if panels.is_empty() {
                return Ok(());
            }
            let cells = area.split_evenly((1, panels.len()));
            for (panel, cell) in panels.iter().zip(&cells) {
                panel.draw(cell)?;
            }
            Ok(())
        },
    )
}
