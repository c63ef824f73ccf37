//! A large sweep drawn over its parameters: an experiment with more runs than
//! [`MAX_RUN_FIGURES`] gets a figure of their own for that many of its runs only ([`drawn`]),
//! and one figure `<experiment>__sweep.svg` over all of them ([`figure`]):
//!
//! - for each numeric swept parameter p (at most [`MAX_PARAMETERS`]): the drift norm
//!   ||theta(T) - theta(0)|| against p and the largest position error max_t |r*(t) - f(theta(t))|
//!   against p, one dot per completed run (log scale);
//! - with two numeric parameters or more, a heat map over the first two: in each cell (a pair
//!   of values) the median log10 of the drift norm of its completed runs;
//! - the distribution of log10 of the drift norm over the completed runs (a histogram of
//!   [`BINS`] bins).
//!
//! **Parameters** are read back from the run's label: the sweep grammar (`catalog::sweep`)
//! writes a swept variant's label as `label [k=v, k2=v2]`, k the last segment of each swept
//! path ([`parameters`]). A parameter is numeric when every run that names it gives a number,
//! and it is drawn when it takes two values or more. A label written as a template names no
//! parameter, and the figure then shows the distribution alone.
//!
//! Everything is drawn from `results/runs.csv` alone: no trace is read for the sweep figure.

use super::layout::{draw_error, Area, Body, Figure};
use super::panels::{decade, ticks, titled, MARGIN, MARK_WIDTH, X_LABEL_AREA, Y_LABEL_AREA};
use super::scale;
use super::style::{colour, font, GRID_COLOUR, LABEL_SIZE};
use crate::error::FigureError;
use analysis::sweep_summary::{extreme, Extreme};
use plotters::prelude::*;
use records::RunRow;
use std::collections::BTreeMap;

/// The most per-run figures one experiment draws; an experiment with more runs is a large
/// sweep and gets the sweep figure.
pub const MAX_RUN_FIGURES: usize = 24;

/// The most swept parameters the sweep figure draws against (in the order of the label).
pub const MAX_PARAMETERS: usize = 3;

/// Bins of the drift norm's distribution.
pub const BINS: usize = 24;

/// The file name of the sweep figure of `experiment` (`<experiment>__sweep.svg`).
pub fn sweep_name(experiment: &str) -> String {
    format!("{experiment}__sweep.svg")
}

/// The swept parameters of a run, as (name, value text), read back from its label's trailing
/// `[k=v, k2=v2]` (module docs); a part without `=` (a labelled value's text) is left out, and a
/// label without the bracket names none.
pub fn parameters(label: &str) -> Vec<(String, String)> {
    let Some((_, inside)) = label.strip_suffix(']').and_then(|l| l.rsplit_once(" [")) else {
        return Vec::new();
    };
    inside
        .split(", ")
        .filter_map(|part| part.split_once('='))
        .map(|(k, v)| (k.trim().to_string(), v.trim().to_string()))
        .collect()
}

/// The numeric swept parameters of `runs` (module docs): each name with each run's value
/// (`None` where the run does not name it), in the order the labels name them, at most
/// [`MAX_PARAMETERS`].
pub fn numeric_parameters(runs: &[&RunRow]) -> Vec<(String, Vec<Option<f64>>)> {
    let parsed: Vec<Vec<(String, String)>> = runs.iter().map(|r| parameters(&r.variant)).collect();
    let mut names: Vec<&str> = Vec::new();
    for p in &parsed {
        for (k, _) in p {
            if !names.contains(&k.as_str()) {
                names.push(k);
            }
        }
    }
    let mut out = Vec::new();
    for name in names {
        let values: Vec<Option<Option<f64>>> = parsed
            .iter()
            .map(|p| {
                p.iter()
                    .find(|(k, _)| k == name)
                    .map(|(_, v)| v.parse::<f64>().ok().filter(|x| x.is_finite()))
            })
            .collect();
        // Numeric: every run naming it gives a number.
        if values.iter().any(|v| matches!(v, Some(None))) {
            continue;
        }
        let values: Vec<Option<f64>> = values.into_iter().map(Option::flatten).collect();
        let mut distinct: Vec<f64> = values.iter().flatten().copied().collect();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        if distinct.len() >= 2 {
            out.push((name.to_string(), values));
        }
        if out.len() == MAX_PARAMETERS {
            break;
        }
    }
    out
}

/// The drift norm of a completed run.
fn drift(r: &RunRow) -> Option<f64> {
    r.completed().then_some(r.drift_norm).flatten()
}

/// The largest position error of a completed run.
fn error(r: &RunRow) -> Option<f64> {
    r.completed().then_some(r.max_pos_err).flatten()
}

