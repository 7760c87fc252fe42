//! The small policies of the local simplifier, after CGAL's Surface_mesh_simplification
//! concepts: which vertex to try next ([`QueueOrder`], a priority), when to stop
//! ([`StopRule`]), and who is told what happened ([`Visitor`]). Constraints are
//! [`Filter`](crate::filter::Filter)s; hole filling strategies are `HoleFiller`s (module `fill`).

use envelope_mesh::{AddFaceError, FaceId, HalfEdgeMesh, VertexId};

/// The priority of a vertex in the removal queue: lower goes first; equal priorities go in
/// the order they were queued (first in, first out). A number, never a yes/no.
pub trait QueueOrder {
    /// Priority of `v`, computed when `v` is (re)queued.
    fn priority(&self, mesh: &HalfEdgeMesh, v: VertexId) -> f64;

    /// True when every vertex gets the same priority, so the queue is first in, first out
    /// and a vertex queued later never overtakes one queued earlier. The local algorithm
    /// then plans independent removals in parallel (same result as one thread).
    fn is_fifo(&self) -> bool {
        false
    }
}

/// The paper's queue (section 5.2): first in, first out; the initial queue in vertex id
/// order, neighbours of a removed vertex appended in their counter-clockwise order.
#[derive(Clone, Copy, Debug, Default)]
pub struct Fifo;

impl QueueOrder for Fifo {
    fn priority(&self, _: &HalfEdgeMesh, _: VertexId) -> f64 {
        0.0
    }
    fn is_fifo(&self) -> bool {
        true
    }
}

/// Flattest fan first: priority `1 - |sum of fan area vectors| / sum of fan areas` (0 for a
/// planar fan, towards 1 for a sharp cone). Not in the paper; a common ordering
/// (Schroeder et al. 1992 use a distance-to-plane criterion).
#[derive(Clone, Copy, Debug, Default)]
pub struct FlatFirst;

impl QueueOrder for FlatFirst {
    fn priority(&self, mesh: &HalfEdgeMesh, v: VertexId) -> f64 {
        let (mut sum, mut total) = (glam::DVec3::ZERO, 0.0);
        for f in mesh.vertex_faces(v) {
            let [a, b, c] = mesh.face_vertices(f).map(|x| mesh.position(x));
            let n = (b - a).cross(c - a);
            sum += n;
            total += n.length();
        }
        if total > 0.0 {
            1.0 - sum.length() / total
        } else {
            1.0
        }
    }
}

/// When to stop before the queue runs empty.
pub trait StopRule {
    /// Checked before each attempt with the current face count.
    fn should_stop(&self, faces: usize) -> bool;
}

/// Run until the queue is empty (the paper: until the error bound prevents every removal).
#[derive(Clone, Copy, Debug, Default)]
pub struct Exhaust;

impl StopRule for Exhaust {
    fn should_stop(&self, _: usize) -> bool {
        false
    }
}

/// Stop once the mesh has at most this many faces.
#[derive(Clone, Copy, Debug)]
pub struct TargetFaces(pub usize);

impl StopRule for TargetFaces {
    fn should_stop(&self, faces: usize) -> bool {
        faces <= self.0
    }
}

/// Why a vertex was not removed. The mesh is unchanged in every case.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rejection {
    /// Already removed or isolated.
    NotAVertex,
    /// A border vertex while there is no border tube (nothing bounds the border, 6.2).
    BorderWithoutTubes,
    /// A kept vertex ([`Barriers::with_kept`](crate::policy::Barriers::with_kept)): never
    /// removed nor moved.
    Kept,
    /// A border vertex with one face: removing it would leave no triangle whose new border
    /// edge the tubes could be checked on.
    Ear,
    /// The fan is not one umbrella (several border gaps).
    NonManifold,
    /// The one-ring repeats a vertex (cannot happen on a valid manifold; kept for safety).
    RepeatedNeighbour,
    /// The valence is above the local algorithm's `MAX_HOLE`.
    HoleTooLarge,
    /// A border vertex whose new border edge misses the tube ring of an input border vertex
    /// it stands for ([`BorderCover`](crate::policy::BorderCover)).
    BorderNotCovered,
    /// No valid triangulation of the hole was found.
    NoValidFill,
    /// No valid triangulation of the hole exists: every triangle on its vertices that meets
    /// the vertex's fiber path is refused (the fiber test, [`FiberTest`](crate::fiber::FiberTest)).
    NoFillAcrossFiber,
    /// The mesh refused the filling (a topology guard; should not happen after the checks).
    MeshRefused(AddFaceError),
}

/// Told about every attempt; all methods default to doing nothing. `()` is the silent
/// visitor.
pub trait Visitor {
    /// Before trying to remove `v`.
    fn on_attempt(&mut self, _v: VertexId) {}
    /// `v` was removed; `faces` are the new faces filling its hole.
    fn on_removed(&mut self, _v: VertexId, _faces: &[FaceId]) {}
    /// `v` was kept, for `reason`.
    fn on_rejected(&mut self, _v: VertexId, _reason: Rejection) {}
    /// Whether the run should stop with `SimplifyError::Cancelled`; asked once per round of
    /// the run (a batch, or one vertex when not batched).
    fn cancelled(&mut self) -> bool {
        false
    }
}

impl Visitor for () {}

/// Shape quality `4 sqrt(3) A / (a² + b² + c²)`: 1 for an equilateral triangle, 0 for a
/// degenerate one. f64, a priority only (validity never rests on it).
#[must_use]
pub fn aspect_ratio(t: [glam::DVec3; 3]) -> f64 {
    let [a, b, c] = t;
    let area2 = (b - a).cross(c - a).length();
    let s = (b - a).length_squared() + (c - b).length_squared() + (a - c).length_squared();
    if s > 0.0 {
        2.0 * 3f64.sqrt() * area2 / s
    } else {
        0.0
    }
}
