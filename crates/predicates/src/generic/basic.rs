//! Collinearity, points on segments and triangles, segment–segment intersection.

use glam::{DVec2, DVec3};

use crate::{Kernel, Orientation, Sign};

/// Where a point lies relative to a closed triangle `[v0, v1, v2]`.
///
/// Edge `i` runs from vertex `i` to vertex `(i + 1) % 3`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TriangleLocation {
    /// Not in the closed triangle (for a 3-D query: also when off the triangle's plane).
    Outside,
    /// In the relative interior of the triangle.
    Interior,
    /// In the relative interior of edge `i` (`v_i` to `v_{i+1}`).
    Edge(u8),
    /// At vertex `i`.
    Vertex(u8),
}

/// Projection that drops coordinate `axis` (0: keeps (y, z); 1: keeps (z, x); 2: keeps (x, y)).
/// With this cyclic order, `orient2d` of the projected points is the `axis` component of the
/// normal `(b-a)×(c-a)`, so orientations agree with the 3-D normal.
#[inline]
pub(crate) fn proj(p: DVec3, axis: usize) -> DVec2 {
    match axis {
        0 => DVec2::new(p.y, p.z),
        1 => DVec2::new(p.z, p.x),
        _ => DVec2::new(p.x, p.y),
    }
}

/// The first axis (in the order z, x, y) along which the normal of `abc` is non-zero, with the
/// sign of that component; `None` when `a, b, c` are collinear (or coincident).
#[inline]
pub(crate) fn normal_axis<K: Kernel>(a: DVec3, b: DVec3, c: DVec3) -> Option<(usize, Orientation)> {
    for axis in [2, 0, 1] {
        let o = K::orient2d(proj(a, axis), proj(b, axis), proj(c, axis));
        if !o.is_degenerate() {
            return Some((axis, o));
        }
    }
    None
}

/// True when the three points lie on one line (coincident points included). Exact.
///
/// The normal `(b-a)×(c-a)` vanishes iff all three of its components do; each component is a
/// 2-D orientation of a coordinate projection.
pub fn collinear<K: Kernel>(a: DVec3, b: DVec3, c: DVec3) -> bool {
    normal_axis::<K>(a, b, c).is_none()
}

/// True when `p` lies in the relative interior of segment `ab` (collinear and strictly between:
/// `(a-p)·(b-p) < 0`). False when `a == b` or `p` is an endpoint. This is the T-junction test.
pub fn point_strictly_inside_segment<K: Kernel>(p: DVec3, a: DVec3, b: DVec3) -> bool {
    collinear::<K>(p, a, b) && K::dot(p, a, p, b) == Sign::Negative
}

/// True when `p` lies on the closed segment `ab` (`a == b` allowed: then `p == a`).
pub fn point_on_segment<K: Kernel>(p: DVec3, a: DVec3, b: DVec3) -> bool {
    collinear::<K>(p, a, b) && K::dot(p, a, p, b) != Sign::Positive
}

/// `x` on the closed 2-D segment `pq`, given that the three are collinear.
#[inline]
fn on_collinear_segment_2d(x: DVec2, p: DVec2, q: DVec2) -> bool {
    p.x.min(q.x) <= x.x && x.x <= p.x.max(q.x) && p.y.min(q.y) <= x.y && x.y <= p.y.max(q.y)
}

/// Closed 2-D segments `pq` and `ab` intersect (degenerate segments allowed).
pub(crate) fn segments_intersect_2d<K: Kernel>(p: DVec2, q: DVec2, a: DVec2, b: DVec2) -> bool {
    let o1 = K::orient2d(p, q, a);
    let o2 = K::orient2d(p, q, b);
    let o3 = K::orient2d(a, b, p);
    let o4 = K::orient2d(a, b, q);
    if o1.is_opposite(o2) && o3.is_opposite(o4) {
        return true;
    }
    (o1.is_degenerate() && on_collinear_segment_2d(a, p, q))
        || (o2.is_degenerate() && on_collinear_segment_2d(b, p, q))
        || (o3.is_degenerate() && on_collinear_segment_2d(p, a, b))
        || (o4.is_degenerate() && on_collinear_segment_2d(q, a, b))
}

