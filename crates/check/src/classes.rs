//! The degeneracy classes and their severities.

/// Whether a class makes a mesh unacceptable input.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// The simplifiers reject a mesh with any element of this class (`envelope check` exits 1).
    Error,
    /// Worth knowing, harmless to the simplifiers.
    Warning,
}

/// A kind of defect [`crate::check`] looks for. The JSON key of each is [`Self::key`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum DegeneracyClass {
    /// A vertex whose faces form more than one fan (includes both ends of a non-manifold edge).
    NonManifoldVertices,
    /// An edge with more than two faces.
    NonManifoldEdges,
    /// A face whose corners are exactly collinear, or that repeats a vertex index.
    ZeroAreaTriangles,
    /// A face of non-zero area and very poor shape (heuristic, f64).
    SliverTriangles,
    /// Two faces on the same three vertex indices.
    DuplicateTriangles,
    /// Two faces (not duplicates) that overlap with positive area in a common plane.
    CoincidentTriangles,
    /// A vertex exactly in the open interior of an edge it does not belong to.
    TJunctions,
    /// A vertex no face uses.
    UnreferencedVertices,
    /// Two or more referenced vertices at exactly the same position (an unwelded seam).
    DuplicateVertices,
    /// An edge run in the same direction by two faces.
    InconsistentOrientation,
    /// Two faces meeting away from the vertices and edge they share (exact test).
    IntersectingTriangles,
}

impl DegeneracyClass {
    /// Every class, in report order.
    pub const ALL: [DegeneracyClass; 11] = [
        Self::NonManifoldVertices,
        Self::NonManifoldEdges,
        Self::ZeroAreaTriangles,
        Self::SliverTriangles,
        Self::DuplicateTriangles,
        Self::CoincidentTriangles,
        Self::TJunctions,
        Self::UnreferencedVertices,
        Self::DuplicateVertices,
        Self::InconsistentOrientation,
        Self::IntersectingTriangles,
    ];

    /// The stable key used in JSON and text output.
    #[must_use]
    pub const fn key(self) -> &'static str {
        match self {
            Self::NonManifoldVertices => "non_manifold_vertices",
            Self::NonManifoldEdges => "non_manifold_edges",
            Self::ZeroAreaTriangles => "zero_area_triangles",
            Self::SliverTriangles => "sliver_triangles",
            Self::DuplicateTriangles => "duplicate_triangles",
            Self::CoincidentTriangles => "coincident_triangles",
            Self::TJunctions => "t_junctions",
            Self::UnreferencedVertices => "unreferenced_vertices",
            Self::DuplicateVertices => "duplicate_vertices",
            Self::InconsistentOrientation => "inconsistent_orientation",
            Self::IntersectingTriangles => "intersecting_triangles",
        }
    }

    /// Whether the class makes the mesh unacceptable input.
    ///
    /// Warnings: unreferenced vertices (ignored by everything downstream) and slivers (a
    /// shape heuristic; sliver triangles are legal input, merely hard on the envelopes).
    /// Everything else is an error: it breaks the paper's input assumptions (section 3 and
    /// 7.1: a manifold or bordered manifold, no interpenetration, no cracks, no T-junctions).
    #[must_use]
    pub const fn severity(self) -> crate::Severity {
        match self {
            Self::UnreferencedVertices | Self::SliverTriangles => crate::Severity::Warning,
            _ => crate::Severity::Error,
        }
    }
}

impl std::fmt::Display for DegeneracyClass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.key())
    }
}
