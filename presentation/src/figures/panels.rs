//! The two kinds of panel: quantities over time (linear or log y axis) and the end-effector path
//! in the x-y plane (equal aspect ratio).

use super::layout::{draw_error, Area};
use super::scale;
use super::style::{
    font, ARM_COLOUR, ARM_START_COLOUR, CAPTION_SIZE, DESIRED_COLOUR, DESIRED_WIDTH, GRID_COLOUR,
    LABEL_SIZE, LINE_WIDTH,
};
use crate::error::FigureError;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use std::ops::Range;

/// Blank space around a panel's plot (px).
pub(super) const MARGIN: u32 = 8;
/// Height of the x tick labels plus the x axis description (px).
pub(super) const X_LABEL_AREA: u32 = 40;
/// Width of the y tick labels plus the y axis description (px).
pub(super) const Y_LABEL_AREA: u32 = 72;
/// Tick labels per axis.
const TICKS: usize = 6;
/// Width (px) and relative x extent of a [`LogLogPanel`]'s point marks.
pub(super) const MARK_WIDTH: u32 = 9;
const MARK_SPAN: f64 = 1.015;

/// One line of a panel.
pub struct Series {
    pub colour: RGBColor,
    pub points: Vec<(f64, f64)>,
}

/// Which y axis a time panel uses.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum YAxis {
    Linear,
    /// Log scale; non-positive values are not drawn.
    Log,
}

/// A panel of quantities over time, t from 0 to `t_end`.
pub struct TimePanel {
    pub caption: String,
    /// The y axis description, with its unit.
    pub y_desc: String,
    pub y_axis: YAxis,
    pub t_end: f64,
    pub series: Vec<Series>,
}

/// The desired and the actual end-effector path in the x-y plane, over the arm's motion.
pub struct PathPanel {
    pub caption: String,
    pub desired: Vec<(f64, f64)>,
    pub actual: Vec<(f64, f64)>,
    pub actual_colour: RGBColor,
    /// The arm's x-y polylines over time, the start pose first; may be empty.
    pub arm: Vec<Vec<(f64, f64)>>,
}

/// Draws the caption at the top of `area`; returns the rest, and the size (px) the plot will
/// have in it once [`plot`] has made room for the axis labels.
pub(super) fn titled<DB: DrawingBackend>(
    area: &Area<DB>,
    caption: &str,
) -> Result<(Area<DB>, (u32, u32)), FigureError> {
    let inner = area
        .titled(caption, font(CAPTION_SIZE))
        .map_err(draw_error)?;
    let (w, h) = inner.dim_in_pixel();
    let plot = (
        w.saturating_sub(2 * MARGIN + Y_LABEL_AREA),
        h.saturating_sub(2 * MARGIN + X_LABEL_AREA),
    );
    Ok((inner, plot))
}

/// A tick label: plain decimals from 1e-3 to 1e5, scientific notation outside.
fn tick(v: f64) -> String {
    let trim = |s: String| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if v == 0.0 {
        "0".to_string()
    } else if (1e-3..1e5).contains(&v.abs()) {
        trim(format!("{v:.4}"))
    } else {
        let s = format!("{v:.2e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        format!("{}e{exponent}", trim(mantissa.to_string()))
    }
}

/// Tick labels for a linear axis over `range`: a tick that is zero but for rounding in the
/// tick arithmetic (far below the axis span) is labelled 0.
pub(super) fn ticks(range: &Range<f64>) -> impl Fn(&f64) -> String {
    let zero = 1e-9 * (range.end - range.start).abs();
    move |v: &f64| tick(if v.abs() < zero { 0.0 } else { *v })
}

/// A log-axis tick label: the power of ten.
pub(super) fn decade(v: &f64) -> String {
    format!("1e{}", v.log10().round())
}

/// Draws axes, grid and lines on `inner` (an area from [`titled`]) with a linear x axis `x`,
/// y axis `y`.
fn plot<DB: DrawingBackend, Y>(
    inner: &Area<DB>,
    x: Range<f64>,
    x_desc: &str,
    y: Y,
    y_desc: &str,
    y_labels: &dyn Fn(&f64) -> String,
    lines: &[(ShapeStyle, Vec<(f64, f64)>)],
) -> Result<(), FigureError>
where
    Y: AsRangedCoord<Value = f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let x_labels = ticks(&x);
    plot_xy(inner, x, x_desc, &x_labels, y, y_desc, y_labels, lines)
}

