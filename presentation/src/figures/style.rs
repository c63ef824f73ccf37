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

/// Twenty distinguishable colours (Tableau's "tab20", dark shades first): series k gets
/// `colour(k)`, so joint i or run k has the same colour in every panel of a figure.
const PALETTE: [RGBColor; 20] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(174, 199, 232),
    RGBColor(255, 187, 120),
    RGBColor(152, 223, 138),
    RGBColor(255, 152, 150),
    RGBColor(197, 176, 213),
    RGBColor(196, 156, 148),
    RGBColor(247, 182, 210),
    RGBColor(199, 199, 199),
    RGBColor(219, 219, 141),
    RGBColor(158, 218, 229),
];

/// The colour of series `k` (the palette repeats past twenty).
pub fn colour(k: usize) -> RGBColor {
    PALETTE[k % PALETTE.len()]
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
