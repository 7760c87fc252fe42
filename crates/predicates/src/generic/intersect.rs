//! Segment–triangle and triangle–triangle intersection of closed simplices (exact).

use glam::{DVec2, DVec3};

use super::basic::{
    TriangleLocation, collinear, locate_2d, locate_coplanar, normal_axis, proj, segments_intersect,
    segments_intersect_2d,
};
use crate::apart::Planar;
use crate::{Kernel, Orientation, Sign};

/// How a closed segment `pq` meets a closed triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SegmentTriangle {
    /// No common point.
    Disjoint,
    /// `p` and `q` lie strictly on opposite sides of the triangle's plane and the segment
    /// crosses it at the given location of the (non-degenerate) triangle:
    /// `Interior` is a proper crossing, `Edge(i)`/`Vertex(i)` a crossing through an edge/vertex.
    Crossing(TriangleLocation),
    /// Exactly one endpoint (`0` for `p`, `1` for `q`) lies in the plane, inside the closed
    /// triangle at `location`; the other is strictly off the plane.
    Endpoint {
        /// `0` for `p`, `1` for `q`.
        endpoint: u8,
        /// Where that endpoint is on the triangle (never `Outside`).
        location: TriangleLocation,
    },
    /// Both endpoints lie in the plane of the non-degenerate triangle and the segment meets
    /// the closed triangle (a single point, a sub-segment, or all of the segment).
    Coplanar,
    /// The triangle is degenerate (collinear vertices: a segment or a point) and the segment
    /// meets it.
    DegenerateTriangle,
}

impl SegmentTriangle {
    /// True unless [`SegmentTriangle::Disjoint`].
    #[must_use]
    pub fn intersects(self) -> bool {
        self != SegmentTriangle::Disjoint
    }
}

/// Classifies how the closed segment `pq` meets the closed triangle `t` (exact).
///
/// Degenerate cases: `p == q` is a point (classified like a segment: `Endpoint { endpoint: 0 }`
/// never occurs for it, a point in the plane gives `Coplanar`); a degenerate triangle gives
/// `DegenerateTriangle` or `Disjoint`.
///
/// ```
/// use envelope_predicates::{segment_triangle, SegmentTriangle, TriangleLocation};
/// use glam::DVec3;
/// let t = [DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 2.0, 0.0)];
/// let down = |x: f64, y: f64| (DVec3::new(x, y, 1.0), DVec3::new(x, y, -1.0));
/// let (p, q) = down(0.5, 0.5);
/// assert_eq!(segment_triangle(p, q, t), SegmentTriangle::Crossing(TriangleLocation::Interior));
/// let (p, q) = down(1.0, 1.0);
/// assert_eq!(segment_triangle(p, q, t), SegmentTriangle::Crossing(TriangleLocation::Edge(1)));
/// let (p, q) = down(3.0, 0.0);
/// assert_eq!(segment_triangle(p, q, t), SegmentTriangle::Disjoint);
/// ```
pub fn segment_triangle<K: Kernel>(p: DVec3, q: DVec3, t: [DVec3; 3]) -> SegmentTriangle {
    let Some((axis, s)) = normal_axis::<K>(t[0], t[1], t[2]) else {
        let meets = (0..3).any(|i| segments_intersect::<K>(p, q, t[i], t[(i + 1) % 3]));
        return if meets {
            SegmentTriangle::DegenerateTriangle
        } else {
            SegmentTriangle::Disjoint
        };
    };
    let sp = K::orient3d(t[0], t[1], t[2], p);
    let sq = K::orient3d(t[0], t[1], t[2], q);
    segment_triangle_with::<K>(p, q, t, axis, s, sp, sq)
}