/// [`plot`] with any x axis `x` (linear or log) labelled by `x_labels`.
#[allow(clippy::too_many_arguments)]
pub(super) fn plot_xy<DB: DrawingBackend, X, Y>(
    inner: &Area<DB>,
    x: X,
    x_desc: &str,
    x_labels: &dyn Fn(&f64) -> String,
    y: Y,
    y_desc: &str,
    y_labels: &dyn Fn(&f64) -> String,
    lines: &[(ShapeStyle, Vec<(f64, f64)>)],
) -> Result<(), FigureError>
where
    X: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y: AsRangedCoord<Value = f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut chart = ChartBuilder::on(inner)
        .margin(MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(x, y)
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .x_labels(TICKS)
        .y_labels(TICKS)
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(x_labels)
        .y_label_formatter(y_labels)
        .label_style(font(LABEL_SIZE))
        .axis_desc_style(font(LABEL_SIZE))
        .bold_line_style(GRID_COLOUR)
        .light_line_style(TRANSPARENT)
        .draw()
        .map_err(draw_error)?;
    for (style, points) in lines {
        chart
            .draw_series(LineSeries::new(points.iter().copied(), *style))
            .map_err(draw_error)?;
    }
    Ok(())
}

impl TimePanel {
    /// Draws the panel into `area`.
    pub fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        let (inner, _) = titled(area, &self.caption)?;
        let keep = |v: f64| v.is_finite() && (self.y_axis == YAxis::Linear || v > 0.0);
        let lines: Vec<(ShapeStyle, Vec<(f64, f64)>)> = self
            .series
            .iter()
            .map(|s| {
                (
                    s.colour.stroke_width(LINE_WIDTH),
                    s.points
                        .iter()
                        .copied()
                        .filter(|&(t, v)| t.is_finite() && keep(v))
                        .collect(),
                )
            })
            .collect();
        let values = lines
            .iter()
            .flat_map(|(_, points)| points.iter().map(|&(_, v)| v));
        let t = scale::bounded(0.0..self.t_end.max(f64::MIN_POSITIVE));
        match self.y_axis {
            YAxis::Linear => {
                let y = scale::linear(values);
                plot(
                    &inner,
                    t,
                    "t (s)",
                    y.clone(),
                    &self.y_desc,
                    &ticks(&y),
                    &lines,
                )
            }
            YAxis::Log => plot(
                &inner,
                t,
                "t (s)",
                scale::log(values).log_scale(),
                &self.y_desc,
                &decade,
                &lines,
            ),
        }
    }
}

impl PathPanel {
    /// Draws the panel into `area`: the arm's poses thin and light with the start pose darker,
    /// over them the desired path wide and pale, and the actual path on top. The equal-aspect
    /// ranges cover the arm as well as the paths.
    pub fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        let (inner, pixels) = titled(area, &self.caption)?;
        let all = || {
            self.desired
                .iter()
                .chain(&self.actual)
                .chain(self.arm.iter().flatten())
        };
        let (x, y) = scale::equal_aspect(
            scale::linear(all().map(|p| p.0)),
            scale::linear(all().map(|p| p.1)),
            pixels,
        );
        let arm_style = |k: usize| {
            if k == 0 {
                ARM_START_COLOUR.stroke_width(LINE_WIDTH)
            } else {
                ARM_COLOUR.stroke_width(LINE_WIDTH)
            }
        };
        // Later poses first, so that the start pose lies over them.
        let mut lines: Vec<(ShapeStyle, Vec<(f64, f64)>)> = self
            .arm
            .iter()
            .enumerate()
            .rev()
            .map(|(k, pose)| (arm_style(k), pose.clone()))
            .collect();
        lines.push((
            DESIRED_COLOUR.stroke_width(DESIRED_WIDTH),
            self.desired.clone(),
        ));
        lines.push((
            self.actual_colour.stroke_width(LINE_WIDTH),
            self.actual.clone(),
        ));
        plot(&inner, x, "x (m)", y.clone(), "y (m)", &ticks(&y), &lines)
    }
}

