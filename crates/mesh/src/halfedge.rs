//! [`HalfEdgeMesh`]: adjacency for an oriented 2-manifold triangle mesh with borders, and the
//! local edits of the paper's local algorithm (Cohen et al. 1996, section 4.3: remove a
//! vertex's fan, fill the hole, undo when the filling fails the envelope test).
//!
//! Layout (after OpenMesh): edge `e` owns half-edges `2e` and `2e + 1`, so the twin of `h` is
//! `h ^ 1`. A half-edge stores its target vertex, next, prev and face (`INVALID` on the
//! border). Border half-edges are linked into border cycles through `next`/`prev`. A vertex
//! stores one outgoing half-edge, a border one whenever it has one. Dead elements go to free
//! lists and their ids are reused.
//!
//! Every write goes through a logging setter; while a [`Checkpoint`] is open the old value is
//! logged, and [`HalfEdgeMesh::rollback`] replays the log backwards, restoring the exact
//! previous state (arrays and free lists included).

use crate::analysis::{EdgeTable, corner_fans, fan_counts, slot_ends};
use crate::{EdgeId, FaceId, HalfedgeId, Topology, TriangleSoup, VertexId};
use glam::DVec3;
use thiserror::Error;

const NO_H: HalfedgeId = HalfedgeId::INVALID;
const NO_F: FaceId = FaceId::INVALID;
const NO_V: VertexId = VertexId::INVALID;

/// Why [`HalfEdgeMesh::from_soup`] refused a soup.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
pub enum BuildError {
    /// A face names a vertex that does not exist.
    #[error("face {face} names vertex {vertex}, which is out of range")]
    IndexOutOfRange {
        /// The face.
        face: FaceId,
        /// The missing vertex.
        vertex: VertexId,
    },
    /// A face repeats a vertex.
    #[error("face {face} repeats a vertex")]
    DegenerateFace {
        /// The face.
        face: FaceId,
    },
    /// An edge with more than two faces.
    #[error("edge {}-{} has more than two faces ({}, {}, {}, ...)", vertices[0], vertices[1], faces[0], faces[1], faces[2])]
    NonManifoldEdge {
        /// Its endpoints, smaller first.
        vertices: [VertexId; 2],
        /// Its first three faces.
        faces: [FaceId; 3],
    },
    /// Two faces run an edge in the same direction.
    #[error("faces {} and {} both run edge {}->{}", faces[0], faces[1], edge[0], edge[1])]
    InconsistentOrientation {
        /// The edge as both faces run it.
        edge: [VertexId; 2],
        /// The two faces.
        faces: [FaceId; 2],
    },
    /// A vertex whose faces form more than one fan.
    #[error("vertex {vertex} has more than one fan of faces")]
    NonManifoldVertex {
        /// The vertex.
        vertex: VertexId,
    },
}

/// Why [`HalfEdgeMesh::add_face`] refused a face. Nothing was changed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
pub enum AddFaceError {
    /// A corner is not a live vertex.
    #[error("vertex {0} is not live")]
    DeadVertex(VertexId),
    /// Two corners are the same vertex.
    #[error("the face repeats vertex {0}")]
    RepeatedVertex(VertexId),
    /// A corner is an interior vertex (its fan is a closed umbrella).
    #[error("vertex {0} is interior; a new face there would be non-manifold")]
    InteriorVertex(VertexId),
    /// The half-edge `from -> to` already has a face (non-manifold edge or flipped face).
    #[error("half-edge {from}->{to} already has a face")]
    HalfedgeOccupied {
        /// Origin of the half-edge.
        from: VertexId,
        /// Target of the half-edge.
        to: VertexId,
    },
    /// The face would touch a non-isolated corner through no existing edge, giving it a
    /// second fan.
    #[error("vertex {0} would get a second fan")]
    NewFan(VertexId),
    /// The border gaps around a corner cannot be relinked (OpenMesh's "patch re-linking").
    #[error("no free border gap to relink around vertex {0}")]
    PatchRelinkingFailed(VertexId),
}

/// Why another edit was refused. Nothing was changed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
pub enum EditError {
    /// Not a live vertex.
    #[error("vertex {0} is not live")]
    DeadVertex(VertexId),
    /// Not a live face (or listed twice).
    #[error("face {0} is not live or is listed twice")]
    DeadFace(FaceId),
    /// The vertex still has faces.
    #[error("vertex {0} is not isolated")]
    NotIsolated(VertexId),
    /// The vertex has several border gaps, so its fan is not one umbrella.
    #[error("vertex {0} has several border gaps")]
    NonManifoldVertex(VertexId),
}

/// A point in the edit history; pass it to [`HalfEdgeMesh::rollback`] or
/// [`HalfEdgeMesh::commit`]. Checkpoints nest and must be closed innermost first.
#[derive(Debug)]
#[must_use = "a checkpoint must be rolled back or committed"]
pub struct Checkpoint {
    log_len: usize,
    depth: u32,
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    Vertex,
    Edge,
    Face,
}

