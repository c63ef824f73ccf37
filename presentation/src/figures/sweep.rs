//! A large sweep drawn over its parameters: an experiment with more runs than
//! [`MAX_RUN_FIGURES`] gets a figure of their own for that many of its runs only (its sample,
//! `analysis::sweep_summary`), and one figure `<experiment>__sweep.svg` over all of them
//! ([`figure`]), drawn from its summary ([`SweepSummary`], aggregated as `results/runs.csv`
//! was read), so its size depends on the number of its parameters' points, never on its runs:
//!
//! - for each numeric swept parameter p (at most [`MAX_PARAMETERS`]): the drift norm
//!   ||theta(T) - theta(0)|| against p and the largest position error max_t |r*(t) - f(theta(t))|
//!   against p (log scale), per point of p (a value, or one of [`MAX_VALUES`] equal intervals
//!   of its range when it takes more values) a bar from the smallest to the largest value of
//!   its completed runs, and a line through the medians (a histogram's median: within 1/64 of
//!   the sweep's range of log10, [`analysis::sweep_summary::Sketch`]);
//! - with two numeric parameters or more, a heat map over the first two: in each cell (a pair
//!   of points) the median log10 of the drift norm of its completed runs (the same median);
//! - the distribution of log10 of the drift norm over the completed runs (a histogram of
//!   [`BINS`] bins).
//!
//! The parameters are read back from the runs' labels (`analysis::sweep_summary::parameters`).
//! A label written as a template names no parameter, and the figure then shows the
//! distribution alone. Everything is drawn from `results/runs.csv` alone: no trace is read for
//! the sweep figure.

use super::layout::{draw_error, Area, Body, Figure};
use super::panels::{decade, ticks, titled, MARGIN, MARK_WIDTH, X_LABEL_AREA, Y_LABEL_AREA};
use super::scale;
use super::style::{colour, font, GRID_COLOUR, LABEL_SIZE};
use crate::error::FigureError;
use analysis::sweep_summary::{Axis, Sketch, SweepSummary};
pub use analysis::sweep_summary::{BINS, MAX_PARAMETERS, MAX_RUN_FIGURES, MAX_VALUES};
use plotters::prelude::*;

/// The file name of the sweep figure of `experiment` (`<experiment>__sweep.svg`).
pub fn sweep_name(experiment: &str) -> String {
    format!("{experiment}__sweep.svg")
}

/// One panel of the sweep figure.
enum Panel {
    /// A quantity (log scale) against a parameter (linear): per point (x, min, median, max).
    Ranges {
        caption: String,
        x_desc: String,
        y_desc: String,
        points: Vec<(f64, f64, f64, f64)>,
    },
    /// The median of log10 of the drift norm over pairs of two parameters' points.
    Heat {
        caption: String,
        x: (String, Vec<f64>),
        y: (String, Vec<f64>),
        /// (x index, y index, median log10 drift norm).
        cells: Vec<(usize, usize, f64)>,
    },
    /// The distribution of log10 of the drift norm: (bin start, bin end, count).
    Histogram {
        caption: String,
        bins: Vec<(f64, f64, usize)>,
    },
}

/// What the sweep figure draws under its title: its panels in two columns.
pub struct SweepBody {
    panels: Vec<Panel>,
}

impl Body for SweepBody {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        let rows = self.panels.len().div_ceil(2).max(1);
        let cells = area.split_evenly((rows, 2));
        for (panel, cell) in self.panels.iter().zip(&cells) {
            panel.draw(cell)?;
        }
        Ok(())
    }
}

