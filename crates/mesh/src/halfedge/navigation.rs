//! Read-only queries on a [`HalfEdgeMesh`]: counts, live ids, positions, half-edge links,
//! one-rings around a vertex, border tests.

use super::{HalfEdgeMesh, NO_H};
use crate::{EdgeId, FaceId, HalfedgeId, VertexId};
use glam::DVec3;

/// Outgoing half-edges of a vertex in counter-clockwise order (seen from outside), starting at
/// the vertex's border half-edge if it has one. Made by [`HalfEdgeMesh::outgoing_halfedges`].
#[derive(Clone, Debug)]
pub struct OutgoingHalfedges<'a> {
    mesh: &'a HalfEdgeMesh,
    start: HalfedgeId,
    cur: HalfedgeId,
}

impl Iterator for OutgoingHalfedges<'_> {
    type Item = HalfedgeId;
    fn next(&mut self) -> Option<HalfedgeId> {
        if !self.cur.is_valid() {
            return None;
        }
        let h = self.cur;
        let n = self.mesh.rotate_ccw(h);
        self.cur = if n == self.start { NO_H } else { n };
        Some(h)
    }
}

impl HalfEdgeMesh {
    /// Number of live vertices (isolated ones included).
    #[must_use]
    pub fn num_vertices(&self) -> usize {
        self.positions.len() - self.free_vertices.len()
    }

    /// Number of live faces.
    #[must_use]
    pub fn num_faces(&self) -> usize {
        self.f_he.len() - self.free_faces.len()
    }

    /// Number of live edges.
    #[must_use]
    pub fn num_edges(&self) -> usize {
        self.he_to.len() / 2 - self.free_edges.len()
    }

