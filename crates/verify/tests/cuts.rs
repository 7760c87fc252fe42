//! The f64 cut (`split_within_f64` in `hausdorff.rs`): a sub-triangle that no single
//! triangle covers, but whose part on each side of a plane through the shared edge of two
//! triangles is within epsilon of the triangle on that side, is proved at once instead of
//! being subdivided along the edge down to about epsilon.

use envelope_mesh::{TriangleSoup, VertexId};
use envelope_verify::{Verdict, one_sided};
use glam::DVec3;

fn soup(positions: Vec<DVec3>, faces: &[[u32; 3]]) -> TriangleSoup {
    TriangleSoup::new(positions, faces.iter().map(|f| f.map(VertexId)).collect())
}

/// A quad with corners 0.1-multiples (rounded, so midpoints are inexact), lifted to `z`
/// along the diagonal 1-3 when `ridge` is set, split along diagonal 0-2 or 1-3.
fn quad(split_02: bool, ridge: f64) -> TriangleSoup {
    let p = vec![
        DVec3::new(0.1, 0.1, 0.0),
        DVec3::new(1.3, 0.2, ridge),
        DVec3::new(1.1, 1.3, 0.0),
        DVec3::new(0.2, 0.9, ridge),
    ];
    let faces: &[[u32; 3]] = if split_02 {
        &[[0, 1, 2], [0, 2, 3]]
    } else {
        &[[0, 1, 3], [1, 2, 3]]
    };
    soup(p, faces)
}

#[test]
fn a_flat_quad_split_the_other_way_is_proved_without_subdividing_the_diagonal() {
    // Distance 0 everywhere; each face of one split straddles the other's diagonal.
    let (a, b) = (quad(true, 0.0), quad(false, 0.0));
    for eps in [1e-3, 1e-6, 1e-9] {
        for (from, to) in [(&a, &b), (&b, &a)] {
            let s = one_sided(from, to, eps, eps * 1e-6);
            assert_eq!(s.verdict, Verdict::Holds, "eps {eps}: {s:?}");
            // Subdividing would take about (diagonal / eps) sub-triangles along it.
            assert!(s.subdivisions <= 8, "eps {eps}: {s:?}");
            assert!(s.upper <= eps, "eps {eps}: {s:?}");
        }
    }
}

#[test]
fn a_folded_quad_against_its_other_split() {
    // The quad folded along 1-3 (a ridge of height 0.05 there): split along 0-2 it is a
    // different surface, up to about 0.025 from the ridge split. Far above that distance
    // the cut proves it quickly; below it, a violation is found.
    let (ridge, valley) = (quad(false, 0.05), quad(true, 0.05));
    let s = one_sided(&valley, &ridge, 0.05, 0.05e-6);
    assert_eq!(s.verdict, Verdict::Holds, "{s:?}");
    assert!(s.subdivisions <= 64, "{s:?}");
    let s = one_sided(&valley, &ridge, 0.001, 0.001e-6);
    assert_eq!(s.verdict, Verdict::Violated, "{s:?}");
    assert!(s.lower > 0.001, "{s:?}");
}
