//! The canvas of a figure: an in-memory SVG with its title strip.

use super::style::{font, CANVAS, TITLE_HEIGHT, TITLE_SIZE};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// A region of an SVG figure that a panel, a title or a legend draws into.
pub type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// Turns a plotters error into the module's error type.
pub fn draw_error(e: impl std::fmt::Display) -> String {
    format!("drawing an SVG: {e}")
}

/// Draws a figure of [`CANVAS`] size on a white background with `title` centred at the top and
/// `body` filling the rest; returns the SVG text.
pub fn figure(
    title: &str,
    body: impl FnOnce(&Area) -> Result<(), String>,
) -> Result<String, String> {
    let mut svg = String::new();
    {
        let canvas = SVGBackend::with_string(&mut svg, CANVAS).into_drawing_area();
        canvas.fill(&WHITE).map_err(draw_error)?;
        let (strip, rest) = canvas.split_vertically(TITLE_HEIGHT);
        let centre = (
            i32::try_from(CANVAS.0 / 2).unwrap_or(0),
            i32::try_from(TITLE_HEIGHT / 2).unwrap_or(0),
        );
        let style = font(TITLE_SIZE)
            .into_text_style(&strip)
            .pos(Pos::new(HPos::Center, VPos::Center));
        strip.draw_text(title, &style, centre).map_err(draw_error)?;
        body(&rest)?;
        canvas.present().map_err(draw_error)?;
    }
    Ok(svg)
}
