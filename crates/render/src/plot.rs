//! Faces against epsilon: one line with markers per named series, both axes logarithmic,
//! drawn by `plotters` as SVG (text as `<text>`) or as PNG on this crate's canvas (text in
//! its bitmap font, so no font library is needed).

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontTransform,
};

use crate::canvas::{Canvas, Size};
use crate::error::RenderError;
use crate::text::{self, GLYPH};

/// One named line of the plot: points `(epsilon as % of the bounding-box diagonal, faces)`.
/// Points with a value that is not positive and finite cannot be on a log axis and are left
/// out.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The legend entry (a model, a tool, or both).
    pub name: String,
    /// `(epsilon %, faces)` pairs, drawn in this order.
    pub points: Vec<(f64, f64)>,
}

/// Series colours (colour-blind safe, after Okabe and Ito), reused in turn.
const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
];

/// The plot as an SVG document.
///
/// ```
/// use envelope_render::plot::{Series, faces_vs_epsilon_svg};
/// use envelope_render::Size;
/// let cup = Series { name: "cup".into(), points: vec![(0.1, 900.0), (1.0, 200.0)] };
/// let svg = faces_vs_epsilon_svg("cup", &[cup], Size::new(640, 400)?)?;
/// assert!(svg.starts_with("<svg") && svg.contains("cup"));
/// # Ok::<(), envelope_render::RenderError>(())
/// ```
pub fn faces_vs_epsilon_svg(
    title: &str,
    series: &[Series],
    size: Size,
) -> Result<String, RenderError> {
    let mut out = String::new();
    {
        let backend = SVGBackend::with_string(&mut out, (size.width(), size.height()));
        draw(backend.into_drawing_area(), title, series, SVG_FONTS)?;
    }
    Ok(out)
}

/// The plot as PNG bytes.
///
/// ```
/// use envelope_render::plot::{Series, faces_vs_epsilon_png};
/// use envelope_render::Size;
/// let cup = Series { name: "cup".into(), points: vec![(0.1, 900.0), (1.0, 200.0)] };
/// let png = faces_vs_epsilon_png("cup", &[cup], Size::new(640, 400)?)?;
/// assert_eq!(&png[1..4], b"PNG");
/// # Ok::<(), envelope_render::RenderError>(())
/// ```
pub fn faces_vs_epsilon_png(
    title: &str,
    series: &[Series],
    size: Size,
) -> Result<Vec<u8>, RenderError> {
    let mut canvas = Canvas::new(size, [255, 255, 255]);
    draw(
        CanvasBackend {
            canvas: &mut canvas,
        }
        .into_drawing_area(),
        title,
        series,
        BITMAP_FONTS,
    )?;
    canvas.to_png()
}

/// Font sizes in pixels: `(labels, title)`.
type Fonts = (f64, f64);
/// Real fonts in an SVG viewer.
const SVG_FONTS: Fonts = (13.0, 22.0);
/// For the bitmap font: `plotters` sizes boxes (legend, margins) by its own estimate, about
/// 0.45 em per character; at these sizes that matches the font's 8 pixels at scales 1 and 2.
const BITMAP_FONTS: Fonts = (18.0, 36.0);

/// The points of `s` a log axis can show.
fn usable(s: &Series) -> Vec<(f64, f64)> {
    let ok = |v: f64| v.is_finite() && v > 0.0;
    s.points
        .iter()
        .copied()
        .filter(|&(x, y)| ok(x) && ok(y))
        .collect()
}

/// A log axis range around `values`: from a power of ten (`plotters` labels a log axis only
/// from its first power of ten on) to a little above the largest (0.1..10 when there is no
/// value).
fn axis(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo > hi {
        return 0.1..10.0;
    }
    // Just below the power of ten, so that rounding in powf cannot skip its label.
    0.999 * 10f64.powf((lo / 1.2).log10().floor())..hi * 1.6
}

