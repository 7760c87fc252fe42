//! The coordinate range the exact predicates can handle, checked once at the boundary.
//!
//! Shewchuk's adaptive predicates are exact only while no intermediate product overflows or
//! underflows. The degree-5 `insphere` determinant is the tightest case in 3-D; keeping every
//! non-zero coordinate magnitude in `[MIN_ALLOWED_MAGNITUDE, MAX_ALLOWED_MAGNITUDE]` keeps all
//! intermediate terms (including the expansion tails) inside f64's normal range. The same
//! constants are mirrored in `envelope-predicates` (a test checks that they agree).

use glam::DVec3;
use thiserror::Error;

/// Largest accepted coordinate magnitude: 2^120 (about 1.3e36).
pub const MAX_ALLOWED_MAGNITUDE: f64 = 1.329_227_995_784_916e36;
/// Smallest accepted non-zero coordinate magnitude: 2^-120 (about 7.5e-37). Zero is accepted.
pub const MIN_ALLOWED_MAGNITUDE: f64 = 7.523_163_845_262_64e-37;

/// Why a coordinate value was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
pub enum CoordError {
    /// Not a number.
    #[error("coordinate is NaN")]
    NaN,
    /// Positive or negative infinity.
    #[error("coordinate is infinite")]
    Infinite,
    /// Magnitude above [`MAX_ALLOWED_MAGNITUDE`].
    #[error("coordinate magnitude is above 2^120, outside the exact predicates' range")]
    TooLarge,
    /// Non-zero magnitude below [`MIN_ALLOWED_MAGNITUDE`] (subnormals included).
    #[error("non-zero coordinate magnitude is below 2^-120, outside the exact predicates' range")]
    TooSmall,
}

/// Checks one coordinate value.
///
/// ```
/// use envelope_mesh::{check_coordinate, CoordError};
/// assert_eq!(check_coordinate(1.5), Ok(()));
/// assert_eq!(check_coordinate(0.0), Ok(()));
/// assert_eq!(check_coordinate(f64::NAN), Err(CoordError::NaN));
/// assert_eq!(check_coordinate(5e-324), Err(CoordError::TooSmall));
/// ```
pub fn check_coordinate(x: f64) -> Result<(), CoordError> {
    if x.is_nan() {
        return Err(CoordError::NaN);
    }
    if x.is_infinite() {
        return Err(CoordError::Infinite);
    }
    let m = x.abs();
    if m > MAX_ALLOWED_MAGNITUDE {
        Err(CoordError::TooLarge)
    } else if m != 0.0 && m < MIN_ALLOWED_MAGNITUDE {
        Err(CoordError::TooSmall)
    } else {
        Ok(())
    }
}

/// A constructed point moved into the exact predicates' range: each coordinate whose non-zero
/// magnitude is below [`MIN_ALLOWED_MAGNITUDE`] becomes zero, the others are kept. For
/// constructions only (offsets, tubes): they are plain f64 approximations anyway, and only the
/// exact proof run on the flushed point counts. Never applied to input coordinates.
///
/// ```
/// use envelope_mesh::flush_tiny;
/// use glam::DVec3;
/// assert_eq!(flush_tiny(DVec3::new(1e-40, -2.0, -1e-300)), DVec3::new(0.0, -2.0, 0.0));
/// ```
#[must_use]
pub fn flush_tiny(p: DVec3) -> DVec3 {
    let f = |x: f64| {
        if x.abs() < MIN_ALLOWED_MAGNITUDE {
            0.0
        } else {
            x
        }
    };
    DVec3::new(f(p.x), f(p.y), f(p.z))
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
    fn range_edges() {
        assert_eq!(check_coordinate(MAX_ALLOWED_MAGNITUDE), Ok(()));
        assert_eq!(check_coordinate(-MIN_ALLOWED_MAGNITUDE), Ok(()));
        assert_eq!(
            check_coordinate(MAX_ALLOWED_MAGNITUDE * 2.0),
            Err(CoordError::TooLarge)
        );
        assert_eq!(
            check_coordinate(MIN_ALLOWED_MAGNITUDE / 2.0),
            Err(CoordError::TooSmall)
        );
        assert_eq!(
            check_coordinate(f64::NEG_INFINITY),
            Err(CoordError::Infinite)
        );
        assert_eq!(check_coordinate(-0.0), Ok(()));
    }
}
