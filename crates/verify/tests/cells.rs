//! Proofs by cells (`cells_within` in `hausdorff/cuts.rs`): a face over many triangles a
//! few times larger than epsilon is cut along planes through their edges until each piece
//! is within epsilon of one triangle, instead of being subdivided along every edge it
//! crosses down to about the margin left under epsilon.

use envelope_mesh::{TriangleSoup, VertexId};
use envelope_verify::{Verdict, one_sided};
use glam::DVec3;

mod support;
use support::distance;

fn soup(positions: Vec<DVec3>, faces: &[[u32; 3]]) -> TriangleSoup {
    TriangleSoup::new(positions, faces.iter().map(|f| f.map(VertexId)).collect())
}

/// A height field over the unit square: `n x n` cells, each split along a diagonal chosen
/// by `flip(i, j)`, heights `z(x, y)`.
fn grid(n: u32, z: impl Fn(f64, f64) -> f64, flip: impl Fn(u32, u32) -> bool) -> TriangleSoup {
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
            p.push(DVec3::new(x, y, z(x, y)));
        }
    }
    let at = |i: u32, j: u32| j * (n + 1) + i;
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if flip(i, j) {
                faces.extend([[a, b, d], [b, c, d]]);
            } else {
                faces.extend([[a, b, c], [a, c, d]]);
            }
        }
    }
    soup(p, &faces)
}

/// One triangle with the given corners (x, y, z).
fn triangle(corners: [[f64; 3]; 3]) -> TriangleSoup {
    soup(corners.map(DVec3::from_array).to_vec(), &[[0, 1, 2]])
}

/// The farthest of `m`-per-side samples of `from`'s first triangle from `to`: a lower
/// estimate of the one-sided distance, up to rounding.
fn sampled_distance(from: &TriangleSoup, to: &TriangleSoup, m: u32) -> f64 {
    let tri = from.faces[0].map(|v| from.positions[v.index()]);
    let faces: Vec<[DVec3; 3]> = to
        .faces
        .iter()
        .map(|f| f.map(|v| to.positions[v.index()]))
        .collect();
    let mut far = 0.0f64;
    for i in 0..=m {
        for j in 0..=m - i {
            let (a, b) = (f64::from(i) / f64::from(m), f64::from(j) / f64::from(m));
            let p = tri[0] + (tri[1] - tri[0]) * a + (tri[2] - tri[0]) * b;
            let d = faces
                .iter()
                .map(|&t| distance(p, t))
                .fold(f64::INFINITY, f64::min);
            far = far.max(d);
        }
    }
    far
}

#[test]
fn a_thin_face_over_a_bowl_is_proved_in_a_few_pieces_per_triangle() {
    // A shallow bowl of 2 x 16 x 16 triangles 1/16 wide and a thin flat triangle across it
    // (a simplifier's output has many), at an epsilon just above its distance (about 1/64
    // of a triangle's width): a sub-triangle is proved only where it is within epsilon of
    // one triangle, and a thin one crosses many; the pieces between the planes through the
    // bowl's edges are each near one.
    let a = 0.005;
    let bowl = grid(
        16,
        |x, y| a * ((x - 0.5).powi(2) + (y - 0.5).powi(2)),
        |i, j| (i + j) % 2 == 0,
    );
    let z = a * 0.05;
    let flat = triangle([[0.05, 0.3, z], [0.95, 0.55, z], [0.1, 0.45, z]]);
    let far = sampled_distance(&flat, &bowl, 200);
    let eps = far * 1.01;
    let s = one_sided(&flat, &bowl, eps, eps * 1e-9);
    assert_eq!(s.verdict, Verdict::Holds, "{s:?}");
    assert!(s.upper <= eps, "{s:?}");
    // About 31 triangles lie under the face. Subdividing alone takes 405 sub-triangles here
    // (measured with the cells turned off), the cells 197 pieces and sub-triangles.
    assert!(s.subdivisions <= 250, "{s:?}");
    // Below the sampled distance, a violation is found all the same.
    let below = far * 0.999;
    let s = one_sided(&flat, &bowl, below, below * 1e-9);
    assert_eq!(s.verdict, Verdict::Violated, "{s:?}");
    assert!(s.lower > below, "{s:?}");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
    /// Flat triangles over random height fields of triangles larger than epsilon, at
    /// epsilons around their distance: no sampled point farther than what is proved, and
    /// none farther than epsilon in what holds.
    #[test]
    fn cells_prove_only_what_holds(
        n in 4u32..10,
        heights in proptest::collection::vec(-1.0f64..1.0, 121),
        amplitude in 0.001f64..0.02,
        flips in proptest::collection::vec(proptest::bool::ANY, 100),
        corners in proptest::collection::vec(0.05f64..0.95, 6),
        lift in -0.01f64..0.01,
        tilt in [-0.01f64..0.01, -0.01f64..0.01],
        ratio in 0.8f64..1.2,
    ) {
        let field = grid(
            n,
            |x, y| {
                let k = (y * f64::from(n)).round() as usize * 11 + (x * f64::from(n)).round() as usize;
                amplitude * heights[k]
            },
            |i, j| flips[(j * 10 + i) as usize],
        );
        let flat = triangle(std::array::from_fn(|k| {
            let (x, y) = (corners[2 * k], corners[2 * k + 1]);
            [x, y, lift + tilt[0] * x + tilt[1] * y]
        }));
        let far = sampled_distance(&flat, &field, 64);
        let eps = (ratio * far).max(1e-6);
        let r = one_sided(&flat, &field, eps, eps * 1e-9);
        let rounding = 1e-12;
        proptest::prop_assert!(r.upper >= far - rounding, "{r:?} far {far}");
        if far > eps + rounding {
            proptest::prop_assert!(r.verdict != Verdict::Holds, "{r:?} far {far}");
        }
        proptest::prop_assert!(r.lower <= r.upper, "{r:?}");
    }
}
