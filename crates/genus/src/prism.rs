//! Alpha-prisms (El-Sana and Varshney 1997, sections 3.1 and 4.1).
//!
//! The alpha-prism of a triangle `t` is the Minkowski sum of `t` with the axis-aligned cube of
//! side `2 alpha` (the L-infinity ball of radius `alpha`): the convex hull of the 24 corners
//! of the three cubes centred at the triangle's vertices.
//!
//! **Constructions.** The 24 corners `v ± alpha` are plain f64, rounded *outward* (a `+alpha`
//! coordinate rounded up, a `-alpha` one rounded down), so the hull of the constructed points
//! contains the exact Minkowski sum. Every decision after that (which corners are extreme,
//! which planes support the hull, whether a point is inside, whether two prisms meet) is
//! exact on those f64 points, through orient3d of `envelope-predicates`.
//!
//! **The 6-bit scheme (4.1).** Each corner gets a bit vector (bit 0..5 = it has the minimum
//! x, maximum x, minimum y, maximum y, minimum z, maximum z of all 24 corners); an edge's bits
//! are the AND of its corners', a cube face's bits the AND of its four edges'. A cube face
//! with non-zero bits lies on the hull (its plane is a coordinate extreme). The paper leaves
//! out "the faces spanned between cubes"; our reading: the remaining facets of a Minkowski sum
//! of a triangle and a cube are (a) a triangle edge swept along a cube edge (a parallelogram
//! spanned by the same cube edge at two triangle vertices) and (b) the triangle translated to
//! one cube corner. We generate those 36 + 8 candidate planes and keep the ones all 24 corners
//! lie on one side of (exact orient3d). Candidates that land on the same plane (coplanar
//! cube faces when the triangle has an axis-parallel edge, a triangle lying in a coordinate
//! plane, collinear or repeated vertices) merge into one facet: a facet is identified by the
//! set of corners exactly on its plane. The property tests compare every hull with a general
//! exact O(n^4) hull ([`crate::details::exact_hull_facets`]).

use std::collections::BTreeSet;

use envelope_predicates::{Orientation, SegmentTriangle, next_up, orient3d, segment_triangle};
use glam::DVec3;

use crate::GenusError;

/// Bit of the minimum x among the 24 corners (bit 0 of the paper's vector).
pub const MIN_X: u8 = 1;
/// Bit of the maximum x.
pub const MAX_X: u8 = 2;
/// Bit of the minimum y.
pub const MIN_Y: u8 = 4;
/// Bit of the maximum y.
pub const MAX_Y: u8 = 8;
/// Bit of the minimum z.
pub const MIN_Z: u8 = 16;
/// Bit of the maximum z.
pub const MAX_Z: u8 = 32;

/// The 12 edges of a cube as pairs of corner indices; corner `k` has offset sign `+` on axis
/// `a` when bit `a` of `k` is set.
pub(crate) const CUBE_EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [2, 3],
    [4, 5],
    [6, 7],
    [0, 2],
    [1, 3],
    [4, 6],
    [5, 7],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];

/// The 6 faces of a cube as four edge indices (into [`CUBE_EDGES`]) and the bit whose face it
/// is, in the order -x, +x, -y, +y, -z, +z.
const CUBE_FACES: [([usize; 4], u8); 6] = [
    ([4, 6, 8, 10], MIN_X),
    ([5, 7, 9, 11], MAX_X),
    ([0, 2, 8, 9], MIN_Y),
    ([1, 3, 10, 11], MAX_Y),
    ([0, 1, 4, 5], MIN_Z),
    ([2, 3, 6, 7], MAX_Z),
];

/// `x + alpha` rounded up (exact when representable).
fn add_up(x: f64, alpha: f64) -> f64 {
    let s = x + alpha;
    // TwoSum error term: the exact sum is s + err.
    let bv = s - x;
    let av = s - bv;
    let err = (x - av) + (alpha - bv);
    if err > 0.0 { next_up(s) } else { s }
}

/// `x - alpha` rounded down.
fn sub_down(x: f64, alpha: f64) -> f64 {
    -add_up(-x, alpha)
}

/// The 8 corners of the cube of L-infinity radius `alpha` around `v`, rounded outward, corner
/// `k` taking `+alpha` on axis `a` when bit `a` of `k` is set (f64 construction).
#[must_use]
pub fn cube_corners(v: DVec3, alpha: f64) -> [DVec3; 8] {
    std::array::from_fn(|k| {
        let c = |a: usize, x: f64| {
            if k >> a & 1 == 1 {
                add_up(x, alpha)
            } else {
                sub_down(x, alpha)
            }
        };
        DVec3::new(c(0, v.x), c(1, v.y), c(2, v.z))
    })
}

