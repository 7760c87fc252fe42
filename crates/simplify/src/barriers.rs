//! [`Barriers`]: the surfaces a candidate triangle must not touch (section 5.1) and the border
//! tubes a new border edge must not touch (section 6.2), as plain triangle data with one
//! static BVH over all of them.

use envelope_mesh::{CoordError, TriangleSoup, check_coordinate};
use envelope_predicates::bvh::{Aabb, Bvh};
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
        let mut triangles = Vec::new();
        let mut kinds = Vec::new();
        let has_tubes = tubes.iter().any(|t| t.num_faces() > 0);
        let all = envelopes
            .iter()
            .map(|s| (s, BarrierKind::Envelope))
            .chain(tubes.iter().map(|s| (s, BarrierKind::Tube)));
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

    /// True when the closed triangle `t` touches an envelope triangle, or when one of the
    /// closed segments `t[i] t[i+1]` with `border_edges[i]` touches a tube triangle. Exact.
    #[must_use]
    pub fn blocks(&self, t: [DVec3; 3], border_edges: [bool; 3]) -> bool {
        let Some(bvh) = &self.bvh else {
            return false;
        };
        let query = Aabb::from_triangle(t);
        let mut hit = false;
        bvh.for_each_overlapping(&query, |i| {
            if hit {
                return;
            }
            let b = self.triangles[i as usize];
            hit = match self.kinds[i as usize] {
                BarrierKind::Envelope => triangles_intersect(t, b),
                BarrierKind::Tube => (0..3).any(|k| {
                    border_edges[k]
                        && segment_triangle(t[k], t[(k + 1) % 3], b) != SegmentTriangle::Disjoint
                }),
            };
        });
        hit
    }
}
