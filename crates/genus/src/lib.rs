//! Controlled simplification of genus (El-Sana and Varshney 1997): L-infinity alpha-prisms,
//! alpha-neighbourhoods, tessellation chains and the triangulation of tessellation regions.
//!
//! * [`AlphaPrism`] (sections 3.1, 4.1): the Minkowski sum of a triangle and an axis-aligned
//!   cube of side `2 alpha`, built with the paper's 6-bit vector scheme; f64 corners (rounded
//!   outward), exact decisions.
//! * [`alpha_close_pairs`] (4.2): pairs of triangles whose prisms meet, from a uniform grid
//!   of cell side `2 alpha`, decided exactly.
//! * [`reduce_genus`] (3.2-3.4): tessellation edges (sharp edges, border edges), chains,
//!   caps over the rims a cube of side `2 alpha` cannot pass, removal of the triangles that
//!   became interior, validation. Every added triangle has input vertices and lies in the
//!   union of the alpha-cubes of its corners, hence in the union of alpha-prisms.
//! * [`reduce_genus_with`] with [`TessellationSource::PrismUnion`] (3.3, 4, the paper's
//!   option "from the full union of alpha-prisms"): also the rims of the regions swallowed
//!   by the union of prisms (faces whose prism meets the prism of a face facing them across
//!   empty space and far away on the surface; see [`union`]), so smooth narrow tunnels fill.
//! * [`reduce_genus_with`] with [`TessellationSource::Closing`] (issue 37): after the sharp
//!   rims, the regions the L-infinity closing by the cube swallows (estimated on voxels,
//!   `closing`) replaced by caps over their loops, peeled back where a loop cannot be capped
//!   (`fill`); every cap through the same exact test and validation.
//!
//! Where the paper is open or garbled, the module docs say which reading we chose
//! ([`prism`] for the hull, `tessellation` and `reduce` for regions and acceptance; the
//! crate README collects them).
//!
//! ```
//! use envelope_genus::{reduce_genus, GenusOptions};
//! use envelope_mesh::generate;
//! let (out, report) = reduce_genus(&generate::box_with_tunnel(), &GenusOptions::new(0.75)).unwrap();
//! assert_eq!((report.genus_in, report.genus_out), (Some(1), Some(0)));
//! assert!(out.num_faces() > 0);
//! ```
#![forbid(unsafe_code)]

mod closing;
mod exact;
mod fill;
mod neighbourhood;
pub mod prism;
mod reduce;
mod rim;
mod steiner;
mod tessellation;
pub mod testmeshes;
mod triangulate;
pub mod union;
mod validation;

use envelope_check::DegeneracyClass;
use envelope_mesh::{FaceId, VertexId};

pub use neighbourhood::alpha_close_pairs;
pub use prism::{AlphaPrism, PointLocation};
pub use reduce::{GenusOptions, GenusReport, reduce_genus, reduce_genus_with};
pub use union::TessellationSource;

/// Why the genus reduction refused its input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GenusError {
    /// `alpha` must be finite and positive.
    #[error("alpha must be a positive finite length, got {0}")]
    InvalidAlpha(f64),
    /// `beta` must be strictly between 0 and 180 degrees.
    #[error("beta must be strictly between 0 and 180 degrees, got {0}")]
    InvalidBeta(f64),
    /// A NaN or infinite coordinate (the vertex, when known).
    #[error("non-finite coordinate{}", .vertex.map_or_else(String::new, |v| format!(" at vertex {}", v.0)))]
    NonFiniteCoordinate {
        /// The vertex.
        vertex: Option<VertexId>,
    },
    /// A face names a vertex that does not exist.
    #[error("face {} has a vertex index out of range", .face.0)]
    IndexOutOfRange {
        /// The face.
        face: FaceId,
    },
    /// The input has a degeneracy the method does not handle (the paper's section 6:
    /// coincident polygons, self-intersections, inconsistent orientation; also non-manifold
    /// edges and duplicate faces).
    #[error("the input has {count} {} (first: {example}); the genus reduction needs a mesh without them", .class.key())]
    Unacceptable {
        /// The degeneracy class.
        class: DegeneracyClass,
        /// How many elements of it.
        count: usize,
        /// The first one, described.
        example: String,
    },
}

/// Specialised pieces, public for tests, fuzzing and benches.
pub mod details {
    pub use crate::exact::{covered_by_corner_cubes, linf_close};
    pub use crate::prism::{cube_corners, vertex_bits};
    pub use crate::steiner::POINT_ERROR;
    pub use crate::tessellation::{
        Chain, EdgeMap, PatchLoop, Patches, face_normals, link_chains, normal_variation, patches,
        tessellation_edges,
    };
    pub use crate::triangulate::triangulate_loop;

    use envelope_predicates::{Exact, Kernel, Orientation};
    use glam::DVec3;
    use std::collections::BTreeSet;

    /// A general exact 3-D convex hull for checking [`crate::AlphaPrism`]: every plane through
    /// three non-collinear points with all points on one closed side (orient3d on the rational
    /// kernel), identified by the set of points exactly on it. O(n^4); meant for the 24
    /// corners of a prism. Returns the facets' point sets (indices into `points`), sorted.
    ///
    /// ```
    /// use envelope_genus::details::exact_hull_facets;
    /// use glam::DVec3;
    /// let cube: Vec<DVec3> = (0..8)
    ///     .map(|k| DVec3::new((k & 1) as f64, (k >> 1 & 1) as f64, (k >> 2 & 1) as f64))
    ///     .collect();
    /// assert_eq!(exact_hull_facets(&cube).len(), 6);
    /// ```
    #[must_use]
    pub fn exact_hull_facets(points: &[DVec3]) -> Vec<Vec<usize>> {
        let n = points.len();
        let mut facets: BTreeSet<Vec<usize>> = BTreeSet::new();
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    let (a, b, c) = (points[i], points[j], points[k]);
                    if a == b || b == c || a == c {
                        continue;
                    }
                    let mut on = Vec::new();
                    let (mut pos, mut neg) = (false, false);
                    for (m, &p) in points.iter().enumerate() {
                        match Exact::orient3d(a, b, c, p) {
                            Orientation::Positive => pos = true,
                            Orientation::Negative => neg = true,
                            Orientation::Degenerate => on.push(m),
                        }
                    }
                    // Collinear a, b, c put every point "on" the degenerate plane.
                    if on.len() == n || (pos && neg) {
                        continue;
                    }
                    facets.insert(on);
                }
            }
        }
        facets.into_iter().collect()
    }
}