/// One facet of an [`AlphaPrism`].
#[derive(Clone, Debug, PartialEq)]
pub struct Facet {
    /// Every hull vertex exactly on the facet's plane (indices into [`AlphaPrism::points`]),
    /// increasing.
    pub on_plane: Vec<usize>,
    /// The extreme ones, counter-clockwise seen from outside (collinear boundary points
    /// dropped).
    pub polygon: Vec<usize>,
}

/// The alpha-prism of one triangle: a convex polytope with f64 vertices (see the module docs).
///
/// ```
/// use envelope_genus::AlphaPrism;
/// use glam::DVec3;
/// let p = AlphaPrism::new([DVec3::ZERO, DVec3::X, DVec3::Y], 0.25).unwrap();
/// // A right triangle in the plane z = 0 swept by a cube: an extruded pentagon, 7 facets.
/// assert_eq!(p.facets.len(), 7);
/// assert!(p.contains(DVec3::new(0.5, 0.5, 0.25)));
/// assert!(!p.contains(DVec3::new(0.5, 0.5, 0.26)));
/// p.sanity_check().unwrap();
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct AlphaPrism {
    /// The distinct corners (deduplicated by exact position), in cube-major order.
    pub points: Vec<DVec3>,
    /// The 6-bit vector of each of [`AlphaPrism::points`] (see the module docs).
    pub bits: Vec<u8>,
    /// Hull facets.
    pub facets: Vec<Facet>,
    /// A fan triangulation of every facet, outward (right-hand normal points out).
    pub triangles: Vec<[usize; 3]>,
    /// Hull edges (pairs of point indices, smaller first), from the facet polygons.
    pub edges: Vec<[usize; 2]>,
    /// Exact bounding box of the points.
    pub bbox: (DVec3, DVec3),
}

impl AlphaPrism {
    /// Builds the alpha-prism of `triangle` (any triangle, degenerate ones included).
    ///
    /// # Errors
    /// [`GenusError::InvalidAlpha`] unless `alpha` is finite and positive;
    /// [`GenusError::NonFiniteCoordinate`] for a NaN or infinite corner.
    pub fn new(triangle: [DVec3; 3], alpha: f64) -> Result<Self, GenusError> {
        if !(alpha.is_finite() && alpha > 0.0) {
            return Err(GenusError::InvalidAlpha(alpha));
        }
        if triangle.iter().any(|p| !p.is_finite()) {
            return Err(GenusError::NonFiniteCoordinate { vertex: None });
        }
        let raw: Vec<DVec3> = triangle
            .iter()
            .flat_map(|&v| cube_corners(v, alpha))
            .collect();
        if raw.iter().any(|p| !p.is_finite()) {
            return Err(GenusError::NonFiniteCoordinate { vertex: None });
        }
        // Deduplicate (repeated triangle vertices give identical cubes).
        let mut points: Vec<DVec3> = Vec::with_capacity(24);
        let mut id = [0usize; 24];
        for (i, p) in raw.iter().enumerate() {
            id[i] = match points.iter().position(|q| q == p) {
                Some(j) => j,
                None => {
                    points.push(*p);
                    points.len() - 1
                }
            };
        }
        let bits = vertex_bits(&points);
        // A reference point strictly inside: the hull of an alpha > 0 cube is full-dimensional;
        // the cube at vertex 0 has two opposite corners, and any point of the hull not on a
        // facet plane works as the reference; we test against every point instead (exact).
        let mut planes: Vec<[usize; 3]> = Vec::new();
        // (1) Cube faces with non-zero face bits.
        for cube in 0..3 {
            for (edges, _bit) in CUBE_FACES {
                let face_bits = edges.iter().fold(0x3f_u8, |acc, &e| {
                    let [a, b] = CUBE_EDGES[e];
                    acc & bits[id[cube * 8 + a]] & bits[id[cube * 8 + b]]
                });
                if face_bits != 0 {
                    let [a, b] = CUBE_EDGES[edges[0]];
                    let [c, d] = CUBE_EDGES[edges[1]];
                    let q = [a, b, c, d].map(|k| id[cube * 8 + k]);
                    if let Some(t) = non_collinear(&points, &q) {
                        planes.push(t);
                    }
                }
            }
        }
        // (2) Parallelograms: the same cube edge at two triangle vertices.
        for (i, j) in [(0, 1), (1, 2), (0, 2)] {
            for [a, b] in CUBE_EDGES {
                let q = [id[i * 8 + a], id[i * 8 + b], id[j * 8 + a], id[j * 8 + b]];
                if let Some(t) = non_collinear(&points, &q) {
                    planes.push(t);
                }
            }
        }
        // (3) The triangle at each cube corner.
        for k in 0..8 {
            let q = [id[k], id[8 + k], id[16 + k]];
            if let Some(t) = non_collinear(&points, &q) {
                planes.push(t);
            }
        }
        let mut seen: BTreeSet<Vec<usize>> = BTreeSet::new();
        let mut facets = Vec::new();
        for t in planes {
            if let Some(on_plane) = supporting_set(&points, t) {
                if seen.insert(on_plane.clone()) {
                    let polygon = order_facet(&points, &on_plane, t);
                    facets.push(Facet { on_plane, polygon });
                }
            }
        }
        let mut triangles = Vec::new();
        let mut edges = BTreeSet::new();
        for f in &facets {
            let p = &f.polygon;
            for k in 1..p.len().saturating_sub(1) {
                triangles.push([p[0], p[k], p[k + 1]]);
            }
            for k in 0..p.len() {
                let (a, b) = (p[k], p[(k + 1) % p.len()]);
                edges.insert([a.min(b), a.max(b)]);
            }
        }
        let mut lo = points[0];
        let mut hi = points[0];
        for p in &points {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        Ok(AlphaPrism {
            points,
            bits,
            facets,
            triangles,
            edges: edges.into_iter().collect(),
            bbox: (lo, hi),
        })
    }

    /// The facet triangles as positions.
    pub fn triangle_positions(&self) -> impl Iterator<Item = [DVec3; 3]> + '_ {
        self.triangles.iter().map(|t| t.map(|i| self.points[i]))
    }

