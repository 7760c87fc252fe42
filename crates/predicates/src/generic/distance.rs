//! Exact comparison of squared distances with a squared tolerance.
//!
//! Every function returns the sign of `dist² − eps2`, where `dist` is the Euclidean distance
//! between the closed simplices computed in infinite precision from the f64 inputs, and `eps2`
//! is taken as the exact value of the given double (pass [`square_rounded_up`](crate::square_rounded_up)`(eps)`
//! to compare against a tolerance `eps` conservatively).
//!
//! A distance is the minimum over a small set of candidate quantities (vertex–vertex,
//! vertex–line, vertex–plane, line–line), each valid only in its Voronoi region; regions are
//! decided by exact signs, and `sign(min_i c_i − e) = min_i sign(c_i − e)`, so no distance is
//! ever constructed. Candidates used outside their region are never smaller than the true
//! distance (a line is closer than its segment, a plane than its triangle), except that they
//! are only admitted inside their region.

use glam::DVec3;

use super::basic::collinear;
use super::intersect::{segment_triangle, triangles_intersect};
use super::segments_intersect;
use crate::{Kernel, Sign};

/// Sign of `dist(p, segment ab)² − eps2` (exact; `a == b` allowed).
pub fn cmp_point_segment<K: Kernel>(p: DVec3, a: DVec3, b: DVec3, eps2: f64) -> Sign {
    let mut s = K::cmp_sq_dist(p, a, eps2).min(K::cmp_sq_dist(p, b, eps2));
    if s == Sign::Negative {
        return s;
    }
    // Interior of the segment: 0 < (p-a)·(b-a) < |b-a|², i.e. both end angles acute.
    if K::dot(a, b, a, p) == Sign::Positive && K::dot(b, a, b, p) == Sign::Positive {
        s = s.min(K::cmp_sq_dist_point_line(p, a, b, eps2));
    }
    s
}

/// Sign of `dist(p, closed triangle t)² − eps2` (exact; degenerate triangles allowed).
///
/// ```
/// use envelope_predicates::{cmp_point_triangle, Sign};
/// use glam::DVec3;
/// let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// // Above the face at height 2: distance² = 4.
/// assert_eq!(cmp_point_triangle(DVec3::new(0.2, 0.2, 2.0), t, 4.0), Sign::Zero);
/// // Beyond vertex X: distance² = 1 + 4 = 5.
/// assert_eq!(cmp_point_triangle(DVec3::new(2.0, 0.0, 2.0), t, 4.0), Sign::Positive);
/// assert_eq!(cmp_point_triangle(DVec3::new(2.0, 0.0, 2.0), t, 5.0), Sign::Zero);
/// ```
pub fn cmp_point_triangle<K: Kernel>(p: DVec3, t: [DVec3; 3], eps2: f64) -> Sign {
    let [a, b, c] = t;
    if !collinear::<K>(a, b, c)
        && K::edge_side(a, b, c, p) != Sign::Negative
        && K::edge_side(b, c, a, p) != Sign::Negative
        && K::edge_side(c, a, b, p) != Sign::Negative
    {
        // The projection of p lies in the closed triangle: the plane distance is the distance.
        return K::cmp_sq_dist_point_plane(p, a, b, c, eps2);
    }
    let mut s = Sign::Positive;
    for i in 0..3 {
        s = s.min(cmp_point_segment::<K>(p, t[i], t[(i + 1) % 3], eps2));
        if s == Sign::Negative {
            break;
        }
    }
    s
}

/// Sign of `dist(segment p0p1, segment q0q1)² − eps2` (exact; degenerate segments allowed).
pub fn cmp_segment_segment<K: Kernel>(
    p0: DVec3,
    p1: DVec3,
    q0: DVec3,
    q1: DVec3,
    eps2: f64,
) -> Sign {
    if segments_intersect::<K>(p0, p1, q0, q1) {
        return K::cmp_sq_dist(p0, p0, eps2);
    }
    let mut s = cmp_point_segment::<K>(p0, q0, q1, eps2)
        .min(cmp_point_segment::<K>(p1, q0, q1, eps2))
        .min(cmp_point_segment::<K>(q0, p0, p1, eps2))
        .min(cmp_point_segment::<K>(q1, p0, p1, eps2));
    if s != Sign::Negative && K::closest_points_interior(p0, p1, q0, q1) {
        s = s.min(K::cmp_sq_dist_line_line(p0, p1, q0, q1, eps2));
    }
    s
}

/// Sign of `dist(segment pq, closed triangle t)² − eps2` (exact; degenerate inputs allowed).
pub fn cmp_segment_triangle<K: Kernel>(p: DVec3, q: DVec3, t: [DVec3; 3], eps2: f64) -> Sign {
    if segment_triangle::<K>(p, q, t).intersects() {
        return K::cmp_sq_dist(p, p, eps2);
    }
    let mut s = cmp_point_triangle::<K>(p, t, eps2).min(cmp_point_triangle::<K>(q, t, eps2));
    for i in 0..3 {
        if s == Sign::Negative {
            break;
        }
        s = s.min(cmp_segment_segment::<K>(p, q, t[i], t[(i + 1) % 3], eps2));
    }
    s
}

/// Sign of `dist(closed triangle t1, closed triangle t2)² − eps2` (exact; degenerate triangles allowed).
///
/// ```
/// use envelope_predicates::{cmp_triangle_triangle, Sign};
/// use glam::DVec3;
/// let t1 = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// let t2 = t1.map(|v| v + DVec3::new(0.0, 0.0, 0.5));
/// assert_eq!(cmp_triangle_triangle(t1, t2, 0.25), Sign::Zero);
/// assert_eq!(cmp_triangle_triangle(t1, t2, 0.2), Sign::Positive);
/// ```
pub fn cmp_triangle_triangle<K: Kernel>(t1: [DVec3; 3], t2: [DVec3; 3], eps2: f64) -> Sign {
    if triangles_intersect::<K>(t1, t2) {
        return K::cmp_sq_dist(t1[0], t1[0], eps2);
    }
    let mut s = Sign::Positive;
    for v in t1 {
        s = s.min(cmp_point_triangle::<K>(v, t2, eps2));
    }
    for v in t2 {
        s = s.min(cmp_point_triangle::<K>(v, t1, eps2));
    }
    for i in 0..3 {
        for j in 0..3 {
            if s == Sign::Negative {
                return s;
            }
            // Vertex–segment candidates are covered above; only the interior–interior
            // line–line candidate is new here.
            let (p0, p1, q0, q1) = (t1[i], t1[(i + 1) % 3], t2[j], t2[(j + 1) % 3]);
            if K::closest_points_interior(p0, p1, q0, q1) {
                s = s.min(K::cmp_sq_dist_line_line(p0, p1, q0, q1, eps2));
            }
        }
    }
    s
}
