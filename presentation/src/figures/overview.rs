//! The overview of one experiment: every run's position error over time on one log-scale plot
//! and, where neural runs exist, their distance to the exact optimum |x_nn - x*| over time.

use super::layout::{Area, Body, Figure};
use super::legend::{self, Arrangement, Entry};
use super::panels::{Series, TimePanel, YAxis};
use super::style::{colour, LEGEND_LINE_WIDTH};
use super::trace::Trace;
use crate::error::FigureError;
use plotters::prelude::*;
use records::runs::RunRow;

/// Width of the legend column on the right (px).
const LEGEND_WIDTH: u32 = 430;

/// "variant / solver", with "failed at t = ... s" on a second line for a failed run.
fn label(run: &RunRow) -> String {
    match run.failed_at {
        Some(t) => format!("{} / {}\n(failed at t = {t:.3} s)", run.variant, run.solver),
        None => format!("{} / {}", run.variant, run.solver),
    }
}

/// What an overview draws under its title: the plots on the left, the legend column on the
/// right.
pub struct OverviewBody {
    entries: Vec<Entry>,
    errors: TimePanel,
    scores: Option<TimePanel>,
}

impl Body for OverviewBody {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        let (width, _) = area.dim_in_pixel();
        let (plots, legend_area) = area.split_horizontally(width.saturating_sub(LEGEND_WIDTH));
        legend::draw(&legend_area, &self.entries, Arrangement::Column)?;
        match &self.scores {
            Some(scores) => {
                let (top, bottom) = plots.split_vertically(plots.dim_in_pixel().1 / 2);
                self.errors.draw(&top)?;
                scores.draw(&bottom)
            }
            None => self.errors.draw(&plots),
        }
    }
}

/// The experiment's figure; `runs` all belong to `experiment`, run k is drawn in colour k.
pub fn figure(experiment: &str, runs: &[(&RunRow, &Trace)]) -> Figure<OverviewBody> {
    let t_end = runs.iter().map(|(run, _)| run.duration).fold(0.0, f64::max);
    let errors = TimePanel {
        caption: "(a) position error |r* - f(theta)| of every run".to_string(),
        y_desc: "error (m)".to_string(),
        y_axis: YAxis::Log,
        t_end,
        series: runs
            .iter()
            .enumerate()
            .map(|(k, (_, trace))| Series {
                colour: colour(k),
                points: trace.over_time(&trace.pos_err),
            })
            .collect(),
    };
    let scored = runs.iter().any(|(_, trace)| trace.is_scored());
    let unit = if runs.iter().any(|(_, trace)| trace.thetaddot.is_some()) {
        "rad/s^2"
    } else {
        "rad/s"
    };
    let scores = scored.then(|| TimePanel {
        caption: "(b) neural solvers: distance to the exact QP optimum |x_nn - x*|".to_string(),
        y_desc: format!("|x_nn - x*| ({unit})"),
        y_axis: YAxis::Log,
        t_end,
        series: runs
            .iter()
            .enumerate()
            .map(|(k, (_, trace))| Series {
                colour: colour(k),
                points: trace.score_over_time(),
            })
            .collect(),
    });
    let entries: Vec<Entry> = runs
        .iter()
        .enumerate()
        .map(|(k, (run, _))| Entry {
            style: colour(k).stroke_width(LEGEND_LINE_WIDTH),
            label: label(run),
        })
        .collect();

    Figure {
        title: format!("{experiment}: overview of {} runs", runs.len()),
        body: OverviewBody {
            entries,
            errors,
            scores,
        },
    }
}
