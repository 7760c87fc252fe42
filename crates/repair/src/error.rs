//! Why a mesh cannot be repaired without moving its surface, named by input element.

use envelope_mesh::{FaceId, VertexId};

/// A repair refused: the input element that no step can change without moving the surface
/// (or that is not a mesh at all). Indices are the input's, from 0.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RepairError {
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a coordinate that is not finite")]
    NonFiniteCoordinate {
        /// The vertex.
        vertex: VertexId,
    },
    /// A face names a vertex that does not exist.
    #[error("face {face} names a vertex beyond the last one ({vertices} vertices)")]
    IndexOutOfRange {
        /// The face.
        face: FaceId,
        /// Vertices in the mesh.
        vertices: usize,
    },
    /// A zero-area face whose segment (or point) is not proved to lie on the other faces:
    /// dropping it could remove part of the surface, keeping it leaves a degenerate face.
    #[error(
        "face {face} [{} {} {}] has zero area and its points are not all on other faces: it cannot be dropped without changing the surface",
        .corners[0], .corners[1], .corners[2]
    )]
    UncoveredDegenerateFace {
        /// The face.
        face: FaceId,
        /// Its corners (after the weld).
        corners: [VertexId; 3],
    },
    /// A component with no consistent orientation (a Möbius band): `face` is where the
    /// orientations propagated from `first` disagree.
    #[error(
        "face {face} is in a non-orientable component (a Moebius band; the component of face {first}): no choice of face orientations agrees on every edge"
    )]
    NonOrientable {
        /// A face where the orientations disagree.
        face: FaceId,
        /// The component's first face.
        first: FaceId,
    },
}
