//! The figures' look: canvas sizes, fonts, line widths and the colour cycle.

use crate::error::FigureError;
use plotters::style::{FontDesc, FontFamily, FontStyle, RGBColor};
use std::sync::OnceLock;

/// DejaVu Sans (see `presentation/assets/DejaVuSans-LICENSE.txt`), embedded so that the PNGs'
/// text needs no system font.
static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Size of every figure (px).
pub const CANVAS: (u32, u32) = (1200, 900);
/// Height of the title strip at the top of a figure (px).
pub const TITLE_HEIGHT: u32 = 44;
/// Font size of a figure's title.
pub const TITLE_SIZE: f64 = 22.0;
/// Font size of a panel's caption.
pub const CAPTION_SIZE: f64 = 16.0;
/// Font size of axis descriptions, tick labels and legend entries.
pub const LABEL_SIZE: f64 = 13.0;
/// Width of a plotted series (px).
pub const LINE_WIDTH: u32 = 1;
/// Width of a line sample in a legend, wider than the series so that its colour reads (px).
pub const LEGEND_LINE_WIDTH: u32 = 2;
/// Width of the desired path, drawn under the actual one so that both stay visible (px).
pub const DESIRED_WIDTH: u32 = 6;
/// Colour of the desired path.
pub const DESIRED_COLOUR: RGBColor = RGBColor(190, 190, 190);
/// Colour of the arm's poses over time in the path panel, lighter than the desired path.
pub const ARM_COLOUR: RGBColor = RGBColor(200, 200, 200);
/// Colour of the arm's start pose in the path panel.
pub const ARM_START_COLOUR: RGBColor = RGBColor(110, 110, 110);
/// Colour of the grid lines.
pub const GRID_COLOUR: RGBColor = RGBColor(225, 225, 225);

/// Paul Tol's "muted" qualitative scheme: nine colours told apart with every common colour
/// vision deficiency and in greyscale print. Series k gets `colour(k)`, so joint i or run k has
/// the same colour in every panel of a figure; a figure draws at most nine series per group
/// (the overview's small multiples), so the cycle repeats only past that.
const PALETTE: [RGBColor; 9] = [
    RGBColor(51, 34, 136),
    RGBColor(136, 204, 238),
    RGBColor(68, 170, 153),
    RGBColor(17, 119, 51),
    RGBColor(153, 153, 51),
    RGBColor(221, 204, 119),
    RGBColor(204, 102, 119),
    RGBColor(136, 34, 85),
    RGBColor(170, 68, 153),
];

/// The colour of series `k` (the palette repeats past nine).
pub fn colour(k: usize) -> RGBColor {
    PALETTE[k % PALETTE.len()]
}

/// A light shade of `c` (halfway to white): the same hue for a second variant of a series
/// (the cost figures draw a quantity on faer in the light shade of its nalgebra colour).
pub fn light(c: RGBColor) -> RGBColor {
    let half = |v: u8| u8::try_from((u16::from(v) + 255) / 2).unwrap_or(u8::MAX);
    RGBColor(half(c.0), half(c.1), half(c.2))
}

/// Registers the embedded font as plotters' `sans-serif` (once a process; later calls return
/// the first outcome). Must run before [`font`] builds a font description, since plotters
/// resolves the family when the description is made.
pub fn register_font() -> Result<(), FigureError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FontFamily::SansSerif.as_str(), FontStyle::Normal, FONT)
            .is_ok()
    });
    ok.then_some(()).ok_or(FigureError::Font)
}

/// A sans-serif font of the given size: the embedded DejaVu Sans in a PNG, the viewer's
/// sans-serif in an SVG (which names the family and leaves the glyphs to the viewer).
pub fn font(size: f64) -> FontDesc<'static> {
    FontDesc::new(FontFamily::SansSerif, size, FontStyle::Normal)
}
