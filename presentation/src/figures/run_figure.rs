//! The figure of one run: (a) end-effector path over the arm's motion, (b) position error,
//! then for a scored run the distance of its solver's command to the exact QP optimum
//! |x - x*| (the headline score), joint angles relative to theta(0), joint velocities, and at
//! the acceleration level joint accelerations and torques, as in the papers' per-run figures.
//! Panels are lettered in the order they are drawn.

use super::arm;
use super::layout::{Area, Body, Figure};
use super::legend::{self, Arrangement, Entry};
use super::panels::{PathPanel, Series, TimePanel, YAxis};
use super::style::{
    colour, ARM_COLOUR, ARM_START_COLOUR, DESIRED_COLOUR, DESIRED_WIDTH, LEGEND_LINE_WIDTH,
};
use super::trace::Trace;
use crate::error::FigureError;
use plotters::prelude::*;
use records::RunRow;

/// Height of the legend strip under the title (px).
const LEGEND_HEIGHT: u32 = 28;
/// Colour of the single-line quantities (actual path, position error).
const ACTUAL_COLOUR: RGBColor = BLACK;

/// "experiment: variant / solver", with "failed at t = ... s" for a failed run.
pub fn title(run: &RunRow) -> String {
    let mut title = format!("{}: {} / {}", run.experiment, run.variant, run.solver);
    if let Some(t) = run.failed_at {
        title.push_str(&format!(" (failed at t = {t:.3} s)"));
    } else if !run.completed() {
        title.push_str(&format!(" ({})", run.status));
    }
    title
}

/// One series per joint, joint i in colour i.
fn per_joint(
    trace: &Trace,
    columns: &[Vec<f64>],
    value: impl Fn(usize, f64) -> f64,
) -> Vec<Series> {
    columns
        .iter()
        .enumerate()
        .map(|(i, column)| {
            let shifted: Vec<f64> = column.iter().map(|&v| value(i, v)).collect();
            Series {
                colour: colour(i),
                points: trace.over_time(&shifted),
            }
        })
        .collect()
}

/// What the figure of a run draws under its title: the legend strip, then the panels two by two.
pub struct RunBody {
    entries: Vec<Entry>,
    path_panel: PathPanel,
    panels: Vec<TimePanel>,
}

impl Body for RunBody {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        let (strip, body) = area.split_vertically(LEGEND_HEIGHT);
        legend::draw(&strip, &self.entries, Arrangement::Strip)?;
        let cells = body.split_evenly(((self.panels.len() + 1).div_ceil(2), 2));
        self.path_panel.draw(&cells[0])?;
        for (panel, cell) in self.panels.iter().zip(&cells[1..]) {
            panel.draw(cell)?;
        }
        Ok(())
    }
}

/// The run's figure.
pub fn figure(run: &RunRow, trace: &Trace) -> Figure<RunBody> {
    let path_panel = path_panel(run, trace);
    let entries = legend_entries(trace, !path_panel.arm.is_empty());
    Figure {
        title: title(run),
        body: RunBody {
            entries,
            path_panel,
            panels: time_panels(run, trace),
        },
    }
}

/// Panel (a): the desired and actual end-effector path in the x-y plane (thinned), with the arm
/// over its motion.
fn path_panel(run: &RunRow, trace: &Trace) -> PathPanel {
    let path = |xy: &[Vec<f64>; 2]| {
        trace
            .thinned()
            .into_iter()
            .map(|k| (xy[0][k], xy[1][k]))
            .collect()
    };
    PathPanel {
        caption: "(a) end-effector path, x-y plane".to_string(),
        desired: path(&trace.desired),
        actual: path(&trace.actual),
        actual_colour: ACTUAL_COLOUR,
        arm: arm::poses(run, trace),
    }
}

/// The panels over time, lettered from (b) in drawing order: the position error, the distance
/// to the exact optimum (a scored run), the joint angles relative to theta(0), the joint
/// velocities, and the accelerations and torques where the trace has them.
fn time_panels(run: &RunRow, trace: &Trace) -> Vec<TimePanel> {
    let joints = |columns: &[Vec<f64>]| per_joint(trace, columns, |_, v| v);
    // (caption, y axis, scale, series) in drawing order.
    let mut panels: Vec<(&str, &str, YAxis, Vec<Series>)> = vec![(
        "position error |r* - f(theta)|",
        "error (m)",
        YAxis::Log,
        vec![Series {
            colour: ACTUAL_COLOUR,
            points: trace.over_time(&trace.pos_err),
        }],
    )];
    if trace.is_scored() {
        panels.push((
            "distance to the exact QP optimum |x - x*|",
            "|x - x*|",
            YAxis::Log,
            vec![Series {
                colour: ACTUAL_COLOUR,
                points: trace.score_over_time(),
            }],
        ));
    }
    panels.extend([
        (
            "joint angles theta_i(t) - theta_i(0)",
            "angle change (rad)",
            YAxis::Linear,
            per_joint(trace, &trace.theta, |i, v| v - trace.theta[i][0]),
        ),
        (
            "joint velocities",
            "velocity (rad/s)",
            YAxis::Linear,
            joints(&trace.thetadot),
        ),
    ]);
    if let Some(thetaddot) = &trace.thetaddot {
        panels.push((
            "joint accelerations",
            "acceleration (rad/s^2)",
            YAxis::Linear,
            joints(thetaddot),
        ));
    }
    if let Some(tau) = &trace.tau {
        panels.push(("joint torques", "torque (N m)", YAxis::Linear, joints(tau)));
    }
    panels
        .into_iter()
        .zip('b'..)
        .map(|((caption, y_desc, y_axis, series), letter)| TimePanel {
            caption: format!("({letter}) {caption}"),
            y_desc: y_desc.to_string(),
            y_axis,
            t_end: run.duration,
            series,
        })
        .collect()
}

/// The legend: desired and actual path, the arm's poses (`arm`: where they are drawn), and one
/// entry per joint.
fn legend_entries(trace: &Trace, arm: bool) -> Vec<Entry> {
    let mut entries = vec![
        Entry {
            style: DESIRED_COLOUR.stroke_width(DESIRED_WIDTH),
            label: "desired r*".to_string(),
        },
        Entry {
            style: ACTUAL_COLOUR.stroke_width(LEGEND_LINE_WIDTH),
            label: "actual f(theta)".to_string(),
        },
    ];
    if arm {
        entries.extend([
            Entry {
                style: ARM_START_COLOUR.stroke_width(LEGEND_LINE_WIDTH),
                label: "arm at t = 0".to_string(),
            },
            Entry {
                style: ARM_COLOUR.stroke_width(LEGEND_LINE_WIDTH),
                label: "arm over time".to_string(),
            },
        ]);
    }
    entries.extend((0..trace.joints()).map(|i| Entry {
        style: colour(i).stroke_width(LEGEND_LINE_WIDTH),
        label: format!("joint {}", i + 1),
    }));
    entries
}
