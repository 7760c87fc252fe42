//! The f64 cuts (`split_within_f64` and `pieces_within` in `hausdorff.rs`): a sub-triangle
//! that no single triangle covers, but whose parts on the sides of planes through the
//! shared edges and corners of triangles are each within epsilon of one triangle, is proved
//! at once instead of being subdivided along the edges down to about epsilon.

use envelope_mesh::{TriangleSoup, VertexId};
use envelope_verify::{Verdict, one_sided};
use glam::DVec3;

mod support;
use support::distance;

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

/// A shallow cone: `n` triangles around an apex at height `h` over the origin, the rim at
/// radius 1 in the plane `z = 0`.
fn cone(n: u32, h: f64) -> TriangleSoup {
    let mut p = vec![DVec3::new(0.0, 0.0, h)];
    for k in 0..n {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
        p.push(DVec3::new(a.cos(), a.sin(), 0.0));
    }
    let faces: Vec<[u32; 3]> = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
    soup(p, &faces)
}

/// One flat triangle over the cone's apex, its corners at radius 0.8 between rim vertices.
fn over_apex() -> TriangleSoup {
    let p = (0..3)
        .map(|k| {
            let a = std::f64::consts::TAU * (f64::from(k) / 3.0 + 1.0 / 12.0);
            DVec3::new(0.8 * a.cos(), 0.8 * a.sin(), 0.0)
        })
        .collect();
    soup(p, &[[0, 1, 2]])
}

#[test]
fn a_triangle_over_a_vertex_is_proved_in_pieces() {
    // The triangle's corners are nearest to three faces of the cone that share only the
    // apex: no single face and no cut through a shared edge covers it, cuts through the apex
    // do (`pieces_within`). Its farthest point from the cone is near the apex's foot, at
    // about h (the cone is shallow).
    let h = 0.01;
    let (flat, cone) = (over_apex(), cone(6, h));
    let s = one_sided(&flat, &cone, 1.5 * h, 1e-9);
    assert_eq!(s.verdict, Verdict::Holds, "{s:?}");
    // Subdividing alone takes 89 sub-triangles here (measured with the pieces turned off).
    assert!(s.subdivisions <= 48, "{s:?}");
    assert!(s.upper <= 1.5 * h, "{s:?}");
    // The lower bound still sees the far points the cuts went through.
    assert!(s.lower >= 0.9 * h, "{s:?}");
    // Below the apex's distance, a violation is found all the same.
    let s = one_sided(&flat, &cone, 0.9 * h, 1e-9);
    assert_eq!(s.verdict, Verdict::Violated, "{s:?}");
    assert!(s.lower > 0.9 * h, "{s:?}");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
    /// Triangles over the apex of cones of random valence, height and tilt, at epsilons
    /// around their distance: no sampled point farther than what is proved, and none
    /// farther than epsilon in what holds.
    #[test]
    fn cut_pieces_prove_only_what_holds(
        n in 3u32..10,
        h in 0.002f64..0.05,
        turn in 0.0f64..1.0,
        lift in -0.01f64..0.01,
        tilt in -0.02f64..0.02,
        ratio in 0.6f64..1.6,
    ) {
        let cone = cone(n, h);
        let mut flat = over_apex();
        let (s, c) = (turn * std::f64::consts::TAU).sin_cos();
        for p in &mut flat.positions {
            *p = DVec3::new(c * p.x - s * p.y, s * p.x + c * p.y, lift + tilt * p.x);
        }
        let tri = [flat.positions[0], flat.positions[1], flat.positions[2]];
        let faces: Vec<[DVec3; 3]> = cone
            .faces
            .iter()
            .map(|f| f.map(|v| cone.positions[v.index()]))
            .collect();
        // The farthest sampled point of the triangle from the cone: a lower estimate of the
        // true distance, up to rounding.
        let m = 96;
        let mut far = 0.0f64;
        for i in 0..=m {
            for j in 0..=m - i {
                let (a, b) = (f64::from(i) / f64::from(m), f64::from(j) / f64::from(m));
                let p = tri[0] + (tri[1] - tri[0]) * a + (tri[2] - tri[0]) * b;
                let d = faces.iter().map(|&t| distance(p, t)).fold(f64::INFINITY, f64::min);
                far = far.max(d);
            }
        }
        let eps = ratio * h;
        let r = one_sided(&flat, &cone, eps, eps * 1e-6);
        let rounding = 1e-12;
        proptest::prop_assert!(r.upper >= far - rounding, "{r:?} far {far}");
        if far > eps + rounding {
            proptest::prop_assert!(r.verdict != Verdict::Holds, "{r:?} far {far}");
        }
        proptest::prop_assert!(r.lower <= r.upper, "{r:?}");
    }
}
