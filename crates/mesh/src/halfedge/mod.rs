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
//!
//! Files: `build` (from and to a soup), `navigation` (read-only queries), `topology` (genus
//! and border loops), `edits` (local edits), `journal` (checkpoints and the undo log),
//! `sanity` (`sanity_check`), `errors`, `tests`.

mod build;
mod edits;
mod errors;
mod journal;
mod navigation;
mod sanity;
#[cfg(test)]
mod tests;
mod topology;

pub use errors::{AddFaceError, BuildError, EditError};
pub use journal::Checkpoint;
pub use navigation::OutgoingHalfedges;

use crate::{EdgeId, FaceId, HalfedgeId, VertexId};
use glam::DVec3;
use journal::Undo;

const NO_H: HalfedgeId = HalfedgeId::INVALID;
const NO_F: FaceId = FaceId::INVALID;
const NO_V: VertexId = VertexId::INVALID;

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
