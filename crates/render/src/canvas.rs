//! An RGB picture in memory, its size limits, and its PNG encoding.

use crate::error::RenderError;
use crate::limits::{MAX_SIDE, MIN_SIDE};
use crate::text;

/// A picture's width and height, each in `MIN_SIDE..=MAX_SIDE`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Size {
    width: u32,
    height: u32,
}

impl Size {
    /// A size, refused unless each side is in `MIN_SIDE..=MAX_SIDE`.
    ///
    /// ```
    /// use envelope_render::Size;
    /// let s = Size::new(640, 480).unwrap();
    /// assert_eq!((s.width(), s.height()), (640, 480));
    /// assert!(Size::new(640, 9000).is_err());
    /// ```
    pub fn new(width: u32, height: u32) -> Result<Size, RenderError> {
        let ok = |s: u32| (MIN_SIDE..=MAX_SIDE).contains(&s);
        if ok(width) && ok(height) {
            Ok(Size { width, height })
        } else {
            Err(RenderError::Size { width, height })
        }
    }

    /// Width in pixels.
    #[must_use]
    pub fn width(self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[must_use]
    pub fn height(self) -> u32 {
        self.height
    }
}

/// An RGB picture, row by row from the top-left corner.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Canvas {
    width: u32,
    height: u32,
    pixels: Vec<[u8; 3]>,
}

impl Canvas {
    /// A picture of `size` filled with `background`.
    ///
    /// ```
    /// use envelope_render::{Canvas, Size};
    /// let c = Canvas::new(Size::new(16, 16).unwrap(), [255, 255, 255]);
    /// assert_eq!(c.pixel(3, 4), Some([255, 255, 255]));
    /// assert_eq!(c.pixel(16, 0), None);
    /// ```
    #[must_use]
    pub fn new(size: Size, background: [u8; 3]) -> Canvas {
        Canvas::blank(size.width, size.height, background)
    }

    /// Any size, for the crate's own buffers (sizes checked by the callers).
    pub(crate) fn blank(width: u32, height: u32, background: [u8; 3]) -> Canvas {
        Canvas {
            width,
            height,
            pixels: vec![background; width as usize * height as usize],
        }
    }

    /// Width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The colour at `(x, y)`, `None` outside the picture.
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        (x < self.width && y < self.height)
            .then(|| self.pixels[y as usize * self.width as usize + x as usize])
    }

    /// Mixes `color` into `(x, y)` with weight `alpha` in `0..=1`; outside the picture,
    /// nothing.
    pub(crate) fn blend(&mut self, x: i64, y: i64, color: [u8; 3], alpha: f64) {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return;
        }
        let p = &mut self.pixels[y as usize * self.width as usize + x as usize];
        let a = alpha.clamp(0.0, 1.0);
        for k in 0..3 {
            let v = f64::from(p[k]) + a * (f64::from(color[k]) - f64::from(p[k]));
            p[k] = v.round() as u8;
        }
    }

    /// Sets `(x, y)`; outside the picture, nothing.
    pub(crate) fn set(&mut self, x: i64, y: i64, color: [u8; 3]) {
        self.blend(x, y, color, 1.0);
    }

    /// Fills the rectangle with top-left `(x, y)` and the given size, clipped.
    pub(crate) fn fill_rect(&mut self, x: i64, y: i64, w: i64, h: i64, color: [u8; 3]) {
        for yy in y.max(0)..(y + h).min(i64::from(self.height)) {
            for xx in x.max(0)..(x + w).min(i64::from(self.width)) {
                self.set(xx, yy, color);
            }
        }
    }

    /// Draws `text` with its top-left corner at `(x, y)` in the 8x8 bitmap font at `scale`,
    /// clipped to the picture.
    ///
    /// ```
    /// use envelope_render::{Canvas, Size};
    /// let mut c = Canvas::new(Size::new(64, 16).unwrap(), [255, 255, 255]);
    /// c.text(0, 0, "#", 1, [0, 0, 0]);
    /// assert!((0..8).any(|x| (0..8).any(|y| c.pixel(x, y) == Some([0, 0, 0]))));
    /// ```
    pub fn text(&mut self, x: i64, y: i64, text: &str, scale: u32, color: [u8; 3]) {
        text::pixels(text, scale, |dx, dy| self.set(x + dx, y + dy, color));
    }

    /// Copies `other` with its top-left corner at `(x, y)`, clipped.
    pub(crate) fn blit(&mut self, other: &Canvas, x: i64, y: i64) {
        for oy in 0..other.height {
            for ox in 0..other.width {
                let c = other.pixels[oy as usize * other.width as usize + ox as usize];
                self.set(x + i64::from(ox), y + i64::from(oy), c);
            }
        }
    }

    /// The picture as PNG bytes: 8-bit RGB, no ancillary chunks (no time, no text), so the
    /// same picture always gives the same bytes.
    ///
    /// ```
    /// use envelope_render::{Canvas, Size};
    /// let png = Canvas::new(Size::new(20, 30).unwrap(), [9, 9, 9]).to_png().unwrap();
    /// assert_eq!(&png[1..4], b"PNG");
    /// ```
    pub fn to_png(&self) -> Result<Vec<u8>, RenderError> {
        let fail = |e: png::EncodingError| RenderError::Png(e.to_string());
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::High);
        let mut writer = encoder.write_header().map_err(fail)?;
        let bytes: Vec<u8> = self.pixels.iter().flatten().copied().collect();
        writer.write_image_data(&bytes).map_err(fail)?;
        writer.finish().map_err(fail)?;
        Ok(out)
    }
}
