//! Local edits on a [`HalfEdgeMesh`]: add and remove vertices and faces, remove a vertex's fan
//! (Cohen et al. 1996, section 4.3), all logged for [`HalfEdgeMesh::rollback`].

use super::journal::{Kind, Undo};
use super::{AddFaceError, EditError, HalfEdgeMesh, NO_F, NO_H, NO_V};
use crate::{EdgeId, FaceId, HalfedgeId, VertexId};
use glam::DVec3;

impl HalfEdgeMesh {
    /// Moves `v` (logged, so undone by [`Self::rollback`]).
    pub fn set_position(&mut self, v: VertexId, p: DVec3) {
        self.rec(Undo::Position(v, self.positions[v.index()]));
        self.positions[v.index()] = p;
    }

    /// Adds an isolated vertex at `p`, reusing a dead id if there is one.
    pub fn add_vertex(&mut self, p: DVec3) -> VertexId {
        let v = if let Some(v) = self.free_vertices.pop() {
            self.rec(Undo::FreePopped(Kind::Vertex, v.0));
            self.set_position(v, p);
            self.rec(Undo::Alive(v, false));
            self.v_alive[v.index()] = true;
            v
        } else {
            self.positions.push(p);
            self.v_out.push(NO_H);
            self.v_alive.push(true);
            self.rec(Undo::Grew(Kind::Vertex));
            VertexId::from_index(self.positions.len() - 1)
        };
        self.debug_check();
        v
    }

    /// Removes an isolated vertex; its id goes to the free list.
    pub fn remove_vertex(&mut self, v: VertexId) -> Result<(), EditError> {
        if !self.contains_vertex(v) {
            return Err(EditError::DeadVertex(v));
        }
        if self.v_out[v.index()].is_valid() {
            return Err(EditError::NotIsolated(v));
        }
        self.rec(Undo::Alive(v, true));
        self.v_alive[v.index()] = false;
        self.free_vertices.push(v);
        self.rec(Undo::FreePushed(Kind::Vertex));
        self.debug_check();
        Ok(())
    }

    /// New edge `from -> to` (returned half-edge), unlinked, both sides border.
    fn new_edge(&mut self, from: VertexId, to: VertexId) -> HalfedgeId {
        let e = if let Some(e) = self.free_edges.pop() {
            self.rec(Undo::FreePopped(Kind::Edge, e.0));
            e
        } else {
            for _ in 0..2 {
                self.he_to.push(NO_V);
                self.he_next.push(NO_H);
                self.he_prev.push(NO_H);
                self.he_face.push(NO_F);
            }
            self.rec(Undo::Grew(Kind::Edge));
            EdgeId::from_index(self.he_to.len() / 2 - 1)
        };
        let h = HalfedgeId(2 * e.0);
        self.reset_halfedge(h, to);
        self.reset_halfedge(HalfedgeId(h.0 + 1), from);
        h
    }

    fn delete_edge(&mut self, e: EdgeId) {
        self.reset_halfedge(HalfedgeId(2 * e.0), NO_V);
        self.reset_halfedge(HalfedgeId(2 * e.0 + 1), NO_V);
        self.free_edges.push(e);
        self.rec(Undo::FreePushed(Kind::Edge));
    }

    fn new_face(&mut self, h: HalfedgeId) -> FaceId {
        let f = if let Some(f) = self.free_faces.pop() {
            self.rec(Undo::FreePopped(Kind::Face, f.0));
            f
        } else {
            self.f_he.push(NO_H);
            self.rec(Undo::Grew(Kind::Face));
            FaceId::from_index(self.f_he.len() - 1)
        };
        self.set_face_halfedge(f, h);
        f
    }

    /// Makes `v`'s outgoing half-edge a border one if it has one. O(valence).
    fn adjust_outgoing(&mut self, v: VertexId) {
        if !self.v_out[v.index()].is_valid() {
            return;
        }
        if let Some(h) = self
            .outgoing_halfedges(v)
            .find(|&h| self.is_border_halfedge(h))
        {
            self.set_out(v, h);
        }
    }

