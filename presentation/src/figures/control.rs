//! The figures of the control experiments (`results/control*.csv`, `results/cycles.csv`):
//!
//! - `control__pareto__<task>.svg`, one per task: every method at the control period (1 ms) as
//!   a point of solve latency (median, us) against accuracy (largest |x - x*| after the first
//!   second); a diverged network is left out (it is listed in the report);
//! - `control__stability.svg`: each network form's rms |x - x*| against the control period,
//!   the points where it diverged drawn at [`DIVERGED_Y`];
//! - `control__cycles.svg`: the drift after each cycle of the many-cycles runs.
//!
//! Floors: an accuracy of 0 (the exact reference itself) is drawn at [`FLOOR`].

use super::layout::{Area, Body, Figure};
use super::legend::{self, Arrangement, Entry};
use super::panels::{LogLogPanel, Series};
use super::style::{colour, LEGEND_LINE_WIDTH};
use crate::error::FigureError;
use plotters::prelude::*;
use records::control::{ControlRow, ControlStatus, CycleRow, Family};
use spec::slug;

/// Width of the legend column on the right (px).
const LEGEND_WIDTH: u32 = 420;
/// Where an accuracy of zero is drawn.
pub const FLOOR: f64 = 1e-16;
/// Where a diverged run is drawn on the stability figure.
pub const DIVERGED_Y: f64 = 1e4;

/// File name of a task's Pareto figure.
pub fn pareto_name(task: &str) -> String {
    format!("control__pareto__{}.svg", slug(task))
}

pub const STABILITY_NAME: &str = "control__stability.svg";
pub const CYCLES_NAME: &str = "control__cycles.svg";

/// One log-log panel with its legend on the right.
pub struct PanelBody {
    entries: Vec<Entry>,
    panel: LogLogPanel,
}

impl Body for PanelBody {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        let (width, _) = area.dim_in_pixel();
        let (plot, legend_area) = area.split_horizontally(width.saturating_sub(LEGEND_WIDTH));
        legend::draw(&legend_area, &self.entries, Arrangement::Column)?;
        self.panel.draw(&plot)
    }
}

/// The figure of labelled series.
fn figure(
    title: String,
    caption: &str,
    x_desc: &str,
    y_desc: &str,
    series: Vec<(String, Vec<(f64, f64)>)>,
    marks: bool,
) -> Figure<PanelBody> {
    let entries = series
        .iter()
        .enumerate()
        .map(|(k, (label, _))| Entry {
            style: colour(k).stroke_width(LEGEND_LINE_WIDTH),
            label: label.clone(),
        })
        .collect();
    let series = series
        .into_iter()
        .enumerate()
        .map(|(k, (_, points))| Series {
            colour: colour(k),
            points,
        })
        .collect();
    Figure {
        title,
        body: PanelBody {
            entries,
            panel: LogLogPanel {
                caption: caption.to_string(),
                x_desc: x_desc.to_string(),
                y_desc: y_desc.to_string(),
                series,
                marks,
            },
        },
    }
}

/// A task's Pareto figure from its rows at period `h_ms`.
pub fn pareto(task: &str, h_ms: f64, rows: &[&ControlRow]) -> Figure<PanelBody> {
    let series = rows
        .iter()
        .filter(|r| r.task == task && r.h_ms == h_ms && r.status == ControlStatus::Ok)
        .map(|r| {
            (
                r.method.clone(),
                vec![(r.solve_p50_us, r.max_dx_settled.max(FLOOR))],
            )
        })
        .collect();
    figure(
        format!("{task}: latency against accuracy at h = {h_ms} ms"),
        "each method at the control period (diverged networks left out)",
        "median solve per tick (us)",
        "max |x - x*| after 1 s (rel.)",
        series,
        true,
    )
}

/// The stability figure: every network form on every task, rms |x - x*| against h.
pub fn stability(rows: &[&ControlRow]) -> Figure<PanelBody> {
    let mut keys: Vec<(String, String)> = rows
        .iter()
        .filter(|r| r.family == Family::Network && r.substeps == 1)
        .map(|r| (r.task.clone(), r.method.clone()))
        .collect();
    keys.sort();
    keys.dedup();
    let series = keys
        .into_iter()
        .map(|(task, method)| {
            let mut points: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.task == task && r.method == method && r.substeps == 1)
                .map(|r| {
                    let y = if r.status == ControlStatus::Ok {
                        r.rms_dx.max(FLOOR)
                    } else {
                        DIVERGED_Y
                    };
                    (r.h_ms, y)
                })
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            (format!("{method} · {task}"), points)
        })
        .collect();
    figure(
        "Networks stepped at the control period: accuracy against h".to_string(),
        "one network step per tick; diverged runs drawn at 1e4",
        "control period h (ms)",
        "rms |x - x*| (rel.)",
        series,
        true,
    )
}

/// The drift after each cycle of every many-cycles run.
pub fn cycles(rows: &[CycleRow]) -> Figure<PanelBody> {
    let mut keys: Vec<(String, String)> = rows
        .iter()
        .map(|r| (r.task.clone(), r.method.clone()))
        .collect();
    keys.sort();
    keys.dedup();
    let series = keys
        .into_iter()
        .map(|(task, method)| {
            let mine: Vec<&CycleRow> = rows
                .iter()
                .filter(|r| r.task == task && r.method == method)
                .collect();
            let period = mine
                .first()
                .and_then(|r| r.h_ms)
                .map_or("continuous".to_string(), |h| format!("{h} ms"));
            let points = mine
                .iter()
                .map(|r| (r.cycle as f64, r.drift.max(FLOOR)))
                .collect();
            (format!("{method} ({period}) · {task}"), points)
        })
        .collect();
    figure(
        "Drift after each cycle".to_string(),
        "|theta(cT) - theta0| after cycle c",
        "cycle c",
        "drift (rad)",
        series,
        true,
    )
}
