//! Legends drawn beside the panels rather than over them: a strip whose entries flow left to
//! right and wrap (a run's joints), or a column with one entry per row (an experiment's runs).

use super::layout::{draw_error, Area};
use super::style::{font, LABEL_SIZE};
use crate::error::FigureError;
use plotters::prelude::*;

/// Length of an entry's line sample (px).
const SAMPLE: i32 = 24;
/// Gap between an entry's sample and its label, and between entries (px).
const GAP: i32 = 8;
/// Height of one legend row (px).
const ROW: i32 = 20;

/// One legend entry: what a line looks like and what it stands for.
pub struct Entry {
    pub style: ShapeStyle,
    pub label: String,
}

/// How entries are arranged.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Arrangement {
    /// Left to right, wrapping to a new row when the next entry would not fit.
    Strip,
    /// One entry per row.
    Column,
}

/// Draws `entries` into `area`; a label's further lines (after `\n`) go on rows of their own
/// under its first, and the next entry starts on a new row. Entries past the bottom of the
/// area are left out.
pub fn draw<DB: DrawingBackend>(
    area: &Area<DB>,
    entries: &[Entry],
    arrangement: Arrangement,
) -> Result<(), FigureError> {
    let px = |v: u32| i32::try_from(v).unwrap_or(i32::MAX);
    let (width, height) = area.dim_in_pixel();
    let (width, height) = (px(width), px(height));
    let style = font(LABEL_SIZE).into_text_style(area);
    let (mut x, mut y) = (GAP, GAP + ROW / 2);
    for entry in entries {
        let lines: Vec<&str> = entry.label.lines().collect();
        let extra_rows = i32::try_from(lines.len().saturating_sub(1)).unwrap_or(i32::MAX);
        let mut text_width = 0;
        for line in &lines {
            text_width = text_width.max(px(area
                .estimate_text_size(line, &style)
                .map_err(draw_error)?
                .0));
        }
        let span = SAMPLE + GAP + text_width;
        if x > GAP && (arrangement == Arrangement::Column || x + span > width) {
            (x, y) = (GAP, y + ROW);
        }
        if y + ROW * extra_rows + ROW / 2 > height {
            break;
        }
        area.draw(&PathElement::new(
            vec![(x, y), (x + SAMPLE, y)],
            entry.style,
        ))
        .map_err(draw_error)?;
        for (row, line) in (0..).zip(&lines) {
            let top = y + ROW * row
                - px(area.estimate_text_size(line, &style).map_err(draw_error)?.1) / 2;
            area.draw(&Text::new(*line, (x + SAMPLE + GAP, top), style.clone()))
                .map_err(draw_error)?;
        }
        x += span + 2 * GAP;
        if extra_rows > 0 {
            (x, y) = (width, y + ROW * extra_rows);
        }
    }
    Ok(())
}