/// [`segment_triangle`] for a non-degenerate triangle with known projection axis, its 2-D
/// orientation there, and the plane sides of `p` and `q`.
fn segment_triangle_with<K: Kernel>(
    p: DVec3,
    q: DVec3,
    t: [DVec3; 3],
    axis: usize,
    s: Orientation,
    sp: Orientation,
    sq: Orientation,
) -> SegmentTriangle {
    use Orientation::Degenerate as Z;
    match (sp, sq) {
        (Z, Z) => {
            let (p2, q2) = (proj(p, axis), proj(q, axis));
            let t2 = t.map(|v| proj(v, axis));
            let meets = locate_2d::<K>(p2, t2, s) != TriangleLocation::Outside
                || locate_2d::<K>(q2, t2, s) != TriangleLocation::Outside
                || (0..3).any(|i| segments_intersect_2d::<K>(p2, q2, t2[i], t2[(i + 1) % 3]));
            if meets {
                SegmentTriangle::Coplanar
            } else {
                SegmentTriangle::Disjoint
            }
        }
        (Z, _) | (_, Z) => {
            let (endpoint, x) = if sp == Z { (0, p) } else { (1, q) };
            match locate_coplanar::<K>(x, t, axis, s) {
                TriangleLocation::Outside => SegmentTriangle::Disjoint,
                location => SegmentTriangle::Endpoint { endpoint, location },
            }
        }
        _ if sp == sq => SegmentTriangle::Disjoint,
        _ => {
            let o = [
                K::orient3d(p, q, t[0], t[1]),
                K::orient3d(p, q, t[1], t[2]),
                K::orient3d(p, q, t[2], t[0]),
            ];
            let pos = o.contains(&Orientation::Positive);
            let neg = o.contains(&Orientation::Negative);
            if pos && neg {
                return SegmentTriangle::Disjoint;
            }
            let loc = match o.map(Orientation::is_degenerate) {
                [false, false, false] => TriangleLocation::Interior,
                [true, false, false] => TriangleLocation::Edge(0),
                [false, true, false] => TriangleLocation::Edge(1),
                [false, false, true] => TriangleLocation::Edge(2),
                [true, false, true] => TriangleLocation::Vertex(0),
                [true, true, false] => TriangleLocation::Vertex(1),
                [false, true, true] => TriangleLocation::Vertex(2),
                // Impossible when p and q are strictly on opposite sides of a non-degenerate plane.
                [true, true, true] => unreachable!("line pq coplanar with all edges"),
            };
            SegmentTriangle::Crossing(loc)
        }
    }
}

/// The algebraic number of crossings of the polyline `path` with the oriented triangles
/// `triangles` (exact): a segment that crosses a triangle's interior counts `+1` when it
/// goes to the side its right-hand normal points to ([`Orientation::Positive`] of
/// `orient3d(t0, t1, t2, end)`), `-1` the other way. `None` when a segment meets a triangle
/// in any other way (through an edge or a vertex, with an endpoint in its plane, in its
/// plane) or a triangle is degenerate: the count is then not decided.
///
/// ```
/// use envelope_predicates::generic::polyline_crossings;
/// use envelope_predicates::Filtered;
/// use glam::DVec3;
/// let t = [DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 2.0, 0.0)];
/// let up = [DVec3::new(0.5, 0.5, -1.0), DVec3::new(0.5, 0.5, 1.0)];
/// assert_eq!(polyline_crossings::<Filtered>(&up, &[t]), Some(1));
/// let there_and_back = [up[0], up[1], DVec3::new(0.4, 0.5, -1.0)];
/// assert_eq!(polyline_crossings::<Filtered>(&there_and_back, &[t]), Some(0));
/// let through_an_edge = [DVec3::new(1.0, 0.0, -1.0), DVec3::new(1.0, 0.0, 1.0)];
/// assert_eq!(polyline_crossings::<Filtered>(&through_an_edge, &[t]), None);
/// ```
pub fn polyline_crossings<K: Kernel>(path: &[DVec3], triangles: &[[DVec3; 3]]) -> Option<i32> {
    crossings::<K>(path, triangles, false)
}

/// [`polyline_crossings`] with every orientation (the sides of the path's points against each
/// triangle's plane, and of a triangle's edges against a crossing segment) told first in
/// error-bounded f64 ([`Planar`]: its sign is the exact one when it answers) and by
/// `K::orient3d` only when it cannot: the same answer, for coordinates in the exact
/// predicates' range (the bound of [`Planar`] assumes them).
pub(crate) fn polyline_crossings_prefiltered<K: Kernel>(
    path: &[DVec3],
    triangles: &[[DVec3; 3]],
) -> Option<i32> {
    crossings::<K>(path, triangles, true)
}

/// Paths up to this many points have the sides of their points against a triangle's plane
/// worked out once (a point ends one segment and starts the next); longer ones per segment.
const CACHED_PATH: usize = 8;