/// Which of `runs` (one experiment's, in key order) get a figure of their own, as ascending
/// indices into `runs`: every run up to [`MAX_RUN_FIGURES`]; beyond, the failed runs first (at
/// most a quarter of the cap, in key order), then the extremes (largest and smallest drift
/// norm and position error: [`analysis::sweep_summary::extreme`]), then runs evenly spaced in
/// key order,
/// up to the cap. Deterministic: the same rows give the same figures.
pub fn drawn(runs: &[&RunRow]) -> Vec<usize> {
    let n = runs.len();
    if n <= MAX_RUN_FIGURES {
        return (0..n).collect();
    }
    let mut chosen: Vec<usize> = runs
        .iter()
        .enumerate()
        .filter(|(_, r)| !r.completed())
        .map(|(i, _)| i)
        .take(MAX_RUN_FIGURES / 4)
        .collect();
    let extremes = Extreme::ALL.map(|e| extreme(runs, e));
    for i in extremes.into_iter().flatten() {
        if !chosen.contains(&i) {
            chosen.push(i);
        }
    }
    // Evenly spaced: the k-th of `slots` at k n / slots, skipping runs already chosen.
    let slots = MAX_RUN_FIGURES - chosen.len();
    for k in 0..slots {
        let mut i = k * n / slots;
        while chosen.contains(&i) && i + 1 < n {
            i += 1;
        }
        if !chosen.contains(&i) {
            chosen.push(i);
        }
    }
    chosen.sort_unstable();
    chosen.truncate(MAX_RUN_FIGURES);
    chosen
}

/// One panel of the sweep figure.
enum Panel {
    /// A quantity (log scale) against a parameter (linear), one dot per run.
    Scatter {
        caption: String,
        x_desc: String,
        y_desc: String,
        points: Vec<(f64, f64)>,
    },
    /// The median of log10 of the drift norm over pairs of two parameters' values.
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
    format!("{v}")
}

