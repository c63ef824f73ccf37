//! The overview of one experiment as small multiples of at most [`MAX_SERIES`] series each:
//! one row per group of runs, the exact column's runs first, then the solvers'. A row draws
//! its runs' position error |r* - f(theta)| over time and, for scored solver runs, their
//! distance to the exact optimum |x - x*| beside it. A group larger than [`MAX_SERIES`] is
//! split by scheme, then into near-equal parts. Panels are lettered in drawing order; colours
//! restart in each row, and the legend column lists each row under its heading with short
//! labels: the variant for an exact run, "variant / solver" for a solver's.

use super::layout::{Area, Body, Figure};
use super::legend::{self, Arrangement, Entry};
use super::panels::{Series, TimePanel, YAxis};
use super::style::{colour, LEGEND_LINE_WIDTH};
use super::trace::Trace;
use crate::error::FigureError;
use plotters::prelude::*;
use records::RunRow;

/// Width of the legend column on the right (px).
const LEGEND_WIDTH: u32 = 360;
/// The most series one panel draws (every one in its own colour).
pub const MAX_SERIES: usize = 8;

/// Labels longer than this (characters) break after their " / ", so they fit the legend column.
const LONG_LABEL: usize = 44;

/// "variant / solver" of a solver's run, broken onto two lines when long.
fn solver_label(run: &RunRow) -> String {
    let label = format!("{} / {}", run.variant, run.solver);
    if label.chars().count() > LONG_LABEL {
        format!("{} /\n{}", run.variant, run.solver)
    } else {
        label
    }
}

/// `label`, with "failed at t = ... s" on a further line for a failed run.
fn with_failure(run: &RunRow, label: String) -> String {
    match run.failed_at {
        Some(t) => format!("{label}\n(failed at t = {t:.3} s)"),
        None => label,
    }
}

/// One row of the overview: its runs' position errors, and their scores where they were scored.
struct Row {
    errors: TimePanel,
    scores: Option<TimePanel>,
}

/// What an overview draws under its title: its rows stacked on the left, the legend column on
/// the right.
pub struct OverviewBody {
    entries: Vec<Entry>,
    rows: Vec<Row>,
}

impl Body for OverviewBody {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        let (width, _) = area.dim_in_pixel();
        let (plots, legend_area) = area.split_horizontally(width.saturating_sub(LEGEND_WIDTH));
        legend::draw(&legend_area, &self.entries, Arrangement::Column)?;
        let cells = plots.split_evenly((self.rows.len().max(1), 1));
        for (row, cell) in self.rows.iter().zip(&cells) {
            match &row.scores {
                Some(scores) => {
                    let (left, right) = cell.split_horizontally(cell.dim_in_pixel().0 / 2);
                    row.errors.draw(&left)?;
                    scores.draw(&right)?;
                }
                None => row.errors.draw(cell)?,
            }
        }
        Ok(())
    }
}

/// A heading row of the legend column: its label alone (the line sample is drawn in the
/// background colour).
fn heading(label: String) -> Entry {
    Entry {
        style: WHITE.stroke_width(1),
        label,
    }
}

type Member<'a, 'b> = &'b (&'a RunRow, &'a Trace);

/// `runs` in groups of at most [`MAX_SERIES`] (module docs), each with what sets it apart
/// (its scheme, and its part) when the runs had to be split; `scheme` names a run's scheme.
/// No runs, no group.
fn groups<T: Copy>(runs: Vec<T>, scheme: impl Fn(T) -> String) -> Vec<(String, Vec<T>)> {
    if runs.is_empty() {
        return Vec::new();
    }
    if runs.len() <= MAX_SERIES {
        return vec![(String::new(), runs)];
    }
    let mut by_scheme: Vec<(String, Vec<T>)> = Vec::new();
    for m in runs {
        let s = scheme(m);
        match by_scheme.iter_mut().find(|(name, _)| *name == s) {
            Some((_, members)) => members.push(m),
            None => by_scheme.push((s, vec![m])),
        }
    }
    let one_scheme = by_scheme.len() == 1;
    let mut out = Vec::new();
    for (scheme, members) in by_scheme {
        let parts = members.len().div_ceil(MAX_SERIES);
        let size = members.len().div_ceil(parts);
        for (i, chunk) in members.chunks(size).enumerate() {
            let mut what = if one_scheme {
                String::new()
            } else {
                format!(", {scheme}")
            };
            if parts > 1 {
                what.push_str(&format!(", part {} of {parts}", i + 1));
            }
            out.push((what, chunk.to_vec()));
        }
    }
    out
}

