//! Triangulating one polygon face (the corners of an OBJ, OFF or PLY polygon) without creating
//! overlapping triangles, also when the polygon is not convex or not planar.
//!
//! The polygon is projected to an axis-aligned plane by dropping one coordinate (exact: the
//! projected problem is the polygon itself, no rounding). The axis of the largest component
//! of the f64 Newell normal is tried first (a heuristic choice, not a guarantee), then the
//! other two. In a projection:
//!
//! 1. the corners are inserted in polygon order into a `spade` constrained Delaunay
//!    triangulation (spade's last-vertex hint keeps a convex polygon near-linear); a corner
//!    that lands on an earlier one (two corners on one position) means "not simple here";
//! 2. every polygon edge is added with `try_add_constraint`; a constraint that crosses an
//!    earlier one (empty result) or passes through a corner (split in several edges) means
//!    "not simple here". Spade decides these with exact orientation tests;
//! 3. the polygon's orientation is decided exactly (`orient2d` at its lowest-leftmost corner),
//!    the triangles on the inner side of the constraint edges are flood-filled without crossing
//!    a constraint, and exactly `n - 2` of them must be found (reaching the outer face means
//!    "not simple here");
//! 4. the triangles are emitted with the polygon's winding (each CDT face is counter-clockwise
//!    in the projection, so they are reversed when the projected polygon is clockwise).
//!
//! Why this is right also for non-planar polygons: the triangles do not overlap in the
//! projection, so their lifts (a height field over the projection plane, each corner keeping
//! its own dropped coordinate) meet only along shared edges and corners: the triangulation
//! never creates an intersection, only the polygon's own (already non-planar) shape.
//!
//! When no axis gives a simple projection the polygon is refused ([`PolygonError::NotSimple`]):
//! it is self-intersecting, or too folded for any height-field triangulation. Costs: inserting
//! the corners is expected `O(n log n)` (near-linear in polygon order); adding the constraints
//! is linear for polygons whose Delaunay triangulation few edges cross, and quadratic in the
//! worst case (long zig-zags), as for any constraint-by-constraint CDT.
//!
//! Coordinates must be finite and within spade's range (2^-142 .. 2^201 in magnitude, or
//! zero), which contains the range the mesh readers accept; a coordinate outside it makes that
//! projection fail, so the polygon is refused rather than mis-triangulated.

use glam::{DVec2, DVec3};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use crate::{Orientation, orient2d};

/// Why a polygon could not be triangulated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PolygonError {
    /// Fewer than three corners.
    TooFewCorners,
    /// No axis-aligned projection of the polygon is a simple polygon (it self-intersects,
    /// touches itself, has two corners on one position, or is folded over in every
    /// projection).
    NotSimple,
}

/// Triangulates the closed polygon `corners` (in order, no repeated points expected) into
/// `n - 2` triangles of corner indices, with the polygon's winding, none overlapping another
/// in the projection used (so none intersecting another in space but along shared edges).
/// Each triangle starts at its lowest corner index, and the triangles are sorted.
///
/// ```
/// use envelope_predicates::polygon::{triangulate_polygon, PolygonError};
/// use glam::DVec3;
/// let p = |x, y| DVec3::new(x, y, 0.0);
/// // A U shape: a fan from corner 0 would cover the notch.
/// let u = [p(0., 0.), p(3., 0.), p(3., 3.), p(2., 3.), p(2., 1.), p(1., 1.), p(1., 3.), p(0., 3.)];
/// let tris = triangulate_polygon(&u).unwrap();
/// assert_eq!(tris.len(), 6);
/// // A bow-tie crosses itself in every projection.
/// let bow = [p(0., 0.), p(1., 1.), p(1., 0.), p(0., 1.)];
/// assert_eq!(triangulate_polygon(&bow), Err(PolygonError::NotSimple));
/// ```
///
/// # Errors
/// [`PolygonError::TooFewCorners`] for fewer than three corners, [`PolygonError::NotSimple`]
/// when no axis-aligned projection is a simple polygon.
pub fn triangulate_polygon(corners: &[DVec3]) -> Result<Vec<[u32; 3]>, PolygonError> {
    if corners.len() < 3 {
        return Err(PolygonError::TooFewCorners);
    }
    if u32::try_from(corners.len()).is_err() {
        return Err(PolygonError::NotSimple);
    }
    for drop in axis_order(newell_normal(corners)) {
        let projected: Vec<DVec2> = corners.iter().map(|&p| project(p, drop)).collect();
        if let Some(triangles) = triangulate_projected(&projected) {
            return Ok(triangles);
        }
    }
    Err(PolygonError::NotSimple)
}

