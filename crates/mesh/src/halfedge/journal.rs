//! The undo log behind [`Checkpoint`]: every write to a [`HalfEdgeMesh`] goes through a
//! logging setter here, and [`HalfEdgeMesh::rollback`] replays the log backwards.

use super::{HalfEdgeMesh, NO_F, NO_H};
use crate::{EdgeId, FaceId, HalfedgeId, VertexId};
use glam::DVec3;

/// A point in the edit history; pass it to [`HalfEdgeMesh::rollback`] or
/// [`HalfEdgeMesh::commit`]. Checkpoints nest and must be closed innermost first.
#[derive(Debug)]
#[must_use = "a checkpoint must be rolled back or committed"]
pub struct Checkpoint {
    log_len: usize,
    depth: u32,
}

#[derive(Clone, Copy, Debug)]
pub(super) enum Kind {
    Vertex,
    Edge,
    Face,
}

#[derive(Clone, Copy, Debug)]
pub(super) enum Undo {
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

impl HalfEdgeMesh {
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

    #[inline]
    pub(super) fn rec(&mut self, u: Undo) {
        if self.depth > 0 {
            self.log.push(u);
        }
    }

    pub(super) fn set_next(&mut self, h: HalfedgeId, n: HalfedgeId) {
        self.rec(Undo::Next(h, self.he_next[h.index()]));
        self.rec(Undo::Prev(n, self.he_prev[n.index()]));
        self.he_next[h.index()] = n;
        self.he_prev[n.index()] = h;
    }

    pub(super) fn set_face(&mut self, h: HalfedgeId, f: FaceId) {
        self.rec(Undo::Face(h, self.he_face[h.index()]));
        self.he_face[h.index()] = f;
    }

    pub(super) fn set_out(&mut self, v: VertexId, h: HalfedgeId) {
        self.rec(Undo::Out(v, self.v_out[v.index()]));
        self.v_out[v.index()] = h;
    }

    pub(super) fn set_face_halfedge(&mut self, f: FaceId, h: HalfedgeId) {
        self.rec(Undo::FaceHalfedge(f, self.f_he[f.index()]));
        self.f_he[f.index()] = h;
    }

    /// Resets a half-edge slot to dead/unlinked values (or sets its target).
    pub(super) fn reset_halfedge(&mut self, h: HalfedgeId, to: VertexId) {
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
}
