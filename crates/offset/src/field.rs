//! Epsilon as a field over the surface (Cohen et al. 6.3, adaptive approximation).
//!
//! The paper lets epsilon vary per vertex ("a function of its distance from the observer",
//! or user-chosen per region). An [`EpsilonField`] is evaluated once per input vertex; the
//! envelopes then treat `eps_v` as the requested offset of vertex `v` on both sides.
//!
//! Epsilon specifications ([`parse_epsilon`]) are either an absolute length (`0.002`) or a
//! percentage of the bounding-box diagonal (`0.5%`, `1/64%`), the unit the paper's tables use.
//!
//! # Per-vertex file format
//!
//! Plain UTF-8 text, one epsilon specification per line, in vertex order (line `i` of the
//! values is vertex `i` of the mesh, as the mesh reader numbers them). Everything from `#` to
//! the end of a line is a comment; blank lines are skipped; surrounding whitespace is
//! ignored. Each value is parsed by [`parse_epsilon`] (so `0.01` and `1/64%` are both
//! accepted) and must be finite and positive. The number of values must equal the number of
//! vertices. [`parse_epsilon_values`] validates text, [`read_epsilon_file`] a path.
use std::path::Path;

use glam::DVec3;

/// An epsilon as the user wrote it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EpsilonSpec {
    /// An absolute length.
    Absolute(f64),
    /// A percentage of the bounding-box diagonal (`0.5` means 0.5 %).
    PercentOfDiagonal(f64),
}

impl EpsilonSpec {
    /// The absolute length for a mesh with bounding-box diagonal `diagonal`.
    #[must_use]
    pub fn resolve(self, diagonal: f64) -> f64 {
        match self {
            EpsilonSpec::Absolute(e) => e,
            EpsilonSpec::PercentOfDiagonal(p) => p / 100.0 * diagonal,
        }
    }
}

/// Why an epsilon specification was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EpsilonParseError {
    /// Nothing to parse.
    #[error("empty epsilon")]
    Empty,
    /// Not a number, a fraction `a/b` or either followed by `%`.
    #[error("not a number (expected e.g. 0.01, 0.5% or 1/64%)")]
    NotANumber,
    /// NaN or infinite (including a zero denominator).
    #[error("epsilon is not finite")]
    NotFinite,
    /// Zero or negative.
    #[error("epsilon must be positive")]
    NotPositive,
}

impl EpsilonParseError {
    /// The reason in a few words, for a message that goes on with [`EPSILON_SYNTAX`].
    #[must_use]
    pub fn reason(self) -> &'static str {
        match self {
            EpsilonParseError::Empty => "empty",
            EpsilonParseError::NotANumber => "not a number",
            EpsilonParseError::NotFinite => "not finite",
            EpsilonParseError::NotPositive => "zero or negative",
        }
    }
}

/// What [`parse_epsilon`] accepts, in the words of an error message.
pub const EPSILON_SYNTAX: &str = "expected a positive length: absolute (0.01) or a percentage of the bounding-box diagonal (2%, 1/64%)";

/// Parses `0.01` (absolute), `0.5%` or `1/64%` (percent of the bounding-box diagonal); a
/// fraction `a/b` is accepted with or without `%`.
///
/// ```
/// use envelope_offset::{parse_epsilon, EpsilonSpec};
/// assert_eq!(parse_epsilon("1/64%"), Ok(EpsilonSpec::PercentOfDiagonal(1.0 / 64.0)));
/// assert_eq!(parse_epsilon(" 0.5% "), Ok(EpsilonSpec::PercentOfDiagonal(0.5)));
/// assert_eq!(parse_epsilon("2e-3"), Ok(EpsilonSpec::Absolute(0.002)));
/// assert!(parse_epsilon("-1%").is_err());
/// ```
pub fn parse_epsilon(s: &str) -> Result<EpsilonSpec, EpsilonParseError> {
    let s = s.trim();
    if s.is_empty() {
        return Err(EpsilonParseError::Empty);
    }
    let (body, percent) = match s.strip_suffix('%') {
        Some(b) => (b.trim_end(), true),
        None => (s, false),
    };
    let number = |t: &str| -> Result<f64, EpsilonParseError> {
        let t = t.trim();
        // Rust accepts "inf"/"nan"; reject them as words, not as numbers.
        if t.is_empty()
            || t.chars()
                .any(|c| c.is_ascii_alphabetic() && c != 'e' && c != 'E')
        {
            return Err(EpsilonParseError::NotANumber);
        }
        t.parse::<f64>().map_err(|_| EpsilonParseError::NotANumber)
    };
    let value = match body.split_once('/') {
        Some((a, b)) => number(a)? / number(b)?,
        None => number(body)?,
    };
    if !value.is_finite() {
        return Err(EpsilonParseError::NotFinite);
    }
    if value <= 0.0 {
        return Err(EpsilonParseError::NotPositive);
    }
    Ok(if percent {
        EpsilonSpec::PercentOfDiagonal(value)
    } else {
        EpsilonSpec::Absolute(value)
    })
}

