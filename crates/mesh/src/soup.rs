//! [`TriangleSoup`]: positions plus index triples, the form every reader produces and every
//! writer takes. It carries no adjacency; build a [`crate::HalfEdgeMesh`] from it for that.

use crate::{FaceId, VertexId};
use glam::DVec3;

/// An indexed triangle list: `positions[v]` is vertex `v`, `faces[f]` its three corners in
/// counter-clockwise order seen from outside (right-hand rule gives the outward normal).
///
/// Positions are plain f64 (no exactness is claimed for anything computed from them here);
/// readers guarantee every coordinate passed [`crate::check_coordinate`] and every index is in
/// range.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleSoup {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Triangles as three vertex ids.
    pub faces: Vec<[VertexId; 3]>,
}

impl TriangleSoup {
    /// A soup from positions and faces.
    #[must_use]
    pub fn new(positions: Vec<DVec3>, faces: Vec<[VertexId; 3]>) -> Self {
        Self { positions, faces }
    }

    /// A soup from raw `[f64; 3]` positions and `[u32; 3]` index triples (handy in tests).
    ///
    /// ```
    /// use envelope_mesh::TriangleSoup;
    /// let s = TriangleSoup::from_raw(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
    /// assert_eq!((s.num_vertices(), s.num_faces()), (3, 1));
    /// ```
    #[must_use]
    pub fn from_raw(positions: &[[f64; 3]], faces: &[[u32; 3]]) -> Self {
        Self {
            positions: positions.iter().map(|&p| DVec3::from_array(p)).collect(),
            faces: faces.iter().map(|f| f.map(VertexId)).collect(),
        }
    }

    /// Number of vertices (referenced or not).
    #[must_use]
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    #[must_use]
    pub fn num_faces(&self) -> usize {
        self.faces.len()
    }

    /// Position of vertex `v`.
    #[must_use]
    pub fn position(&self, v: VertexId) -> DVec3 {
        self.positions[v.index()]
    }

    /// The three corner positions of face `f`.
    #[must_use]
    pub fn triangle(&self, f: FaceId) -> [DVec3; 3] {
        self.faces[f.index()].map(|v| self.positions[v.index()])
    }

    /// Iterator over face ids.
    pub fn face_ids(&self) -> impl ExactSizeIterator<Item = FaceId> + use<> {
        (0..self.faces.len() as u32).map(FaceId)
    }

    /// Axis-aligned bounding box `(min, max)` of all positions, `None` when there are none.
    #[must_use]
    pub fn bounding_box(&self) -> Option<(DVec3, DVec3)> {
        let first = *self.positions.first()?;
        Some(
            self.positions
                .iter()
                .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
        )
    }

    /// Length of the bounding-box diagonal (0 for an empty soup). The papers state epsilon as a
    /// fraction of this length.
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        self.bounding_box()
            .map_or(0.0, |(lo, hi)| (hi - lo).length())
    }

    /// Whether every face index is below `num_vertices()`.
    #[must_use]
    pub fn indices_in_range(&self) -> bool {
        let n = self.positions.len();
        self.faces.iter().flatten().all(|v| v.index() < n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bbox_and_diagonal() {
        let s = TriangleSoup::from_raw(
            &[[0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [0.0, 4.0, 0.0]],
            &[[0, 1, 2]],
        );
        assert_eq!(s.diagonal(), 5.0);
        assert!(s.indices_in_range());
        assert_eq!(TriangleSoup::default().diagonal(), 0.0);
        let bad = TriangleSoup::from_raw(&[[0.0; 3]], &[[0, 1, 2]]);
        assert!(!bad.indices_in_range());
    }
}
