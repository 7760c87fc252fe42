//! The coordinate range in which the adaptive (Shewchuk) predicates are exact.
//!
//! Every finite double with magnitude in `[2^-120, 2^120]` is an integer multiple of `2^-172`, so
//! every term of a degree-`k` predicate expansion (insphere: `k = 5`) is a multiple of
//! `2^(-172 k) >= 2^-860`, far above the subnormal range, and bounded by about `2^(121 k + 10)
//! <= 2^615`, far below overflow. No intermediate product of the expansion arithmetic can
//! underflow or overflow, which is the only condition under which Shewchuk's predicates are exact.
//! Inputs outside the range are still answered exactly by the filtered kernel: it falls back to
//! the exact kernel. The same two constants bound input coordinates in `envelope-mesh`.

/// Largest coordinate magnitude for which the fast adaptive path is used: `2^120` (about 1.3e36).
pub const MAX_ALLOWED_MAGNITUDE: f64 = 1.329_227_995_784_916e36;
/// Smallest non-zero coordinate magnitude for which the fast adaptive path is used: `2^-120`
/// (about 7.5e-37). Zero is in range.
pub const MIN_ALLOWED_MAGNITUDE: f64 = 7.523_163_845_262_64e-37;

/// True when `x` is zero or its magnitude is in `[MIN_ALLOWED_MAGNITUDE, MAX_ALLOWED_MAGNITUDE]`.
/// NaN and infinities are out of range.
///
/// ```
/// use envelope_predicates::in_exact_range;
/// assert!(in_exact_range(0.0) && in_exact_range(-3.5) && in_exact_range(2f64.powi(120)));
/// assert!(!in_exact_range(5e-324) && !in_exact_range(1e37) && !in_exact_range(f64::NAN));
/// ```
#[inline]
#[must_use]
pub fn in_exact_range(x: f64) -> bool {
    let m = x.abs();
    m <= MAX_ALLOWED_MAGNITUDE && (m >= MIN_ALLOWED_MAGNITUDE || m == 0.0)
}

/// True when every coordinate of every point is [`in_exact_range`].
#[inline]
pub(crate) fn all_in_range(points: &[glam::DVec3]) -> bool {
    points
        .iter()
        .all(|p| in_exact_range(p.x) && in_exact_range(p.y) && in_exact_range(p.z))
}

/// Rounds up to the next representable double (identity on `+inf` and NaN).
#[must_use]
pub fn next_up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let b = x.to_bits();
    f64::from_bits(if x > 0.0 { b + 1 } else { b - 1 })
}

/// Rounds down to the previous representable double (identity on `-inf` and NaN).
#[must_use]
pub fn next_down(x: f64) -> f64 {
    -next_up(-x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_are_powers_of_two() {
        assert_eq!(MAX_ALLOWED_MAGNITUDE, 2f64.powi(120));
        assert_eq!(MIN_ALLOWED_MAGNITUDE, 2f64.powi(-120));
    }

    #[test]
    fn next_up_down() {
        assert_eq!(next_up(1.0), 1.0 + f64::EPSILON);
        assert_eq!(next_down(1.0), 1.0 - f64::EPSILON / 2.0);
        assert_eq!(next_up(0.0), 5e-324);
        assert_eq!(next_down(0.0), -5e-324);
        assert_eq!(next_up(-5e-324), -0.0);
        assert_eq!(next_up(f64::MAX), f64::INFINITY);
    }
}
