//! A dense stack of faces (quadratically many overlapping boxes) is decided within the pair
//! budget: violated at the first intersecting pair, undecided when none is found.

use envelope_mesh::{TriangleSoup, VertexId};
use envelope_verify::{Options, Verdict, certify};
use glam::DVec3;

/// `n` translated copies of one slanted triangle, `dx` apart along x (parallel planes: apart
/// when `dx > 0`, coincident when `dx == 0`), every box overlapping every other.
fn stack(n: u32, dx: f64) -> TriangleSoup {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for i in 0..n {
        let o = DVec3::new(f64::from(i) * dx, 0.0, 0.0);
        positions.extend([
            o,
            o + DVec3::new(1.0, 0.0, 1.0),
            o + DVec3::new(0.0, 1.0, 0.5),
        ]);
        faces.push([VertexId(3 * i), VertexId(3 * i + 1), VertexId(3 * i + 2)]);
    }
    TriangleSoup::new(positions, faces)
}

#[test]
fn a_dense_stack_is_decided_within_the_budget() {
    // 3,000 faces: about 4.5 million overlapping pairs, above 48 per face plus 2^22.
    let apart = stack(3000, 1e-6);
    let c = certify(&apart, &apart, &Options::new(0.1));
    assert!(c.self_intersections_undecided);
    assert_eq!(c.self_intersections.as_deref(), Some(&[][..]));
    assert_eq!(c.verdict, Verdict::Undecided);
    assert_eq!(c.to_json()["self_intersections"]["undecided"], true);

    let coincident = stack(3000, 0.0);
    let c = certify(&coincident, &coincident, &Options::new(0.1));
    assert!(!c.self_intersections_undecided);
    assert_eq!(c.self_intersections.as_ref().map(Vec::len), Some(1));
    assert!(!c.self_intersections_complete);
    assert_eq!(c.verdict, Verdict::Violated);

    // Below the budget every pair is tested and listed, as before.
    let small = stack(100, 0.0);
    let c = certify(&small, &small, &Options::new(0.1));
    assert!(!c.self_intersections_undecided && c.self_intersections_complete);
    assert_eq!(
        c.self_intersections.as_ref().map(Vec::len),
        Some(100 * 99 / 2)
    );
}

#[test]
fn repeated_triangles_are_measured_once() {
    // 200,000 copies of one face of a tetrahedron as `approx`: before each closed triangle
    // was kept once, every probe of the target's corner-key table walked all the copies
    // (quadratic in the copies).
    let tet = envelope_mesh::generate::tetrahedron();
    let face = tet.faces[0];
    let stack = TriangleSoup::new(tet.positions.clone(), vec![face; 200_000]);
    let c = certify(&tet, &stack, &Options::new(0.01));
    assert_eq!(c.verdict, Verdict::Violated);
    assert_eq!(c.orig_to_approx.verdict, Verdict::Violated);
    assert_eq!(c.approx_to_orig.verdict, Verdict::Holds);
    let one = TriangleSoup::new(tet.positions.clone(), vec![face]);
    let d = certify(&tet, &one, &Options::new(0.01));
    assert_eq!(c.orig_to_approx.upper, d.orig_to_approx.upper);
}
