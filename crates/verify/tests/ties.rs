//! Ties: faces exactly epsilon away from the other mesh over a whole region or along a
//! curve. Every point is within epsilon (non-strict), so `certify` must say it holds, and
//! it must say so without subdividing down to the resolution (which, along a curve, used to
//! take millions of exact tests: the fuzzer found it as a timeout).

use envelope_mesh::{TriangleSoup, VertexId};
use envelope_verify::{Verdict, one_sided};
use glam::DVec3;

fn soup(positions: Vec<DVec3>, faces: &[[u32; 3]]) -> TriangleSoup {
    TriangleSoup::new(positions, faces.iter().map(|f| f.map(VertexId)).collect())
}

/// The unit square at z = 0, two triangles sharing the diagonal (0,0)-(1,1).
fn square() -> TriangleSoup {
    let v = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    soup(
        vec![v(0.0, 0.0), v(1.0, 0.0), v(1.0, 1.0), v(0.0, 1.0)],
        &[[0, 1, 2], [0, 2, 3]],
    )
}

fn lifted(corners: [[f64; 2]; 3], z: f64) -> TriangleSoup {
    soup(
        corners.map(|[x, y]| DVec3::new(x, y, z)).to_vec(),
        &[[0, 1, 2]],
    )
}

#[test]
fn a_face_exactly_epsilon_above_one_triangle_holds() {
    // Corners 0.1, 0.3, ...: the midpoints of subdivision are rounded, so only the exact
    // rational corners prove the tie.
    let from = lifted([[0.6, 0.1], [0.9, 0.3], [0.95, 0.8]], 0.25);
    let s = one_sided(&from, &square(), 0.25, 0.25e-6);
    assert_eq!(s.verdict, Verdict::Holds, "{s:?}");
    assert!(s.upper <= 0.25 && s.subdivisions < 100, "{s:?}");
}

#[test]
fn a_face_exactly_epsilon_above_a_shared_edge_holds() {
    let from = lifted([[0.1, 0.2], [0.9, 0.3], [0.4, 0.8]], 0.25);
    let s = one_sided(&from, &square(), 0.25, 0.25e-6);
    assert_eq!(s.verdict, Verdict::Holds, "{s:?}");
    assert!(s.upper <= 0.25 && s.subdivisions < 100, "{s:?}");
    // Just above epsilon, the same face is violated, with a lower bound above epsilon.
    let s = one_sided(&from, &square(), 0.2499, 0.2499e-6);
    assert_eq!(s.verdict, Verdict::Violated, "{s:?}");
    assert!(s.lower > 0.2499, "{s:?}");
}

#[test]
fn a_tie_at_a_point_the_split_cannot_prove_is_undecided_not_violated() {
    // A fan of six thin triangles around the origin and a face eps above it with a corner
    // right above the fan's centre: the sub-triangles at that corner keep its angle, which
    // spans more than two fan triangles, at every level.
    let mut positions = vec![DVec3::ZERO];
    for k in 0..6 {
        let a = f64::from(k) * std::f64::consts::PI / 12.0 - 0.2;
        positions.push(DVec3::new(a.cos(), a.sin(), 0.0) * 2.0);
    }
    let faces: Vec<[u32; 3]> = (1..6).map(|k| [0, k, k + 1]).collect();
    let fan = soup(positions, &faces);
    let from = lifted([[0.0, 0.0], [1.0, 0.05], [0.6, 0.7]], 0.25);
    let s = one_sided(&from, &fan, 0.25, 0.25e-6);
    assert_ne!(s.verdict, Verdict::Violated, "{s:?}");
    assert!(s.subdivisions <= 1 << 16, "{s:?}");
    // Either way the interval holds epsilon.
    assert!(s.lower <= 0.25 && 0.25 <= s.upper, "{s:?}");
}

/// A fuzzed pair of mostly degenerate triangles (segments meeting at one point), epsilon
/// 1.015625: `approx -> orig` has a witness, and two faces whose ties the budget ends. The
/// verdict is `violated` whatever those two are, so they must not get the full budget.
#[test]
fn a_violated_direction_does_not_spend_the_full_budget_on_undecided_faces() {
    let tris = |p: &[[f64; 3]]| {
        let faces: Vec<[u32; 3]> = (0..p.len() as u32 / 3)
            .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
            .collect();
        soup(
            p.iter().map(|&[x, y, z]| DVec3::new(x, y, z)).collect(),
            &faces,
        )
    };
    let orig = tris(&[
        [0.0, 3.3125, 0.0],
        [-0.3125, 2.5625, 0.125],
        [-0.0625, 1.9375, -0.3125],
        [-0.5625, -0.0625, -0.0625],
        [-0.0625, -0.0625, -0.8125],
        [-0.8125, -0.8125, -0.8125],
        [-0.8125, -0.0625, -0.8125],
        [-0.0625, -0.0625, -0.0625],
        [-0.0625, -0.0625, -0.0625],
        [-0.0625, -0.0625, -0.0625],
        [-0.0625, -0.0625, -0.0625],
        [-0.0625, -0.0625, 2.8125],
    ]);
    let approx = tris(&[
        [0.0, -0.3125, 2.5625],
        [0.125, -0.0625, 1.9375],
        [-0.3125, 2.8125, -0.5625],
        [-0.0625, -0.0625, -0.0625],
        [-0.0625, -0.0625, -0.0625],
        [-0.0625, 2.5, -0.0625],
        [-0.0625, -0.0625, -0.0625],
        [-0.0625, -0.0625, 0.9375],
        [-3.125, -0.0625, -0.0625],
        [-0.0625, 2.5625, -0.0625],
        [-0.0625, -0.0625, 2.5],
        [-0.0625, -0.0625, -0.0625],
        [-0.0625, -0.0625, -0.0625],
        [-0.0625, 4.0625, -0.0625],
        [-0.0625, 0.0, -0.0625],
    ]);
    let s = one_sided(&approx, &orig, 1.015625, 1.015625e-6);
    assert_eq!(s.verdict, Verdict::Violated, "{s:?}");
    assert!(s.lower > 1.015625 && s.subdivisions < 20_000, "{s:?}");
}
