//! The genus reduction's output inside the input's alpha-prisms, checked exactly and
//! independently of how the step reasoned: every added triangle is covered by its corners'
//! cubes, each corner's cube lies in the alpha-prism of an input face at that corner (an
//! input vertex, or a point on an input edge within `POINT_ERROR alpha` of it, whose cube
//! is taken at `alpha (1 - 2 POINT_ERROR)`), and every piece of a split input face lies in
//! the alpha-prism of an input face at its corner that is an input vertex.

use envelope_genus::details::{POINT_ERROR, covered_by_corner_cubes, cube_corners};
use envelope_genus::{AlphaPrism, GenusReport};
use envelope_mesh::{TriangleSoup, VertexId};
use glam::DVec3;

/// The input vertex at `p`, if any.
fn input_vertex(input: &TriangleSoup, p: DVec3) -> Option<VertexId> {
    input
        .positions
        .iter()
        .position(|&q| q == p)
        .map(VertexId::from_index)
}

/// The input faces with a corner `v`.
fn faces_at(input: &TriangleSoup, v: VertexId) -> Vec<[DVec3; 3]> {
    input
        .faces
        .iter()
        .filter(|t| t.contains(&v))
        .map(|t| t.map(|w| input.position(w)))
        .collect()
}

/// L-infinity distance from `p` to the segment `a b` (f64: only picks the edge; the check
/// that matters is the exact prism containment).
fn linf_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * t)).abs().max_element()
}

/// The input faces on an edge within about `POINT_ERROR alpha` of the point `p`.
fn faces_at_point(input: &TriangleSoup, p: DVec3, alpha: f64) -> Vec<[DVec3; 3]> {
    input
        .faces
        .iter()
        .map(|t| t.map(|w| input.position(w)))
        .filter(|t| {
            (0..3).any(|k| linf_to_segment(p, t[k], t[(k + 1) % 3]) <= 2.0 * POINT_ERROR * alpha)
        })
        .collect()
}

fn cube_in_some_prism(faces: &[[DVec3; 3]], p: DVec3, radius: f64, alpha: f64) -> bool {
    faces.iter().any(|&t| {
        AlphaPrism::new(t, alpha)
            .is_ok_and(|prism| cube_corners(p, radius).iter().all(|&c| prism.contains(c)))
    })
}

/// Asserts the module docs on `out`, the reduction of `input` at `alpha` reported by `r`.
pub fn assert_inside_prisms(input: &TriangleSoup, out: &TriangleSoup, r: &GenusReport, alpha: f64) {
    let shrunk = alpha * (1.0 - 2.0 * POINT_ERROR);
    for &f in &r.added_faces {
        let t = out.triangle(f);
        let all_input = t.iter().all(|&p| input_vertex(input, p).is_some());
        let radius = if all_input { alpha } else { shrunk };
        assert!(
            covered_by_corner_cubes(t, radius),
            "added face {f:?} outside its corners' cubes"
        );
        for p in t {
            let (faces, radius) = match input_vertex(input, p) {
                Some(v) => (faces_at(input, v), alpha),
                None => (faces_at_point(input, p, alpha), shrunk),
            };
            assert!(
                !faces.is_empty(),
                "added corner {p} is neither an input vertex nor on an input edge"
            );
            assert!(
                cube_in_some_prism(&faces, p, radius, alpha),
                "the cube at added corner {p} is outside the alpha-prisms"
            );
        }
    }
    for &f in &r.piece_faces {
        let t = out.triangle(f);
        let inside = t.iter().filter_map(|&p| input_vertex(input, p)).any(|v| {
            faces_at(input, v).into_iter().any(|face| {
                AlphaPrism::new(face, alpha).is_ok_and(|prism| t.iter().all(|&c| prism.contains(c)))
            })
        });
        assert!(
            inside,
            "piece {f:?} is not inside the alpha-prism of an input face"
        );
    }
    assert_eq!(
        r.faces_out,
        r.faces_in + r.triangles_added + r.pieces - r.triangles_removed,
        "face counts"
    );
}