/// Location of a point relative to a non-degenerate 2-D triangle with orientation `s` (not degenerate).
pub(crate) fn locate_2d<K: Kernel>(p: DVec2, t: [DVec2; 3], s: Orientation) -> TriangleLocation {
    let mut zeros = [false; 3];
    for i in 0..3 {
        let o = K::orient2d(t[i], t[(i + 1) % 3], p);
        if o.is_opposite(s) {
            return TriangleLocation::Outside;
        }
        zeros[i] = o.is_degenerate();
    }
    match zeros {
        [false, false, false] => TriangleLocation::Interior,
        [true, false, false] => TriangleLocation::Edge(0),
        [false, true, false] => TriangleLocation::Edge(1),
        [false, false, true] => TriangleLocation::Edge(2),
        [true, false, true] => TriangleLocation::Vertex(0),
        [true, true, false] => TriangleLocation::Vertex(1),
        [false, true, true] => TriangleLocation::Vertex(2),
        [true, true, true] => unreachable!("non-degenerate triangle"),
    }
}

/// Location of `p` relative to the closed triangle `t` in 3-D (exact).
///
/// * Off the plane of a non-degenerate triangle: [`TriangleLocation::Outside`].
/// * Degenerate triangle (collinear or coincident vertices): the triangle is the segment hull of
///   its vertices; `p` is reported at a `Vertex(i)` it coincides with (lowest `i`), else on the
///   relative interior of an `Edge(i)` containing it (lowest `i`), else `Outside`. Never `Interior`.
///
/// ```
/// use envelope_predicates::{point_in_triangle, TriangleLocation};
/// use glam::DVec3;
/// let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// assert_eq!(point_in_triangle(DVec3::new(0.25, 0.25, 0.0), t), TriangleLocation::Interior);
/// assert_eq!(point_in_triangle(DVec3::new(0.5, 0.5, 0.0), t), TriangleLocation::Edge(1));
/// assert_eq!(point_in_triangle(DVec3::Y, t), TriangleLocation::Vertex(2));
/// assert_eq!(point_in_triangle(DVec3::new(0.25, 0.25, 1e-300), t), TriangleLocation::Outside);
/// ```
pub fn point_in_triangle<K: Kernel>(p: DVec3, t: [DVec3; 3]) -> TriangleLocation {
    match normal_axis::<K>(t[0], t[1], t[2]) {
        Some((axis, s)) => {
            if !K::orient3d(t[0], t[1], t[2], p).is_degenerate() {
                return TriangleLocation::Outside;
            }
            locate_2d::<K>(proj(p, axis), t.map(|v| proj(v, axis)), s)
        }
        None => locate_degenerate::<K>(p, t),
    }
}

/// Location of `p` relative to a triangle known to be coplanar with it (skips the orient3d test).
pub(crate) fn locate_coplanar<K: Kernel>(
    p: DVec3,
    t: [DVec3; 3],
    axis: usize,
    s: Orientation,
) -> TriangleLocation {
    locate_2d::<K>(proj(p, axis), t.map(|v| proj(v, axis)), s)
}

fn locate_degenerate<K: Kernel>(p: DVec3, t: [DVec3; 3]) -> TriangleLocation {
    for i in 0..3 {
        if p == t[i] {
            return TriangleLocation::Vertex(i as u8);
        }
    }
    for i in 0..3 {
        if point_strictly_inside_segment::<K>(p, t[i], t[(i + 1) % 3]) {
            return TriangleLocation::Edge(i as u8);
        }
    }
    TriangleLocation::Outside
}

/// Closed segments `pq` and `ab` in 3-D intersect (exact; degenerate segments allowed).
///
/// Non-coplanar segments never meet. Coplanar ones are projected along an axis on which the
/// projection is injective on their common plane (found from a non-collinear triple); when all
/// four points are collinear, along a coordinate in which they are not all equal.
pub fn segments_intersect<K: Kernel>(p: DVec3, q: DVec3, a: DVec3, b: DVec3) -> bool {
    if !K::orient3d(p, q, a, b).is_degenerate() {
        return false;
    }
    for (x, y, z) in [(p, q, a), (p, q, b), (a, b, p), (a, b, q)] {
        if let Some((axis, _)) = normal_axis::<K>(x, y, z) {
            return segments_intersect_2d::<K>(
                proj(p, axis),
                proj(q, axis),
                proj(a, axis),
                proj(b, axis),
            );
        }
    }
    // All four on one line (or coincident): compare intervals along a varying coordinate.
    for i in 0..3 {
        let c = [p[i], q[i], a[i], b[i]];
        if c.iter().any(|&v| v != c[0]) {
            let (lo1, hi1) = (c[0].min(c[1]), c[0].max(c[1]));
            let (lo2, hi2) = (c[2].min(c[3]), c[2].max(c[3]));
            return lo1.max(lo2) <= hi1.min(hi2);
        }
    }
    true
}
