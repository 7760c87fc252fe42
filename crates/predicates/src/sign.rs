//! The answers predicates give: [`Sign`] and [`Orientation`]. No caller compares a float with 0.

/// The exact sign of a real number (a determinant, a difference of squared distances, ...).
///
/// Ordered `Negative < Zero < Positive`, so `min`/`max` over signs behave like over the numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Sign {
    /// The value is < 0.
    Negative,
    /// The value is exactly 0.
    Zero,
    /// The value is > 0.
    Positive,
}

impl Sign {
    /// The sign of `-x` given the sign of `x`.
    #[must_use]
    pub fn reverse(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }

    /// The sign of an [`Ordering`](std::cmp::Ordering) of `x` against 0.
    #[must_use]
    pub fn from_ordering(o: std::cmp::Ordering) -> Sign {
        match o {
            std::cmp::Ordering::Less => Sign::Negative,
            std::cmp::Ordering::Equal => Sign::Zero,
            std::cmp::Ordering::Greater => Sign::Positive,
        }
    }

    /// `x` compared with 0, as an [`Ordering`](std::cmp::Ordering).
    #[must_use]
    pub fn to_ordering(self) -> std::cmp::Ordering {
        match self {
            Sign::Negative => std::cmp::Ordering::Less,
            Sign::Zero => std::cmp::Ordering::Equal,
            Sign::Positive => std::cmp::Ordering::Greater,
        }
    }
}

/// The sign of `x * y` given the signs of `x` and `y`.
impl std::ops::Mul for Sign {
    type Output = Sign;
    fn mul(self, other: Sign) -> Sign {
        match (self, other) {
            (Sign::Zero, _) | (_, Sign::Zero) => Sign::Zero,
            (a, b) if a == b => Sign::Positive,
            _ => Sign::Negative,
        }
    }
}

/// The orientation of a point tuple: the sign of an orientation determinant, with a name.
///
/// * 2-D, `orient2d(a, b, c)`: [`Positive`](Orientation::Positive) when `a, b, c` turn
///   counter-clockwise (the y axis 90° counter-clockwise from the x axis), [`Negative`](Orientation::Negative)
///   when clockwise, [`Degenerate`](Orientation::Degenerate) when collinear (or coincident).
/// * 3-D, `orient3d(a, b, c, d)`: the sign of `det[b-a, c-a, d-a] = ((b-a)×(c-a))·(d-a)`.
///   [`Positive`](Orientation::Positive) when `d` lies on the side of the plane `abc` that the
///   right-hand normal `(b-a)×(c-a)` points to (seen from `d`, `a, b, c` turn counter-clockwise);
///   [`Degenerate`](Orientation::Degenerate) when the four points are coplanar. This is CGAL's
///   `orientation(a, b, c, d)` and the opposite of Shewchuk's `orient3d`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Orientation {
    /// Clockwise (2-D) / `d` on the side opposite the normal of `abc` (3-D).
    Negative,
    /// Collinear (2-D) / coplanar (3-D).
    Degenerate,
    /// Counter-clockwise (2-D) / `d` on the side the right-hand normal of `abc` points to (3-D).
    Positive,
}

impl Orientation {
    /// The orientation with the sign of `s`.
    #[must_use]
    pub fn from_sign(s: Sign) -> Orientation {
        match s {
            Sign::Negative => Orientation::Negative,
            Sign::Zero => Orientation::Degenerate,
            Sign::Positive => Orientation::Positive,
        }
    }

    /// The sign of the orientation determinant.
    #[must_use]
    pub fn sign(self) -> Sign {
        match self {
            Orientation::Negative => Sign::Negative,
            Orientation::Degenerate => Sign::Zero,
            Orientation::Positive => Sign::Positive,
        }
    }

    /// The orientation after swapping two points.
    #[must_use]
    pub fn reverse(self) -> Orientation {
        Orientation::from_sign(self.sign().reverse())
    }

    /// True for [`Orientation::Degenerate`].
    #[must_use]
    pub fn is_degenerate(self) -> bool {
        self == Orientation::Degenerate
    }

    /// True when one is `Positive` and the other `Negative` (strictly opposite sides).
    #[must_use]
    pub fn is_opposite(self, other: Orientation) -> bool {
        matches!(
            (self, other),
            (Orientation::Positive, Orientation::Negative)
                | (Orientation::Negative, Orientation::Positive)
        )
    }
}
