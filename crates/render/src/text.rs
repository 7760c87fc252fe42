//! Text without system fonts: the public-domain 8x8 bitmap font of `font8x8` (basic Latin),
//! drawn at whole-number scales, and the number formats captions use.

use font8x8::legacy::BASIC_LEGACY;

/// Height and advance of one glyph at scale 1, in pixels.
pub const GLYPH: u32 = 8;

/// The glyph rows of `c` (bit 0 is the leftmost pixel); characters outside ASCII print as `?`.
fn glyph(c: char) -> [u8; 8] {
    let i = if c.is_ascii() {
        c as usize
    } else {
        '?' as usize
    };
    BASIC_LEGACY[i]
}

/// Width in pixels of `text` drawn at `scale`.
///
/// ```
/// assert_eq!(envelope_render::text::width("abc", 2), 48);
/// ```
#[must_use]
pub fn width(text: &str, scale: u32) -> u32 {
    let n = u32::try_from(text.chars().count()).unwrap_or(u32::MAX);
    n.saturating_mul(GLYPH * scale.max(1))
}

/// Calls `plot(x, y)` for every lit pixel of `text` at `scale`, relative to its top-left
/// corner.
pub(crate) fn pixels(text: &str, scale: u32, mut plot: impl FnMut(i64, i64)) {
    let s = i64::from(scale.max(1));
    for (k, c) in text.chars().enumerate() {
        let left = k as i64 * i64::from(GLYPH) * s;
        for (row, bits) in glyph(c).iter().enumerate() {
            for col in 0..8 {
                if bits >> col & 1 == 1 {
                    for dy in 0..s {
                        for dx in 0..s {
                            plot(left + col * s + dx, row as i64 * s + dy);
                        }
                    }
                }
            }
        }
    }
}

/// `n` with a comma between groups of three digits, as captions print face counts.
///
/// ```
/// use envelope_render::text::thousands;
/// assert_eq!(thousands(4032), "4,032");
/// assert_eq!(thousands(999), "999");
/// assert_eq!(thousands(1_234_567), "1,234,567");
/// ```
#[must_use]
pub fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// `x` with about three significant digits, trailing zeros dropped; an exponent outside
/// 1e-3..1e5 (for colour-bar and axis labels).
///
/// ```
/// use envelope_render::text::short;
/// assert_eq!(short(0.015625), "0.0156");
/// assert_eq!(short(1.0), "1");
/// assert_eq!(short(250.0), "250");
/// assert_eq!(short(1.5e-7), "1.50e-7");
/// assert_eq!(short(0.0), "0");
/// ```
#[must_use]
pub fn short(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || !a.is_finite() {
        return format!("{x}");
    }
    if !(1e-3..1e5).contains(&a) {
        return format!("{x:.2e}");
    }
    // Digits after the point so that three significant digits show.
    let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}