impl Panel {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        match self {
            Panel::Scatter {
                caption,
                x_desc,
                y_desc,
                points,
            } => {
                let (inner, _) = titled(area, caption)?;
                let points: Vec<(f64, f64)> = points
                    .iter()
                    .copied()
                    .filter(|&(x, y)| x.is_finite() && y.is_finite() && y > 0.0)
                    .collect();
                let x = scale::linear(points.iter().map(|p| p.0));
                let y = scale::log(points.iter().map(|p| p.1));
                // A dot is a short horizontal segment, wide as a marker.
                let half = 2e-3 * (x.end - x.start);
                let style = colour(0).stroke_width(MARK_WIDTH);
                let dots: Vec<(ShapeStyle, Vec<(f64, f64)>)> = points
                    .iter()
                    .map(|&(px, py)| (style, vec![(px - half, py), (px + half, py)]))
                    .collect();
                let x_labels = ticks(&x);
                super::panels::plot_xy(
                    &inner,
                    x,
                    x_desc,
                    &x_labels,
                    y.log_scale(),
                    y_desc,
                    &decade,
                    &dots,
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

/// The median of `values` (not empty).
fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// The sweep figure of `experiment` over all its `runs` (module docs).
pub fn figure(experiment: &str, runs: &[&RunRow]) -> Figure<SweepBody> {
    let params = numeric_parameters(runs);
    let mut panels = Vec::new();
    let mut letters = 'a'..;
    let mut next = || letters.next().unwrap_or('?');
    for (name, values) in &params {
        let against = |metric: fn(&RunRow) -> Option<f64>| -> Vec<(f64, f64)> {
            runs.iter()
                .zip(values)
                .filter_map(|(r, v)| Some(((*v)?, metric(r)?)))
                .collect()
        };
        panels.push(Panel::Scatter {
            caption: format!("({}) drift norm against {name}", next()),
            x_desc: name.clone(),
            y_desc: "||theta(T) - theta(0)|| (rad)".to_string(),
            points: against(drift),
        });
        panels.push(Panel::Scatter {
            caption: format!("({}) largest position error against {name}", next()),
            x_desc: name.clone(),
            y_desc: "max |r* - f(theta)| (m)".to_string(),
            points: against(error),
        });
    }
    if let [(xn, xv), (yn, yv), ..] = &params[..] {
        let distinct = |v: &[Option<f64>]| {
            let mut d: Vec<f64> = v.iter().flatten().copied().collect();
            d.sort_by(f64::total_cmp);
            d.dedup();
            d
        };
        let (xs, ys) = (distinct(xv), distinct(yv));
        let index = |d: &[f64], v: f64| d.binary_search_by(|x| x.total_cmp(&v)).ok();
        let mut by_cell: BTreeMap<(usize, usize), Vec<f64>> = BTreeMap::new();
        for ((r, x), y) in runs.iter().zip(xv).zip(yv) {
            let (Some(x), Some(y), Some(d)) = (*x, *y, drift(r).filter(|d| *d > 0.0)) else {
                continue;
            };
            if let (Some(i), Some(j)) = (index(&xs, x), index(&ys, y)) {
                by_cell.entry((i, j)).or_default().push(d.log10());
            }
        }
        let cells = by_cell
            .into_iter()
            .map(|((i, j), mut v)| (i, j, median(&mut v)))
            .collect();
        panels.push(Panel::Heat {
            caption: format!(
                "({}) median log10 drift norm over {xn} and {yn} (light: smallest, dark: largest)",
                next()
            ),
            x: (xn.clone(), xs),
            y: (yn.clone(), ys),
            cells,
        });
    }
    let logs: Vec<f64> = runs
        .iter()
        .filter_map(|r| drift(r).filter(|d| *d > 0.0))
        .map(f64::log10)
        .collect();
    let (lo, hi) = logs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, &v| {
            (a.0.min(v), a.1.max(v))
        });
    let bins = if logs.is_empty() {
        Vec::new()
    } else {
        let width = if hi > lo {
            (hi - lo) / BINS as f64
        } else {
            1.0
        };
        let mut counts = vec![0usize; BINS];
        for v in &logs {
            let k = (((v - lo) / width) as usize).min(BINS - 1);
            counts[k] += 1;
        }
        counts
            .into_iter()
            .enumerate()
            .map(|(k, c)| (lo + k as f64 * width, lo + (k + 1) as f64 * width, c))
            .collect()
    };
    panels.push(Panel::Histogram {
        caption: format!(
            "({}) distribution of the drift norm ({} completed runs)",
            next(),
            logs.len()
        ),
        bins,
    });
    let failed = runs.iter().filter(|r| !r.completed()).count();
    Figure {
        title: format!(
            "{experiment}: {} runs over {}{}",
            runs.len(),
            if params.is_empty() {
                "its variants".to_string()
            } else {
                params
                    .iter()
                    .map(|(n, _)| n.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            },
            if failed > 0 {
                format!(" ({failed} failed)")
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
    use spec::RunKey;
    use spec::SolverKind;

    /// `n` runs of one experiment sweeping mu (n / 100 values) and scale (100 values), every
    /// 97th failed.
    fn sweep(n: usize) -> Vec<RunRow> {
        (0..n)
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
            .collect()
    }

    #[test]
    fn parameters_are_read_back_from_generated_labels() {
        assert_eq!(
            parameters("ZNN (eq. 22) [mu=0.25, reverse=false]"),
            [
                ("mu".to_string(), "0.25".to_string()),
                ("reverse".to_string(), "false".to_string())
            ]
        );
        assert_eq!(parameters("MVN [reversed, a=0.1]").len(), 1);
        assert!(parameters("finite-time (kong2019 eq. 14)").is_empty());
        assert!(parameters("{phi} template").is_empty());
    }

    /// A merged 10^4-run sweep draws at most MAX_RUN_FIGURES run figures, its failures and
    /// extremes among them, and one sweep figure over its two parameters.
    #[test]
    fn a_large_sweep_draws_a_bounded_number_of_figures() {
        let rows = sweep(10_000);
        let runs: Vec<&RunRow> = rows.iter().collect();
        let chosen = drawn(&runs);
        assert_eq!(chosen.len(), MAX_RUN_FIGURES);
        assert!(
            chosen.windows(2).all(|w| w[0] < w[1]),
            "ascending, distinct"
        );
        assert!(chosen.contains(&5), "the first failure");
        let failures = chosen.iter().filter(|&&i| !runs[i].completed()).count();
        assert_eq!(failures, MAX_RUN_FIGURES / 4);
        for e in Extreme::ALL {
            let i = extreme(&runs, e).unwrap();
            assert!(chosen.contains(&i), "{e:?} {i}");
        }
        assert_eq!(drawn(&runs), chosen, "deterministic");
        // Small experiments draw every run.
        assert_eq!(drawn(&runs[..MAX_RUN_FIGURES]).len(), MAX_RUN_FIGURES);
        let params = numeric_parameters(&runs);
        let names: Vec<&str> = params.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["mu", "scale"]);
        let f = figure("big-sweep", &runs);
        // 2 scatter panels per parameter, the heat map and the distribution.
        assert_eq!(f.body.panels.len(), 2 * 2 + 2);
        assert!(f.title.contains("10000 runs over mu, scale"), "{}", f.title);
        assert!(f.title.contains("(104 failed)"), "{}", f.title);
        let svg = f.svg().unwrap();
        assert!(svg.contains("<svg"), "drawn");
    }
}
