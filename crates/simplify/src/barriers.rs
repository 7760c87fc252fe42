//! [`Barriers`]: the surfaces a candidate triangle must not touch (section 5.1) and the border
//! tubes a new border edge must not touch (section 6.2), as plain triangle data with one
//! static BVH over all of them.

use envelope_mesh::{CoordError, TriangleSoup, check_coordinate};
use envelope_predicates::bvh::{Aabb, Bvh, NodeKind};
use envelope_predicates::{SegmentTriangle, segment_triangle, triangles_intersect};
use glam::DVec3;
use thiserror::Error;

/// What a barrier triangle constrains.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BarrierKind {
    /// An envelope surface (outer or inner, section 4): no candidate triangle may touch it.
    Envelope,
    /// A border tube (section 6.2): no new *border edge* may touch it. Tubes are not tested
    /// against whole triangles: the surface near a border leaves the tube through its wall.
    Tube,
    /// A border wall ([`crate::border_walls`]): joins the outer and inner envelopes along a
    /// border, and like them no candidate triangle may touch it.
    Wall,
}

/// Why [`Barriers::new`] refused its input. Names the surface (index in the argument order:
/// envelopes first, then tubes) and the element.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
pub enum BarrierError {
    /// A face names a vertex the soup does not have.
    #[error("barrier surface {surface}: face {face} names a vertex out of range")]
    IndexOutOfRange {
        /// The surface.
        surface: usize,
        /// The face.
        face: usize,
    },
    /// A coordinate the exact predicates cannot take.
    #[error("barrier surface {surface}: vertex {vertex}: {error}")]
    Coordinate {
        /// The surface.
        surface: usize,
        /// The vertex.
        vertex: usize,
        /// What is wrong with it.
        error: CoordError,
    },
}

/// The envelopes and border tubes, flattened into one triangle list with one BVH.
///
/// The triangles are the f64 points the envelope builder constructed; every test against
/// them is exact (closed triangles: touching counts as intersecting).
///
/// ```
/// use envelope_mesh::generate;
/// use envelope_simplify::Barriers;
/// let b = Barriers::new(vec![generate::icosphere(1, 1.1), generate::icosphere(1, 0.9)], vec![]).unwrap();
/// assert_eq!(b.num_triangles(), 160);
/// assert!(!b.has_tubes());
/// ```
#[derive(Clone, Debug, Default)]
pub struct Barriers {
    triangles: Vec<[DVec3; 3]>,
    kinds: Vec<BarrierKind>,
    bvh: Option<Bvh>,
    has_tubes: bool,
}

impl Barriers {
    /// No barrier at all: only the self-intersection part of the validity test remains.
    #[must_use]
    pub fn none() -> Self {
        Self::default()
    }

    /// Envelope surfaces (outer, inner; any number) and border tubes. Validates indices and
    /// coordinates (the exact-predicate range).
    pub fn new(
        envelopes: Vec<TriangleSoup>,
        tubes: Vec<TriangleSoup>,
    ) -> Result<Self, BarrierError> {
        Self::with_walls(envelopes, tubes, Vec::new())
    }

    /// Like [`Barriers::new`], plus border walls ([`BarrierKind::Wall`], full barriers).
    /// Surfaces are numbered envelopes first, then tubes, then walls.
    pub fn with_walls(
        envelopes: Vec<TriangleSoup>,
        tubes: Vec<TriangleSoup>,
        walls: Vec<TriangleSoup>,
    ) -> Result<Self, BarrierError> {
        let mut triangles = Vec::new();
        let mut kinds = Vec::new();
        let has_tubes = tubes.iter().any(|t| t.num_faces() > 0);
        let all = envelopes
            .iter()
            .map(|s| (s, BarrierKind::Envelope))
            .chain(tubes.iter().map(|s| (s, BarrierKind::Tube)))
            .chain(walls.iter().map(|s| (s, BarrierKind::Wall)));
        for (surface, (soup, kind)) in all.enumerate() {
            for (vertex, p) in soup.positions.iter().enumerate() {
                for x in p.to_array() {
                    check_coordinate(x).map_err(|error| BarrierError::Coordinate {
                        surface,
                        vertex,
                        error,
                    })?;
                }
            }
            if !soup.indices_in_range() {
                let face = soup
                    .faces
                    .iter()
                    .position(|f| f.iter().any(|v| v.index() >= soup.num_vertices()))
                    .unwrap_or(0);
                return Err(BarrierError::IndexOutOfRange { surface, face });
            }
            for f in soup.face_ids() {
                triangles.push(soup.triangle(f));
                kinds.push(kind);
            }
        }
        let boxes: Vec<Aabb> = triangles.iter().map(|&t| Aabb::from_triangle(t)).collect();
        let bvh = (!boxes.is_empty()).then(|| Bvh::new(&boxes));
        Ok(Self {
            triangles,
            kinds,
            bvh,
            has_tubes,
        })
    }

