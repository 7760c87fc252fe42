//! Hand-known answers for every derived predicate and its degenerate cases, on the checked kernel.

use envelope_predicates::generic::{self as g};
use envelope_predicates::{
    Checked, Containment, Exact, Filtered, SegmentTriangle, Shared, Sign, TriangleLocation,
};
use glam::DVec3;

#[cfg(not(feature = "gmp"))]
type K = Checked<Filtered, Exact>;
/// With the feature `gmp` the two exact kernels are checked against each other too.
#[cfg(feature = "gmp")]
type K = Checked<Filtered, Checked<Exact, envelope_predicates::ExactGmp>>;

fn d3(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

const T: [DVec3; 3] = [
    DVec3::ZERO,
    DVec3::new(2.0, 0.0, 0.0),
    DVec3::new(0.0, 2.0, 0.0),
];

#[test]
fn collinear_and_t_junctions() {
    let (a, b) = (d3(0.0, 0.0, 0.0), d3(3.0, 3.0, 3.0));
    assert!(g::collinear::<K>(a, b, d3(1.0, 1.0, 1.0)));
    assert!(g::collinear::<K>(a, a, d3(1.0, 2.0, 3.0)));
    assert!(!g::collinear::<K>(a, b, d3(1.0, 1.0, 1.0 + 1e-15)));
    assert!(g::point_strictly_inside_segment::<K>(
        d3(1.0, 1.0, 1.0),
        a,
        b
    ));
    assert!(!g::point_strictly_inside_segment::<K>(a, a, b));
    assert!(!g::point_strictly_inside_segment::<K>(
        d3(4.0, 4.0, 4.0),
        a,
        b
    ));
    assert!(!g::point_strictly_inside_segment::<K>(a, a, a));
    assert!(g::point_on_segment::<K>(b, a, b));
    assert!(g::point_on_segment::<K>(a, a, a));
    // 0.1 * 3 is not 0.3 in doubles: (0.1, 0.2, 0.3) is not on the line through 0 and (1, 2, 3)?
    // It is: 0.2 = 2 * 0.1 and 0.3 vs 3 * 0.1 differ, so not collinear.
    assert!(!g::collinear::<K>(a, d3(1.0, 2.0, 3.0), d3(0.1, 0.2, 0.3)));
    assert!(g::collinear::<K>(a, d3(1.0, 2.0, 4.0), d3(0.25, 0.5, 1.0)));
}

#[test]
fn point_in_triangle_all_cases() {
    use TriangleLocation::*;
    assert_eq!(g::point_in_triangle::<K>(d3(0.5, 0.5, 0.0), T), Interior);
    assert_eq!(g::point_in_triangle::<K>(d3(1.0, 0.0, 0.0), T), Edge(0));
    assert_eq!(g::point_in_triangle::<K>(d3(1.0, 1.0, 0.0), T), Edge(1));
    assert_eq!(g::point_in_triangle::<K>(d3(0.0, 1.0, 0.0), T), Edge(2));
    assert_eq!(g::point_in_triangle::<K>(T[0], T), Vertex(0));
    assert_eq!(g::point_in_triangle::<K>(T[1], T), Vertex(1));
    assert_eq!(g::point_in_triangle::<K>(T[2], T), Vertex(2));
    assert_eq!(g::point_in_triangle::<K>(d3(1.5, 1.5, 0.0), T), Outside);
    assert_eq!(g::point_in_triangle::<K>(d3(0.5, 0.5, 1e-300), T), Outside);
    // Vertical triangle (normal along x): the projection must not lose it.
    let v = [d3(0.0, 0.0, 0.0), d3(0.0, 1.0, 0.0), d3(0.0, 0.0, 1.0)];
    assert_eq!(g::point_in_triangle::<K>(d3(0.0, 0.25, 0.25), v), Interior);
    assert_eq!(g::point_in_triangle::<K>(d3(0.0, 0.5, 0.5), v), Edge(1));
    // Degenerate triangles: a segment and a point.
    let seg = [d3(0.0, 0.0, 0.0), d3(1.0, 1.0, 1.0), d3(2.0, 2.0, 2.0)];
    assert_eq!(g::point_in_triangle::<K>(d3(0.5, 0.5, 0.5), seg), Edge(0));
    assert_eq!(g::point_in_triangle::<K>(d3(1.0, 1.0, 1.0), seg), Vertex(1));
    assert_eq!(g::point_in_triangle::<K>(d3(3.0, 3.0, 3.0), seg), Outside);
    let pt = [DVec3::ONE; 3];
    assert_eq!(g::point_in_triangle::<K>(DVec3::ONE, pt), Vertex(0));
    assert_eq!(g::point_in_triangle::<K>(DVec3::ZERO, pt), Outside);
}

#[test]
fn segment_triangle_all_cases() {
    use SegmentTriangle::*;
    use TriangleLocation::*;
    let st = |p: DVec3, q: DVec3| g::segment_triangle::<K>(p, q, T);
    let vert = |x: f64, y: f64| (d3(x, y, 1.0), d3(x, y, -1.0));
    let (p, q) = vert(0.5, 0.5);
    assert_eq!(st(p, q), Crossing(Interior));
    let (p, q) = vert(1.0, 0.0);
    assert_eq!(st(p, q), Crossing(Edge(0)));
    let (p, q) = vert(2.0, 0.0);
    assert_eq!(st(p, q), Crossing(Vertex(1)));
    let (p, q) = vert(2.0, 2.0);
    assert_eq!(st(p, q), Disjoint);
    // Endpoint touching.
    assert_eq!(
        st(d3(0.5, 0.5, 0.0), d3(0.5, 0.5, 1.0)),
        Endpoint {
            endpoint: 0,
            location: Interior
        }
    );
    assert_eq!(
        st(d3(9.0, 9.0, 1.0), d3(0.0, 2.0, 0.0)),
        Endpoint {
            endpoint: 1,
            location: Vertex(2)
        }
    );
    assert_eq!(st(d3(3.0, 3.0, 0.0), d3(3.0, 3.0, 1.0)), Disjoint);
    // Same side.
    assert_eq!(st(d3(0.5, 0.5, 1.0), d3(0.5, 0.5, 2.0)), Disjoint);
    // Coplanar: inside, crossing an edge, touching a vertex, outside.
    assert_eq!(st(d3(0.2, 0.2, 0.0), d3(0.3, 0.3, 0.0)), Coplanar);
    assert_eq!(st(d3(-1.0, 0.5, 0.0), d3(3.0, 0.5, 0.0)), Coplanar);
    assert_eq!(st(d3(2.0, 0.0, 0.0), d3(3.0, -1.0, 0.0)), Coplanar);
    assert_eq!(st(d3(3.0, 0.0, 0.0), d3(0.0, 3.0, 0.0)), Disjoint);
    // Degenerate segment (a point).
    assert_eq!(st(d3(0.5, 0.5, 0.0), d3(0.5, 0.5, 0.0)), Coplanar);
    assert_eq!(st(d3(0.5, 0.5, 1.0), d3(0.5, 0.5, 1.0)), Disjoint);
    // Degenerate triangle (a segment on the x axis).
    let dt = [d3(0.0, 0.0, 0.0), d3(1.0, 0.0, 0.0), d3(2.0, 0.0, 0.0)];
    assert_eq!(
        g::segment_triangle::<K>(d3(1.5, -1.0, 0.0), d3(1.5, 1.0, 0.0), dt),
        DegenerateTriangle
    );
    assert_eq!(
        g::segment_triangle::<K>(d3(1.5, -1.0, 1.0), d3(1.5, 1.0, 1.0), dt),
        Disjoint
    );
    assert_eq!(
        g::segment_triangle::<K>(d3(2.0, 0.0, 0.0), d3(5.0, 0.0, 0.0), dt),
        DegenerateTriangle
    );
    assert_eq!(
        g::segment_triangle::<K>(d3(2.5, 0.0, 0.0), d3(5.0, 0.0, 0.0), dt),
        Disjoint
    );
}

#[test]
fn segments_intersect_cases() {
    let s = |a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]| {
        g::segments_intersect::<K>(
            DVec3::from(a),
            DVec3::from(b),
            DVec3::from(c),
            DVec3::from(d),
        )
    };
    assert!(s([0., 0., 0.], [2., 2., 0.], [0., 2., 0.], [2., 0., 0.]));
    assert!(!s([0., 0., 0.], [2., 2., 0.], [0., 2., 1.], [2., 0., 1.]));
    assert!(s([0., 0., 0.], [2., 2., 2.], [1., 1., 1.], [5., 5., 5.])); // collinear overlap
    assert!(s([0., 0., 0.], [2., 2., 2.], [2., 2., 2.], [5., 5., 5.])); // collinear touch
    assert!(!s([0., 0., 0.], [2., 2., 2.], [3., 3., 3.], [5., 5., 5.])); // collinear apart
    assert!(s([1., 1., 1.], [1., 1., 1.], [0., 0., 0.], [2., 2., 2.])); // point on segment
    assert!(!s([1., 1., 1.], [1., 1., 1.], [2., 2., 2.], [2., 2., 2.])); // two points
    assert!(s([0., 0., 0.], [0., 0., 4.], [0., 0., 4.], [1., 7., 4.])); // T at endpoint
}

