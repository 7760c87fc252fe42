//! Property tests: filtered == exact on near-degenerate inputs (through `Checked`), symmetry
//! and permutation laws, and consistency between intersection and distance predicates.

use envelope_predicates::generic as g;
use envelope_predicates::{Checked, Exact, Filtered, Kernel, Orientation, Sign};
use glam::DVec3;
use proptest::prelude::*;

#[cfg(not(feature = "gmp"))]
type K = Checked<Filtered, Exact>;
/// With the feature `gmp` the two exact kernels are checked against each other too.
#[cfg(feature = "gmp")]
type K = Checked<Filtered, Checked<Exact, envelope_predicates::ExactGmp>>;

fn coord() -> impl Strategy<Value = f64> {
    prop_oneof![
        // Small integer grid, scaled by a power of ten: many exact degeneracies.
        (-4i32..=4, 0u32..4).prop_map(|(i, k)| i as f64 / 10f64.powi(k as i32)),
        // Plain doubles.
        -10.0f64..10.0,
    ]
}

fn point() -> impl Strategy<Value = DVec3> {
    (coord(), coord(), coord()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// A point, or a point snapped onto a line/plane through other points (near-degenerate).
fn near_point(a: DVec3, b: DVec3, c: DVec3) -> impl Strategy<Value = DVec3> {
    prop_oneof![
        point(),
        (-2.0f64..3.0).prop_map(move |t| a + (b - a) * t),
        (-1.0f64..2.0, -1.0f64..2.0).prop_map(move |(s, t)| a + (b - a) * s + (c - a) * t),
        Just(a),
        Just((a + b) * 0.5),
    ]
}

fn tri_pair() -> impl Strategy<Value = ([DVec3; 3], [DVec3; 3])> {
    (point(), point(), point()).prop_flat_map(|(a, b, c)| {
        let t1 = [a, b, c];
        (
            near_point(a, b, c),
            near_point(a, b, c),
            near_point(b, c, a),
        )
            .prop_map(move |(p, q, r)| (t1, [p, q, r]))
    })
}

fn eps2() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        (0u32..40).prop_map(|i| i as f64 / 16.0),
        0.0f64..4.0
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    #[test]
    fn orient3d_permutation_laws((t, u) in tri_pair()) {
        let [a, b, c] = t;
        let d = u[0];
        let o = K::orient3d(a, b, c, d);
        prop_assert_eq!(K::orient3d(b, a, c, d), o.reverse());
        prop_assert_eq!(K::orient3d(a, c, b, d), o.reverse());
        prop_assert_eq!(K::orient3d(a, b, d, c), o.reverse());
        prop_assert_eq!(K::orient3d(b, c, a, d), o);
        prop_assert_eq!(K::orient3d(d, a, b, c).reverse(), o);
        let _ = K::insphere(a, b, c, d, u[1]);
    }

    #[test]
    fn tri_tri_symmetric_and_rotation_invariant((t1, t2) in tri_pair()) {
        let r = g::triangles_intersect::<K>(t1, t2);
        prop_assert_eq!(g::triangles_intersect::<K>(t2, t1), r);
        prop_assert_eq!(g::triangles_intersect::<K>([t1[1], t1[2], t1[0]], t2), r);
        prop_assert_eq!(g::triangles_intersect::<K>(t1, [t2[2], t2[0], t2[1]]), r);
        prop_assert_eq!(g::triangles_intersect::<K>([t1[0], t1[2], t1[1]], [t2[1], t2[0], t2[2]]), r);
        // Intersection iff distance zero.
        prop_assert_eq!(g::cmp_triangle_triangle::<K>(t1, t2, 0.0) == Sign::Zero, r);
        // Intersection iff an edge of one meets the other (closed triangles: the
        // intersection, when there is one, has a point on an edge of one of them).
        let edge_meets = |a: [DVec3; 3], b: [DVec3; 3]| {
            (0..3).any(|i| g::segment_triangle::<K>(a[i], a[(i + 1) % 3], b).intersects())
        };
        prop_assert_eq!(edge_meets(t1, t2) || edge_meets(t2, t1), r);
        let ov = g::triangles_overlap_with_area::<K>(t1, t2);
        prop_assert_eq!(g::triangles_overlap_with_area::<K>(t2, [t1[2], t1[1], t1[0]]), ov);
        prop_assert!(!ov || r);
    }

    #[test]
    fn segment_triangle_consistent((t, u) in tri_pair()) {
        let (p, q) = (u[0], u[1]);
        let st = g::segment_triangle::<K>(p, q, t);
        prop_assert_eq!(g::segment_triangle::<K>(q, p, t).intersects(), st.intersects());
        prop_assert_eq!(g::segment_triangle::<K>(p, q, [t[1], t[2], t[0]]).intersects(), st.intersects());
        prop_assert_eq!(g::cmp_segment_triangle::<K>(p, q, t, 0.0) == Sign::Zero, st.intersects());
        // A segment meets a triangle iff the degenerate triangle (p, q, q) meets it.
        prop_assert_eq!(g::triangles_intersect::<K>([p, q, q], t), st.intersects());
    }

    #[test]
    fn distances_agree_and_are_monotone((t1, t2) in tri_pair(), e in eps2()) {
        let p = t2[0];
        let s = g::cmp_point_triangle::<K>(p, t1, e);
        prop_assert_eq!(g::cmp_point_triangle::<K>(p, [t1[2], t1[0], t1[1]], e), s);
        // Monotone in eps2.
        if s == Sign::Negative { prop_assert_eq!(g::cmp_point_triangle::<K>(p, t1, e + 1.0), Sign::Negative); }
        let tt = g::cmp_triangle_triangle::<K>(t1, t2, e);
        prop_assert_eq!(g::cmp_triangle_triangle::<K>(t2, t1, e), tt);
        // dist(t1, t2) <= dist(p, t1) since p is a vertex of t2.
        prop_assert!(tt <= s);
        let ss = g::cmp_segment_segment::<K>(t1[0], t1[1], t2[0], t2[1], e);
        prop_assert_eq!(g::cmp_segment_segment::<K>(t2[1], t2[0], t1[1], t1[0], e), ss);
        prop_assert!(tt <= ss);
        let st = g::cmp_segment_triangle::<K>(t2[0], t2[1], t1, e);
        prop_assert!(tt <= st && st <= s);
    }

    #[test]
    fn point_triangle_distance_matches_float_reference(t in (point(), point(), point()), p in point()) {
        let t = [t.0, t.1, t.2];
        let d2 = reference_sq_dist(p, t);
        // Away from the decision boundary the exact answer must match the f64 reference.
        if d2 > 1e-6 {
            prop_assert_eq!(g::cmp_point_triangle::<K>(p, t, d2 * (1.0 + 1e-9)), Sign::Negative);
            prop_assert_eq!(g::cmp_point_triangle::<K>(p, t, d2 * (1.0 - 1e-9)), Sign::Positive);
        }
    }

    #[test]
    fn collinear_and_segment_laws(a in point(), b in point(), t in -2.0f64..3.0) {
        let p = a + (b - a) * t;
        let c = g::collinear::<K>(a, b, p);
        prop_assert_eq!(g::collinear::<K>(p, b, a), c);
        prop_assert_eq!(g::collinear::<K>(b, p, a), c);
        let inside = g::point_strictly_inside_segment::<K>(p, a, b);
        prop_assert_eq!(g::point_strictly_inside_segment::<K>(p, b, a), inside);
        prop_assert!(!inside || (c && p != a && p != b));
    }

    #[test]
    fn orient2d_laws(a in point(), b in point(), c in point()) {
        let (a, b, c) = (a.truncate(), b.truncate(), c.truncate());
        let o = K::orient2d(a, b, c);
        prop_assert_eq!(K::orient2d(b, c, a), o);
        prop_assert_eq!(K::orient2d(b, a, c), o.reverse());
        prop_assert_eq!(o == Orientation::Degenerate, K::orient2d(a, c, b) == Orientation::Degenerate);
    }
}

/// Plain f64 point–triangle squared distance (Ericson, Real-Time Collision Detection 5.1.5).
fn reference_sq_dist(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let seg = |a: DVec3, b: DVec3| {
        let ab = b - a;
        let l = ab.length_squared();
        let t = if l > 0.0 {
            ((p - a).dot(ab) / l).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (a + ab * t - p).length_squared()
    };
    let mut best = seg(a, b).min(seg(b, c)).min(seg(c, a));
    let n = (b - a).cross(c - a);
    let nn = n.length_squared();
    if nn > 1e-12 {
        let d = (p - a).dot(n);
        let q = p - n * (d / nn);
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(x, y)| (y - x).cross(q - x).dot(n) >= 0.0);
        if inside {
            best = best.min(d * d / nn);
        }
    }
    best
}

/// `n` points `v + i u + j w` of a plane through `v` spanned by small integer vectors `u`, `w`
/// (not parallel), with `i, j` in `-4..=4`: integer coordinates, so every orientation is exact
/// and many are exactly zero.
fn plane_points(v: DVec3, n: usize) -> impl Strategy<Value = Vec<DVec3>> {
    let int3 = || (-2i32..=2, -2i32..=2, -2i32..=2);
    let d = |(x, y, z): (i32, i32, i32)| DVec3::new(x.into(), y.into(), z.into());
    (int3(), int3())
        .prop_map(move |(u, w)| (d(u), d(w)))
        .prop_filter("a plane", |(u, w)| u.cross(*w) != DVec3::ZERO)
        .prop_flat_map(move |(u, w)| {
            prop::collection::vec((-4i32..=4, -4i32..=4), n).prop_map(move |ij| {
                ij.iter()
                    .map(|&(i, j)| v + u * f64::from(i) + w * f64::from(j))
                    .collect()
            })
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]
    /// Coplanar faces sharing one vertex (the 2-D shortcut of `adjacent_triangles_intersect`)
    /// against an independent answer: they meet beyond `v` iff a point just off `v` along one
    /// of the four edges at `v` lies in both closed triangles (`point_in_triangle`; the
    /// offset `(x - v) / 65536` is exact on these integer coordinates and well inside both
    /// triangles' reach from `v`).
    #[test]
    fn coplanar_faces_at_a_vertex_meet_as_their_sectors_do(
        p in plane_points(DVec3::new(3.0, -1.0, 2.0), 4),
    ) {
        let v = DVec3::new(3.0, -1.0, 2.0);
        let (t1, t2) = ([v, p[0], p[1]], [v, p[2], p[3]]);
        prop_assume!(!g::collinear::<K>(v, p[0], p[1]) && !g::collinear::<K>(v, p[2], p[3]));
        let near = |x: DVec3| v + (x - v) / 65536.0;
        let reference = p.iter().any(|&x| {
            let q = near(x);
            g::point_in_triangle::<K>(q, t1) != g::TriangleLocation::Outside
                && g::point_in_triangle::<K>(q, t2) != g::TriangleLocation::Outside
        });
        let got = g::adjacent_triangles_intersect::<K>(t1, t2, g::Shared::Vertex(0, 0));
        prop_assert_eq!(got, reference, "t1 {:?} t2 {:?}", t1, t2);
        // Symmetric, and the same with the vertex elsewhere in the triangles.
        prop_assert_eq!(g::adjacent_triangles_intersect::<K>(t2, t1, g::Shared::Vertex(0, 0)), got);
        let r2 = [t2[1], t2[2], v];
        prop_assert_eq!(g::adjacent_triangles_intersect::<K>(t1, r2, g::Shared::Vertex(0, 2)), got);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]
    /// Coplanar triangles (the 2-D shortcut of `triangles_intersect`) against the general
    /// characterisation: two closed triangles meet iff an edge of one meets the other
    /// (`segment_triangle`, which decides coplanar segments on its own path).
    #[test]
    fn coplanar_triangles_meet_iff_an_edge_meets(p in plane_points(DVec3::new(-1.0, 2.0, 5.0), 6)) {
        let (t1, t2) = ([p[0], p[1], p[2]], [p[3], p[4], p[5]]);
        let edge_meets = |a: [DVec3; 3], b: [DVec3; 3]| {
            (0..3).any(|i| g::segment_triangle::<K>(a[i], a[(i + 1) % 3], b).intersects())
        };
        let reference = edge_meets(t1, t2) || edge_meets(t2, t1);
        prop_assert_eq!(g::triangles_intersect::<K>(t1, t2), reference, "{:?} {:?}", t1, t2);
        prop_assert_eq!(g::triangles_intersect::<K>(t2, t1), reference);
        prop_assert_eq!(g::triangles_intersect::<K>([t1[1], t1[2], t1[0]], [t2[0], t2[2], t2[1]]), reference);
    }
}

/// A scale that keeps every coordinate in the adaptive range (1), or pushes some below or
/// above it (the free functions then take the exact path for the whole predicate).
fn scale() -> impl Strategy<Value = f64> {
    prop_oneof![4 => Just(1.0), 1 => Just(1e-125), 1 => Just(1e38), 1 => Just(2f64.powi(-118))]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    /// The crate's free functions check the range of all their points once and then skip it
    /// in every orientation test; their answers are the exact kernel's, in range or not.
    #[test]
    fn free_functions_are_the_exact_answers((t1, t2) in tri_pair(), s in scale()) {
        use envelope_predicates::{indexed_triangles_intersect, segment_triangle, triangles_intersect};
        let (t1, t2) = (t1.map(|p| p * s), t2.map(|p| p * s));
        prop_assert_eq!(triangles_intersect(t1, t2), g::triangles_intersect::<Exact>(t1, t2));
        prop_assert_eq!(
            segment_triangle(t2[0], t2[1], t1),
            g::segment_triangle::<Exact>(t2[0], t2[1], t1)
        );
        // Sharing a vertex, then an edge (ids name corners; positions follow the ids).
        let v = [t1[0], t2[1], t2[2]];
        let shared = indexed_triangles_intersect(t1, [0, 1, 2], v, [0, 4, 5]);
        prop_assert_eq!(
            shared,
            g::adjacent_triangles_intersect::<Exact>(t1, v, envelope_predicates::Shared::Vertex(0, 0))
        );
        let e = [t1[0], t1[1], t2[2]];
        prop_assert_eq!(
            indexed_triangles_intersect(t1, [0, 1, 2], e, [0, 1, 5]),
            g::adjacent_triangles_intersect::<Exact>(t1, e, envelope_predicates::Shared::Edge([0, 1], [0, 1]))
        );
        // `faces_intersect` (f64 pre-tests, then exact) on the same three cases, both orders.
        let pos = [t1[0], t1[1], t1[2], t2[0], t2[1], t2[2]];
        let cases = [
            ([3, 4, 5], g::triangles_intersect::<Exact>(t1, t2)),
            ([0, 4, 5], shared),
            ([0, 1, 5], g::adjacent_triangles_intersect::<Exact>(t1, e, envelope_predicates::Shared::Edge([0, 1], [0, 1]))),
        ];
        for (other, expected) in cases {
            prop_assert_eq!(envelope_predicates::faces_intersect(&pos, [0, 1, 2], other), expected);
            prop_assert_eq!(envelope_predicates::faces_intersect(&pos, other, [1, 2, 0]), expected);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    /// `prepared_faces_intersect` gives `faces_intersect`'s answers (which the test above
    /// ties to the exact kernel), with no, one and two shared vertices, in both orders.
    #[test]
    fn prepared_faces_give_the_same_answers((t1, t2) in tri_pair(), s in scale()) {
        use envelope_predicates::{faces_intersect, prepared_faces_intersect, PreparedFace};
        let pos: Vec<DVec3> = t1.iter().chain(&t2).map(|&p| p * s).collect();
        for (f, g) in [([0, 1, 2], [3, 4, 5]), ([0, 1, 2], [0, 4, 5]), ([0, 1, 2], [2, 1, 5]), ([0, 1, 2], [1, 2, 0])] {
            let (a, b) = (PreparedFace::new(&pos, f), PreparedFace::new(&pos, g));
            prop_assert_eq!(prepared_faces_intersect(&a, &b), faces_intersect(&pos, f, g));
            prop_assert_eq!(prepared_faces_intersect(&b, &a), faces_intersect(&pos, g, f));
        }
    }
}

/// The crossing number of `polyline_crossings`' docs, from other exact predicates: undecided
/// when a path point lies in a triangle's plane (a degenerate triangle's plane is
/// everywhere) or a segment crosses a triangle through an edge or a vertex; otherwise each
/// segment that crosses a triangle's interior (`segment_triangle` on the exact kernel) counts
/// `+1` when it ends on the positive side, `-1` when on the negative one.
fn crossings_by_definition(path: &[DVec3], tris: &[[DVec3; 3]]) -> Option<i32> {
    use envelope_predicates::TriangleLocation::Interior;
    use envelope_predicates::{SegmentTriangle, TriangleLocation};
    if path.len() < 2 {
        return Some(0);
    }
    let in_a_plane = tris.iter().any(|t| {
        path.iter()
            .any(|&x| Exact::orient3d(t[0], t[1], t[2], x) == Orientation::Degenerate)
    });
    if in_a_plane {
        return None;
    }
    let mut sum = 0;
    for t in tris {
        for s in path.windows(2) {
            match g::segment_triangle::<Exact>(s[0], s[1], *t) {
                SegmentTriangle::Crossing(Interior) => {
                    let end = Exact::orient3d(t[0], t[1], t[2], s[1]);
                    sum += if end == Orientation::Positive { 1 } else { -1 };
                }
                SegmentTriangle::Crossing(
                    TriangleLocation::Edge(_) | TriangleLocation::Vertex(_),
                ) => {
                    return None;
                }
                _ => {}
            }
        }
    }
    Some(sum)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// A decided crossing number of a path with a closed outward-oriented surface (a
    /// tetrahedron) is the change of containment between its ends: +1 from inside to
    /// outside, -1 back, 0 when both are on one side (`point_in_surface` counts ray
    /// crossings by parity, independently). Random paths of one and two segments, many
    /// through the grid's degeneracies (those are undecided: `None`).
    #[test]
    fn polyline_crossings_are_the_change_of_containment(
        corners in (point(), point(), point(), point()),
        path in prop::collection::vec(point(), 2..4),
    ) {
        use envelope_predicates::{Containment, orient3d, point_in_surface, polyline_crossings};
        let (a, b, c, d) = corners;
        let mut pos = vec![a, b, c, d];
        match orient3d(a, b, c, d) {
            Orientation::Degenerate => return Ok(()),
            // Faces below are outward for d on the negative side of abc.
            Orientation::Positive => pos.swap(0, 1),
            Orientation::Negative => {}
        }
        let faces = [[0u32, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]];
        let tris: Vec<[DVec3; 3]> = faces.iter().map(|f| f.map(|i| pos[i as usize])).collect();
        let inside = |p: DVec3| match point_in_surface(p, &pos, &faces) {
            Containment::Inside => Some(1),
            Containment::Outside => Some(0),
            Containment::On => None,
        };
        let (Some(first), Some(last)) = (inside(path[0]), inside(path[path.len() - 1])) else {
            return Ok(());
        };
        if let Some(n) = polyline_crossings(&path, &tris) {
            prop_assert_eq!(n, first - last);
            prop_assert_eq!(Some(n), g::polyline_crossings::<K>(&path, &tris));
        }
    }

    /// The crate's `polyline_crossings` (in range: each plane side of the path's points
    /// asked once, of the f64 plane first) and the generic one on the checking kernel answer
    /// what the definition does, `None` included: paths of one to twelve points (past the cached
    /// length of eight) through triangles (degenerate ones among them, on the grid of small
    /// integers), crossing them, or with path points in their planes, on edges, at corners.
    #[test]
    fn polyline_crossings_match_the_exact_kernel(
        tris in prop::collection::vec((point(), point(), point()), 1..5),
        path in prop::collection::vec((point(), 0u8..6), 1..13),
        on_planes in any::<bool>(),
    ) {
        use envelope_predicates::polyline_crossings;
        let tris: Vec<[DVec3; 3]> = tris.iter().map(|&(a, b, c)| [a, b, c]).collect();
        // Some path points put on a triangle's plane, edge or corner (only when `on_planes`:
        // any of them makes the count undecided), or above and below its centroid
        // (consecutive ones then cross it).
        let path: Vec<DVec3> = path
            .iter()
            .enumerate()
            .map(|(i, &(p, k))| {
                // Points two by two around one triangle.
                let t = tris[(i / 2) % tris.len()];
                let centroid = (t[0] + t[1] + t[2]) / 3.0;
                let normal = (t[1] - t[0]).cross(t[2] - t[0]);
                match k {
                    0 => p,
                    1..=3 if !on_planes => p,
                    1 => t[0] + (t[1] - t[0]) * 0.5,
                    2 => t[0] + (t[1] - t[0]) * 0.25 + (t[2] - t[0]) * 0.5,
                    3 => t[2],
                    4 => centroid + normal,
                    _ => centroid - normal,
                }
            })
            .collect();
        let expected = crossings_by_definition(&path, &tris);
        prop_assert_eq!(polyline_crossings(&path, &tris), expected);
        prop_assert_eq!(g::polyline_crossings::<K>(&path, &tris), expected);
    }

    /// `strictly_one_side_of_plane` is every point's `orient3d` equal and non-zero.
    #[test]
    fn one_side_of_a_plane_is_equal_orientations(t in (point(), point(), point()), pts in prop::collection::vec(point(), 1..4)) {
        use envelope_predicates::{orient3d, strictly_one_side_of_plane};
        let t = [t.0, t.1, t.2];
        let o: Vec<Orientation> = pts.iter().map(|&p| orient3d(t[0], t[1], t[2], p)).collect();
        let expected = o[0] != Orientation::Degenerate && o.iter().all(|&x| x == o[0]);
        prop_assert_eq!(strictly_one_side_of_plane(t, &pts), expected);
        prop_assert_eq!(g::strictly_one_side_of_plane::<K>(t, &pts), expected);
    }
}
