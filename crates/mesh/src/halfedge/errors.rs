//! Why an edit or a build was refused: [`BuildError`], [`AddFaceError`], [`EditError`].

use crate::{FaceId, VertexId};
use thiserror::Error;

/// Why [`HalfEdgeMesh::from_soup`](super::HalfEdgeMesh::from_soup) refused a soup.
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

/// Why [`HalfEdgeMesh::add_face`](super::HalfEdgeMesh::add_face) refused a face. Nothing was changed.
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