    /// Number of barrier triangles (envelopes and tubes).
    #[must_use]
    pub fn num_triangles(&self) -> usize {
        self.triangles.len()
    }

    /// Whether there is at least one tube triangle. Without tubes nothing bounds a border's
    /// creep (section 6.2), so the local simplifier keeps every border vertex.
    #[must_use]
    pub fn has_tubes(&self) -> bool {
        self.has_tubes
    }

    /// Barrier triangle `i` and its kind.
    #[must_use]
    pub fn triangle(&self, i: usize) -> ([DVec3; 3], BarrierKind) {
        (self.triangles[i], self.kinds[i])
    }

    /// True when the closed triangle `t` touches an envelope or wall triangle, or when one of the
    /// closed segments `t[i] t[i+1]` with `border_edges[i]` touches a tube triangle. Exact.
    #[must_use]
    pub fn blocks(&self, t: [DVec3; 3], border_edges: [bool; 3]) -> bool {
        let Some(bvh) = &self.bvh else {
            return false;
        };
        let Some(root) = bvh.root() else {
            return false;
        };
        let query = Aabb::from_triangle(t);
        let plane = SlabFilter::new(t);
        let mut stack = vec![root];
        while let Some(n) = stack.pop() {
            let bounds = bvh.bounds(n);
            if !bounds.overlaps(&query) || plane.separates(&bounds) {
                continue;
            }
            match bvh.kind(n) {
                NodeKind::Interior(a, b) => {
                    stack.push(b);
                    stack.push(a);
                }
                NodeKind::Leaf(items) => {
                    for &i in items {
                        let b = self.triangles[i as usize];
                        let hit = match self.kinds[i as usize] {
                            BarrierKind::Envelope | BarrierKind::Wall => {
                                !plane.separates(&Aabb::from_triangle(b))
                                    && triangles_intersect(t, b)
                            }
                            BarrierKind::Tube => (0..3).any(|k| {
                                border_edges[k]
                                    && segment_triangle(t[k], t[(k + 1) % 3], b)
                                        != SegmentTriangle::Disjoint
                            }),
                        };
                        if hit {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }
}

/// A conservative f64 separation test along the normal of a triangle `t`: `separates(box)`
/// is true only when the exact values of `n . x` over the box and over `t` do not overlap
/// (so the box cannot meet `t`). `n` is the f64 cross product, any vector would do: the
/// test is a separating-axis test on that axis, with every dot product's rounding error
/// (at most `3u sum |n_i x_i|`, bounded by `1e-15 |n|_1 max|x|` plus an underflow term)
/// added on both sides. It only prunes work; the decisions are the exact predicates'.
struct SlabFilter {
    n: DVec3,
    n1: f64,
    t_min: f64,
    t_max: f64,
    t_mag: f64,
}

impl SlabFilter {
    fn new(t: [DVec3; 3]) -> Self {
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        let d = t.map(|p| n.dot(p));
        let t_mag = t.iter().map(|p| p.abs().max_element()).fold(0.0, f64::max);
        Self {
            n,
            n1: n.abs().element_sum(),
            t_min: d[0].min(d[1]).min(d[2]),
            t_max: d[0].max(d[1]).max(d[2]),
            t_mag,
        }
    }

    fn separates(&self, b: &Aabb) -> bool {
        if !self.n1.is_finite() || self.n1 == 0.0 {
            return false;
        }
        let lo = DVec3::select(self.n.cmpge(DVec3::ZERO), b.min, b.max);
        let hi = DVec3::select(self.n.cmpge(DVec3::ZERO), b.max, b.min);
        let (b_min, b_max) = (self.n.dot(lo), self.n.dot(hi));
        let mag = self
            .t_mag
            .max(b.min.abs().max_element())
            .max(b.max.abs().max_element());
        let slack = 2.0 * (1e-15 * self.n1 * mag + 1e-300);
        b_min > self.t_max + slack || b_max < self.t_min - slack
    }
}