fn crossings<K: Kernel>(path: &[DVec3], triangles: &[[DVec3; 3]], prefilter: bool) -> Option<i32> {
    use Orientation::{Degenerate, Negative, Positive};
    let cached = path.len() <= CACHED_PATH;
    let mut sides = [Degenerate; CACHED_PATH];
    let mut sum = 0;
    for t in triangles {
        let plane = prefilter.then(|| Planar::new(*t));
        let side = |x: DVec3| match plane.as_ref().and_then(|p| p.side(x)) {
            Some(true) => Positive,
            Some(false) => Negative,
            None => K::orient3d(t[0], t[1], t[2], x),
        };
        // Read in the order the segments ask: the same answers, the same first `None`.
        if cached && path.len() >= 2 {
            for (s, &x) in sides.iter_mut().zip(path) {
                *s = side(x);
            }
        }
        for (k, s) in path.windows(2).enumerate() {
            let (x, y) = (s[0], s[1]);
            let (sx, sy) = if cached {
                (sides[k], sides[k + 1])
            } else {
                (side(x), side(y))
            };
            if sx == Degenerate || sy == Degenerate {
                return None;
            }
            if sx == sy {
                continue;
            }
            let o = [(0, 1), (1, 2), (2, 0)].map(|(i, j)| {
                let filtered = prefilter.then(|| Planar::new([x, y, t[i]]).side(t[j]));
                match filtered.flatten() {
                    Some(true) => Positive,
                    Some(false) => Negative,
                    None => K::orient3d(x, y, t[i], t[j]),
                }
            });
            if o.contains(&Positive) && o.contains(&Negative) {
                continue;
            }
            if o.contains(&Degenerate) {
                return None;
            }
            sum += if sy == Positive { 1 } else { -1 };
        }
    }
    Some(sum)
}

/// Whether every point of `points` (at least one) lies strictly on one side of the plane of
/// `t` (exact; false for a degenerate `t`).
///
/// ```
/// use envelope_predicates::generic::strictly_one_side_of_plane;
/// use envelope_predicates::Filtered;
/// use glam::DVec3;
/// let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// assert!(strictly_one_side_of_plane::<Filtered>(t, &[DVec3::Z, DVec3::new(5.0, 1.0, 0.1)]));
/// assert!(!strictly_one_side_of_plane::<Filtered>(t, &[DVec3::Z, DVec3::new(5.0, 1.0, 0.0)]));
/// ```
pub fn strictly_one_side_of_plane<K: Kernel>(t: [DVec3; 3], points: &[DVec3]) -> bool {
    let Some((first, rest)) = points.split_first() else {
        return false;
    };
    let side = K::orient3d(t[0], t[1], t[2], *first);
    side != Orientation::Degenerate
        && rest
            .iter()
            .all(|&x| K::orient3d(t[0], t[1], t[2], x) == side)
}

/// True when all three are the same strict side.
#[inline]
fn strictly_one_side(o: [Orientation; 3]) -> bool {
    !o[0].is_degenerate() && o[0] == o[1] && o[1] == o[2]
}

/// True when the closed triangles `t1` and `t2` have a common point (touching counts), exact.
///
/// Handles coplanar triangles (2-D overlap) and degenerate triangles (segments, points). The
/// answer is the exact geometric one, so it is symmetric in `t1, t2` and invariant under any
/// permutation of either triangle's vertices.
///
/// Method: after a plane-side rejection, two closed triangles meet iff an edge of one meets
/// the other (their intersection is convex; one of its extreme points lies on an edge).
///
/// ```
/// use envelope_predicates::triangles_intersect;
/// use glam::DVec3;
/// let t1 = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// let t2 = [DVec3::new(0.2, 0.2, -1.0), DVec3::new(0.2, 0.2, 1.0), DVec3::new(5.0, 5.0, 0.0)];
/// assert!(triangles_intersect(t1, t2));
/// let t3 = t2.map(|p| p + DVec3::new(0.0, 0.0, 1.5));
/// assert!(!triangles_intersect(t1, t3));
/// ```
pub fn triangles_intersect<K: Kernel>(t1: [DVec3; 3], t2: [DVec3; 3]) -> bool {
    let s2 = t2.map(|v| K::orient3d(t1[0], t1[1], t1[2], v));
    if strictly_one_side(s2) {
        return false;
    }
    if s2.iter().all(|s| s.is_degenerate()) {
        // `t2` in the plane of `t1` (when `t1` is not degenerate): a 2-D question.
        if let Some(meet) = coplanar_triangles_meet::<K>(t1, t2) {
            return meet;
        }
    }
    let s1 = t1.map(|v| K::orient3d(t2[0], t2[1], t2[2], v));
    if strictly_one_side(s1) {
        return false;
    }
    if s1.iter().chain(&s2).all(|s| !s.is_degenerate()) {
        return straddling_triangles_meet::<K>(t1, s1, t2, s2);
    }
    edges_meet::<K>(t1, t2, s1) || edges_meet::<K>(t2, t1, s2)
}