/// Why a per-vertex epsilon file was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EpsilonFileError {
    /// The file could not be read.
    #[error("cannot read the epsilon file ({0:?})")]
    Io(std::io::ErrorKind),
    /// A value line is malformed (1-based line number).
    #[error("line {line}: {error}")]
    Line {
        /// 1-based line number in the file.
        line: usize,
        /// What is wrong with it.
        error: EpsilonParseError,
    },
    /// The number of values differs from the number of vertices.
    #[error("{got} epsilon values for {expected} vertices")]
    Count {
        /// Number of vertices.
        expected: usize,
        /// Number of values found.
        got: usize,
    },
}

/// Parses per-vertex epsilon text (see the module docs for the format).
pub(crate) fn parse_epsilon_values(
    text: &str,
    expected: usize,
) -> Result<Vec<EpsilonSpec>, EpsilonFileError> {
    let mut out = Vec::with_capacity(expected);
    for (i, line) in text.lines().enumerate() {
        let body = line.split_once('#').map_or(line, |(b, _)| b).trim();
        if body.is_empty() {
            continue;
        }
        out.push(
            parse_epsilon(body).map_err(|error| EpsilonFileError::Line { line: i + 1, error })?,
        );
    }
    if out.len() != expected {
        return Err(EpsilonFileError::Count {
            expected,
            got: out.len(),
        });
    }
    Ok(out)
}

/// Reads a per-vertex epsilon file (see the module docs for the format).
pub fn read_epsilon_file(
    path: &Path,
    expected: usize,
) -> Result<Vec<EpsilonSpec>, EpsilonFileError> {
    let text = std::fs::read_to_string(path).map_err(|e| EpsilonFileError::Io(e.kind()))?;
    parse_epsilon_values(&text, expected)
}

/// The requested epsilon over the surface, evaluated per input vertex (section 6.3).
pub enum EpsilonField {
    /// The same epsilon everywhere (absolute length).
    Constant(f64),
    /// One absolute epsilon per vertex, in vertex order.
    PerVertex(Vec<f64>),
    /// A function of the vertex position, e.g. growing with the distance to a viewpoint.
    Function(Box<dyn Fn(DVec3) -> f64 + Sync + Send>),
}

impl std::fmt::Debug for EpsilonField {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EpsilonField::Constant(e) => write!(f, "Constant({e})"),
            EpsilonField::PerVertex(v) => write!(f, "PerVertex({} values)", v.len()),
            EpsilonField::Function(_) => write!(f, "Function(..)"),
        }
    }
}

impl EpsilonField {
    /// Per-vertex values from specifications (resolving percentages with `diagonal`).
    #[must_use]
    pub fn from_specs(specs: &[EpsilonSpec], diagonal: f64) -> EpsilonField {
        EpsilonField::PerVertex(specs.iter().map(|s| s.resolve(diagonal)).collect())
    }

    /// A field growing linearly with the distance to `viewpoint`: `near` at distance 0,
    /// `near + slope * d` at distance `d`.
    #[must_use]
    pub fn distance_to_viewpoint(viewpoint: DVec3, near: f64, slope: f64) -> EpsilonField {
        EpsilonField::Function(Box::new(move |p| near + slope * p.distance(viewpoint)))
    }