#[derive(Clone, Copy, Debug)]
enum Undo {
    Next(HalfedgeId, HalfedgeId),
    Prev(HalfedgeId, HalfedgeId),
    To(HalfedgeId, VertexId),
    Face(HalfedgeId, FaceId),
    Out(VertexId, HalfedgeId),
    Alive(VertexId, bool),
    Position(VertexId, DVec3),
    FaceHalfedge(FaceId, HalfedgeId),
    FreePushed(Kind),
    FreePopped(Kind, u32),
    Grew(Kind),
}

/// Half-edge adjacency for an oriented 2-manifold triangle mesh, possibly with borders.
///
/// Between edits a vertex may transiently have several border gaps (for instance after a fan
/// next to the border is removed); [`Self::is_manifold_vertex`] tells, and
/// [`Self::add_face`] never creates a new gap.
///
/// ```
/// use envelope_mesh::{generate, HalfEdgeMesh};
/// let mut m = HalfEdgeMesh::from_soup(&generate::icosphere(1, 1.0)).unwrap();
/// let v = m.vertices().next().unwrap();
/// let t = m.begin();
/// let hole = m.remove_vertex_fan(v).unwrap();
/// assert_eq!(hole.len(), 5); // an icosahedron corner: a closed 5-cycle
/// assert!(m.is_isolated(v));
/// m.rollback(t);
/// assert_eq!(m.topology().genus, Some(0));
/// m.sanity_check().unwrap();
/// ```
#[derive(Clone, Debug, Default)]
pub struct HalfEdgeMesh {
    positions: Vec<DVec3>,
    v_out: Vec<HalfedgeId>,
    v_alive: Vec<bool>,
    he_to: Vec<VertexId>,
    he_next: Vec<HalfedgeId>,
    he_prev: Vec<HalfedgeId>,
    he_face: Vec<FaceId>,
    f_he: Vec<HalfedgeId>,
    free_vertices: Vec<VertexId>,
    free_edges: Vec<EdgeId>,
    free_faces: Vec<FaceId>,
    log: Vec<Undo>,
    depth: u32,
}