/// The (f64, inexact) Newell normal: only orders the projections to try.
fn newell_normal(corners: &[DVec3]) -> DVec3 {
    let n = corners.len();
    let mut normal = DVec3::ZERO;
    for i in 0..n {
        let (p, q) = (corners[i], corners[(i + 1) % n]);
        normal += DVec3::new(
            (p.y - q.y) * (p.z + q.z),
            (p.z - q.z) * (p.x + q.x),
            (p.x - q.x) * (p.y + q.y),
        );
    }
    normal
}

/// The coordinates to drop, largest normal component first (a NaN normal keeps x, y, z).
fn axis_order(normal: DVec3) -> [usize; 3] {
    let a = normal.abs().to_array();
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| a[j].total_cmp(&a[i]));
    order
}

/// Drops coordinate `drop`, keeping a right-handed pair (y z, z x or x y).
fn project(p: DVec3, drop: usize) -> DVec2 {
    match drop {
        0 => DVec2::new(p.y, p.z),
        1 => DVec2::new(p.z, p.x),
        _ => DVec2::new(p.x, p.y),
    }
}

/// Exact orientation of a polygon at its lowest-leftmost corner (degenerate there when the
/// polygon is not simple).
fn polygon_orientation(p: &[DVec2]) -> Orientation {
    let n = p.len();
    let m = (0..n)
        .min_by(|&i, &j| p[i].y.total_cmp(&p[j].y).then(p[i].x.total_cmp(&p[j].x)))
        .unwrap_or(0);
    orient2d(p[(m + n - 1) % n], p[m], p[(m + 1) % n])
}