/// Guigue and Devillers' test (2003) for two triangles that each strictly straddle the
/// other's plane: no vertex on the other's plane (`s1[i]`: side of `t1[i]` of `t2`'s plane,
/// `s2` the other way; none degenerate, not all on one side). Two more orientations decide.
///
/// Each triangle is turned (a rotation, which keeps its orientation) so that its first
/// vertex `p` is the one alone on its side of the other's plane; the other triangle's last
/// two vertices are swapped when that side is the negative one (so both `p` lie on the
/// positive sides). Each triangle meets the other's plane in a segment of the line where
/// the planes cross; the triangles meet iff the two segments overlap (closed: touching
/// counts), that is iff `orient3d(p1, q1, p2, q2) <= 0` and `orient3d(p1, r1, r2, p2) <= 0`
/// in this crate's convention. Checked against the edge test on 150,000 random pairs, grid
/// and real coordinates (`straddling_test_matches_the_edge_test`).
fn straddling_triangles_meet<K: Kernel>(
    t1: [DVec3; 3],
    s1: [Orientation; 3],
    t2: [DVec3; 3],
    s2: [Orientation; 3],
) -> bool {
    let alone = |s: [Orientation; 3]| {
        if s[0] == s[1] {
            2
        } else if s[0] == s[2] {
            1
        } else {
            0
        }
    };
    let (i, j) = (alone(s1), alone(s2));
    let (p1, mut q1, mut r1) = (t1[i], t1[(i + 1) % 3], t1[(i + 2) % 3]);
    let (p2, mut q2, mut r2) = (t2[j], t2[(j + 1) % 3], t2[(j + 2) % 3]);
    if s1[i] == Orientation::Negative {
        std::mem::swap(&mut q2, &mut r2);
    }
    if s2[j] == Orientation::Negative {
        std::mem::swap(&mut q1, &mut r1);
    }
    K::orient3d(p1, q1, p2, q2) != Orientation::Positive
        && K::orient3d(p1, r1, r2, p2) != Orientation::Positive
}

/// For `t2` in the plane of `t1`: whether the closed triangles meet; `None` when either is
/// degenerate (the general path decides).
///
/// In the coordinate projection along which `t1` is not degenerate the plane maps one-to-one.
/// Two closed convex polygons are disjoint iff a line through an edge of one has the other
/// strictly on its outer side (separating axis theorem in the plane), which exact 2-D
/// orientations decide.
fn coplanar_triangles_meet<K: Kernel>(t1: [DVec3; 3], t2: [DVec3; 3]) -> Option<bool> {
    let ((p1, o1), (p2, o2)) = projected_pair::<K>(t1, t2)?;
    Some(!edge_separates::<K>(p1, o1, p2, true) && !edge_separates::<K>(p2, o2, p1, true))
}

/// A projected triangle with its 2-D orientation.
type Projected = ([DVec2; 3], Orientation);

/// `t1` and `t2` in the coordinate projection along which `t1` is not degenerate, each with
/// its 2-D orientation; `None` when either is degenerate there. For `t2` in the plane of
/// `t1` the projection is one-to-one on that plane.
fn projected_pair<K: Kernel>(t1: [DVec3; 3], t2: [DVec3; 3]) -> Option<(Projected, Projected)> {
    let (axis, o1) = normal_axis::<K>(t1[0], t1[1], t1[2])?;
    let (p1, p2) = (t1.map(|v| proj(v, axis)), t2.map(|v| proj(v, axis)));
    let o2 = K::orient2d(p2[0], p2[1], p2[2]);
    (!o2.is_degenerate()).then_some(((p1, o1), (p2, o2)))
}