#[test]
fn triangles_intersect_cases() {
    let ti = |a: [DVec3; 3], b: [DVec3; 3]| g::triangles_intersect::<K>(a, b);
    let shift = |t: [DVec3; 3], v: DVec3| t.map(|p| p + v);
    // Piercing.
    let pierce = [d3(0.5, 0.5, -1.0), d3(0.5, 0.5, 1.0), d3(5.0, 5.0, 0.0)];
    assert!(ti(T, pierce));
    assert!(!ti(T, shift(pierce, d3(0.0, 0.0, 1.5))));
    // Touching at a vertex, at an edge, edge across edge.
    assert!(ti(
        T,
        [d3(2.0, 0.0, 0.0), d3(3.0, 0.0, 1.0), d3(3.0, 1.0, 1.0)]
    ));
    assert!(ti(
        T,
        [d3(0.0, 0.0, 0.0), d3(2.0, 0.0, 0.0), d3(1.0, 0.0, 5.0)]
    ));
    assert!(ti(
        T,
        [d3(1.0, -1.0, 0.0), d3(1.0, 1.0, 0.0), d3(1.0, 0.0, 3.0)]
    ));
    // Coplanar overlap, containment, and disjoint.
    assert!(ti(T, shift(T, d3(0.5, 0.5, 0.0))));
    assert!(ti(
        T,
        [d3(0.1, 0.1, 0.0), d3(0.2, 0.1, 0.0), d3(0.1, 0.2, 0.0)]
    ));
    assert!(!ti(T, shift(T, d3(2.5, 0.0, 0.0))));
    assert!(ti(T, shift(T, d3(2.0, 0.0, 0.0)))); // share one vertex point
    // Degenerate triangles: segment piercing, segment in plane, point on face, point off.
    let seg = [d3(0.5, 0.5, -1.0), d3(0.5, 0.5, 0.0), d3(0.5, 0.5, 1.0)];
    assert!(ti(T, seg));
    assert!(ti(seg, T));
    assert!(!ti(T, shift(seg, d3(3.0, 0.0, 0.0))));
    let p = [d3(0.5, 0.5, 0.0); 3];
    assert!(ti(T, p) && ti(p, T));
    let p_off = [d3(0.5, 0.5, 1e-300); 3];
    assert!(!ti(T, p_off));
    // Two degenerate triangles.
    let s2 = [d3(0.0, 0.0, 0.0), d3(0.5, 0.5, 0.0), d3(1.0, 1.0, 0.0)];
    let s3 = [d3(0.0, 1.0, 0.0), d3(0.5, 0.5, 0.0), d3(1.0, 0.0, 0.0)];
    assert!(ti(s2, s3));
    assert!(!ti(s2, shift(s3, DVec3::Z)));
}

