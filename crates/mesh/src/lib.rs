//! Indexed triangle meshes for the envelope engine.
//!
//! * [`TriangleSoup`]: positions plus index triples, what readers produce; [`Attributes`]:
//!   per-corner texture coordinates, normals and colours beside it.
//! * [`analyze`] / [`Topology`]: components, border loops, Euler characteristic, genus,
//!   manifoldness and orientability of *any* soup; the [`degeneracy`] finders name the
//!   offending elements (non-manifold edges and vertices, duplicate faces and vertices,
//!   repeated indices, unreferenced vertices, orientation conflicts).
//! * [`HalfEdgeMesh`]: full adjacency for manifold (possibly bordered) meshes, with the local
//!   edits the simplifiers need (remove a vertex's fan, add a face, undo via [`Checkpoint`])
//!   in time proportional to the edit, and an always-compiled `sanity_check()`.
//! * [`generate`]: deterministic test meshes with known topology.
//! * Typed ids ([`VertexId`], [`FaceId`], [`HalfedgeId`], [`EdgeId`]) and the coordinate range
//!   check ([`check_coordinate`]) every reader applies.
//!
//! Nothing here makes a geometric decision: exact predicates live in `envelope-predicates`,
//! and geometric input checks (zero-area triangles, T-junctions, intersections) in
//! `envelope-check`.
//!
//! Feature `debug-checks`: every [`HalfEdgeMesh`] edit runs `sanity_check()` in debug builds
//! and panics on failure.
#![forbid(unsafe_code)]

mod analysis;
mod attributes;
mod coords;
pub mod degeneracy;
pub mod generate;
mod halfedge;
mod ids;
mod soup;
mod topology;

pub use attributes::{Attributes, Wedges};
pub use coords::{
    CoordError, MAX_ALLOWED_MAGNITUDE, MIN_ALLOWED_MAGNITUDE, check_coordinate, flush_tiny,
};
pub use halfedge::{
    AddFaceError, BuildError, Checkpoint, EditError, HalfEdgeMesh, OutgoingHalfedges,
};
pub use ids::{EdgeId, FaceId, HalfedgeId, VertexId};
pub use soup::TriangleSoup;
pub use topology::{Component, Topology, VertexFaces, analyze, vertex_components};