    /// Adds triangle `v` (counter-clockwise), refusing anything that would make the mesh
    /// non-manifold or inconsistently oriented: an interior corner, a half-edge that already
    /// has a face, or a non-isolated corner reached through no existing edge (a new fan).
    /// When the face closes a gap at a vertex with several border gaps, the border cycles are
    /// relinked as in OpenMesh's `add_face`. O(sum of the corners' valences).
    ///
    /// Because of the new-fan rule, some hole fillings cannot be added one face at a time in
    /// any order (for instance when the hole's border is pinched); use [`Self::add_faces`]
    /// for those.
    ///
    /// ```
    /// use envelope_mesh::{AddFaceError, HalfEdgeMesh, TriangleSoup, VertexId};
    /// let s = TriangleSoup::from_raw(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]], &[[0, 1, 2]]);
    /// let mut m = HalfEdgeMesh::from_soup(&s).unwrap();
    /// assert!(m.add_face([VertexId(1), VertexId(3), VertexId(2)]).is_ok());
    /// assert_eq!(
    ///     m.add_face([VertexId(0), VertexId(1), VertexId(3)]),
    ///     Err(AddFaceError::HalfedgeOccupied { from: VertexId(0), to: VertexId(1) })
    /// );
    /// ```
    pub fn add_face(&mut self, v: [VertexId; 3]) -> Result<FaceId, AddFaceError> {
        self.add_face_impl(v, true)
    }

    /// [`Self::add_face`]; `strict` refuses a new fan at a non-isolated vertex.
    fn add_face_impl(&mut self, v: [VertexId; 3], strict: bool) -> Result<FaceId, AddFaceError> {
        for i in 0..3 {
            if !self.contains_vertex(v[i]) {
                return Err(AddFaceError::DeadVertex(v[i]));
            }
            if v[i] == v[(i + 1) % 3] {
                return Err(AddFaceError::RepeatedVertex(v[i]));
            }
        }
        let mut he = [NO_H; 3];
        let mut is_new = [false; 3];
        for i in 0..3 {
            let out = self.v_out[v[i].index()];
            if out.is_valid() && !self.is_border_halfedge(out) {
                return Err(AddFaceError::InteriorVertex(v[i]));
            }
            match self.find_halfedge(v[i], v[(i + 1) % 3]) {
                Some(h) if !self.is_border_halfedge(h) => {
                    return Err(AddFaceError::HalfedgeOccupied {
                        from: v[i],
                        to: v[(i + 1) % 3],
                    });
                }
                Some(h) => he[i] = h,
                None => is_new[i] = true,
            }
        }
        for i in 0..3 {
            let ii = (i + 1) % 3;
            if strict && is_new[i] && is_new[ii] && self.v_out[v[ii].index()].is_valid() {
                return Err(AddFaceError::NewFan(v[ii]));
            }
        }
        // Relink patches: two existing consecutive half-edges not yet consecutive in the
        // border cycle.
        let mut next_cache: Vec<(HalfedgeId, HalfedgeId)> = Vec::with_capacity(9);
        for i in 0..3 {
            let ii = (i + 1) % 3;
            if is_new[i] || is_new[ii] {
                continue;
            }
            let (inner_prev, inner_next) = (he[i], he[ii]);
            if self.next(inner_prev) == inner_next {
                continue;
            }
            // Find a free gap between boundary_prev and boundary_next.
            let outer_prev = self.twin(inner_next);
            let mut boundary_prev = outer_prev;
            loop {
                boundary_prev = self.twin(self.next(boundary_prev));
                if self.is_border_halfedge(boundary_prev) && boundary_prev != inner_prev {
                    break;
                }
            }
            let boundary_next = self.next(boundary_prev);
            if boundary_next == inner_next {
                return Err(AddFaceError::PatchRelinkingFailed(v[ii]));
            }
            let patch_start = self.next(inner_prev);
            let patch_end = self.prev(inner_next);
            next_cache.push((boundary_prev, patch_start));
            next_cache.push((patch_end, boundary_next));
            next_cache.push((inner_prev, inner_next));
        }
        // From here on nothing fails.
        for i in 0..3 {
            if is_new[i] {
                he[i] = self.new_edge(v[i], v[(i + 1) % 3]);
            }
        }
        let f = self.new_face(he[0]);
        let mut needs_adjust = [false; 3];
        for i in 0..3 {
            let ii = (i + 1) % 3;
            let vh = v[ii];
            let (inner_prev, inner_next) = (he[i], he[ii]);
            let outer_prev = self.twin(inner_next);
            let outer_next = self.twin(inner_prev);
            match (is_new[i], is_new[ii]) {
                (true, false) => {
                    let boundary_prev = self.prev(inner_next);
                    next_cache.push((boundary_prev, outer_next));
                    self.set_out(vh, outer_next);
                }
                (false, true) => {
                    let boundary_next = self.next(inner_prev);
                    next_cache.push((outer_prev, boundary_next));
                    self.set_out(vh, boundary_next);
                }
                (true, true) => {
                    let boundary_next = self.v_out[vh.index()];
                    if boundary_next.is_valid() {
                        // A new fan at a border vertex (non-strict only): splice it into the
                        // border cycle before the existing gap.
                        let boundary_prev = self.prev(boundary_next);
                        next_cache.push((boundary_prev, outer_next));
                        next_cache.push((outer_prev, boundary_next));
                    } else {
                        self.set_out(vh, outer_next);
                        next_cache.push((outer_prev, outer_next));
                    }
                }
                (false, false) => needs_adjust[ii] = self.v_out[vh.index()] == inner_next,
            }
            if is_new[i] || is_new[ii] {
                next_cache.push((inner_prev, inner_next));
            }
            self.set_face(he[i], f);
        }
        for (a, b) in next_cache {
            self.set_next(a, b);
        }
        for i in 0..3 {
            if needs_adjust[i] {
                self.adjust_outgoing(v[i]);
            }
        }
        self.debug_check();
        Ok(f)
    }