/// The experiment's figure; `runs` all belong to `experiment` (module docs).
pub fn figure(experiment: &str, runs: &[(&RunRow, &Trace)]) -> Figure<OverviewBody> {
    let t_end = runs.iter().map(|(run, _)| run.duration).fold(0.0, f64::max);
    let (exact, solvers): (Vec<Member>, Vec<Member>) =
        runs.iter().partition(|(run, _)| run.is_exact());
    let unit = if runs.iter().any(|(_, trace)| trace.thetaddot.is_some()) {
        "rad/s^2"
    } else {
        "rad/s"
    };
    // Each panel with its letter, in drawing order.
    let mut letters = 'a'..;
    let mut panel = |caption: String, y_desc: String, series: Vec<Series>| {
        let letter = letters.next().unwrap_or('?');
        let panel = TimePanel {
            caption: format!("({letter}) {caption}"),
            y_desc,
            y_axis: YAxis::Log,
            t_end,
            series,
        };
        (letter, panel)
    };
    let mut rows = Vec::new();
    let mut entries = Vec::new();
    for (group, is_exact) in [(exact, true), (solvers, false)] {
        let name = if is_exact { "exact column" } else { "solvers" };
        for (what, members) in groups(group, |m| m.0.scheme.clone()) {
            let (error_letter, errors) = panel(
                format!("{name}{what}: position error"),
                "error (m)".to_string(),
                (0..)
                    .zip(&members)
                    .map(|(k, (_, trace))| Series {
                        colour: colour(k),
                        points: trace.over_time(&trace.pos_err),
                    })
                    .collect(),
            );
            let scored = members.iter().any(|(_, trace)| trace.is_scored());
            let scores = scored.then(|| {
                panel(
                    format!("{name}{what}: |x - x*|"),
                    format!("|x - x*| ({unit})"),
                    (0..)
                        .zip(&members)
                        .map(|(k, (_, trace))| Series {
                            colour: colour(k),
                            points: trace.score_over_time(),
                        })
                        .collect(),
                )
            });
            let letters = match &scores {
                Some((score_letter, _)) => format!("({error_letter}), ({score_letter})"),
                None => format!("({error_letter})"),
            };
            let scores = scores.map(|(_, panel)| panel);
            entries.push(heading(format!("{letters} {name}{what}")));
            entries.extend((0..).zip(&members).map(|(k, (run, _))| Entry {
                style: colour(k).stroke_width(LEGEND_LINE_WIDTH),
                label: with_failure(
                    run,
                    if is_exact {
                        run.variant.clone()
                    } else {
                        solver_label(run)
                    },
                ),
            }));
            rows.push(Row { errors, scores });
        }
    }
    Figure {
        title: format!("{experiment}: overview of {} runs", runs.len()),
        body: OverviewBody { entries, rows },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_groups_split_by_scheme_then_into_near_equal_parts() {
        let named = |n: usize, schemes: usize| -> Vec<(usize, usize)> {
            (0..n).map(|k| (k, k % schemes)).collect()
        };
        let sizes = |g: &[(String, Vec<(usize, usize)>)]| -> Vec<usize> {
            g.iter().map(|(_, m)| m.len()).collect()
        };
        let scheme = |m: (usize, usize)| format!("S{}", m.1);
        assert!(groups(named(0, 1), scheme).is_empty());
        let small = groups(named(MAX_SERIES, 2), scheme);
        assert_eq!(sizes(&small), [MAX_SERIES]);
        assert_eq!(small[0].0, "");
        let by_scheme = groups(named(18, 3), scheme);
        assert_eq!(sizes(&by_scheme), [6, 6, 6]);
        assert_eq!(by_scheme[1].0, ", S1");
        let parts = groups(named(10, 1), scheme);
        assert_eq!(sizes(&parts), [5, 5]);
        assert_eq!(parts[1].0, ", part 2 of 2");
        let both = groups(named(20, 2), scheme);
        assert!(both.iter().all(|(_, m)| m.len() <= MAX_SERIES));
        assert_eq!(both.iter().map(|(_, m)| m.len()).sum::<usize>(), 20);
    }
}