/// The triangulation of a projected polygon, `None` when it is not simple.
fn triangulate_projected(p: &[DVec2]) -> Option<Vec<[u32; 3]>> {
    let n = p.len();
    let ccw = match polygon_orientation(p) {
        Orientation::Positive => true,
        Orientation::Negative => false,
        Orientation::Degenerate => return None,
    };
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let mut handles = Vec::with_capacity(n);
    for (i, q) in p.iter().enumerate() {
        let h = cdt.insert(Point2::new(q.x, q.y)).ok()?;
        // Spade merges a point equal to an earlier one: two corners on one position.
        if h.index() != i {
            return None;
        }
        handles.push(h);
    }
    for i in 0..n {
        // One edge back means the whole polygon edge is one constraint: nothing crossed, no
        // corner on it.
        if cdt
            .try_add_constraint(handles[i], handles[(i + 1) % n])
            .len()
            != 1
        {
            return None;
        }
    }
    let mut inside = vec![false; cdt.num_all_faces()];
    let mut stack = Vec::new();
    for i in 0..n {
        let (a, b) = (handles[i], handles[(i + 1) % n]);
        // The inner side is to the left of each edge of a counter-clockwise polygon.
        let (a, b) = if ccw { (a, b) } else { (b, a) };
        let face = cdt.get_edge_from_neighbors(a, b)?.face().as_inner()?.fix();
        if !inside[face.index()] {
            inside[face.index()] = true;
            stack.push(face);
        }
    }
    let mut found = Vec::with_capacity(n - 2);
    while let Some(f) = stack.pop() {
        found.push(f);
        if found.len() > n - 2 {
            return None;
        }
        for e in cdt.face(f).adjacent_edges() {
            if cdt.is_constraint_edge(e.as_undirected().fix()) {
                continue;
            }
            // Leaving through a non-constraint edge onto the outer face: the polygon leaks.
            let g = e.rev().face().as_inner()?.fix();
            if !inside[g.index()] {
                inside[g.index()] = true;
                stack.push(g);
            }
        }
    }
    if found.len() != n - 2 {
        return None;
    }
    let mut triangles: Vec<[u32; 3]> = found
        .into_iter()
        .map(|f| {
            let [a, b, c] = cdt.face(f).vertices().map(|v| v.fix().index() as u32);
            let t = if ccw { [a, b, c] } else { [a, c, b] };
            // Lowest corner first, triangles sorted: the output does not depend on spade's
            // internal numbering (a convex quad cut along 0-2 reads [0, 1, 2], [0, 2, 3]).
            let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
            [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
        })
        .collect();
    triangles.sort_unstable();
    Some(triangles)
}

/// Whether the interiors of two counter-clockwise triangles in the plane overlap: they do
/// unless an edge of one has the other entirely on its closed outer side (separating axis,
/// decided by exact [`orient2d`]). Triangles that only touch do not overlap.
///
/// ```
/// use envelope_predicates::polygon::interiors_overlap;
/// use glam::DVec2;
/// let t = [DVec2::ZERO, DVec2::X, DVec2::Y];
/// assert!(interiors_overlap(t, [DVec2::splat(0.1), DVec2::new(2.0, 0.1), DVec2::new(0.1, 2.0)]));
/// assert!(!interiors_overlap(t, [DVec2::X, DVec2::ONE, DVec2::Y])); // shares an edge only
/// ```
#[must_use]
pub fn interiors_overlap(s: [DVec2; 3], t: [DVec2; 3]) -> bool {
    let separates = |a: [DVec2; 3], b: [DVec2; 3]| {
        (0..3).any(|k| {
            b.iter()
                .all(|&q| orient2d(a[k], a[(k + 1) % 3], q) != Orientation::Positive)
        })
    };
    !separates(s, t) && !separates(t, s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::triangles_intersect;

    fn p(x: f64, y: f64) -> DVec3 {
        DVec3::new(x, y, 0.0)
    }

    /// Signed doubled area of a triangle in the xy plane (exact for the small integers used).
    fn area(c: &[DVec3], t: [u32; 3]) -> f64 {
        let [a, b, d] = t.map(|i| c[i as usize]);
        (b - a).truncate().perp_dot((d - a).truncate())
    }

    /// `n - 2` triangles, each turning like the polygon, and the areas adding up to the
    /// polygon's: with no overlap and every triangle inside, the sum is exact.
    fn assert_partition(c: &[DVec3], tris: &[[u32; 3]]) {
        assert_eq!(tris.len(), c.len() - 2);
        let n = c.len();
        let poly: f64 = (0..n)
            .map(|i| c[i].truncate().perp_dot(c[(i + 1) % n].truncate()))
            .sum();
        let sum: f64 = tris.iter().map(|&t| area(c, t)).sum();
        for &t in tris {
            assert!(
                area(c, t) * poly.signum() > 0.0,
                "{t:?} turns the wrong way"
            );
        }
        assert!((sum - poly).abs() <= 1e-9 * poly.abs(), "{sum} vs {poly}");
    }

    #[test]
    fn u_shape_both_windings() {
        let mut u = vec![
            p(0., 0.),
            p(3., 0.),
            p(3., 3.),
            p(2., 3.),
            p(2., 1.),
            p(1., 1.),
            p(1., 3.),
            p(0., 3.),
        ];
        let tris = triangulate_polygon(&u).unwrap();
        assert_partition(&u, &tris);
        u.reverse();
        let tris = triangulate_polygon(&u).unwrap();
        assert_partition(&u, &tris);
    }

    #[test]
    fn star_no_two_triangles_intersect_but_along_shared_corners() {
        let n = 200;
        let c: Vec<DVec3> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                let r = if i % 2 == 0 { 10.0 } else { 3.0 };
                DVec3::new(r * a.cos(), r * a.sin(), 0.0)
            })
            .collect();
        let tris = triangulate_polygon(&c).unwrap();
        assert_eq!(tris.len(), n - 2);
        for &t in &tris {
            assert!(area(&c, t) > 0.0);
        }
        // No two interiors overlap (exact separating-edge test in the plane of the star).
        let flat = |t: [u32; 3]| t.map(|v| c[v as usize].truncate());
        for (i, &s) in tris.iter().enumerate() {
            for &t in &tris[i + 1..] {
                assert!(!interiors_overlap(flat(s), flat(t)), "{s:?} {t:?}");
            }
        }
        // And triangles sharing no corner do not meet at all (3-D exact test).
        for (i, &s) in tris.iter().enumerate() {
            for &t in &tris[i + 1..] {
                if s.iter().any(|v| t.contains(v)) {
                    continue;
                }
                let f = |t: [u32; 3]| t.map(|v| c[v as usize]);
                assert!(!triangles_intersect(f(s), f(t)), "{s:?} {t:?}");
            }
        }
    }

    #[test]
    fn vertical_and_non_planar_polygons() {
        // A square in the xz plane: the Newell normal picks y to drop.
        let sq = [
            DVec3::new(0., 0., 0.),
            DVec3::new(1., 0., 0.),
            DVec3::new(1., 0., 1.),
            DVec3::new(0., 0., 1.),
        ];
        assert_eq!(triangulate_polygon(&sq).unwrap().len(), 2);
        let skew = [
            DVec3::new(0., 0., 0.),
            DVec3::new(1., 0., 0.),
            DVec3::new(1., 1., 1.),
            DVec3::new(0., 1., 0.),
        ];
        let tris = triangulate_polygon(&skew).unwrap();
        assert_eq!(tris.len(), 2);
        // Winding kept: both triangles' normals point up like the polygon's.
        for t in tris {
            let [a, b, c] = t.map(|i| skew[i as usize]);
            assert!((b - a).cross(c - a).z > 0.0);
        }
    }

    #[test]
    fn refusals() {
        assert_eq!(
            triangulate_polygon(&[p(0., 0.), p(1., 0.)]),
            Err(PolygonError::TooFewCorners)
        );
        let bow = [p(0., 0.), p(1., 1.), p(1., 0.), p(0., 1.)];
        assert_eq!(triangulate_polygon(&bow), Err(PolygonError::NotSimple));
        // A corner on another edge (touching itself).
        let touch = [p(0., 0.), p(4., 0.), p(4., 4.), p(2., 0.), p(0., 4.)];
        assert_eq!(triangulate_polygon(&touch), Err(PolygonError::NotSimple));
        // Two corners on one position.
        let twice = [
            p(0., 0.),
            p(2., 0.),
            p(1., 1.),
            p(2., 2.),
            p(0., 2.),
            p(1., 1.),
        ];
        assert_eq!(triangulate_polygon(&twice), Err(PolygonError::NotSimple));
        // All corners on a line.
        let flat = [p(0., 0.), p(1., 0.), p(2., 0.), p(3., 0.)];
        assert_eq!(triangulate_polygon(&flat), Err(PolygonError::NotSimple));
        // A pentagram winds twice.
        let star: Vec<DVec3> = (0..5)
            .map(|i| {
                let a = std::f64::consts::TAU * f64::from(2 * i) / 5.0;
                p(a.cos(), a.sin())
            })
            .collect();
        assert_eq!(triangulate_polygon(&star), Err(PolygonError::NotSimple));
    }

    #[test]
    fn collinear_corners_on_an_edge() {
        let c = [p(0., 0.), p(1., 0.), p(2., 0.), p(2., 2.), p(0., 2.)];
        let tris = triangulate_polygon(&c).unwrap();
        assert_partition(&c, &tris);
    }

    #[test]
    fn large_convex_polygon() {
        let n = 100_000;
        let c: Vec<DVec3> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                DVec3::new(a.cos(), a.sin(), 0.5 * a.cos())
            })
            .collect();
        let t = std::time::Instant::now();
        assert_eq!(triangulate_polygon(&c).unwrap().len(), n - 2);
        eprintln!("100000-gon: {:?}", t.elapsed());
    }
}