    /// Exact containment of `p` in the closed prism: no facet has `p` strictly outside.
    #[must_use]
    pub fn contains(&self, p: DVec3) -> bool {
        self.locate(p) != PointLocation::Outside
    }

    /// Exact location of `p` relative to the closed prism.
    #[must_use]
    pub fn locate(&self, p: DVec3) -> PointLocation {
        if (0..3).any(|a| p[a] < self.bbox.0[a] || p[a] > self.bbox.1[a]) {
            return PointLocation::Outside;
        }
        let mut boundary = false;
        for t in &self.triangles {
            match orient3d(self.points[t[0]], self.points[t[1]], self.points[t[2]], p) {
                Orientation::Positive => return PointLocation::Outside,
                Orientation::Degenerate => boundary = true,
                Orientation::Negative => {}
            }
        }
        if boundary {
            PointLocation::Boundary
        } else {
            PointLocation::Inside
        }
    }

    /// Whether the closed prisms share a point, decided exactly: they do iff a vertex of one
    /// is in the other or an edge of one meets a facet triangle of the other (every vertex of
    /// the intersection polytope is of one of those kinds). A bounding-box test rejects first.
    #[must_use]
    pub fn intersects(&self, other: &AlphaPrism) -> bool {
        if (0..3).any(|a| self.bbox.1[a] < other.bbox.0[a] || other.bbox.1[a] < self.bbox.0[a]) {
            return false;
        }
        if self.points.iter().any(|&p| other.contains(p))
            || other.points.iter().any(|&p| self.contains(p))
        {
            return true;
        }
        let edges_meet = |a: &AlphaPrism, b: &AlphaPrism| {
            a.edges.iter().any(|&[i, j]| {
                b.triangle_positions().any(|t| {
                    segment_triangle(a.points[i], a.points[j], t) != SegmentTriangle::Disjoint
                })
            })
        };
        edges_meet(self, other) || edges_meet(other, self)
    }

    /// Verifies the invariants: every facet supports the hull (all points on its inner side,
    /// exact), polygons are convex and outward, Euler's formula `V - E + F = 2` holds for the
    /// extreme vertices, and each point's bits match the coordinate extremes.
    ///
    /// # Errors
    /// A description of the first violated invariant.
    pub fn sanity_check(&self) -> Result<(), String> {
        if vertex_bits(&self.points) != self.bits {
            return Err("bit vectors do not match the coordinate extremes".into());
        }
        for (n, t) in self.triangles.iter().enumerate() {
            let [a, b, c] = t.map(|i| self.points[i]);
            if crate::exact::collinear(a, b, c) {
                return Err(format!("facet triangle {n} is degenerate"));
            }
            for (k, &p) in self.points.iter().enumerate() {
                if orient3d(a, b, c, p) == Orientation::Positive {
                    return Err(format!("point {k} is outside facet triangle {n}"));
                }
            }
        }
        let mut used: BTreeSet<usize> = BTreeSet::new();
        for f in &self.facets {
            used.extend(f.polygon.iter().copied());
        }
        let chi = used.len() as i64 - self.edges.len() as i64 + self.facets.len() as i64;
        if chi != 2 {
            return Err(format!("V - E + F = {chi}, not 2"));
        }
        Ok(())
    }
}