/// Whether some edge of the 2-D triangle `a` (orientation `o`, not degenerate) has all of
/// `b` on its outer side: strictly (`strict`: then the closed triangles are apart), or on
/// the closed outer half-plane (then their interiors are).
fn edge_separates<K: Kernel>(a: [DVec2; 3], o: Orientation, b: [DVec2; 3], strict: bool) -> bool {
    (0..3).any(|i| {
        let (x, y) = (a[i], a[(i + 1) % 3]);
        b.iter().all(|&q| {
            let side = K::orient2d(x, y, q);
            if strict {
                side.is_opposite(o)
            } else {
                side != o
            }
        })
    })
}

/// Some edge of `a` meets the closed triangle `b`; `sides[i]` is `orient3d(b, a[i])`.
fn edges_meet<K: Kernel>(a: [DVec3; 3], b: [DVec3; 3], sides: [Orientation; 3]) -> bool {
    match normal_axis::<K>(b[0], b[1], b[2]) {
        Some((axis, s)) => (0..3).any(|i| {
            let j = (i + 1) % 3;
            segment_triangle_with::<K>(a[i], a[j], b, axis, s, sides[i], sides[j]).intersects()
        }),
        None => (0..3).any(|i| segment_triangle::<K>(a[i], a[(i + 1) % 3], b).intersects()),
    }
}

/// Which vertices two mesh faces share, as local vertex indices (`0..3`) into each triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shared {
    /// `t1[i] == t2[j]` is the only shared vertex.
    Vertex(usize, usize),
    /// `t1[i0] == t2[j0]` and `t1[i1] == t2[j1]`: a shared edge (local indices `[i0, i1]`, `[j0, j1]`).
    Edge([usize; 2], [usize; 2]),
}

/// Intersection test for adjacent mesh faces: true only when the closed triangles meet
/// somewhere other than their shared vertex or shared edge.
///
/// The shared vertices must have identical positions (they are the same mesh vertex).
///
/// * Shared edge `uw`, non-degenerate faces: they meet elsewhere iff they are coplanar and the
///   opposite vertices lie on the same side of `uw` (a fold-over); otherwise their
///   intersection is exactly the edge.
/// * Shared vertex `v`, non-degenerate faces: they meet elsewhere iff the edge opposite `v` in
///   one face meets the other face (that edge does not contain `v`).
/// * Degenerate faces are the union of their two edges at the shared vertex (or a segment on
///   the shared edge's line) and are tested as such.
///
/// ```
/// use envelope_predicates::{adjacent_triangles_intersect, Shared};
/// use glam::DVec3;
/// let (u, w) = (DVec3::ZERO, DVec3::X);
/// // Two faces folded onto each other across the edge uw.
/// let t1 = [u, w, DVec3::new(0.5, 1.0, 0.0)];
/// let t2 = [w, u, DVec3::new(0.3, 2.0, 0.0)];
/// assert!(adjacent_triangles_intersect(t1, t2, Shared::Edge([0, 1], [1, 0])));
/// // A flat, non-overlapping neighbour.
/// let t3 = [w, u, DVec3::new(0.3, -2.0, 0.0)];
/// assert!(!adjacent_triangles_intersect(t1, t3, Shared::Edge([0, 1], [1, 0])));
/// ```
pub fn adjacent_triangles_intersect<K: Kernel>(
    t1: [DVec3; 3],
    t2: [DVec3; 3],
    shared: Shared,
) -> bool {
    match shared {
        Shared::Vertex(i, j) => {
            debug_assert_eq!(t1[i], t2[j], "shared vertex positions differ");
            let v = t1[i];
            meets_beyond_vertex::<K>(
                v,
                [t1[(i + 1) % 3], t1[(i + 2) % 3]],
                [t2[(j + 1) % 3], t2[(j + 2) % 3]],
            )
        }
        Shared::Edge([i0, i1], [j0, j1]) => {
            debug_assert!(
                t1[i0] == t2[j0] && t1[i1] == t2[j1],
                "shared edge positions differ"
            );
            let (u, w) = (t1[i0], t1[i1]);
            let a = t1[3 - i0 - i1];
            let b = t2[3 - j0 - j1];
            meets_beyond_edge::<K>(u, w, a, b)
        }
    }
}

