//! Colour ramps: scalar values to colours, shared by error maps (`envelope verify --map`) and
//! renders.

/// Matplotlib's *viridis* at eight evenly spaced stops (`0, 1/7, ..., 1`), as sRGB bytes;
/// [`viridis`] interpolates linearly between them (perceptually uniform enough for a map, and
/// monotone in lightness).
const VIRIDIS: [[u8; 3]; 8] = [
    [0x44, 0x01, 0x54],
    [0x46, 0x32, 0x7e],
    [0x36, 0x5c, 0x8d],
    [0x27, 0x7f, 0x8e],
    [0x1f, 0xa1, 0x87],
    [0x4a, 0xc1, 0x6d],
    [0xa0, 0xda, 0x39],
    [0xfd, 0xe7, 0x25],
];

/// The viridis colour of `t` in `0..=1` (clamped; NaN gives the low end), as sRGB bytes.
///
/// ```
/// use envelope_render::ramp::viridis;
/// assert_eq!(viridis(0.0), [0x44, 0x01, 0x54]);
/// assert_eq!(viridis(1.0), [0xfd, 0xe7, 0x25]);
/// assert_eq!(viridis(f64::NAN), viridis(0.0));
/// ```
#[must_use]
pub fn viridis(t: f64) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (VIRIDIS.len() - 1) as f64;
    let i = (x.floor() as usize).min(VIRIDIS.len() - 2);
    let f = x - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    std::array::from_fn(|k| {
        let v = f64::from(a[k]) + f * (f64::from(b[k]) - f64::from(a[k]));
        v.round().clamp(0.0, 255.0) as u8
    })
}

/// Where `value` falls in `lo..=hi`, in `0..=1` (0 when the range is empty or not finite).
///
/// ```
/// use envelope_render::ramp::normalize;
/// assert_eq!(normalize(1.5, 1.0, 2.0), 0.5);
/// assert_eq!(normalize(3.0, 2.0, 2.0), 0.0);
/// ```
#[must_use]
pub fn normalize(value: f64, lo: f64, hi: f64) -> f64 {
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) {
        return 0.0;
    }
    ((value - lo) / span).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stops_are_hit_and_lightness_rises() {
        for (i, stop) in VIRIDIS.iter().enumerate() {
            assert_eq!(viridis(i as f64 / 7.0), *stop);
        }
        // Luma rises along the ramp, so a larger error always reads lighter.
        let luma = |c: [u8; 3]| {
            0.299 * f64::from(c[0]) + 0.587 * f64::from(c[1]) + 0.114 * f64::from(c[2])
        };
        let mut last = -1.0;
        for k in 0..=100 {
            let l = luma(viridis(f64::from(k) / 100.0));
            assert!(l > last, "luma falls at {k}");
            last = l;
        }
    }
}