/// The colour of a heat map's cell at `f` in [0, 1] (light yellow to dark red).
fn heat(f: f64) -> RGBColor {
    let f = if f.is_finite() {
        f.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mix = |a: u8, b: u8| (f64::from(a) + f * (f64::from(b) - f64::from(a))).round() as u8;
    RGBColor(mix(255, 189), mix(237, 0), mix(160, 38))
}

/// A parameter's value as a tick label.
fn value_text(v: f64) -> String {
    let short = format!("{v}");
    if short.len() <= 8 {
        short
    } else {
        format!("{v:.3e}")
    }
}

impl Panel {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        match self {
            Panel::Ranges {
                caption,
                x_desc,
                y_desc,
                points,
            } => {
                let (inner, _) = titled(area, caption)?;
                let x = scale::linear(points.iter().map(|p| p.0));
                let y = scale::log(points.iter().flat_map(|p| [p.1, p.3]));
                // A bar from the smallest to the largest value, a tick wide as a marker at the
                // median, and a line through the medians.
                let half = 4e-3 * (x.end - x.start);
                let bar = colour(0).stroke_width(MARK_WIDTH);
                let mut lines: Vec<(ShapeStyle, Vec<(f64, f64)>)> = Vec::new();
                for &(px, lo, median, hi) in points {
                    lines.push((bar, vec![(px, lo), (px, hi)]));
                    lines.push((bar, vec![(px - half, median), (px + half, median)]));
                }
                lines.push((
                    colour(1).stroke_width(1),
                    points.iter().map(|p| (p.0, p.2)).collect(),
                ));
                let x_labels = ticks(&x);
                super::panels::plot_xy(
                    &inner,
                    x,
                    x_desc,
                    &x_labels,
                    y.log_scale(),
                    y_desc,
                    &decade,
                    &lines,
                )
            }
            Panel::Histogram { caption, bins } => {
                let (inner, _) = titled(area, caption)?;
                let x = scale::linear(bins.iter().flat_map(|b| [b.0, b.1]));
                let top = bins.iter().map(|b| b.2).max().unwrap_or(1).max(1) as f64;
                let y = 0.0..top * 1.05;
                let mut outline = Vec::with_capacity(4 * bins.len());
                for &(lo, hi, count) in bins {
                    let c = count as f64;
                    outline.extend([(lo, 0.0), (lo, c), (hi, c), (hi, 0.0)]);
                }
                let x_labels = ticks(&x);
                let y_labels = ticks(&y);
                super::panels::plot_xy(
                    &inner,
                    x,
                    "log10 drift norm (rad)",
                    &x_labels,
                    y,
                    "runs",
                    &y_labels,
                    &[(colour(0).stroke_width(2), outline)],
                )
            }
            Panel::Heat {
                caption,
                x,
                y,
                cells,
            } => {
                let (inner, _) = titled(area, caption)?;
                let (lo, hi) = cells
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |a, c| {
                        (a.0.min(c.2), a.1.max(c.2))
                    });
                let span = if hi > lo { hi - lo } else { 1.0 };
                let (nx, ny) = (x.1.len(), y.1.len());
                // Cell i is centred on i: a tick on a whole number names its value.
                let label = |values: &[f64], v: f64| {
                    let i = v.round();
                    if i >= 0.0 && (i as usize) < values.len() && (v - i).abs() < 1e-9 {
                        value_text(values[i as usize])
                    } else {
                        String::new()
                    }
                };
                let mut chart = ChartBuilder::on(&inner)
                    .margin(MARGIN)
                    .x_label_area_size(X_LABEL_AREA)
                    .y_label_area_size(Y_LABEL_AREA)
                    .build_cartesian_2d(-0.5..nx as f64 - 0.5, -0.5..ny as f64 - 0.5)
                    .map_err(draw_error)?;
                chart
                    .configure_mesh()
                    .x_labels(nx.min(12))
                    .y_labels(ny.min(12))
                    .x_desc(x.0.as_str())
                    .y_desc(y.0.as_str())
                    .x_label_formatter(&|v: &f64| label(&x.1, *v))
                    .y_label_formatter(&|v: &f64| label(&y.1, *v))
                    .label_style(font(LABEL_SIZE))
                    .axis_desc_style(font(LABEL_SIZE))
                    .bold_line_style(GRID_COLOUR)
                    .light_line_style(TRANSPARENT)
                    .draw()
                    .map_err(draw_error)?;
                chart
                    .draw_series(cells.iter().map(|&(i, j, v)| {
                        let (i, j) = (i as f64, j as f64);
                        Rectangle::new(
                            [(i - 0.5, j - 0.5), (i + 0.5, j + 0.5)],
                            heat((v - lo) / span).filled(),
                        )
                    }))
                    .map_err(draw_error)?;
                Ok(())
            }
        }
    }
}

/// A sketch's (min, median, max), when it has values.
fn range_of(s: &Sketch) -> Option<(f64, f64, f64)> {
    Some((s.min, s.median()?, s.max))
}

/// An axis's description: its name, and its intervals when it is cut into them.
fn axis_desc(a: &Axis) -> String {
    match a.intervals {
        Some(_) => format!("{} ({} intervals)", a.name, a.len()),
        None => a.name.clone(),
    }
}