/// `[v, a1, b1] ∩ [v, a2, b2] != {v}`.
fn meets_beyond_vertex<K: Kernel>(v: DVec3, [a1, b1]: [DVec3; 2], [a2, b2]: [DVec3; 2]) -> bool {
    let t1 = [v, a1, b1];
    let t2 = [v, a2, b2];
    // Plane-side rejection: the other face touches this plane only at v.
    let s = [a2, b2].map(|x| K::orient3d(v, a1, b1, x));
    if !s[0].is_degenerate() && s[0] == s[1] {
        return false;
    }
    if s[0].is_degenerate() && s[1].is_degenerate() {
        // Both faces in one plane (when the first is not degenerate): a 2-D question,
        // answered without the exact zeros the general path would compute again.
        if let Some(o) = coplanar_sectors_meet::<K>(v, [a1, b1], [a2, b2]) {
            return o;
        }
    }
    let s = [a1, b1].map(|x| K::orient3d(v, a2, b2, x));
    if !s[0].is_degenerate() && s[0] == s[1] {
        return false;
    }
    let d1 = collinear::<K>(v, a1, b1);
    let d2 = collinear::<K>(v, a2, b2);
    match (d1, d2) {
        (false, false) => {
            segment_triangle::<K>(a1, b1, t2).intersects()
                || segment_triangle::<K>(a2, b2, t1).intersects()
        }
        (true, _) => spoke_meets::<K>(v, a1, t2, d2) || spoke_meets::<K>(v, b1, t2, d2),
        (false, true) => spoke_meets::<K>(v, a2, t1, false) || spoke_meets::<K>(v, b2, t1, false),
    }
}

/// For `a2`, `b2` in the plane of `[v, a1, b1]`: whether `[v, a1, b1] ∩ [v, a2, b2] != {v}`,
/// `None` when either triangle is degenerate (the general path decides).
///
/// Near `v` each triangle is its sector (the cone at `v` spanned by its two edges, of angle
/// strictly between 0 and pi), and each lies inside its sector; so the triangles meet beyond
/// `v` iff the sectors do, iff a boundary ray of one lies in the other (the intersection of
/// two such sectors, when it is more than `v`, is a sector bounded by rays of theirs). In
/// the coordinate projection along which `[v, a1, b1]` is not degenerate the plane maps
/// one-to-one, so the 2-D orientations decide exactly.
fn coplanar_sectors_meet<K: Kernel>(
    v: DVec3,
    [a1, b1]: [DVec3; 2],
    [a2, b2]: [DVec3; 2],
) -> Option<bool> {
    let (axis, o1) = normal_axis::<K>(v, a1, b1)?;
    let p = |x: DVec3| proj(x, axis);
    let (v, a1, b1, a2, b2) = (p(v), p(a1), p(b1), p(a2), p(b2));
    let o2 = K::orient2d(v, a2, b2);
    if o2.is_degenerate() {
        return None;
    }
    // The closed sector (v; a, b) of orientation o contains the ray from v through x (x != v).
    let in_sector = |a, b, o: Orientation, x| {
        let ok = |s: Orientation| s == o || s.is_degenerate();
        ok(K::orient2d(v, a, x)) && ok(K::orient2d(v, x, b))
    };
    Some(
        in_sector(a1, b1, o1, a2)
            || in_sector(a1, b1, o1, b2)
            || in_sector(a2, b2, o2, a1)
            || in_sector(a2, b2, o2, b1),
    )
}

/// `[v, a] ∩ t != {v}` for a triangle `t = [v, x, y]` (degenerate when `t_degenerate`).
fn spoke_meets<K: Kernel>(v: DVec3, a: DVec3, t: [DVec3; 3], t_degenerate: bool) -> bool {
    if a == v {
        return false;
    }
    if t_degenerate {
        // t is the union of the spokes [v, t1] and [v, t2].
        same_ray::<K>(v, a, t[1]) || same_ray::<K>(v, a, t[2])
    } else {
        super::point_in_triangle::<K>(a, t) != TriangleLocation::Outside
            || segments_intersect::<K>(v, a, t[1], t[2])
    }
}

/// `x != v`, `y != v`, and `x`, `y` on the same ray from `v`.
fn same_ray<K: Kernel>(v: DVec3, x: DVec3, y: DVec3) -> bool {
    x != v && y != v && collinear::<K>(v, x, y) && K::dot(v, x, v, y) == Sign::Positive
}