/// Equal when every element slot, link, position and free list is equal (the undo log is not
/// compared). After [`HalfEdgeMesh::rollback`] the mesh equals its state at
/// [`HalfEdgeMesh::begin`].
impl PartialEq for HalfEdgeMesh {
    fn eq(&self, o: &Self) -> bool {
        self.positions == o.positions
            && self.v_out == o.v_out
            && self.v_alive == o.v_alive
            && self.he_to == o.he_to
            && self.he_next == o.he_next
            && self.he_prev == o.he_prev
            && self.he_face == o.he_face
            && self.f_he == o.f_he
            && self.free_vertices == o.free_vertices
            && self.free_edges == o.free_edges
            && self.free_faces == o.free_faces
    }
}

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
    // ----------------------------------------------------------------- construction

    /// Builds the adjacency of a soup, keeping every vertex id and face id (unreferenced
    /// vertices become isolated vertices). Errors name the first offending element (faces in
    /// order, then edges in `(min, max)` order, then vertices).
    ///
    /// ```
    /// use envelope_mesh::{generate, BuildError, HalfEdgeMesh, VertexId};
    /// assert!(matches!(
    ///     HalfEdgeMesh::from_soup(&generate::bow_tie()),
    ///     Err(BuildError::NonManifoldVertex { vertex: VertexId(0) })
    /// ));
    /// ```
    pub fn from_soup(soup: &TriangleSoup) -> Result<Self, BuildError> {
        let nv = soup.positions.len();
        for (f, tri) in soup.faces.iter().enumerate() {
            let face = FaceId::from_index(f);
            if let Some(&vertex) = tri.iter().find(|v| v.index() >= nv) {
                return Err(BuildError::IndexOutOfRange { face, vertex });
            }
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
                return Err(BuildError::DegenerateFace { face });
            }
        }
        let valid = vec![true; soup.faces.len()];
        let table = EdgeTable::build(soup, &valid);
        for e in 0..table.num_edges() {
            let sl = table.edge_slots(e);
            if sl.len() > 2 {
                return Err(BuildError::NonManifoldEdge {
                    vertices: table.ends[e].map(VertexId),
                    faces: [FaceId(sl[0] / 3), FaceId(sl[1] / 3), FaceId(sl[2] / 3)],
                });
            }
            if let [s, t] = *sl {
                let (a, b) = slot_ends(&soup.faces, s);
                if slot_ends(&soup.faces, t).0 == a {
                    return Err(BuildError::InconsistentOrientation {
                        edge: [VertexId(a), VertexId(b)],
                        faces: [FaceId(s / 3), FaceId(t / 3)],
                    });
                }
            }
        }
        let fans = corner_fans(soup, &table);
        if let Some(v) = fan_counts(soup, &valid, &fans).iter().position(|&n| n > 1) {
            return Err(BuildError::NonManifoldVertex {
                vertex: VertexId::from_index(v),
            });
        }

        let ne = table.num_edges();
        let nf = soup.faces.len();
        let mut m = Self {
            positions: soup.positions.clone(),
            v_out: vec![NO_H; nv],
            v_alive: vec![true; nv],
            he_to: vec![NO_V; 2 * ne],
            he_next: vec![NO_H; 2 * ne],
            he_prev: vec![NO_H; 2 * ne],
            he_face: vec![NO_F; 2 * ne],
            f_he: vec![NO_H; nf],
            ..Self::default()
        };
        // Half-edge of slot s: 2e if it runs lo -> hi, else 2e + 1.
        let slot_he = |s: u32| -> HalfedgeId {
            let (a, b) = slot_ends(&soup.faces, s);
            HalfedgeId(2 * table.slot_edge[s as usize] + u32::from(a > b))
        };
        for e in 0..ne {
            let [lo, hi] = table.ends[e];
            m.he_to[2 * e] = VertexId(hi);
            m.he_to[2 * e + 1] = VertexId(lo);
        }
        for f in 0..nf {
            let hs = [0, 1, 2].map(|i| slot_he((3 * f + i) as u32));
            for i in 0..3 {
                let h = hs[i].index();
                m.he_face[h] = FaceId::from_index(f);
                m.he_next[h] = hs[(i + 1) % 3];
                m.he_prev[h] = hs[(i + 2) % 3];
                // Any outgoing half-edge for now; border ones override below.
                m.v_out[soup.faces[f][i].index()] = hs[i];
            }
            m.f_he[f] = hs[0];
        }
        // Border half-edges: next is the border half-edge leaving the target, found by
        // rotating counter-clockwise around the target from the twin.
        for h in 0..2 * ne {
            let h = HalfedgeId::from_index(h);
            if m.he_face[h.index()].is_valid() {
                continue;
            }
            let mut g = m.twin(h);
            while m.he_face[g.index()].is_valid() {
                g = m.twin(m.he_prev[g.index()]);
            }
            m.he_next[h.index()] = g;
            m.he_prev[g.index()] = h;
            let o = m.origin(g);
            m.v_out[o.index()] = g;
        }
        m.debug_check();
        Ok(m)
    }

    /// The live vertices in increasing id order and the live faces in increasing id order, as
    /// a soup with compacted ids (a face keeps its corner order, see [`Self::face_vertices`]).
    #[must_use]
    pub fn to_soup(&self) -> TriangleSoup {
        self.to_soup_with_ids().0
    }

    /// [`Self::to_soup`], plus the mesh id of each soup vertex and of each soup face.
    #[must_use]
    pub fn to_soup_with_ids(&self) -> (TriangleSoup, Vec<VertexId>, Vec<FaceId>) {
        let vids: Vec<VertexId> = self.vertices().collect();
        let fids: Vec<FaceId> = self.faces().collect();
        let mut new_of = vec![NO_V; self.positions.len()];
        for (i, v) in vids.iter().enumerate() {
            new_of[v.index()] = VertexId::from_index(i);
        }
        let soup = TriangleSoup {
            positions: vids.iter().map(|v| self.positions[v.index()]).collect(),
            faces: fids
                .iter()
                .map(|&f| self.face_vertices(f).map(|v| new_of[v.index()]))
                .collect(),
        };
        (soup, vids, fids)
    }

    /// [`crate::analyze`] of this mesh, with ids renamed back to the mesh's.
    #[must_use]
    pub fn topology(&self) -> Topology {
        let (soup, vids, fids) = self.to_soup_with_ids();
        let mut t = crate::analyze(&soup);
        t.rename(&vids, &fids);
        t
    }

    /// The genus and the number of border loops of [`Self::topology`] (`genus`,
    /// `num_border_loops()`), counted on the half-edges in linear time, without the soup,
    /// when every vertex is manifold (each component's vertices, edges and faces by a walk
    /// over the faces, its border loops by the border cycles; consistent orientation makes
    /// every component orientable); from [`Self::topology`] otherwise. For a report on a
    /// simplifier's output, where `topology` builds and sorts an edge table.
    ///
    /// ```
    /// use envelope_mesh::{generate, HalfEdgeMesh};
    /// let m = HalfEdgeMesh::from_soup(&generate::torus(1.0, 0.3, 12, 8)).unwrap();
    /// assert_eq!(m.genus_and_border_loops(), (Some(1), 0));
    /// let m = HalfEdgeMesh::from_soup(&generate::open_cylinder(1.0, 2.0, 12, 4)).unwrap();
    /// assert_eq!(m.genus_and_border_loops(), (Some(0), 2));
    /// ```
    #[must_use]
    pub fn genus_and_border_loops(&self) -> (Option<u32>, usize) {
        let from_topology = || {
            let t = self.topology();
            (t.genus, t.num_border_loops())
        };
        if self.vertices().any(|v| !self.is_manifold_vertex(v)) {
            return from_topology();
        }
        // Per component: vertices, edges, faces, border loops.
        let mut counts: Vec<[i64; 4]> = Vec::new();
        let mut comp = vec![u32::MAX; self.f_he.len()];
        let mut seen = vec![false; self.positions.len()];
        let mut stack = Vec::new();
        for f in self.faces() {
            if comp[f.index()] != u32::MAX {
                continue;
            }
            let c = counts.len() as u32;
            let mut k = [0i64; 4];
            comp[f.index()] = c;
            stack.push(f);
            while let Some(g) = stack.pop() {
                k[2] += 1;
                let mut h = self.face_halfedge(g);
                for _ in 0..3 {
                    let v = self.origin(h);
                    k[0] += i64::from(!std::mem::replace(&mut seen[v.index()], true));
                    let t = self.twin(h);
                    match self.face(t) {
                        Some(o) => {
                            k[1] += i64::from(h.0 < t.0);
                            if comp[o.index()] == u32::MAX {
                                comp[o.index()] = c;
                                stack.push(o);
                            }
                        }
                        None => k[1] += 1,
                    }
                    h = self.next(h);
                }
            }
            counts.push(k);
        }
        let mut walked = vec![false; self.he_face.len()];
        for e in self.edges() {
            for i in 0..2 {
                let h = self.edge_halfedge(e, i);
                if !self.is_border_halfedge(h) || walked[h.index()] {
                    continue;
                }
                let Some(f) = self.face(self.twin(h)) else {
                    return from_topology(); // an edge with no face at all
                };
                let mut x = h;
                for _ in 0..self.he_face.len() {
                    walked[x.index()] = true;
                    x = self.next(x);
                    if x == h || !self.is_border_halfedge(x) {
                        break;
                    }
                }
                if x != h {
                    return from_topology();
                }
                counts[comp[f.index()] as usize][3] += 1;
            }
        }
        let genus = counts.iter().try_fold(0u32, |sum, &[v, e, f, b]| {
            Some(sum + crate::topology::genus_of(v - e + f, b)?)
        });
        let loops = counts.iter().map(|k| k[3] as usize).sum();
        (genus, loops)
    }

    // ----------------------------------------------------------------- element access

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

    /// Moves `v` (logged, so undone by [`Self::rollback`]).
    pub fn set_position(&mut self, v: VertexId, p: DVec3) {
        self.rec(Undo::Position(v, self.positions[v.index()]));
        self.positions[v.index()] = p;
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
    fn rotate_ccw(&self, h: HalfedgeId) -> HalfedgeId {
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

    fn border_gaps(&self, v: VertexId) -> usize {
        if !self.is_border_vertex(v) {
            return 0;
        }
        self.outgoing_halfedges(v)
            .filter(|&h| self.is_border_halfedge(h))
            .count()
    }

    // ----------------------------------------------------------------- transactions

    /// Opens a checkpoint: edits from now on are logged until the matching
    /// [`Self::rollback`] or [`Self::commit`].
    pub fn begin(&mut self) -> Checkpoint {
        self.depth += 1;
        Checkpoint {
            log_len: self.log.len(),
            depth: self.depth,
        }
    }

    /// Undoes every edit since `cp` was opened; the mesh is then equal (`==`) to what it was.
    ///
    /// # Panics
    /// If an inner checkpoint is still open.
    pub fn rollback(&mut self, cp: Checkpoint) {
        assert_eq!(cp.depth, self.depth, "close inner checkpoints first");
        while self.log.len() > cp.log_len {
            let u = self.log.pop().expect("log longer than checkpoint");
            self.undo(u);
        }
        self.close(cp);
        self.debug_check();
    }

    /// Keeps the edits since `cp` (they stay undoable by an enclosing checkpoint).
    ///
    /// # Panics
    /// If an inner checkpoint is still open.
    pub fn commit(&mut self, cp: Checkpoint) {
        assert_eq!(cp.depth, self.depth, "close inner checkpoints first");
        self.close(cp);
    }

    fn close(&mut self, cp: Checkpoint) {
        self.depth = cp.depth - 1;
        if self.depth == 0 {
            self.log.clear();
        }
    }

    fn undo(&mut self, u: Undo) {
        match u {
            Undo::Next(h, o) => self.he_next[h.index()] = o,
            Undo::Prev(h, o) => self.he_prev[h.index()] = o,
            Undo::To(h, o) => self.he_to[h.index()] = o,
            Undo::Face(h, o) => self.he_face[h.index()] = o,
            Undo::Out(v, o) => self.v_out[v.index()] = o,
            Undo::Alive(v, o) => self.v_alive[v.index()] = o,
            Undo::Position(v, o) => self.positions[v.index()] = o,
            Undo::FaceHalfedge(f, o) => self.f_he[f.index()] = o,
            Undo::FreePushed(k) => {
                match k {
                    Kind::Vertex => self.free_vertices.pop().map(|_| ()),
                    Kind::Edge => self.free_edges.pop().map(|_| ()),
                    Kind::Face => self.free_faces.pop().map(|_| ()),
                }
                .expect("free list underflow in undo");
            }
            Undo::FreePopped(k, id) => match k {
                Kind::Vertex => self.free_vertices.push(VertexId(id)),
                Kind::Edge => self.free_edges.push(EdgeId(id)),
                Kind::Face => self.free_faces.push(FaceId(id)),
            },
            Undo::Grew(k) => match k {
                Kind::Vertex => {
                    self.positions.pop();
                    self.v_out.pop();
                    self.v_alive.pop();
                }
                Kind::Edge => {
                    for _ in 0..2 {
                        self.he_to.pop();
                        self.he_next.pop();
                        self.he_prev.pop();
                        self.he_face.pop();
                    }
                }
                Kind::Face => {
                    self.f_he.pop();
                }
            },
        }
    }

    // ----------------------------------------------------------------- logged primitives

    #[inline]
    fn rec(&mut self, u: Undo) {
        if self.depth > 0 {
            self.log.push(u);
        }
    }

    fn set_next(&mut self, h: HalfedgeId, n: HalfedgeId) {
        self.rec(Undo::Next(h, self.he_next[h.index()]));
        self.rec(Undo::Prev(n, self.he_prev[n.index()]));
        self.he_next[h.index()] = n;
        self.he_prev[n.index()] = h;
    }

    fn set_face(&mut self, h: HalfedgeId, f: FaceId) {
        self.rec(Undo::Face(h, self.he_face[h.index()]));
        self.he_face[h.index()] = f;
    }

    fn set_out(&mut self, v: VertexId, h: HalfedgeId) {
        self.rec(Undo::Out(v, self.v_out[v.index()]));
        self.v_out[v.index()] = h;
    }

    fn set_face_halfedge(&mut self, f: FaceId, h: HalfedgeId) {
        self.rec(Undo::FaceHalfedge(f, self.f_he[f.index()]));
        self.f_he[f.index()] = h;
    }

    /// Resets a half-edge slot to dead/unlinked values (or sets its target).
    fn reset_halfedge(&mut self, h: HalfedgeId, to: VertexId) {
        let i = h.index();
        self.rec(Undo::To(h, self.he_to[i]));
        self.rec(Undo::Next(h, self.he_next[i]));
        self.rec(Undo::Prev(h, self.he_prev[i]));
        self.rec(Undo::Face(h, self.he_face[i]));
        self.he_to[i] = to;
        self.he_next[i] = NO_H;
        self.he_prev[i] = NO_H;
        self.he_face[i] = NO_F;
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

    // ----------------------------------------------------------------- local edits

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

    // ----------------------------------------------------------------- checks

    #[inline]
    fn debug_check(&self) {
        #[cfg(all(feature = "debug-checks", debug_assertions))]
        if let Err(e) = self.sanity_check() {
            panic!("HalfEdgeMesh::sanity_check failed: {e}");
        }
    }

    /// Verifies every adjacency invariant; `Err` names the first violation. O(n log n).
    ///
    /// Checked: array lengths; face cycles of length 3 with consistent face links; twin
    /// targets differ (no loops); `prev(next(h)) == h`; `origin(next(h)) == target(h)`; border
    /// half-edges link to border half-edges; no edge without a face; no two edges with the
    /// same endpoints; targets are live vertices; each live vertex's outgoing half-edge leaves
    /// it, is a border one when the vertex has any, and the counter-clockwise rotation from it
    /// visits every outgoing half-edge exactly once (one umbrella, gaps linked in one cycle);
    /// isolated vertices have no edge; free lists hold exactly the dead ids, once each.
    pub fn sanity_check(&self) -> Result<(), String> {
        let nv = self.positions.len();
        let nh = self.he_to.len();
        let nf = self.f_he.len();
        if self.v_out.len() != nv || self.v_alive.len() != nv {
            return Err("vertex array lengths differ".into());
        }
        if nh % 2 != 0
            || self.he_next.len() != nh
            || self.he_prev.len() != nh
            || self.he_face.len() != nh
        {
            return Err("half-edge array lengths differ".into());
        }
        let live_h = |h: HalfedgeId| h.index() < nh && self.he_to[h.index()].is_valid();
        // Free lists.
        let mut free_v = vec![false; nv];
        for &v in &self.free_vertices {
            if v.index() >= nv || self.v_alive[v.index()] || free_v[v.index()] {
                return Err(format!(
                    "free vertex list entry {v} is live, out of range or repeated"
                ));
            }
            free_v[v.index()] = true;
        }
        if let Some(v) = (0..nv).find(|&v| !self.v_alive[v] && !free_v[v]) {
            return Err(format!("dead vertex v{v} is not on the free list"));
        }
        let mut free_e = vec![false; nh / 2];
        for &e in &self.free_edges {
            if e.index() >= nh / 2 || self.he_to[2 * e.index()].is_valid() || free_e[e.index()] {
                return Err(format!(
                    "free edge list entry {e} is live, out of range or repeated"
                ));
            }
            free_e[e.index()] = true;
        }
        for e in 0..nh / 2 {
            let (a, b) = (
                self.he_to[2 * e].is_valid(),
                self.he_to[2 * e + 1].is_valid(),
            );
            if a != b {
                return Err(format!("edge e{e} is half dead"));
            }
            if !a && !free_e[e] {
                return Err(format!("dead edge e{e} is not on the free list"));
            }
        }
        let mut free_f = vec![false; nf];
        for &f in &self.free_faces {
            if f.index() >= nf || self.f_he[f.index()].is_valid() || free_f[f.index()] {
                return Err(format!(
                    "free face list entry {f} is live, out of range or repeated"
                ));
            }
            free_f[f.index()] = true;
        }
        if let Some(f) = (0..nf).find(|&f| !self.f_he[f].is_valid() && !free_f[f]) {
            return Err(format!("dead face f{f} is not on the free list"));
        }
        // Faces.
        for f in self.faces() {
            let h = self.f_he[f.index()];
            if !live_h(h) {
                return Err(format!("face {f} points at dead half-edge {h}"));
            }
            let mut g = h;
            for _ in 0..3 {
                if self.he_face[g.index()] != f {
                    return Err(format!(
                        "half-edge {g} in the cycle of {f} has another face"
                    ));
                }
                g = self.he_next[g.index()];
                if !live_h(g) {
                    return Err(format!("face {f}'s cycle reaches a dead half-edge"));
                }
            }
            if g != h {
                return Err(format!("face {f}'s cycle is not of length 3"));
            }
        }
        // Half-edges.
        let mut out_count = vec![0u32; nv];
        let mut keys = Vec::new();
        for h in (0..nh).map(HalfedgeId::from_index).filter(|&h| live_h(h)) {
            let (to, next, prev) = (self.target(h), self.next(h), self.prev(h));
            if to.index() >= nv || !self.v_alive[to.index()] {
                return Err(format!("half-edge {h} points at dead vertex {to}"));
            }
            if to == self.origin(h) {
                return Err(format!("half-edge {h} is a loop at {to}"));
            }
            if !live_h(next) || !live_h(prev) {
                return Err(format!("half-edge {h} links to a dead half-edge"));
            }
            if self.he_prev[next.index()] != h || self.he_next[prev.index()] != h {
                return Err(format!("half-edge {h}: next/prev not inverse"));
            }
            if self.origin(next) != to {
                return Err(format!("half-edge {h}: next does not leave its target"));
            }
            let f = self.he_face[h.index()];
            if f.is_valid() {
                if !self.contains_face(f) {
                    return Err(format!("half-edge {h} has dead face {f}"));
                }
            } else {
                if self.he_face[next.index()].is_valid() {
                    return Err(format!("border half-edge {h} links to a face half-edge"));
                }
                if self.is_border_halfedge(self.twin(h)) {
                    return Err(format!("edge {} has no face", self.edge(h)));
                }
            }
            out_count[self.origin(h).index()] += 1;
            if h.0 % 2 == 0 {
                let (a, b) = (to.0.min(self.origin(h).0), to.0.max(self.origin(h).0));
                keys.push(((u64::from(a) << 32) | u64::from(b), h));
            }
        }
        keys.sort_unstable();
        if let Some(w) = keys.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(format!(
                "half-edges {} and {} duplicate an edge",
                w[0].1, w[1].1
            ));
        }
        // Vertices.
        for v in self.vertices() {
            let h = self.v_out[v.index()];
            let deg = out_count[v.index()] as usize;
            if !h.is_valid() {
                if deg != 0 {
                    return Err(format!("vertex {v} has edges but no outgoing half-edge"));
                }
                continue;
            }
            if !live_h(h) || self.origin(h) != v {
                return Err(format!(
                    "vertex {v}'s outgoing half-edge {h} does not leave it"
                ));
            }
            let mut g = h;
            let mut seen = 0usize;
            let mut any_border = false;
            loop {
                if self.origin(g) != v {
                    return Err(format!("rotation around {v} leaves the vertex at {g}"));
                }
                seen += 1;
                any_border |= self.is_border_halfedge(g);
                if seen > deg {
                    return Err(format!("rotation around {v} does not return"));
                }
                g = self.rotate_ccw(g);
                if g == h {
                    break;
                }
            }
            if seen != deg {
                return Err(format!(
                    "vertex {v}: rotation visits {seen} of {deg} outgoing half-edges (split umbrella)"
                ));
            }
            if any_border && !self.is_border_halfedge(h) {
                return Err(format!(
                    "vertex {v} is on the border but its half-edge {h} is not"
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate;

    fn mesh(s: &TriangleSoup) -> HalfEdgeMesh {
        let m = HalfEdgeMesh::from_soup(s).unwrap();
        m.sanity_check().unwrap();
        m
    }

    #[test]
    fn round_trips_every_generator() {
        for s in [
            generate::tetrahedron(),
            generate::icosphere(2, 1.0),
            generate::uv_sphere(7, 4, 1.0),
            generate::torus(2.0, 0.5, 9, 5),
            generate::open_cylinder(1.0, 1.0, 6, 3),
            generate::box_mesh(DVec3::ONE, 2),
            generate::plate_with_holes(2),
            generate::box_with_tunnel(),
            generate::block_with_pocket(),
            generate::disk_with_holes(3),
        ] {
            let m = mesh(&s);
            assert_eq!(m.to_soup(), s);
            assert_eq!(m.topology(), crate::analyze(&s));
            let t = crate::analyze(&s);
            assert_eq!(
                (m.num_vertices(), m.num_faces(), m.num_edges()),
                (s.num_vertices(), s.num_faces(), t.num_edges)
            );
        }
    }

    #[test]
    fn build_errors_name_the_element() {
        use BuildError::*;
        assert_eq!(
            HalfEdgeMesh::from_soup(&generate::three_triangles_on_edge()),
            Err(NonManifoldEdge {
                vertices: [VertexId(0), VertexId(1)],
                faces: [FaceId(0), FaceId(1), FaceId(2)]
            })
        );
        assert!(matches!(
            HalfEdgeMesh::from_soup(&generate::moebius_strip(6)),
            Err(InconsistentOrientation { .. })
        ));
        let s = TriangleSoup::from_raw(&[[0.0; 3]; 3], &[[0, 1, 2], [0, 2, 2]]);
        assert_eq!(
            HalfEdgeMesh::from_soup(&s),
            Err(DegenerateFace { face: FaceId(1) })
        );
        let s = TriangleSoup::from_raw(&[[0.0; 3]; 3], &[[0, 1, 3]]);
        assert_eq!(
            HalfEdgeMesh::from_soup(&s),
            Err(IndexOutOfRange {
                face: FaceId(0),
                vertex: VertexId(3)
            })
        );
        let s = TriangleSoup::from_raw(&[[0.0; 3]; 4], &[[0, 1, 2], [0, 1, 3]]);
        assert_eq!(
            HalfEdgeMesh::from_soup(&s),
            Err(InconsistentOrientation {
                edge: [VertexId(0), VertexId(1)],
                faces: [FaceId(0), FaceId(1)]
            })
        );
    }

    #[test]
    fn one_ring_is_ordered_counter_clockwise() {
        let m = mesh(&generate::icosphere(1, 1.0));
        let v = VertexId(0);
        let n: Vec<VertexId> = m.vertex_neighbors(v).collect();
        let f: Vec<FaceId> = m.vertex_faces(v).collect();
        assert_eq!((n.len(), f.len(), m.valence(v)), (5, 5, 5));
        for i in 0..5 {
            // Face i is (v, n[i], n[i+1]) up to rotation.
            let fv = m.face_vertices(f[i]);
            let k = fv.iter().position(|&x| x == v).unwrap();
            assert_eq!([fv[(k + 1) % 3], fv[(k + 2) % 3]], [n[i], n[(i + 1) % 5]]);
        }
        assert!(!m.is_border_vertex(v) && m.is_manifold_vertex(v));
    }

    #[test]
    fn border_vertices_start_at_their_border_halfedge() {
        let m = mesh(&generate::open_cylinder(1.0, 1.0, 6, 2));
        let v = VertexId(0);
        assert!(m.is_border_vertex(v));
        let h = m.vertex_halfedge(v).unwrap();
        assert!(m.is_border_halfedge(h) && m.is_border_edge(m.edge(h)));
        assert_eq!(m.vertex_faces(v).count(), m.valence(v) - 1);
        assert_eq!(m.find_halfedge(v, m.target(h)), Some(h));
        assert_eq!(m.origin(h), v);
        assert_eq!(m.twin(m.twin(h)), h);
        assert_eq!(m.edge_halfedge(m.edge(h), h.0 & 1), h);
    }

    #[test]
    fn remove_and_refill_interior_fan() {
        let s = generate::icosphere(1, 1.0);
        let mut m = mesh(&s);
        let before = m.clone();
        let v = VertexId(0);
        let p = m.position(v);
        let hole = m.remove_vertex_fan(v).unwrap();
        m.sanity_check().unwrap();
        assert_eq!(hole.len(), 5);
        assert!(m.is_isolated(v));
        let t = m.topology();
        assert_eq!((t.border_loops.len(), t.genus), (1, Some(0)));
        assert_eq!(t.unreferenced_vertices, vec![v]);
        // The soup loop runs as the surrounding faces run it: the hole cycle reversed.
        let l = &t.border_loops[0];
        let k = l.iter().position(|&x| x == hole[0]).unwrap();
        assert!((0..5).all(|i| l[(k + 5 - i) % 5] == hole[i]));
        m.remove_vertex(v).unwrap();
        let c = m.add_vertex(p);
        assert_eq!(c, v, "the freed id is reused");
        for i in 0..5 {
            m.add_face([c, hole[i], hole[(i + 1) % 5]]).unwrap();
            m.sanity_check().unwrap();
        }
        assert_eq!(m.topology(), before.topology());
        assert_eq!(m.num_faces(), before.num_faces());
    }

    #[test]
    fn remove_border_fan_gives_open_chain() {
        let mut m = mesh(&generate::open_cylinder(1.0, 1.0, 6, 2));
        let v = VertexId(0);
        let ring: Vec<VertexId> = m.vertex_neighbors(v).collect();
        let chain = m.remove_vertex_fan(v).unwrap();
        m.sanity_check().unwrap();
        assert_eq!(chain.len(), ring.len());
        assert_eq!(chain.last(), ring.first());
        // The chain's consecutive pairs are border half-edges.
        for w in chain.windows(2) {
            let h = m.find_halfedge(w[0], w[1]).unwrap();
            assert!(m.is_border_halfedge(h));
        }
        for w in chain.windows(2) {
            m.add_face([v, w[0], w[1]]).unwrap();
        }
        m.sanity_check().unwrap();
        assert_eq!(
            m.topology(),
            crate::analyze(&generate::open_cylinder(1.0, 1.0, 6, 2))
        );
    }

    #[test]
    fn several_gaps_and_relinking() {
        // Open a hole at vertex 0 of an icosphere, then remove the fan of the middle
        // neighbour of a hole vertex x: x is left with two fans (two border gaps). Refilling
        // in an interleaved order exercises OpenMesh's patch relinking.
        let s = generate::icosphere(1, 1.0);
        let mut m = mesh(&s);
        let hole0 = m.remove_vertex_fan(VertexId(0)).unwrap();
        let x = hole0[0];
        let ring: Vec<VertexId> = m.vertex_neighbors(x).collect();
        assert_eq!(ring.len(), 5);
        let v = ring[3]; // faces at x: (x, r1, r2) .. (x, r4, r0); r3 is the middle
        assert!(!m.is_border_vertex(v));
        let hole = m.remove_vertex_fan(v).unwrap();
        m.sanity_check().unwrap();
        assert!(!m.is_manifold_vertex(x));
        assert_eq!(m.remove_vertex_fan(x), Err(EditError::NonManifoldVertex(x)));
        assert_eq!(m.topology().components[0].genus, None);
        let k = hole.len();
        let order: Vec<usize> = (0..k).step_by(2).chain((1..k).step_by(2)).collect();
        let mut refused = Vec::new();
        for &i in &order {
            if m.add_face([v, hole[i], hole[(i + 1) % k]]).is_err() {
                refused.push(i);
            }
            m.sanity_check().unwrap();
        }
        for &i in &refused {
            m.add_face([v, hole[i], hole[(i + 1) % k]]).unwrap();
            m.sanity_check().unwrap();
        }
        assert!(m.vertices().all(|x| m.is_manifold_vertex(x)));
        for i in 0..hole0.len() {
            m.add_face([VertexId(0), hole0[i], hole0[(i + 1) % hole0.len()]])
                .unwrap();
        }
        m.sanity_check().unwrap();
        assert_eq!(m.topology(), crate::analyze(&s));
    }

    #[test]
    fn add_face_refusals() {
        let mut m = mesh(&generate::icosphere(0, 1.0));
        let n: Vec<VertexId> = m.vertex_neighbors(VertexId(0)).collect();
        assert_eq!(
            m.add_face([VertexId(0), n[1], n[0]]),
            Err(AddFaceError::InteriorVertex(VertexId(0)))
        );
        let hole = m.remove_vertex_fan(VertexId(0)).unwrap();
        let before = m.clone();
        // Flipped face on an existing border half-edge's twin side.
        assert_eq!(
            m.add_face([hole[1], hole[0], VertexId(0)]),
            Err(AddFaceError::HalfedgeOccupied {
                from: hole[1],
                to: hole[0]
            })
        );
        // A face touching a hole vertex through no edge.
        let far = m.add_vertex(DVec3::ZERO);
        let far2 = m.add_vertex(DVec3::ONE);
        assert_eq!(
            m.add_face([hole[0], far, far2]),
            Err(AddFaceError::NewFan(hole[0]))
        );
        assert_eq!(
            m.add_face([far, far, far2]),
            Err(AddFaceError::RepeatedVertex(far))
        );
        m.remove_vertex(far2).unwrap();
        assert_eq!(
            m.add_face([far, far2, hole[0]]),
            Err(AddFaceError::DeadVertex(far2))
        );
        m.remove_vertex(far).unwrap();
        // A free-standing triangle is fine.
        let a = m.add_vertex(DVec3::X);
        let b = m.add_vertex(DVec3::Y);
        let c = m.add_vertex(DVec3::Z);
        let f = m.add_face([a, b, c]).unwrap();
        assert_eq!(m.face_vertices(f), [a, b, c]);
        assert_eq!(m.topology().components.len(), 2);
        m.remove_faces(&[f]).unwrap();
        assert_eq!(m.remove_faces(&[f]), Err(EditError::DeadFace(f)));
        for x in [c, b, a] {
            m.remove_vertex(x).unwrap();
        }
        m.sanity_check().unwrap();
        assert_eq!(m.topology(), before.topology());
    }

    #[test]
    fn rollback_restores_identical_mesh() {
        let mut m = mesh(&generate::torus(2.0, 0.5, 8, 6));
        let before = m.clone();
        let outer = m.begin();
        let hole = m.remove_vertex_fan(VertexId(3)).unwrap();
        let mid = m.clone();
        let inner = m.begin();
        m.remove_vertex(VertexId(3)).unwrap();
        let c = m.add_vertex(DVec3::ZERO);
        m.set_position(VertexId(5), DVec3::ONE);
        for i in 0..hole.len() {
            m.add_face([c, hole[i], hole[(i + 1) % hole.len()]])
                .unwrap();
        }
        m.remove_faces(&[FaceId(0), FaceId(7)]).unwrap();
        m.rollback(inner);
        assert_eq!(m, mid);
        let again = m.begin();
        m.remove_vertex_fan(VertexId(20)).unwrap();
        m.commit(again);
        m.rollback(outer);
        assert_eq!(m, before);
        m.sanity_check().unwrap();
        // No checkpoint open: edits are not logged.
        m.remove_vertex_fan(VertexId(1)).unwrap();
        assert!(m.log.is_empty());
    }

    #[test]
    fn removing_an_isolated_triangle_kills_its_edges() {
        let mut m = mesh(&TriangleSoup::from_raw(&[[0.0; 3]; 3], &[[0, 1, 2]]));
        m.remove_faces(&[FaceId(0)]).unwrap();
        m.sanity_check().unwrap();
        assert_eq!((m.num_faces(), m.num_edges(), m.num_vertices()), (0, 0, 3));
        assert!((0..3).all(|v| m.is_isolated(VertexId(v))));
        m.add_face([VertexId(0), VertexId(1), VertexId(2)]).unwrap();
        m.sanity_check().unwrap();
        assert_eq!(m.topology().genus, Some(0));
    }
}