    /// Adds a batch of faces (a hole filling), all or nothing. Inside the batch a face may
    /// transiently give a vertex a second fan (as OpenMesh allows), so any order works; at
    /// the end no corner may have more border gaps than `max(1, gaps before)`, otherwise the
    /// batch is undone and [`AddFaceError::NewFan`] names the vertex. Returns the new face ids
    /// in input order. On any error nothing is changed. O(sum of the corners' valences).
    ///
    /// ```
    /// use envelope_mesh::{generate, HalfEdgeMesh, VertexId};
    /// let mut m = HalfEdgeMesh::from_soup(&generate::icosphere(0, 1.0)).unwrap();
    /// let hole = m.remove_vertex_fan(VertexId(0)).unwrap();
    /// // The middle triangle of the pentagon first: a new fan at three vertices for a while.
    /// let fill = [[hole[1], hole[3], hole[0]], [hole[1], hole[2], hole[3]], [hole[0], hole[3], hole[4]]];
    /// let ids = m.add_faces(&fill).unwrap();
    /// assert_eq!(ids.len(), 3);
    /// assert_eq!(m.topology().genus, Some(0));
    /// ```
    pub fn add_faces(&mut self, faces: &[[VertexId; 3]]) -> Result<Vec<FaceId>, AddFaceError> {
        let mut corners: Vec<VertexId> = faces.iter().flatten().copied().collect();
        corners.sort_unstable();
        corners.dedup();
        if let Some(&v) = corners.iter().find(|&&v| !self.contains_vertex(v)) {
            return Err(AddFaceError::DeadVertex(v));
        }
        let before: Vec<usize> = corners.iter().map(|&v| self.border_gaps(v)).collect();
        let cp = self.begin();
        let mut ids = Vec::with_capacity(faces.len());
        for &f in faces {
            match self.add_face_impl(f, false) {
                Ok(id) => ids.push(id),
                Err(e) => {
                    self.rollback(cp);
                    return Err(e);
                }
            }
        }
        for (&v, &b) in corners.iter().zip(&before) {
            if self.border_gaps(v) > b.max(1) {
                self.rollback(cp);
                return Err(AddFaceError::NewFan(v));
            }
        }
        self.commit(cp);
        Ok(ids)
    }