    /// Live vertex ids, increasing.
    pub fn vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        (0..self.positions.len())
            .filter(|&v| self.v_alive[v])
            .map(VertexId::from_index)
    }

    /// Live face ids, increasing.
    pub fn faces(&self) -> impl Iterator<Item = FaceId> + '_ {
        (0..self.f_he.len())
            .filter(|&f| self.f_he[f].is_valid())
            .map(FaceId::from_index)
    }

    /// Live edge ids, increasing.
    pub fn edges(&self) -> impl Iterator<Item = EdgeId> + '_ {
        (0..self.he_to.len() / 2)
            .filter(|&e| self.he_to[2 * e].is_valid())
            .map(EdgeId::from_index)
    }

    /// Whether `v` is a live vertex.
    #[must_use]
    pub fn contains_vertex(&self, v: VertexId) -> bool {
        self.v_alive.get(v.index()).copied().unwrap_or(false)
    }

    /// Whether `f` is a live face.
    #[must_use]
    pub fn contains_face(&self, f: FaceId) -> bool {
        self.f_he.get(f.index()).is_some_and(|h| h.is_valid())
    }

    /// Position of `v`.
    #[must_use]
    pub fn position(&self, v: VertexId) -> DVec3 {
        self.positions[v.index()]
    }

    /// The corners of `f`, counter-clockwise; the first is the origin of
    /// [`Self::face_halfedge`].
    #[must_use]
    pub fn face_vertices(&self, f: FaceId) -> [VertexId; 3] {
        let h = self.f_he[f.index()];
        let n = self.next(h);
        [self.origin(h), self.target(h), self.target(n)]
    }

    /// A half-edge of `f`.
    #[must_use]
    pub fn face_halfedge(&self, f: FaceId) -> HalfedgeId {
        self.f_he[f.index()]
    }

    /// An outgoing half-edge of `v` (a border one if `v` is on the border), `None` if `v` is
    /// isolated.
    #[must_use]
    pub fn vertex_halfedge(&self, v: VertexId) -> Option<HalfedgeId> {
        Some(self.v_out[v.index()]).filter(|h| h.is_valid())
    }

    /// Next half-edge around the face (or border cycle).
    #[must_use]
    pub fn next(&self, h: HalfedgeId) -> HalfedgeId {
        self.he_next[h.index()]
    }

    /// Previous half-edge around the face (or border cycle).
    #[must_use]
    pub fn prev(&self, h: HalfedgeId) -> HalfedgeId {
        self.he_prev[h.index()]
    }

    /// The opposite half-edge, `h ^ 1`.
    #[must_use]
    pub fn twin(&self, h: HalfedgeId) -> HalfedgeId {
        HalfedgeId(h.0 ^ 1)
    }

    /// Target vertex of `h`.
    #[must_use]
    pub fn target(&self, h: HalfedgeId) -> VertexId {
        self.he_to[h.index()]
    }

    /// Origin vertex of `h`.
    #[must_use]
    pub fn origin(&self, h: HalfedgeId) -> VertexId {
        self.he_to[(h.0 ^ 1) as usize]
    }

    /// The face of `h`, `None` on the border.
    #[must_use]
    pub fn face(&self, h: HalfedgeId) -> Option<FaceId> {
        Some(self.he_face[h.index()]).filter(|f| f.is_valid())
    }

    /// The edge of `h`.
    #[must_use]
    pub fn edge(&self, h: HalfedgeId) -> EdgeId {
        EdgeId(h.0 / 2)
    }

    /// Half-edge `i` (0 or 1) of `e`.
    #[must_use]
    pub fn edge_halfedge(&self, e: EdgeId, i: u32) -> HalfedgeId {
        HalfedgeId(2 * e.0 + (i & 1))
    }

    /// The half-edge `a -> b`, if the edge exists. O(valence of `a`).
    #[must_use]
    pub fn find_halfedge(&self, a: VertexId, b: VertexId) -> Option<HalfedgeId> {
        self.outgoing_halfedges(a).find(|&h| self.target(h) == b)
    }

    /// Counter-clockwise successor of outgoing half-edge `h` around its origin.
    pub(super) fn rotate_ccw(&self, h: HalfedgeId) -> HalfedgeId {
        self.twin(self.prev(h))
    }

    /// Outgoing half-edges of `v`, counter-clockwise, starting at [`Self::vertex_halfedge`].
    #[must_use]
    pub fn outgoing_halfedges(&self, v: VertexId) -> OutgoingHalfedges<'_> {
        let start = self.v_out[v.index()];
        OutgoingHalfedges {
            mesh: self,
            start,
            cur: start,
        }
    }

    /// Neighbouring vertices of `v`, in the order of [`Self::outgoing_halfedges`].
    pub fn vertex_neighbors(&self, v: VertexId) -> impl Iterator<Item = VertexId> + '_ {
        self.outgoing_halfedges(v).map(|h| self.target(h))
    }

    /// Faces around `v`, in the order of [`Self::outgoing_halfedges`] (each face is the one
    /// left of an outgoing half-edge).
    pub fn vertex_faces(&self, v: VertexId) -> impl Iterator<Item = FaceId> + '_ {
        self.outgoing_halfedges(v).filter_map(|h| self.face(h))
    }

    /// Number of edges at `v`.
    #[must_use]
    pub fn valence(&self, v: VertexId) -> usize {
        self.outgoing_halfedges(v).count()
    }

    /// Whether `h` has no face.
    #[must_use]
    pub fn is_border_halfedge(&self, h: HalfedgeId) -> bool {
        !self.he_face[h.index()].is_valid()
    }

    /// Whether either half-edge of `e` has no face.
    #[must_use]
    pub fn is_border_edge(&self, e: EdgeId) -> bool {
        self.is_border_halfedge(HalfedgeId(2 * e.0))
            || self.is_border_halfedge(HalfedgeId(2 * e.0 + 1))
    }

    /// Whether `v` has a border half-edge (isolated vertices are not border vertices).
    #[must_use]
    pub fn is_border_vertex(&self, v: VertexId) -> bool {
        let h = self.v_out[v.index()];
        h.is_valid() && self.is_border_halfedge(h)
    }

    /// Whether `v` is live and has no edge.
    #[must_use]
    pub fn is_isolated(&self, v: VertexId) -> bool {
        self.contains_vertex(v) && !self.v_out[v.index()].is_valid()
    }

    /// Whether `v`'s faces form at most one fan (at most one border gap).
    #[must_use]
    pub fn is_manifold_vertex(&self, v: VertexId) -> bool {
        self.border_gaps(v) <= 1
    }

    pub(super) fn border_gaps(&self, v: VertexId) -> usize {
        if !self.is_border_vertex(v) {
            return 0;
        }
        self.outgoing_halfedges(v)
            .filter(|&h| self.is_border_halfedge(h))
            .count()
    }
}
