//! Indexed triangle meshes for the envelope engine.
//!
//! * [`TriangleSoup`]: positions plus index triples, what readers produce.
//! * [`HalfEdgeMesh`]: full adjacency for manifold (possibly bordered) meshes, with the local
//!   edits the simplifiers need (remove a vertex's fan, fill a hole, undo) in time
//!   proportional to the edit.
//! * Topology: components, border loops, Euler characteristic, genus, orientability.
//! * Typed ids ([`VertexId`], [`FaceId`], [`HalfedgeId`], [`EdgeId`]) and the coordinate range
//!   check ([`check_coordinate`]) every reader applies.
//!
//! Nothing here makes a geometric decision: exact predicates live in `envelope-predicates`,
//! and geometric input checks (zero-area triangles, T-junctions, intersections) in
//! `envelope-check`.
#![forbid(unsafe_code)]

mod coords;
mod ids;
mod soup;

pub use coords::{CoordError, MAX_ALLOWED_MAGNITUDE, MIN_ALLOWED_MAGNITUDE, check_coordinate};
pub use ids::{EdgeId, FaceId, HalfedgeId, VertexId};
pub use soup::TriangleSoup;