/// The sweep figure of `experiment` from its summary `s` (module docs).
pub fn figure(experiment: &str, s: &SweepSummary) -> Figure<SweepBody> {
    let mut panels = Vec::new();
    let mut letters = 'a'..;
    let mut next = || letters.next().unwrap_or('?');
    for (axis, sketches) in s.axes.iter().zip(&s.against) {
        let points = |pick: fn(&(Sketch, Sketch)) -> &Sketch| -> Vec<(f64, f64, f64, f64)> {
            sketches
                .iter()
                .enumerate()
                .filter_map(|(i, p)| {
                    let (lo, median, hi) = range_of(pick(p))?;
                    Some((axis.position(i), lo, median, hi))
                })
                .collect()
        };
        panels.push(Panel::Ranges {
            caption: format!(
                "({}) drift norm against {}: min, median, max",
                next(),
                axis.name
            ),
            x_desc: axis_desc(axis),
            y_desc: "||theta(T) - theta(0)|| (rad)".to_string(),
            points: points(|p| &p.0),
        });
        panels.push(Panel::Ranges {
            caption: format!(
                "({}) largest position error against {}: min, median, max",
                next(),
                axis.name
            ),
            x_desc: axis_desc(axis),
            y_desc: "max |r* - f(theta)| (m)".to_string(),
            points: points(|p| &p.1),
        });
    }
    if let [x, y, ..] = &s.axes[..] {
        let cells = s
            .heat
            .iter()
            .enumerate()
            .filter_map(|(k, c)| Some((k % x.len(), k / x.len(), c.median()?.log10())))
            .collect();
        let positions = |a: &Axis| (0..a.len()).map(|i| a.position(i)).collect();
        panels.push(Panel::Heat {
            caption: format!(
                "({}) median log10 drift norm over {} and {} (light: smallest, dark: largest)",
                next(),
                x.name,
                y.name
            ),
            x: (axis_desc(x), positions(x)),
            y: (axis_desc(y), positions(y)),
            cells,
        });
    }
    panels.push(Panel::Histogram {
        caption: format!(
            "({}) distribution of the drift norm ({} completed runs)",
            next(),
            s.drawn_drift()
        ),
        bins: s.histogram.clone(),
    });
    Figure {
        title: format!(
            "{experiment}: {} runs over {}{}",
            s.runs,
            if s.axes.is_empty() {
                "its variants".to_string()
            } else {
                s.axes
                    .iter()
                    .map(|a| a.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            },
            if s.failed > 0 {
                format!(" ({} failed)", s.failed)
            } else {
                String::new()
            }
        ),
        body: SweepBody { panels },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use analysis::sweep_summary::Held;
    use records::RunRow;
    use spec::RunKey;
    use spec::SolverKind;

    /// The summary of `n` runs of one experiment sweeping mu (n / 100 values) and scale (100
    /// values), every 97th failed, read as the report reads them.
    fn sweep(n: usize) -> SweepSummary {
        let rows: Vec<RunRow> = (0..n)
            .map(|i| {
                let (mu, scale) = (i / 100, i % 100);
                let label = format!("ZNN [mu={mu}, scale={}]", 0.01 * scale as f64);
                let key = RunKey::parse(&format!("big-sweep / v{i:05} / exact")).unwrap();
                let mut r = RunRow::blank(&key, SolverKind::Exact);
                r.variant = label;
                if i % 97 == 5 {
                    r.status = records::Status::Failed;
                    r.failed_at = Some(1.0);
                } else {
                    r.drift_norm = Some(1e-6 * (1.0 + mu as f64) * (1.0 + scale as f64));
                    r.max_pos_err = Some(1e-5 / (1.0 + i as f64));
                }
                r
            })
            .collect();
        let dir = inputs::Scratch::dir(&format!("sweep-fig-{n}"));
        let path = dir.join("runs.csv");
        std::fs::write(&path, records::runs_csv(&rows).unwrap()).unwrap();
        let held = Held::read(&path, &|_| true).unwrap();
        drop(dir);
        held.sweeps.into_iter().next().unwrap()
    }

    /// A merged 10^4-run sweep draws one sweep figure over its two parameters whose size does
    /// not grow with its runs: per parameter a bar per point (its values, or MAX_VALUES
    /// intervals), a heat map and the distribution; 10^4 and 4 x 10^4 runs over as many
    /// points give figures of the same size to within a few per cent.
    #[test]
    fn a_large_sweep_figure_is_bounded_by_its_parameters_points() {
        let s = sweep(10_000);
        let f = figure("big-sweep", &s);
        // 2 range panels per parameter, the heat map and the distribution.
        assert_eq!(f.body.panels.len(), 2 * 2 + 2);
        assert!(f.title.contains("10000 runs over mu, scale"), "{}", f.title);
        assert!(f.title.contains("(104 failed)"), "{}", f.title);
        let Panel::Ranges { points, .. } = &f.body.panels[0] else {
            panic!("a range panel first")
        };
        // mu: 100 values, cut into MAX_VALUES intervals.
        assert_eq!(points.len(), MAX_VALUES);
        assert!(points.iter().all(|&(_, lo, m, hi)| lo <= m && m <= hi));
        let svg = f.svg().unwrap();
        assert!(svg.contains("<svg"), "drawn");
        assert!(svg.contains("mu (40 intervals)"), "the axis says it is cut");
        let larger = figure("big-sweep", &sweep(40_000)).svg().unwrap();
        let ratio = larger.len() as f64 / svg.len() as f64;
        assert!(
            (0.9..1.1).contains(&ratio),
            "{} against {}",
            larger.len(),
            svg.len()
        );
    }
}