    /// Removes one face, leaving a hole (OpenMesh's `delete_face`): edges left with no face
    /// die, vertices left with no edge become isolated (not removed).
    fn remove_face_unchecked(&mut self, f: FaceId) {
        let h0 = self.f_he[f.index()];
        let hs = [h0, self.next(h0), self.prev(h0)];
        let mut dead = Vec::with_capacity(3);
        for &h in &hs {
            self.set_face(h, NO_F);
            if self.is_border_halfedge(self.twin(h)) {
                dead.push(h);
            }
        }
        self.set_face_halfedge(f, NO_H);
        self.free_faces.push(f);
        self.rec(Undo::FreePushed(Kind::Face));
        let vs = hs.map(|h| self.target(h));
        for h0 in dead {
            let h1 = self.twin(h0);
            let (v0, v1) = (self.target(h0), self.target(h1));
            let (next0, prev0) = (self.next(h0), self.prev(h0));
            let (next1, prev1) = (self.next(h1), self.prev(h1));
            self.set_next(prev0, next1);
            self.set_next(prev1, next0);
            if self.v_out[v0.index()] == h1 {
                self.set_out(v0, if next0 == h1 { NO_H } else { next0 });
            }
            if self.v_out[v1.index()] == h0 {
                self.set_out(v1, if next1 == h0 { NO_H } else { next1 });
            }
            self.delete_edge(self.edge(h0));
        }
        for v in vs {
            self.adjust_outgoing(v);
        }
    }

    /// Removes the given faces (distinct, live), leaving holes. Edges left with no face die;
    /// vertices left with no edge stay as isolated vertices. O(faces x valence).
    pub fn remove_faces(&mut self, faces: &[FaceId]) -> Result<(), EditError> {
        let mut sorted = faces.to_vec();
        sorted.sort_unstable();
        for (i, &f) in sorted.iter().enumerate() {
            if !self.contains_face(f) || (i > 0 && sorted[i - 1] == f) {
                return Err(EditError::DeadFace(f));
            }
        }
        for &f in faces {
            self.remove_face_unchecked(f);
        }
        self.debug_check();
        Ok(())
    }

    /// Removes every face around `v`, leaving `v` isolated (not removed), and returns the
    /// boundary of the created hole in the direction its border half-edges run (the order of
    /// [`Self::vertex_neighbors`]):
    ///
    /// * interior `v`: the closed cycle of its neighbours `x0, x1, .., x(k-1)` (the loop closes
    ///   from the last back to the first);
    /// * border `v`: the open chain from the neighbour after `v`'s border half-edge around to
    ///   that half-edge's target, `x1, .., x(k-1), x0`, which now joins the old border.
    ///
    /// An isolated `v` gives an empty list. Refused for a vertex with several border gaps.
    ///
    /// Note the direction: the hole's border half-edges run `x0 -> x1 -> ..`, so
    /// [`Self::topology`] (which directs border loops as the remaining faces run them) lists
    /// the same loop reversed.
    pub fn remove_vertex_fan(&mut self, v: VertexId) -> Result<Vec<VertexId>, EditError> {
        if !self.contains_vertex(v) {
            return Err(EditError::DeadVertex(v));
        }
        if self.border_gaps(v) > 1 {
            return Err(EditError::NonManifoldVertex(v));
        }
        let hs: Vec<HalfedgeId> = self.outgoing_halfedges(v).collect();
        let mut ring: Vec<VertexId> = hs.iter().map(|&h| self.target(h)).collect();
        if hs.first().is_some_and(|&h| self.is_border_halfedge(h)) {
            ring.rotate_left(1);
        }
        let faces: Vec<FaceId> = hs.iter().filter_map(|&h| self.face(h)).collect();
        for f in faces {
            self.remove_face_unchecked(f);
        }
        debug_assert!(!self.v_out[v.index()].is_valid());
        self.debug_check();
        Ok(ring)
    }
}