    /// The epsilon of every position; errors name the first vertex with a non-finite or
    /// non-positive value, or a count mismatch.
    ///
    /// The range rule every envelope builder shares: a value above the bounding-box diagonal
    /// of `positions` acts as the diagonal (envelopes that far out add nothing, and huge
    /// offsets only slow the growth down); a value below 2^-40 times the
    /// largest coordinate magnitude is refused (the offset would vanish in the rounding), and
    /// so are coordinates whose envelopes would leave the predicates' range.
    ///
    /// ```
    /// use envelope_offset::{EnvelopeError, EpsilonField};
    /// use glam::DVec3;
    /// let p = [DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0)];
    /// assert_eq!(EpsilonField::Constant(1e9).evaluate(&p).unwrap(), vec![5.0, 5.0]);
    /// assert!(matches!(
    ///     EpsilonField::Constant(1e-15).evaluate(&p),
    ///     Err(EnvelopeError::EpsilonTooSmall { .. })
    /// ));
    /// ```
    pub fn evaluate(&self, positions: &[DVec3]) -> Result<Vec<f64>, crate::EnvelopeError> {
        let mut values = self.evaluate_unchecked(positions)?;
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for p in positions.iter().filter(|p| p.is_finite()) {
            (lo, hi) = (lo.min(*p), hi.max(*p));
        }
        if lo.x > hi.x {
            return Ok(values);
        }
        let diagonal = (hi - lo).length();
        let magnitude = lo.abs().max(hi.abs()).max_element();
        if diagonal > 0.0 {
            for e in &mut values {
                *e = e.min(diagonal);
            }
        }
        let floor = crate::error::EPSILON_FLOOR * magnitude;
        if let Some(i) = values.iter().position(|&e| e < floor) {
            return Err(crate::EnvelopeError::EpsilonTooSmall {
                vertex: (!matches!(self, EpsilonField::Constant(_)))
                    .then_some(envelope_mesh::VertexId(i as u32)),
                epsilon: values[i],
                floor,
                magnitude,
            });
        }
        let largest = values.iter().copied().fold(0.0, f64::max);
        // Outer envelope and tubes reach `magnitude + epsilon`; room for one more epsilon.
        if magnitude + 2.0 * largest > 0.5 * envelope_mesh::MAX_ALLOWED_MAGNITUDE {
            return Err(crate::EnvelopeError::CoordinatesTooLarge {
                magnitude,
                epsilon: largest,
            });
        }
        Ok(values)
    }

    /// [`EpsilonField::evaluate`] without the range rule: finite positive values only.
    fn evaluate_unchecked(&self, positions: &[DVec3]) -> Result<Vec<f64>, crate::EnvelopeError> {
        let values: Vec<f64> = match self {
            EpsilonField::Constant(e) => vec![*e; positions.len()],
            EpsilonField::PerVertex(v) => {
                if v.len() != positions.len() {
                    return Err(crate::EnvelopeError::EpsilonCount {
                        expected: positions.len(),
                        got: v.len(),
                    });
                }
                v.clone()
            }
            EpsilonField::Function(f) => positions.iter().map(|&p| f(p)).collect(),
        };
        if let Some(i) = values.iter().position(|e| !(e.is_finite() && *e > 0.0)) {
            return Err(crate::EnvelopeError::BadEpsilon {
                vertex: envelope_mesh::VertexId(i as u32),
            });
        }
        Ok(values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Comments, blank lines and both kinds of value; a count mismatch is an error.
    #[test]
    fn epsilon_values_parse_with_comments() {
        let v = parse_epsilon_values("# eps per vertex\n0.1\n1/64%  # nose\n\n2e-2\n", 3).unwrap();
        assert_eq!(v[1], EpsilonSpec::PercentOfDiagonal(1.0 / 64.0));
        assert!(parse_epsilon_values("0.1\n", 2).is_err());
    }
}