#[test]
fn adjacent_shared_edge() {
    let (u, w) = (d3(0.0, 0.0, 0.0), d3(1.0, 0.0, 0.0));
    let a = d3(0.5, 1.0, 0.0);
    let e = |b: DVec3| {
        g::adjacent_triangles_intersect::<K>([u, w, a], [w, u, b], Shared::Edge([0, 1], [1, 0]))
    };
    assert!(!e(d3(0.5, -1.0, 0.0))); // flat neighbour
    assert!(!e(d3(0.5, 1.0, 1.0))); // bent
    assert!(!e(d3(0.5, -1.0, 1e-300))); // nearly flat
    assert!(e(d3(0.2, 3.0, 0.0))); // folded onto the face
    assert!(e(a)); // identical third vertex
    assert!(e(d3(7.0, 1e-300, 0.0))); // a thin fold
    // Degenerate faces.
    let beyond = d3(2.0, 0.0, 0.0);
    assert!(!g::adjacent_triangles_intersect::<K>(
        [u, w, beyond],
        [w, u, a],
        Shared::Edge([0, 1], [1, 0])
    ));
    assert!(g::adjacent_triangles_intersect::<K>(
        [u, w, beyond],
        [w, u, d3(3.0, 0.0, 0.0)],
        Shared::Edge([0, 1], [1, 0])
    ));
    assert!(!g::adjacent_triangles_intersect::<K>(
        [u, w, beyond],
        [w, u, d3(-1.0, 0.0, 0.0)],
        Shared::Edge([0, 1], [1, 0])
    ));
}

