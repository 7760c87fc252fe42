//! `envelope::repair`, one small mesh per step that needs exactly that step: the counts, the
//! checker's verdict afterwards, and the surface unchanged (certified both ways at a tiny
//! epsilon against the original).

use envelope::advanced::check::DegeneracyClass;
use envelope::advanced::mesh::{TriangleSoup, generate};
use envelope::advanced::repair::RepairError;
use envelope::{Epsilon, Error, Mesh, RepairStep as Step, Verdict};

/// What the checker finds where split sheets still touch.
const TOUCHING: &[DegeneracyClass] = &[
    DegeneracyClass::DuplicateVertices,
    DegeneracyClass::IntersectingTriangles,
];

fn mesh(soup: TriangleSoup) -> Mesh {
    Mesh::from_soup(soup)
}

/// Every point of each within a billionth of the diagonal of the other, proved.
fn assert_same_surface(orig: &Mesh, repaired: &Mesh) {
    let c = envelope::verify(orig, repaired, Epsilon::relative(1e-9)).unwrap();
    assert_eq!(c.approx_to_orig.verdict, Verdict::Holds, "repaired -> orig");
    assert_eq!(c.orig_to_approx.verdict, Verdict::Holds, "orig -> repaired");
}

/// The counts of every step, in `Step::ALL` order.
fn counts(r: &envelope::Repaired) -> Vec<usize> {
    Step::ALL
        .iter()
        .map(|&s| r.report().step(s).count)
        .collect()
}

fn only(step: Step, n: usize) -> Vec<usize> {
    Step::ALL
        .iter()
        .map(|&s| if s == step { n } else { 0 })
        .collect()
}

/// Repairs, asserts the counts and the unchanged surface, returns the result.
fn repaired(orig: &Mesh, expected: &[usize]) -> envelope::Repaired {
    let r = envelope::repair(orig).unwrap();
    assert_eq!(counts(&r), expected, "{}", r.report());
    assert_same_surface(orig, r.mesh());
    r
}

/// A soup with its faces' corners unshared (as an STL file has them).
fn unwelded(s: &TriangleSoup) -> TriangleSoup {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for f in s.face_ids() {
        let n = positions.len() as u32;
        positions.extend(s.triangle(f).map(|p| p.to_array()));
        faces.push([n, n + 1, n + 2]);
    }
    TriangleSoup::from_raw(&positions, &faces)
}

#[test]
fn weld_of_an_unwelded_sphere() {
    let sphere = generate::icosphere(1, 1.0);
    let orig = mesh(unwelded(&sphere));
    assert!(!envelope::check(&orig).acceptable());
    let n = 3 * sphere.num_faces() - sphere.num_vertices();
    let r = repaired(&orig, &only(Step::Weld, n));
    assert!(r.acceptable());
    assert_eq!(r.mesh().num_vertices(), sphere.num_vertices());
}

#[test]
fn duplicate_face_in_either_orientation() {
    let mut s = generate::icosphere(1, 1.0);
    let [a, b, c] = s.faces[5];
    s.faces.push([a, c, b]);
    s.faces.push([b, c, a]);
    let orig = mesh(s);
    assert!(!envelope::check(&orig).acceptable());
    let r = repaired(&orig, &only(Step::DuplicateFaces, 2));
    assert!(r.acceptable());
    assert_eq!(r.mesh(), &mesh(generate::icosphere(1, 1.0)));
}

#[test]
fn unreferenced_vertex() {
    let mut s = generate::icosphere(1, 1.0);
    s.positions.insert(0, glam::DVec3::new(5.0, 5.0, 5.0));
    for v in s.faces.iter_mut().flatten() {
        v.0 += 1;
    }
    let orig = mesh(s);
    let r = repaired(&orig, &only(Step::UnreferencedVertices, 1));
    assert!(r.acceptable());
    assert_eq!(r.mesh(), &mesh(generate::icosphere(1, 1.0)));
}

#[test]
fn flipped_face_in_a_component() {
    let mut s = generate::icosphere(1, 1.0);
    s.faces[7].swap(1, 2);
    let orig = mesh(s);
    assert!(!envelope::check(&orig).acceptable());
    let r = repaired(&orig, &only(Step::Orientation, 1));
    assert!(r.acceptable());
    assert_eq!(r.mesh(), &mesh(generate::icosphere(1, 1.0)));
}

#[test]
fn non_manifold_edge_with_three_faces() {
    let orig = mesh(generate::three_triangles_on_edge());
    let r = repaired(&orig, &[0, 0, 0, 0, 1, 2, 0, 0]);
    // The three sheets still touch along the edge: their copies of its ends are duplicate
    // vertices and their faces meet away from shared vertices.
    assert_eq!(r.left(), TOUCHING);
    let t = envelope::advanced::mesh::analyze(r.mesh().soup());
    assert!(t.manifold && t.consistently_oriented);
    assert_eq!(t.components.len(), 3);
}