/// `[u, w, a] ∩ [u, w, b]` is not contained in the segment `uw`.
fn meets_beyond_edge<K: Kernel>(u: DVec3, w: DVec3, a: DVec3, b: DVec3) -> bool {
    if u == w {
        return meets_beyond_vertex::<K>(u, [w, a], [w, b]);
    }
    match (normal_axis::<K>(u, w, a), normal_axis::<K>(u, w, b)) {
        (Some((axis, sa)), Some(_)) => {
            if !K::orient3d(u, w, a, b).is_degenerate() {
                return false;
            }
            let sb = K::orient2d(proj(u, axis), proj(w, axis), proj(b, axis));
            sa == sb
        }
        (None, None) => {
            // Both faces lie on the line uw: they overlap beyond the edge iff a and b stick out
            // past the same endpoint.
            let side = |x: DVec3| {
                if K::dot(u, w, w, x) == Sign::Positive {
                    1
                } else if K::dot(w, u, u, x) == Sign::Positive {
                    -1
                } else {
                    0
                }
            };
            let (sa, sb) = (side(a), side(b));
            sa != 0 && sa == sb
        }
        // A non-degenerate face meets the line uw exactly in the segment uw.
        _ => false,
    }
}

/// True when two closed triangles are coplanar, both non-degenerate, and their interiors
/// overlap (intersection with positive area): coincident or partly coincident faces.
///
/// Uses the separating-axis theorem in the projection: the interiors are disjoint iff the
/// other triangle lies in the closed outer half-plane of some edge of one of them.
///
/// ```
/// use envelope_predicates::triangles_overlap_with_area;
/// use glam::DVec3;
/// let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// assert!(triangles_overlap_with_area(t, [t[1], t[2], t[0]]));
/// // Sharing only an edge: no area in common.
/// assert!(!triangles_overlap_with_area(t, [DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)]));
/// ```
pub fn triangles_overlap_with_area<K: Kernel>(t1: [DVec3; 3], t2: [DVec3; 3]) -> bool {
    // A degenerate `t1` passes the plane test (every orientation is zero) and is refused
    // by the projection.
    if t2
        .iter()
        .any(|&v| !K::orient3d(t1[0], t1[1], t1[2], v).is_degenerate())
    {
        return false;
    }
    let Some(((p1, s1), (p2, s2))) = projected_pair::<K>(t1, t2) else {
        return false;
    };
    !edge_separates::<K>(p1, s1, p2, false) && !edge_separates::<K>(p2, s2, p1, false)
}

#[cfg(test)]
mod straddling_tests {
    use super::*;
    use crate::{Exact, Filtered};

    /// The two-orientation test gives the edge test's answer on every pair where it applies
    /// (each triangle strictly straddling the other's plane), on grid points (many touching
    /// and collinear cases: the last two orientations are often zero) and random doubles,
    /// with the filtered kernel and the exact one.
    #[test]
    fn straddling_test_matches_the_edge_test() {
        let mut next = crate::xorshift(0x1234_5678_9abc_def0);
        let (mut applied, mut met) = (0, 0);
        for round in 0..150_000 {
            let mut pt = || {
                let mut c = || {
                    if next() % 2 == 0 {
                        (next() % 7) as f64 - 3.0
                    } else {
                        (next() >> 11) as f64 / (1u64 << 53) as f64 * 6.0 - 3.0
                    }
                };
                DVec3::new(c(), c(), c())
            };
            let (t1, t2) = ([pt(), pt(), pt()], [pt(), pt(), pt()]);
            let s2 = t2.map(|v| Filtered::orient3d(t1[0], t1[1], t1[2], v));
            let s1 = t1.map(|v| Filtered::orient3d(t2[0], t2[1], t2[2], v));
            if strictly_one_side(s1)
                || strictly_one_side(s2)
                || s1.iter().chain(&s2).any(|s| s.is_degenerate())
            {
                continue;
            }
            applied += 1;
            let edges = edges_meet::<Filtered>(t1, t2, s1) || edges_meet::<Filtered>(t2, t1, s2);
            met += usize::from(edges);
            assert_eq!(
                straddling_triangles_meet::<Filtered>(t1, s1, t2, s2),
                edges,
                "{t1:?} {t2:?}"
            );
            if round % 16 == 0 {
                assert_eq!(straddling_triangles_meet::<Exact>(t1, s1, t2, s2), edges);
            }
        }
        assert!(
            applied > 50_000 && met > 10_000 && met < applied - 10_000,
            "{applied} {met}"
        );
    }
}