/// An axis tick: about three significant digits.
fn tick(v: &f64) -> String {
    text::short(*v)
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    series: &[Series],
    (label, heading): Fonts,
) -> Result<(), RenderError> {
    let fail = |e: DrawingAreaErrorKind<DB::ErrorType>| RenderError::Plot(e.to_string());
    root.fill(&WHITE).map_err(fail)?;
    let points: Vec<Vec<(f64, f64)>> = series.iter().map(usable).collect();
    let xs = axis(points.iter().flatten().map(|p| p.0));
    let ys = axis(points.iter().flatten().map(|p| p.1));
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", heading))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(72)
        .build_cartesian_2d(xs.log_scale(), ys.log_scale())
        .map_err(fail)?;
    chart
        .configure_mesh()
        .x_desc("epsilon (% of the bounding-box diagonal)")
        .y_desc("faces")
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .x_labels(12)
        .y_labels(12)
        .label_style(("sans-serif", label))
        .axis_desc_style(("sans-serif", label))
        .light_line_style(RGBColor(240, 240, 240))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()
        .map_err(fail)?;
    for (i, (s, pts)) in series.iter().zip(&points).enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        chart
            .draw_series(LineSeries::new(
                pts.iter().copied(),
                Color::stroke_width(&color, 2),
            ))
            .map_err(fail)?
            .label(s.name.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], Color::stroke_width(&color, 2))
            });
        // A different marker per series, so lines read apart without colour too.
        let it = pts.iter().copied();
        match i % 3 {
            0 => chart.draw_series(it.map(|p| Circle::new(p, 4, color.filled()))),
            1 => chart.draw_series(it.map(|p| TriangleMarker::new(p, 5, color.filled()))),
            _ => chart.draw_series(it.map(|p| Cross::new(p, 4, Color::stroke_width(&color, 2)))),
        }
        .map_err(fail)?;
    }
    if !series.is_empty() {
        chart
            .configure_series_labels()
            .label_font(("sans-serif", label))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(180, 180, 180))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(fail)?;
    }
    root.present().map_err(fail)
}

/// `plotters` drawing on a [`Canvas`], with text in the bitmap font.
struct CanvasBackend<'a> {
    canvas: &'a mut Canvas,
}

/// The bitmap font's scale for a `plotters` font size in pixels (see [`BITMAP_FONTS`]).
fn font_scale(size: f64) -> u32 {
    ((size / 18.0).round() as u32).max(1)
}

impl DrawingBackend for CanvasBackend<'_> {
    type ErrorType = std::convert::Infallible;

    fn get_size(&self) -> (u32, u32) {
        (self.canvas.width(), self.canvas.height())
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        Ok(())
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        Ok(())
    }

    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let (r, g, b) = color.rgb;
        self.canvas.blend(
            i64::from(point.0),
            i64::from(point.1),
            [r, g, b],
            color.alpha,
        );
        Ok(())
    }

    fn estimate_text_size<TStyle: BackendTextStyle>(
        &self,
        text: &str,
        style: &TStyle,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        let s = font_scale(style.size());
        Ok((text::width(text, s), GLYPH * s))
    }

    fn draw_text<TStyle: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &TStyle,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let s = font_scale(style.size());
        let (w, h) = (i64::from(text::width(text, s)), i64::from(GLYPH * s));
        let anchor = style.anchor();
        let dx = match anchor.h_pos {
            HPos::Left => 0,
            HPos::Right => -w,
            HPos::Center => -w / 2,
        };
        let dy = match anchor.v_pos {
            VPos::Top => 0,
            VPos::Center => -h / 2,
            VPos::Bottom => -h,
        };
        let c = style.color();
        let (r, g, b) = c.rgb;
        let transform = style.transform();
        let (px, py) = (i64::from(pos.0), i64::from(pos.1));
        text::pixels(text, s, |x, y| {
            let (x, y) = (x + dx, y + dy);
            // Clockwise rotations, as `plotters` defines them.
            let (x, y) = match transform {
                FontTransform::None => (x, y),
                FontTransform::Rotate90 => (-y, x),
                FontTransform::Rotate180 => (-x, -y),
                FontTransform::Rotate270 => (y, -x),
            };
            self.canvas.blend(px + x, py + y, [r, g, b], c.alpha);
        });
        Ok(())
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        plotters_backend::rasterizer::draw_line(self, from, to, style)
    }
}