#[test]
fn adjacent_shared_vertex() {
    let v = DVec3::ZERO;
    let t1 = [v, d3(2.0, 0.0, 0.0), d3(0.0, 2.0, 0.0)];
    let sv = |t2: [DVec3; 3]| g::adjacent_triangles_intersect::<K>(t1, t2, Shared::Vertex(0, 0));
    assert!(!sv([v, d3(-1.0, 0.0, 0.0), d3(0.0, -1.0, 0.0)])); // fan neighbour, flat
    assert!(!sv([v, d3(-1.0, 0.0, 1.0), d3(0.0, -1.0, 1.0)])); // bent away
    assert!(sv([v, d3(1.0, 1.0, -1.0), d3(1.0, 1.0, 1.0)])); // crosses through the face
    assert!(sv([v, d3(1.0, 0.2, 0.0), d3(0.2, 1.0, 0.0)])); // coplanar inside
    assert!(sv([v, d3(3.0, 1.0, 0.0), d3(1.0, 3.0, 0.0)])); // coplanar overlapping wedge
    assert!(!sv([v, d3(-3.0, 1.0, 0.0), d3(-1.0, 3.0, 0.0)])); // coplanar, other wedge
    // Touching along the edge direction (shared edge line, no shared index): intersects beyond v.
    assert!(sv([v, d3(1.0, 0.0, 0.0), d3(1.0, 0.0, 1.0)]));
    // Rotated vertex positions.
    let t2 = [d3(1.0, 1.0, -1.0), d3(1.0, 1.0, 1.0), v];
    assert!(g::adjacent_triangles_intersect::<K>(
        [t1[1], t1[2], v],
        t2,
        Shared::Vertex(2, 2)
    ));
    // Degenerate faces at the shared vertex.
    let spoke = [v, d3(1.0, 0.5, 0.0), d3(2.0, 1.0, 0.0)];
    assert!(sv(spoke));
    let spoke_out = [v, d3(-1.0, 0.5, 0.0), d3(-2.0, 1.0, 0.0)];
    assert!(!sv(spoke_out));
    let both = [v, d3(-1.0, 0.0, 0.0), d3(1.0, 0.0, 0.0)]; // v in the middle of the segment
    assert!(sv(both));
    let seg1 = [v, d3(1.0, 1.0, 1.0), d3(2.0, 2.0, 2.0)];
    let seg2 = [v, d3(3.0, 3.0, 3.0), d3(-1.0, -1.0, -1.0)];
    assert!(g::adjacent_triangles_intersect::<K>(
        seg1,
        seg2,
        Shared::Vertex(0, 0)
    ));
    let seg3 = [v, d3(-3.0, -3.0, -3.0), d3(1.0, 0.0, 0.0)];
    assert!(!g::adjacent_triangles_intersect::<K>(
        seg1,
        seg3,
        Shared::Vertex(0, 0)
    ));
}

#[test]
fn coplanar_overlap_with_area() {
    let o = |a: [DVec3; 3], b: [DVec3; 3]| g::triangles_overlap_with_area::<K>(a, b);
    assert!(o(T, T));
    assert!(o(T, [T[2], T[0], T[1]]));
    assert!(o(T, [T[0], T[2], T[1]])); // reversed orientation
    assert!(o(T, T.map(|p| p + d3(0.5, 0.5, 0.0))));
    assert!(!o(T, T.map(|p| p + d3(2.0, 0.0, 0.0)))); // only a vertex in common
    assert!(!o(T, [T[1], T[2], d3(2.0, 2.0, 0.0)])); // only an edge in common
    assert!(!o(T, T.map(|p| p + d3(0.0, 0.0, 1e-300)))); // parallel planes
    assert!(!o(
        T,
        [d3(0.0, 0.0, 0.0), d3(1.0, 1.0, 0.0), d3(2.0, 2.0, 0.0)]
    )); // degenerate
}

