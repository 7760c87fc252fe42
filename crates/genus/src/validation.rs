//! The validation of a genus-reduced output: `envelope-check`'s classes that the output
//! must not have more of than the input, and the examples of those it has more of (each
//! step blames caps from them in its own way); and that no fill takes material away.

use std::collections::HashMap;

use envelope_check::{CheckOptions, DegeneracyClass, Element, check};
use envelope_mesh::{FaceId, TriangleSoup, VertexId};
use glam::DVec3;

/// Classes the output must not have more of than the input.
pub(crate) const VALIDATED: [DegeneracyClass; 7] = [
    DegeneracyClass::CoincidentTriangles,
    DegeneracyClass::DuplicateTriangles,
    DegeneracyClass::IntersectingTriangles,
    DegeneracyClass::NonManifoldEdges,
    DegeneracyClass::NonManifoldVertices,
    DegeneracyClass::InconsistentOrientation,
    DegeneracyClass::ZeroAreaTriangles,
];

pub(crate) fn class_counts(soup: &TriangleSoup) -> HashMap<DegeneracyClass, usize> {
    let report = check(
        soup,
        &CheckOptions {
            max_examples: 0,
            ..CheckOptions::default()
        },
    );
    VALIDATED
        .iter()
        .map(|&c| (c, report.finding(c).count))
        .collect()
}

/// One example of a validated class the output has more of than the input: its faces (none
/// for a vertex), its vertex (for a vertex finding), and whether it is a pair of faces.
pub(crate) struct NewFinding {
    pub(crate) faces: Vec<FaceId>,
    pub(crate) vertex: Option<VertexId>,
    pub(crate) pair: bool,
}

/// The examples of every validated class `out` has more findings of than `baseline`;
/// `None` when it has no more of any.
pub(crate) fn new_findings(
    out: &TriangleSoup,
    baseline: &HashMap<DegeneracyClass, usize>,
) -> Option<Vec<NewFinding>> {
    let options = CheckOptions {
        max_examples: usize::MAX,
        ..CheckOptions::default()
    };
    let report = check(out, &options);
    let mut any = false;
    let mut found = Vec::new();
    for class in VALIDATED {
        let finding = report.finding(class);
        if finding.count <= baseline.get(&class).copied().unwrap_or(0) {
            continue;
        }
        any = true;
        for e in &finding.examples {
            let (faces, vertex) = match e {
                Element::Face { face, .. } => (vec![*face], None),
                Element::FacePair { faces } => (faces.to_vec(), None),
                Element::Edge { faces, .. } => (faces.clone(), None),
                Element::Vertex { vertex, .. } => (Vec::new(), Some(*vertex)),
                _ => (Vec::new(), None),
            };
            let pair = matches!(e, Element::FacePair { .. });
            found.push(NewFinding {
                faces,
                vertex,
                pair,
            });
        }
    }
    any.then_some(found)
}

/// A fill: the faces it removes and the caps it adds, as positions (f64).
#[derive(Default)]
pub(crate) struct Fill {
    pub(crate) removed: Vec<[DVec3; 3]>,
    pub(crate) caps: Vec<[DVec3; 3]>,
}

impl Fill {
    /// Whether the fill would take material away from the solid: the volume its removed
    /// faces and caps enclose together (f64, six times, from a corner of the first face so
    /// the terms stay small), counted with the input's orientation `sign` (the sign of its
    /// signed volume), is negative beyond its rounding. Filling a hole, tunnel or pocket only
    /// adds material (the closing contains the solid); a region taken on the wrong side of
    /// its rims (the whole part around a few faces) takes nearly all of it away while
    /// leaving a closed, clean surface that none of [`VALIDATED`] sees. An f64 estimate that
    /// only refuses; asked only of inputs without borders (a solid), where the removed faces
    /// and the caps of a fill close up.
    pub(crate) fn takes_material(&self, sign: f64) -> bool {
        let Some(o) = self.caps.first().or(self.removed.first()).map(|t| t[0]) else {
            return false;
        };
        let term = |t: &[DVec3; 3]| (t[0] - o).dot((t[1] - o).cross(t[2] - o));
        let (mut sum, mut size) = (0.0, 0.0);
        for (faces, s) in [(&self.caps, 1.0), (&self.removed, -1.0)] {
            for t in faces {
                let v = term(t);
                sum += s * v;
                size += v.abs();
            }
        }
        sign * sum < -1e-9 * size
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fill(removed: &[[DVec3; 3]], caps: &[[DVec3; 3]]) -> Fill {
        Fill {
            removed: removed.to_vec(),
            caps: caps.to_vec(),
        }
    }

    #[test]
    fn a_cap_over_a_dent_adds_material_and_a_cap_on_the_wrong_side_takes_it() {
        // The tetrahedron (0, x, y, z) oriented outward; its three faces at the origin form a
        // dent seen from outside, capped by the face (x, y, z) run the same way.
        let (o, x, y, z) = (DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z);
        let dent = [[o, y, x], [o, x, z], [o, z, y]];
        // The solid around the dent is outside the tetrahedron, so the dent's faces point
        // into it: reversed, and the cap (x, y, z) reversed too, facing the dent.
        let dent_in: Vec<[DVec3; 3]> = dent.iter().map(|t| [t[0], t[2], t[1]]).collect();
        let cap = [[x, z, y]];
        assert!(
            !fill(&dent_in, &cap).takes_material(1.0),
            "filling the dent adds"
        );
        // The same surfaces as a bump on the solid: capping it takes it away.
        let bump = dent.to_vec();
        let cap_bump = [[x, y, z]];
        assert!(
            fill(&bump, &cap_bump).takes_material(1.0),
            "cutting the bump takes"
        );
        // The input's orientation flips the reading.
        assert!(!fill(&bump, &cap_bump).takes_material(-1.0));
        // A flat cap over a flat region: no change either way.
        let flat = [[o, x, y]];
        assert!(!fill(&flat, &flat).takes_material(1.0));
    }
}
