//! The mesh users hand in and get back.

use envelope_mesh::{Attributes, TriangleSoup, VertexId, generate};
use glam::DVec3;

/// A triangle mesh: vertex positions and triangles of vertex indices, counter-clockwise seen
/// from outside, with optional per-corner [`Attributes`] (texture coordinates, normals,
/// colours).
///
/// A `Mesh` made by [`Mesh::new`] or [`load`](crate::load) has every index in range and every coordinate
/// finite; whether it is acceptable input for the simplifier (manifold, no degenerate or
/// intersecting faces) is `envelope::check`'s question.
///
/// ```
/// let square = envelope::Mesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// assert_eq!((square.num_vertices(), square.num_faces()), (4, 2));
/// assert!(envelope::Mesh::new(vec![[0.0; 3]], vec![[0, 1, 2]]).is_err());
/// # Ok::<(), envelope::MeshError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    soup: TriangleSoup,
    attributes: Attributes,
}

impl Mesh {
    /// A mesh from positions and triangles, refused when a coordinate is not finite or a
    /// triangle names a vertex that does not exist.
    ///
    /// # Errors
    /// A [`MeshError`] naming the first offending vertex or triangle (indices from 0).
    pub fn new(positions: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Result<Mesh, MeshError> {
        if let Some(v) = positions
            .iter()
            .position(|p| p.iter().any(|c| !c.is_finite()))
        {
            return Err(MeshError::NonFiniteCoordinate {
                vertex: v,
                position: positions[v],
            });
        }
        let n = positions.len();
        if let Some(f) = triangles
            .iter()
            .position(|t| t.iter().any(|&i| i as usize >= n))
        {
            return Err(MeshError::IndexOutOfRange {
                triangle: f,
                corners: triangles[f],
                vertices: n,
            });
        }
        Ok(Mesh::from_soup(TriangleSoup::new(
            positions.into_iter().map(DVec3::from_array).collect(),
            triangles.into_iter().map(|t| t.map(VertexId)).collect(),
        )))
    }

    /// The built-in model of `envelope demo`: a cup with a curved fluted wall, a sharp bottom
    /// crease and an open rim.
    #[must_use]
    pub fn demo() -> Mesh {
        Mesh::from_soup(generate::demo_model())
    }

    /// Vertices.
    #[must_use]
    pub fn num_vertices(&self) -> usize {
        self.soup.num_vertices()
    }

    /// Triangles.
    #[must_use]
    pub fn num_faces(&self) -> usize {
        self.soup.num_faces()
    }

    /// The vertex positions, in index order.
    pub fn positions(&self) -> impl ExactSizeIterator<Item = [f64; 3]> + '_ {
        self.soup.positions.iter().map(|p| p.to_array())
    }

    /// The triangles, in order.
    pub fn triangles(&self) -> impl ExactSizeIterator<Item = [u32; 3]> + '_ {
        self.soup.faces.iter().map(|f| f.map(|v| v.0))
    }

    /// The length of the bounding box's diagonal (0 for an empty mesh): what relative
    /// epsilons are fractions of.
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        self.soup.diagonal()
    }

    /// The engine's representation, for the crates under `envelope::advanced`.
    #[must_use]
    pub fn soup(&self) -> &TriangleSoup {
        &self.soup
    }

    /// A mesh from the engine's representation (no validation: [`Mesh::new`] validates).
    #[must_use]
    pub fn from_soup(soup: TriangleSoup) -> Mesh {
        Mesh {
            soup,
            attributes: Attributes::default(),
        }
    }

    /// A mesh from a soup and attributes made for it (no validation: the carrying code makes
    /// one corner triple per face with indices in range).
    pub(crate) fn from_parts(soup: TriangleSoup, attributes: Attributes) -> Mesh {
        debug_assert!(attributes.is_valid_for(soup.num_faces()));
        Mesh { soup, attributes }
    }

    /// The per-corner attributes (all absent for a mesh made from positions alone).
    #[must_use]
    pub fn attributes(&self) -> &Attributes {
        &self.attributes
    }

    /// This mesh with `attributes`, refused unless each present attribute has a corner list
    /// per triangle, every index in range and every value finite.
    ///
    /// # Errors
    /// [`MeshError::InvalidAttributes`].
    pub fn with_attributes(mut self, attributes: Attributes) -> Result<Mesh, MeshError> {
        if !attributes.is_valid_for(self.num_faces()) {
            return Err(MeshError::InvalidAttributes {
                triangles: self.num_faces(),
            });
        }
        self.attributes = attributes;
        Ok(self)
    }

    /// The engine's representation (the attributes are dropped).
    #[must_use]
    pub fn into_soup(self) -> TriangleSoup {
        self.soup
    }

    /// The engine's representation and the attributes.
    #[must_use]
    pub fn into_parts(self) -> (TriangleSoup, Attributes) {
        (self.soup, self.attributes)
    }
}

/// Why [`Mesh::new`] refused its arrays.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a coordinate that is not finite: {position:?}")]
    NonFiniteCoordinate {
        /// The vertex (from 0).
        vertex: usize,
        /// Its position.
        position: [f64; 3],
    },
    /// A triangle names a vertex that does not exist.
    #[error(
        "triangle {triangle} {corners:?} names a vertex beyond the last one ({vertices} vertices)"
    )]
    IndexOutOfRange {
        /// The triangle (from 0).
        triangle: usize,
        /// Its corners.
        corners: [u32; 3],
        /// Vertices in the mesh.
        vertices: usize,
    },
    /// An attribute's corner lists do not match the triangles, name a missing value, or a
    /// value is not finite.
    #[error(
        "the attributes do not fit the mesh: each needs one corner triple per triangle \
         ({triangles}), indices below its value count and finite values"
    )]
    InvalidAttributes {
        /// Triangles in the mesh.
        triangles: usize,
    },
}
