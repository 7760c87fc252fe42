//! Every alpha-prism (6-bit scheme plus the faces between cubes) equals the general exact
//! convex hull of its 24 corners, including the degenerate cases of section 4.1: triangles
//! with axis-parallel edges, triangles in a coordinate plane, collinear and repeated
//! vertices, and many coplanar corners.

use envelope_genus::details::{cube_corners, exact_hull_facets};
use envelope_genus::{AlphaPrism, PointLocation};
use glam::DVec3;
use proptest::prelude::*;

fn assert_same_hull(t: [DVec3; 3], alpha: f64) {
    let prism = AlphaPrism::new(t, alpha).unwrap();
    prism.sanity_check().unwrap();
    let mut ours: Vec<Vec<usize>> = prism.facets.iter().map(|f| f.on_plane.clone()).collect();
    ours.sort();
    let exact = exact_hull_facets(&prism.points);
    assert_eq!(ours, exact, "triangle {t:?} alpha {alpha}");
    // The corners generated are exactly the deduplicated cube corners.
    let all: Vec<DVec3> = t.iter().flat_map(|&v| cube_corners(v, alpha)).collect();
    assert!(all.iter().all(|p| prism.points.contains(p)));
    // The triangle itself is strictly inside.
    for v in t {
        assert_eq!(prism.locate(v), PointLocation::Inside);
    }
}

/// Small integer coordinates make axis-parallel edges, coordinate planes, collinear and
/// repeated vertices frequent.
fn grid_point() -> impl Strategy<Value = DVec3> {
    (-3i32..=3, -3i32..=3, -3i32..=3).prop_map(|(x, y, z)| DVec3::new(x.into(), y.into(), z.into()))
}

fn any_point() -> impl Strategy<Value = DVec3> {
    (-10.0f64..10.0, -10.0f64..10.0, -10.0f64..10.0).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn grid_triangles(a in grid_point(), b in grid_point(), c in grid_point(),
                      alpha in prop_oneof![Just(0.5), Just(1.0), Just(1.5), 0.1f64..3.0]) {
        assert_same_hull([a, b, c], alpha);
    }

    #[test]
    fn random_triangles(a in any_point(), b in any_point(), c in any_point(), alpha in 0.01f64..5.0) {
        assert_same_hull([a, b, c], alpha);
    }

    #[test]
    fn triangles_in_a_coordinate_plane(a in any_point(), b in any_point(), c in any_point(),
                                       axis in 0usize..3, alpha in 0.01f64..5.0) {
        let flat = |mut p: DVec3| { p[axis] = 1.25; p };
        assert_same_hull([flat(a), flat(b), flat(c)], alpha);
    }

    #[test]
    fn degenerate_triangles(a in any_point(), b in any_point(), s in -2.0f64..2.0, alpha in 0.01f64..5.0) {
        // Repeated vertex, a point, and (nearly always exactly or nearly) collinear.
        assert_same_hull([a, a, b], alpha);
        assert_same_hull([a, a, a], alpha);
        assert_same_hull([a, b, a + (b - a) * s], alpha);
    }

    #[test]
    fn prisms_meet_iff_some_point_is_shared(a in grid_point(), b in grid_point(), c in grid_point(),
                                            d in grid_point(), alpha in prop_oneof![Just(0.5), 0.1f64..1.5]) {
        // Two degenerate "triangles" (points): cubes meet iff |a - d|_inf <= 2 alpha.
        let p = AlphaPrism::new([a, a, a], alpha).unwrap();
        let q = AlphaPrism::new([d, d, d], alpha).unwrap();
        let close = envelope_genus::details::linf_close(a, d, alpha);
        // Outward rounding may only add contact; with dyadic alpha it is exact.
        if alpha == 0.5 { prop_assert_eq!(p.intersects(&q), close); }
        else if close { prop_assert!(p.intersects(&q)); }
        // A prism meets the prism of any triangle sharing a vertex.
        let r = AlphaPrism::new([a, b, c], alpha).unwrap();
        let s = AlphaPrism::new([c, d, b], alpha).unwrap();
        prop_assert!(r.intersects(&s));
        prop_assert_eq!(r.intersects(&s), s.intersects(&r));
    }
}

#[test]
fn bits_follow_the_paper() {
    let p = AlphaPrism::new([DVec3::ZERO, DVec3::X * 4.0, DVec3::Y * 4.0], 1.0).unwrap();
    // The corner (-1, -1, -1) of the first cube is min x, min y, min z.
    let k = p
        .points
        .iter()
        .position(|&q| q == DVec3::splat(-1.0))
        .unwrap();
    assert_eq!(
        p.bits[k],
        envelope_genus::prism::MIN_X | envelope_genus::prism::MIN_Y | envelope_genus::prism::MIN_Z
    );
    // (5, 1, 1) of the second cube: max x, max z.
    let k = p
        .points
        .iter()
        .position(|&q| q == DVec3::new(5.0, 1.0, 1.0))
        .unwrap();
    assert_eq!(
        p.bits[k],
        envelope_genus::prism::MAX_X | envelope_genus::prism::MAX_Z
    );
}
