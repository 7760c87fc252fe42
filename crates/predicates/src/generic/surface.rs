//! Point versus closed triangulated surface, by exact ray parity with symbolic perturbation.

use glam::{DVec2, DVec3};

use super::basic::{TriangleLocation, point_in_triangle, proj};
use crate::{Kernel, Orientation};

/// Where a point is relative to a closed surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Containment {
    /// In the bounded region (odd crossing parity).
    Inside,
    /// On a face (closed triangle) of the surface.
    On,
    /// In the unbounded region (even crossing parity).
    Outside,
}

/// Classifies `p` against the closed triangulated surface given by `positions` and `faces`
/// (exact).
///
/// Method: if `p` lies on some closed face, `On`. Otherwise count the faces crossed by the ray
/// from `p` in direction `+x`, with the ray origin perturbed symbolically to
/// `p + (0, ε, ε²)` (ε → 0⁺) so that it never passes through an edge or vertex: projected onto
/// the `(y, z)` plane, a zero `orient2d(a, b, p)` is replaced by the sign of its derivative along
/// the perturbation, which is decided by comparing coordinates of `a` and `b`. Faces whose
/// `(y, z)` projection is degenerate (parallel to the ray) are never crossed by the perturbed ray.
/// Odd parity means `Inside`. The answer is exact for any closed (every edge used an even number
/// of times) surface, self-intersecting or not, and does not depend on face orientation; for
/// an open surface the parity is still well-defined but relative to the `+x` ray.
///
/// ```
/// use envelope_predicates::{point_in_surface, Containment};
/// use glam::DVec3;
/// // A tetrahedron.
/// let pos = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
/// let faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
/// assert_eq!(point_in_surface(DVec3::splat(0.1), &pos, &faces), Containment::Inside);
/// // The +x ray from here runs exactly along the edge from vertex 0 to vertex 1: still exact.
/// assert_eq!(point_in_surface(DVec3::new(-1.0, 0.0, 0.0), &pos, &faces), Containment::Outside);
/// assert_eq!(point_in_surface(DVec3::new(0.5, 0.5, 0.0), &pos, &faces), Containment::On);
/// ```
pub fn point_in_surface<K: Kernel>(
    p: DVec3,
    positions: &[DVec3],
    faces: &[[u32; 3]],
) -> Containment {
    let tri = |f: &[u32; 3]| f.map(|i| positions[i as usize]);
    if faces
        .iter()
        .any(|f| point_in_triangle::<K>(p, tri(f)) != TriangleLocation::Outside)
    {
        return Containment::On;
    }
    let p2 = proj(p, 0);
    let mut parity = false;
    for f in faces {
        let t = tri(f);
        // Cheap rejection on the projected bounding box (exact comparisons).
        let (lo_y, hi_y) = (
            t[0].y.min(t[1].y).min(t[2].y),
            t[0].y.max(t[1].y).max(t[2].y),
        );
        let (lo_z, hi_z) = (
            t[0].z.min(t[1].z).min(t[2].z),
            t[0].z.max(t[1].z).max(t[2].z),
        );
        if p.y < lo_y || p.y > hi_y || p.z < lo_z || p.z > hi_z || t.iter().all(|v| v.x < p.x) {
            continue;
        }
        let t2 = t.map(|v| proj(v, 0));
        let s = K::orient2d(t2[0], t2[1], t2[2]);
        if s.is_degenerate() {
            continue;
        }
        let inside = (0..3).all(|i| perturbed_orient2d::<K>(t2[i], t2[(i + 1) % 3], p2) == s);
        if !inside {
            continue;
        }
        // The x component of the normal is s; the ray hits at t > 0 iff p is on the side
        // opposite to the normal's x direction (p is off the plane: not On).
        let side = K::orient3d(t[0], t[1], t[2], p);
        debug_assert!(!side.is_degenerate());
        if side.is_opposite(s) {
            parity = !parity;
        }
    }
    if parity {
        Containment::Inside
    } else {
        Containment::Outside
    }
}

/// `orient2d(a, b, c + (ε, ε²))` for infinitesimal ε > 0; `Degenerate` only when `a == b`.
fn perturbed_orient2d<K: Kernel>(a: DVec2, b: DVec2, c: DVec2) -> Orientation {
    let o = K::orient2d(a, b, c);
    if !o.is_degenerate() {
        return o;
    }
    // d/dc.x = -(b.y - a.y), d/dc.y = b.x - a.x.
    if a.y != b.y {
        if a.y > b.y {
            Orientation::Positive
        } else {
            Orientation::Negative
        }
    } else if a.x != b.x {
        if b.x > a.x {
            Orientation::Positive
        } else {
            Orientation::Negative
        }
    } else {
        Orientation::Degenerate
    }
}