/// Where a point is relative to a closed convex polytope.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointLocation {
    /// Strictly inside.
    Inside,
    /// On a facet.
    Boundary,
    /// Strictly outside.
    Outside,
}

/// The 6-bit vectors of `points` (exact f64 comparisons).
#[must_use]
pub fn vertex_bits(points: &[DVec3]) -> Vec<u8> {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in points {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    points
        .iter()
        .map(|p| {
            let mut b = 0u8;
            for a in 0..3 {
                if p[a] == lo[a] {
                    b |= 1 << (2 * a);
                }
                if p[a] == hi[a] {
                    b |= 1 << (2 * a + 1);
                }
            }
            b
        })
        .collect()
}

/// Three of `q` that are not collinear (exact), if any.
fn non_collinear(points: &[DVec3], q: &[usize]) -> Option<[usize; 3]> {
    let n = q.len();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let (a, b, c) = (points[q[i]], points[q[j]], points[q[k]]);
                if !crate::exact::collinear(a, b, c) {
                    return Some([q[i], q[j], q[k]]);
                }
            }
        }
    }
    None
}

/// If every point lies on one closed side of the plane through `t`, the indices exactly on the
/// plane (increasing); `None` when points lie strictly on both sides.
pub(crate) fn supporting_set(points: &[DVec3], t: [usize; 3]) -> Option<Vec<usize>> {
    let [a, b, c] = t.map(|i| points[i]);
    let (mut pos, mut neg) = (false, false);
    let mut on = Vec::new();
    for (k, &p) in points.iter().enumerate() {
        match orient3d(a, b, c, p) {
            Orientation::Positive => pos = true,
            Orientation::Negative => neg = true,
            Orientation::Degenerate => on.push(k),
        }
        if pos && neg {
            return None;
        }
    }
    (pos || neg).then_some(on)
}

/// Orders the coplanar points `on` (plane through `t`) into a convex polygon,
/// counter-clockwise seen from outside, dropping points in the relative interior of edges or
/// of the facet (gift wrapping with exact orient3d against an off-plane point).
pub(crate) fn order_facet(points: &[DVec3], on: &[usize], t: [usize; 3]) -> Vec<usize> {
    let [a, b, c] = t.map(|i| points[i]);
    // An off-plane point, and the orientation sign "(p, q, r) counter-clockwise from outside".
    let Some(off) = (0..points.len()).find(|&k| !orient3d(a, b, c, points[k]).is_degenerate())
    else {
        return Vec::new();
    };
    let inside = points[off];
    // ccw(p, q, r) from outside <=> orient3d(p, q, r, inside) is Negative.
    let turn = |p: usize, q: usize, r: usize| orient3d(points[p], points[q], points[r], inside);
    // Start: the lexicographically smallest point is extreme.
    let start = *on
        .iter()
        .min_by(|&&i, &&j| {
            let (p, q) = (points[i], points[j]);
            p.x.total_cmp(&q.x)
                .then(p.y.total_cmp(&q.y))
                .then(p.z.total_cmp(&q.z))
        })
        .expect("a supporting plane holds three points");
    let mut poly = vec![start];
    let mut cur = start;
    loop {
        // Next: the candidate such that no point is strictly to its right (clockwise).
        let mut next = if on[0] == cur { on[1] } else { on[0] };
        for &r in on {
            if r == cur || r == next {
                continue;
            }
            match turn(cur, next, r) {
                Orientation::Positive => next = r, // r is clockwise of cur->next
                Orientation::Degenerate => {
                    // Collinear: take the farther one (exact via dot-sign of projections).
                    let (pc, pn, pr) = (points[cur], points[next], points[r]);
                    if crate::exact::farther(pc, pn, pr) {
                        next = r;
                    }
                }
                Orientation::Negative => {}
            }
        }
        if next == start || poly.len() > on.len() {
            break;
        }
        poly.push(next);
        cur = next;
    }
    poly
}
