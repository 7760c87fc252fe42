//! Why the envelopes could not be built, and the limits on the input past which they are not.
use envelope_mesh::VertexId;

/// Why the envelopes could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EnvelopeError {
    /// No faces.
    #[error("the mesh has no faces")]
    Empty,
    /// A face names a vertex that does not exist.
    #[error("a face index is out of range")]
    IndexOutOfRange,
    /// Non-manifold edges or vertices.
    #[error("the mesh is not manifold")]
    NotManifold,
    /// Faces are not consistently oriented.
    #[error("the mesh is not consistently oriented")]
    NotOriented,
    /// Per-vertex epsilon count differs from the vertex count.
    #[error("{got} epsilon values for {expected} vertices")]
    EpsilonCount {
        /// Vertices.
        expected: usize,
        /// Values.
        got: usize,
    },
    /// A non-finite or non-positive epsilon.
    #[error("epsilon of vertex {} is not finite and positive", .vertex.0)]
    BadEpsilon {
        /// The first such vertex.
        vertex: VertexId,
    },
    /// An epsilon too small to be represented as an offset beside the mesh's coordinates
    /// (below 2^-40 times the largest coordinate magnitude).
    #[error(
        "epsilon {epsilon:e}{} is below 2^-40 times the largest coordinate magnitude \
         {magnitude:e} (at least {floor:e} is needed): offsets that small are lost in the \
         rounding of the coordinates; use a larger epsilon or move the mesh toward the origin",
        .vertex.map(|v| format!(" (vertex {})", v.0)).unwrap_or_default()
    )]
    EpsilonTooSmall {
        /// The first such vertex (`None` for a constant epsilon).
        vertex: Option<VertexId>,
        /// Its epsilon.
        epsilon: f64,
        /// The smallest accepted epsilon.
        floor: f64,
        /// The largest coordinate magnitude of the mesh.
        magnitude: f64,
    },
    /// Coordinates so large that envelopes around them leave the exact predicates' range.
    #[error(
        "coordinates up to {magnitude:e} with epsilon {epsilon:e} would put envelope points \
         beyond 2^119, outside the exact predicates' range; scale the mesh down"
    )]
    CoordinatesTooLarge {
        /// The largest coordinate magnitude of the mesh.
        magnitude: f64,
        /// The largest epsilon (after clamping to the diagonal).
        epsilon: f64,
    },
    /// A tube ring with too few or too many vertices.
    #[error(
        "{0} tube segments: a tube ring needs {lo} to {hi} vertices",
        lo = TUBE_SEGMENTS.start(),
        hi = TUBE_SEGMENTS.end()
    )]
    TubeSegments(u32),
    /// The caller set [`EnvelopeOptions::abandon`](crate::EnvelopeOptions::abandon): the
    /// envelopes were no longer wanted.
    #[error("the envelope build was abandoned by its caller")]
    Abandoned,
}

/// The smallest epsilon, as a fraction of the largest coordinate magnitude, that
/// [`crate::EpsilonField::evaluate`] accepts: 2^-40 leaves an offset about 4,000 units in the last
/// place of the coordinates it is added to.
pub(crate) const EPSILON_FLOOR: f64 = 9.094_947_017_729_282e-13;

/// The vertices a tube ring may have: fewer than 3 make no ring around a border edge, more
/// than 64 only cost memory (each ring vertex is a tube vertex per border vertex).
pub const TUBE_SEGMENTS: std::ops::RangeInclusive<u32> = 3..=64;