/// One profile of the setup inference: the best relative residual (log scale, ticks at 1, 2
/// and 5 times each power of ten over a span of at most two decades) against the value of one
/// parameter, and the best fit marked by a vertical and a horizontal line crossing at it.
pub struct ProfilePanel {
    pub caption: String,
    /// The parameter and its unit.
    pub x_desc: String,
    pub x: Range<f64>,
    pub points: Vec<(f64, f64)>,
    /// The best fit (parameter value, residual), if known.
    pub best: Option<(f64, f64)>,
}

impl ProfilePanel {
    /// Draws the panel into `area`.
    pub fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        let (inner, _) = titled(area, &self.caption)?;
        let ok = |&(x, v): &(f64, f64)| x.is_finite() && v.is_finite() && v > 0.0;
        let points: Vec<(f64, f64)> = self.points.iter().copied().filter(ok).collect();
        let best = self.best.filter(ok);
        let y = scale::log(points.iter().chain(&best).map(|p| p.1));
        let mut lines = vec![(super::style::colour(0).stroke_width(2), points)];
        if let Some((bx, by)) = best {
            let mark = super::style::colour(1).stroke_width(1);
            lines.push((mark, vec![(bx, y.start), (bx, y.end)]));
            lines.push((mark, vec![(self.x.start, by), (self.x.end, by)]));
        }
        let x_labels = ticks(&self.x);
        let key_points = scale::log_ticks(&y);
        plot_xy(
            &inner,
            self.x.clone(),
            &self.x_desc,
            &x_labels,
            y.log_scale().with_key_points(key_points),
            "relative residual",
            &|v: &f64| tick(*v),
            &lines,
        )
    }
}

/// Quantities against a size, both axes logarithmic (a power law is a straight line): the x
/// axis spans the points' x from 10 % below to 10 % above, with a tick at each x of the data,
/// the y axis whole decades.
pub struct LogLogPanel {
    pub caption: String,
    /// The x quantity and its unit.
    pub x_desc: String,
    /// The y quantity and its unit.
    pub y_desc: String,
    pub series: Vec<Series>,
    /// A dot at every point besides the lines (for series of one point).
    pub marks: bool,
}

impl LogLogPanel {
    /// Draws the panel into `area`; non-positive or non-finite points are left out.
    pub fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        let (inner, _) = titled(area, &self.caption)?;
        let lines: Vec<(ShapeStyle, Vec<(f64, f64)>)> = self
            .series
            .iter()
            .map(|s| {
                let points = s
                    .points
                    .iter()
                    .copied()
                    .filter(|&(x, y)| x.is_finite() && y.is_finite() && x > 0.0 && y > 0.0)
                    .collect();
                (s.colour.stroke_width(2), points)
            })
            .collect();
        let xs = lines.iter().flat_map(|(_, p)| p.iter().map(|q| q.0));
        let (lo, hi) = xs.fold((f64::INFINITY, 0.0f64), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
        let x = if lo <= hi {
            lo / 1.1..hi * 1.1
        } else {
            1.0..10.0
        };
        let mut x_ticks: Vec<f64> = lines
            .iter()
            .flat_map(|(_, p)| p.iter().map(|q| q.0))
            .collect();
        x_ticks.sort_by(f64::total_cmp);
        x_ticks.dedup();
        let y = scale::log(lines.iter().flat_map(|(_, p)| p.iter().map(|q| q.1)));
        let mut shapes = lines.clone();
        if self.marks {
            // A dot is a short segment of the series' colour, wide as a marker.
            for (style, points) in &lines {
                for &(px, py) in points {
                    shapes.push((
                        style.color.stroke_width(MARK_WIDTH),
                        vec![(px / MARK_SPAN, py), (px * MARK_SPAN, py)],
                    ));
                }
            }
        }
        plot_xy(
            &inner,
            x.log_scale().with_key_points(x_ticks),
            &self.x_desc,
            &|v: &f64| tick(*v),
            y.log_scale(),
            &self.y_desc,
            &decade,
            &shapes,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::{decade, ticks};

    #[test]
    fn tick_labels_are_short() {
        let label = ticks(&(-1.0..1.0));
        assert_eq!(label(&0.0), "0");
        assert_eq!(label(&-2.78e-17), "0");
        assert_eq!(label(&0.25), "0.25");
        assert_eq!(label(&-3.0), "-3");
        assert_eq!(ticks(&(0.0..1e-5))(&2.5e-6), "2.5e-6");
        assert_eq!(label(&1.0e7), "1e7");
        assert_eq!(decade(&1e-6), "1e-6");
    }
}