#[test]
fn non_manifold_edge_with_four_faces() {
    // Two closed tetrahedra sharing edge 0-1.
    let orig = mesh(TriangleSoup::from_raw(
        &[
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
        ],
        &[
            [0, 2, 1],
            [0, 1, 3],
            [1, 2, 3],
            [0, 3, 2],
            [0, 4, 1],
            [0, 1, 5],
            [1, 4, 5],
            [0, 5, 4],
        ],
    ));
    assert!(!envelope::check(&orig).acceptable());
    let r = repaired(&orig, &[0, 0, 0, 0, 1, 2, 0, 0]);
    let t = envelope::advanced::mesh::analyze(r.mesh().soup());
    assert!(t.manifold && t.consistently_oriented);
    assert_eq!(t.components.len(), 2);
    assert_eq!(r.mesh().num_vertices(), 8);
    assert_eq!(r.left(), TOUCHING);
}

#[test]
fn bow_tie_vertex() {
    let orig = mesh(generate::bow_tie());
    let r = repaired(&orig, &only(Step::NonManifoldVertices, 1));
    assert_eq!(r.mesh().num_vertices(), 6);
    assert_eq!(r.left(), TOUCHING);
}

/// A flat 2 x 2 square: a left column of two triangles whose edge 1-2 holds vertex 4, the
/// midpoint the right column's three triangles use.
fn t_junction() -> TriangleSoup {
    TriangleSoup::from_raw(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
        ],
        &[[0, 1, 2], [0, 2, 3], [1, 5, 4], [5, 6, 4], [4, 6, 2]],
    )
}

#[test]
fn t_junction_closes_the_crack() {
    let orig = mesh(t_junction());
    assert!(
        envelope::check(&orig)
            .errors()
            .any(|c| c == DegeneracyClass::TJunctions)
    );
    let r = repaired(&orig, &only(Step::TJunctions, 1));
    assert!(r.acceptable(), "{:?}", r.left());
    assert_eq!(r.mesh().num_faces(), 6);
    assert_eq!(r.check().border_loops, 1);
}

#[test]
fn zero_area_face_in_the_crack_is_dropped_then_the_t_junction_split() {
    let mut s = t_junction();
    s.faces
        .push([1, 4, 2].map(envelope::advanced::mesh::VertexId));
    let orig = mesh(s);
    let r = repaired(&orig, &[0, 0, 1, 1, 0, 0, 0, 0]);
    assert!(r.acceptable(), "{:?}", r.left());
    let json = r.to_json();
    assert_eq!(json["steps"][2]["examples"][0]["face"], 5);
    assert_eq!(json["acceptable"], true);
}

#[test]
fn zero_area_face_off_the_surface_is_refused() {
    let mut s = t_junction();
    let far = s.positions.len() as u32;
    s.positions.push(glam::DVec3::new(3.0, 0.0, 0.0));
    s.faces
        .push([1, 5, far].map(envelope::advanced::mesh::VertexId));
    let err = envelope::repair(&mesh(s)).unwrap_err();
    let Error::Repair(RepairError::UncoveredDegenerateFace { face, .. }) = &err else {
        panic!("{err}");
    };
    assert_eq!(face.0, 5);
    assert!(err.to_string().contains("face f5"), "{err}");
}

#[test]
fn moebius_is_refused_naming_a_face() {
    let err = envelope::repair(&mesh(generate::moebius_strip(6))).unwrap_err();
    assert!(
        matches!(err, Error::Repair(RepairError::NonOrientable { .. })),
        "{err}"
    );
    assert!(err.to_string().contains("face f"), "{err}");
}

#[test]
fn every_step_at_once_on_an_unwelded_sphere() {
    let sphere = generate::icosphere(1, 1.0);
    let mut s = unwelded(&sphere);
    s.faces.push(s.faces[0]); // duplicate
    s.faces[3].swap(1, 2); // flipped
    s.positions.push(glam::DVec3::splat(9.0)); // unreferenced
    let orig = mesh(s);
    let r = envelope::repair(&orig).unwrap();
    assert_eq!(r.report().step(Step::DuplicateFaces).count, 1);
    assert_eq!(r.report().step(Step::Orientation).count, 1);
    assert_eq!(r.report().step(Step::UnreferencedVertices).count, 1);
    assert!(r.acceptable());
    assert_same_surface(&orig, r.mesh());
    // Certified simplification of the repaired mesh holds against the original.
    let simplified = envelope::Simplifier::new(Epsilon::percent(5.0))
        .run(r.mesh())
        .unwrap();
    let c = envelope::verify(&orig, simplified.mesh(), Epsilon::percent(5.0)).unwrap();
    assert_eq!(c.approx_to_orig.verdict, Verdict::Holds);
    assert_eq!(c.orig_to_approx.verdict, Verdict::Holds);
}
