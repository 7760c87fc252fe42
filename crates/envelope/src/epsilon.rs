//! The tolerance: an absolute length, or a part of the input's bounding-box diagonal.

use std::fmt;
use std::str::FromStr;

use envelope_offset::{EPSILON_SYNTAX, EpsilonSpec, parse_epsilon};

use crate::{Error, Mesh};

/// How far the output may be from the input, both ways.
///
/// Parsed from the command line's syntax: `0.01` is absolute, `1%` and `1/64%` are
/// percentages of the bounding-box diagonal.
///
/// ```
/// use envelope::Epsilon;
/// let e: Epsilon = "1/64%".parse()?;
/// assert_eq!(e, Epsilon::percent(1.0 / 64.0));
/// assert_eq!(e.to_string(), "0.015625%");
/// assert_eq!(Epsilon::relative(0.5).resolve(&envelope::Mesh::demo()),
///            0.5 * envelope::Mesh::demo().diagonal());
/// assert!("-1%".parse::<Epsilon>().is_err());
/// # Ok::<(), envelope::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Epsilon(Kind);

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Spec(EpsilonSpec),
    Fraction(f64),
}

impl Epsilon {
    /// An absolute length.
    #[must_use]
    pub fn absolute(length: f64) -> Epsilon {
        Epsilon(Kind::Spec(EpsilonSpec::Absolute(length)))
    }

    /// A fraction of the bounding-box diagonal (`0.01` is 1 %).
    #[must_use]
    pub fn relative(fraction: f64) -> Epsilon {
        Epsilon(Kind::Fraction(fraction))
    }

    /// A percentage of the bounding-box diagonal (`1.0` is 1 %), resolved exactly as the
    /// command line resolves `1%`.
    #[must_use]
    pub fn percent(percent: f64) -> Epsilon {
        Epsilon(Kind::Spec(EpsilonSpec::PercentOfDiagonal(percent)))
    }

    /// The absolute length for `mesh`.
    #[must_use]
    pub fn resolve(self, mesh: &Mesh) -> f64 {
        self.resolve_for_diagonal(mesh.diagonal())
    }

    /// The absolute length for a mesh whose bounding-box diagonal is `diagonal`.
    #[must_use]
    pub fn resolve_for_diagonal(self, diagonal: f64) -> f64 {
        match self.0 {
            Kind::Spec(spec) => spec.resolve(diagonal),
            Kind::Fraction(f) => f * diagonal,
        }
    }

    /// Whether it is a part of the diagonal (not an absolute length).
    #[must_use]
    pub fn is_relative(self) -> bool {
        !matches!(self.0, Kind::Spec(EpsilonSpec::Absolute(_)))
    }

    /// Refuses a value that is not finite and positive.
    pub(crate) fn validate(self) -> Result<Epsilon, Error> {
        let x = match self.0 {
            Kind::Spec(EpsilonSpec::Absolute(x) | EpsilonSpec::PercentOfDiagonal(x))
            | Kind::Fraction(x) => x,
        };
        if x.is_finite() && x > 0.0 {
            Ok(self)
        } else {
            Err(Error::InvalidEpsilon(format!(
                "{self} is not a positive finite length"
            )))
        }
    }
}

impl From<EpsilonSpec> for Epsilon {
    fn from(spec: EpsilonSpec) -> Self {
        Epsilon(Kind::Spec(spec))
    }
}

impl FromStr for Epsilon {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self, Error> {
        parse_epsilon(s)
            .map(Epsilon::from)
            .map_err(|e| Error::InvalidEpsilon(format!("{s:?}: {}; {EPSILON_SYNTAX}", e.reason())))
    }
}

impl fmt::Display for Epsilon {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Kind::Spec(EpsilonSpec::Absolute(x)) => write!(f, "{x}"),
            Kind::Spec(EpsilonSpec::PercentOfDiagonal(p)) => write!(f, "{p}%"),
            Kind::Fraction(x) => write!(f, "{}%", x * 100.0),
        }
    }
}
