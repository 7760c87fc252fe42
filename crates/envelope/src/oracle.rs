//! The oracles: is a mesh acceptable input, and is an output within epsilon of its input.

use envelope_check::{CheckOptions, CheckReport};
use envelope_verify::{Certificate, Options, certify};

use crate::{Epsilon, Error, Mesh};

/// Every degeneracy class of section 7.1 with its elements: whether `mesh` is acceptable
/// input for the simplifier ([`CheckReport::acceptable`]).
///
/// ```
/// let report = envelope::check(&envelope::Mesh::demo());
/// assert!(report.acceptable());
/// ```
#[must_use]
pub fn check(mesh: &Mesh) -> CheckReport {
    envelope_check::check(mesh.soup(), &CheckOptions::default())
}

/// Certifies `approx` against `orig`, whoever made it: every point of each within `epsilon`
/// of the other (exact branch and bound), no self-intersection of `approx` but those `orig`
/// had (a pair of unchanged `orig` faces that met there already, listed in
/// [`Certificate::kept_intersections`]: what the simplifier leaves of a self-intersecting
/// input), the same genus, components and border loops. A relative epsilon is a part of
/// `orig`'s diagonal.
///
/// ```
/// use envelope::{Epsilon, Verdict};
/// let cup = envelope::Mesh::demo();
/// let certificate = envelope::verify(&cup, &cup, Epsilon::percent(0.1))?;
/// assert_eq!(certificate.verdict, Verdict::Holds);
/// # Ok::<(), envelope::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidEpsilon`] when epsilon does not resolve to a positive finite length.
pub fn verify(orig: &Mesh, approx: &Mesh, epsilon: Epsilon) -> Result<Certificate, Error> {
    let eps = resolve(orig, epsilon)?;
    let options = Options {
        allow_input_intersections: true,
        ..Options::new(eps)
    };
    Ok(certify(orig.soup(), approx.soup(), &options))
}

/// `epsilon` as a length on `orig`: positive and finite, or [`Error::InvalidEpsilon`].
pub(crate) fn resolve(orig: &Mesh, epsilon: Epsilon) -> Result<f64, Error> {
    let eps = epsilon.validate()?.resolve(orig);
    if !(eps.is_finite() && eps > 0.0) {
        return Err(Error::InvalidEpsilon(format!(
            "{epsilon} is {eps} on a mesh whose diagonal is {}",
            orig.diagonal()
        )));
    }
    Ok(eps)
}
