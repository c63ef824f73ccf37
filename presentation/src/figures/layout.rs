//! The canvas of a figure: a title strip over a body, drawn once against any plotters backend
//! and emitted twice, as SVG text and as PNG bytes.
//!
//! The body's drawing code is generic over [`DrawingBackend`] ([`Body`]), so the SVG and the PNG
//! come from the same calls. They differ only in text: the SVG leaves glyphs to the viewer and
//! lays text out with a crude per-character estimate ([`SvgText`]), the PNG rasterises the
//! embedded DejaVu Sans and lays text out with its real metrics.

use super::style::{font, register_font, CANVAS, TITLE_HEIGHT, TITLE_SIZE};
use crate::error::FigureError;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind,
};

/// A region of a figure that a panel, a title or a legend draws into, on backend `DB`.
pub type Area<DB> = DrawingArea<DB, Shift>;

/// Turns a plotters error (generic over the backend) into the module's error type.
pub fn draw_error(e: impl std::fmt::Display) -> FigureError {
    FigureError::Draw(e.to_string())
}

/// What a figure draws under its title, on any backend.
pub trait Body {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError>;
}

/// A figure of [`CANVAS`] size: `title` centred at the top, `body` filling the rest.
pub struct Figure<B> {
    pub title: String,
    pub body: B,
}

/// A figure rendered both ways.
pub struct Rendered {
    pub svg: String,
    pub png: Vec<u8>,
}

impl<B: Body> Figure<B> {
    /// The figure as SVG text and as PNG bytes.
    pub fn render(&self) -> Result<Rendered, FigureError> {
        Ok(Rendered {
            svg: self.svg()?,
            png: self.png()?,
        })
    }

    /// The SVG text.
    pub fn svg(&self) -> Result<String, FigureError> {
        let mut svg = String::new();
        {
            let canvas = SvgText(SVGBackend::with_string(&mut svg, CANVAS)).into_drawing_area();
            self.draw(&canvas)?;
        }
        Ok(svg)
    }

    /// The PNG bytes: 8-bit RGB, the text in the embedded font.
    pub fn png(&self) -> Result<Vec<u8>, FigureError> {
        let (width, height) = CANVAS;
        let mut rgb = vec![0u8; 3 * width as usize * height as usize];
        {
            let canvas = BitMapBackend::with_buffer(&mut rgb, CANVAS).into_drawing_area();
            self.draw(&canvas)?;
        }
        encode_png(&rgb, CANVAS)
    }

    /// Draws the white background, the title and the body on `canvas`, then presents it.
    fn draw<DB: DrawingBackend>(&self, canvas: &Area<DB>) -> Result<(), FigureError> {
        register_font()?;
        canvas.fill(&WHITE).map_err(draw_error)?;
        let (strip, rest) = canvas.split_vertically(TITLE_HEIGHT);
        let centre = (
            i32::try_from(CANVAS.0 / 2).unwrap_or(0),
            i32::try_from(TITLE_HEIGHT / 2).unwrap_or(0),
        );
        let style = font(TITLE_SIZE)
            .into_text_style(&strip)
            .pos(Pos::new(HPos::Center, VPos::Center));
        strip
            .draw_text(&self.title, &style, centre)
            .map_err(draw_error)?;
        self.body.draw(&rest)?;
        canvas.present().map_err(draw_error)
    }
}

/// Encodes an RGB buffer of `size` pixels as 8-bit RGB PNG (the default deflate level: the best
/// level took three times as long for files of about the same size; a palette does not fit, as
/// the anti-aliased lines and text give nearly every figure more than 256 colours). No timestamp
/// or other metadata, so equal pixels give equal bytes.
fn encode_png(rgb: &[u8], (width, height): (u32, u32)) -> Result<Vec<u8>, FigureError> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Default);
        encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(rgb)?;
        writer.finish()?;
    }
    Ok(bytes)
}

/// The SVG backend with the text metric the figures were laid out with before the PNGs came:
/// plotters' font-less estimate (an em of `size / 1.24^2`, 0.7 em a byte), so that the SVGs stay
/// byte-identical now that plotters measures text with the embedded font (the `ab_glyph`
/// feature replaces that estimate for every backend). An SVG viewer draws the text in its own
/// font anyway; every other call goes to the SVG backend unchanged.
struct SvgText<'a>(SVGBackend<'a>);

impl DrawingBackend for SvgText<'_> {
    type ErrorType = <SVGBackend<'static> as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.present()
    }

    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_pixel(point, color)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_rect(upper_left, bottom_right, style, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_path(path, style)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_circle(center, radius, style, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.fill_polygon(vert, style)
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_text(text, style, pos)
    }

    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        Ok(naive_text_size(style.size(), text))
    }

    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.blit_bitmap(pos, size, src)
    }
}

/// Width and height (px) of `text` at font size `size` by plotters' font-less estimate
/// (plotters 0.3.7, `style/font/naive.rs`): the layout box from (0, -em) to
/// (0.7 em x bytes, 0.24 em), each end rounded.
fn naive_text_size(size: f64, text: &str) -> (u32, u32) {
    let em = size / 1.24 / 1.24;
    let round = |v: f64| v.round() as i32;
    let (top, bottom) = (-round(em), round(em * 0.24));
    let width = round(em * 0.7 * text.len() as f64);
    (width.unsigned_abs(), (bottom - top).unsigned_abs())
}

#[cfg(test)]
mod tests {
    use super::naive_text_size;

    #[test]
    fn the_svg_text_metric_is_plotters_font_less_estimate() {
        // size 13: em = 8.455, box (0, -8) .. (59, 2) for ten bytes.
        assert_eq!(naive_text_size(13.0, "0123456789"), (59, 10));
        assert_eq!(naive_text_size(22.0, ""), (0, 17));
    }
}