#[test]
fn distances_hand_values() {
    use Sign::*;
    // Point–triangle in each Voronoi region of T (z = 0, legs 2).
    let pt = |p: DVec3, e2: f64| g::cmp_point_triangle::<K>(p, T, e2);
    assert_eq!(pt(d3(0.5, 0.5, 3.0), 9.0), Zero); // face
    assert_eq!(pt(d3(0.5, 0.5, 3.0), 8.0), Positive);
    assert_eq!(pt(d3(1.0, -1.0, 1.0), 2.0), Zero); // edge 0
    assert_eq!(pt(d3(2.0, 2.0, 0.0), 2.0), Zero); // edge 1, in plane
    assert_eq!(pt(d3(3.0, -1.0, 0.0), 2.0), Zero); // vertex 1
    assert_eq!(pt(d3(-1.0, -1.0, -1.0), 3.0), Zero); // vertex 0
    assert_eq!(pt(d3(-1.0, -1.0, -1.0), 3.0000000000000004), Negative);
    assert_eq!(pt(d3(0.5, 0.5, 0.0), 0.0), Zero); // on the face
    assert_eq!(pt(d3(0.5, 0.5, 0.0), -1.0), Positive);
    // Degenerate triangle: the segment [0, 2] on x.
    let seg = [d3(0.0, 0.0, 0.0), d3(2.0, 0.0, 0.0), d3(1.0, 0.0, 0.0)];
    assert_eq!(
        g::cmp_point_triangle::<K>(d3(1.0, 3.0, 4.0), seg, 25.0),
        Zero
    );
    // Point–segment with a degenerate segment.
    assert_eq!(
        g::cmp_point_segment::<K>(d3(3.0, 4.0, 0.0), DVec3::ZERO, DVec3::ZERO, 25.0),
        Zero
    );
    // Segment–segment: skew lines at distance 1, closest points interior.
    let ss = g::cmp_segment_segment::<K>(
        d3(-1.0, 0.0, 0.0),
        d3(1.0, 0.0, 0.0),
        d3(0.0, -1.0, 1.0),
        d3(0.0, 1.0, 1.0),
        1.0,
    );
    assert_eq!(ss, Zero);
    // Parallel segments, offset along their direction: endpoint distance sqrt(1 + 1).
    let ss = g::cmp_segment_segment::<K>(
        d3(0.0, 0.0, 0.0),
        d3(1.0, 0.0, 0.0),
        d3(2.0, 1.0, 0.0),
        d3(3.0, 1.0, 0.0),
        2.0,
    );
    assert_eq!(ss, Zero);
    // Crossing segments: distance 0.
    let ss = g::cmp_segment_segment::<K>(
        d3(-1.0, 0.0, 0.0),
        d3(1.0, 0.0, 0.0),
        d3(0.0, -1.0, 0.0),
        d3(0.0, 1.0, 0.0),
        0.0,
    );
    assert_eq!(ss, Zero);
    // Segment–triangle: a segment above the face, parallel, at height 2.
    let st = g::cmp_segment_triangle::<K>(d3(0.2, 0.2, 2.0), d3(0.5, 0.3, 2.0), T, 4.0);
    assert_eq!(st, Zero);
    // Segment passing beside edge 1 (x + y = 2) at distance sqrt(2)/2 ... squared 0.5.
    let st = g::cmp_segment_triangle::<K>(d3(1.5, 1.5, -1.0), d3(1.5, 1.5, 1.0), T, 0.5);
    assert_eq!(st, Zero);
    // Triangle–triangle: parallel copy at height 0.5, and an edge–edge configuration.
    let up = T.map(|p| p + d3(0.0, 0.0, 0.5));
    assert_eq!(g::cmp_triangle_triangle::<K>(T, up, 0.25), Zero);
    let far = [d3(1.0, -1.0, 1.0), d3(1.0, -1.0, 3.0), d3(1.0, -3.0, 1.0)];
    // Closest: T's edge 0 (y = 0, z = 0) to far's vertex (1, -1, 1): squared 2.
    assert_eq!(g::cmp_triangle_triangle::<K>(T, far, 2.0), Zero);
    let crossing_edges = [d3(1.0, -1.0, 1.0), d3(1.0, 1.0, 1.0), d3(1.0, 0.0, 5.0)];
    // Edge (1,-1,1)-(1,1,1) runs above T's interior at height 1: distance 1 (face region).
    assert_eq!(g::cmp_triangle_triangle::<K>(T, crossing_edges, 1.0), Zero);
    // Pure edge–edge: skew edges above the corner (2, 0, 0).
    let skew = [d3(3.0, -1.0, 1.0), d3(3.0, 1.0, -1.0), d3(9.0, 0.0, 0.0)];
    // The edge x=3 vs T's vertex (2,0,0): line (3, t, -t): closest to (2,0,0) at t=0: squared 1.
    assert_eq!(g::cmp_triangle_triangle::<K>(T, skew, 1.0), Zero);
    assert_eq!(g::cmp_triangle_triangle::<K>(T, T, 0.0), Zero);
}

