//! The validation of a genus-reduced output: `envelope-check`'s classes that the output
//! must not have more of than the input, and the examples of those it has more of (each
//! step blames caps from them in its own way).

use std::collections::HashMap;

use envelope_check::{CheckOptions, DegeneracyClass, Element, check};
use envelope_mesh::{FaceId, TriangleSoup, VertexId};

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