#[test]
fn edge_edge_distance_is_used() {
    // Two segments crossing in projection, 1 apart in z, closest points interior to both:
    // neither endpoint is close. Triangles built around them extend away from each other.
    let t1 = [d3(-1.0, 0.0, 0.0), d3(1.0, 0.0, 0.0), d3(0.0, -5.0, -5.0)];
    let t2 = [d3(0.0, -1.0, 1.0), d3(0.0, 1.0, 1.0), d3(5.0, 0.0, 6.0)];
    assert_eq!(g::cmp_triangle_triangle::<K>(t1, t2, 1.0), Sign::Zero);
    assert_eq!(g::cmp_triangle_triangle::<K>(t1, t2, 0.99), Sign::Positive);
    assert_eq!(
        g::cmp_segment_triangle::<K>(t2[0], t2[1], t1, 1.0),
        Sign::Zero
    );
}

fn cube() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut pos = Vec::new();
    for i in 0..8 {
        pos.push(d3(
            (i & 1) as f64,
            ((i >> 1) & 1) as f64,
            ((i >> 2) & 1) as f64,
        ));
    }
    let faces = vec![
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6], // z = 0, z = 1
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7], // y = 0, y = 1
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5], // x = 0, x = 1
    ];
    (pos, faces)
}

#[test]
fn point_in_surface_cube() {
    let (pos, faces) = cube();
    let c = |p: DVec3| g::point_in_surface::<K>(p, &pos, &faces);
    assert_eq!(c(d3(0.5, 0.5, 0.5)), Containment::Inside);
    assert_eq!(c(d3(1.5, 0.5, 0.5)), Containment::Outside);
    assert_eq!(c(d3(-0.5, 0.5, 0.5)), Containment::Outside);
    assert_eq!(c(d3(1.0, 0.5, 0.5)), Containment::On);
    assert_eq!(c(d3(1.0, 1.0, 1.0)), Containment::On);
    // Rays through edges and vertices of the triangulation (diagonals y = z on the x faces).
    assert_eq!(c(d3(0.25, 0.5, 0.5)), Containment::Inside);
    assert_eq!(c(d3(0.5, 0.0 + 1e-300, 1e-300)), Containment::Inside);
    assert_eq!(c(d3(-1.0, 0.0, 0.0)), Containment::Outside);
    assert_eq!(c(d3(-1.0, 1.0, 1.0)), Containment::Outside);
    assert_eq!(c(d3(-1.0, 0.5, 0.5)), Containment::Outside);
    assert_eq!(c(d3(0.5, 1.0, 0.5)), Containment::On);
    assert_eq!(
        c(d3(0.5, envelope_predicates::next_up(1.0), 0.5)),
        Containment::Outside
    );
    assert_eq!(
        c(d3(0.5, envelope_predicates::next_down(1.0), 0.5)),
        Containment::Inside
    );
    // Grid of points including every face/edge/vertex alignment.
    for i in -1..=5 {
        for j in -1..=5 {
            for k in -1..=5 {
                let p = d3(i as f64 / 4.0, j as f64 / 4.0, k as f64 / 4.0);
                let inside = |x: f64| (0.0..=1.0).contains(&x);
                let strictly = |x: f64| x > 0.0 && x < 1.0;
                let expect = if strictly(p.x) && strictly(p.y) && strictly(p.z) {
                    Containment::Inside
                } else if inside(p.x) && inside(p.y) && inside(p.z) {
                    Containment::On
                } else {
                    Containment::Outside
                };
                assert_eq!(c(p), expect, "{p:?}");
            }
        }
    }
}
