//! Input checking, as in section 7.1 of *Simplification Envelopes* (Cohen et al. 1996).
//!
//! The paper accepts only manifold triangle meshes (or bordered manifolds) and rejects
//! "other forms of degenerate meshes": it names non-manifold vertices, non-manifold edges,
//! sliver triangles, coincident triangles, T-junctions and intersecting triangles. [`check`]
//! detects those and a few more classes, names every offending element, and says which
//! classes make a mesh unacceptable input ([`Severity::Error`]) and which are only worth
//! knowing ([`Severity::Warning`]).
//!
//! Every class that the envelope guarantee depends on is decided by the exact predicates of
//! `envelope-predicates` (zero area = exactly collinear corners; T-junction = a vertex exactly
//! in the open interior of an edge; coincident = coplanar overlap with positive area;
//! intersection = closed triangles meeting away from what they share). The one heuristic class
//! is [`DegeneracyClass::SliverTriangles`]: a shape-quality threshold computed in f64, reported
//! as a warning because no guarantee rests on it.
//!
//! Time and memory stay linear in the input: when the faces' boxes overlap in more pairs than
//! `envelope_predicates::bvh::pair_budget` allows (a stack of coincident faces has
//! quadratically many), the pairwise classes and the T-junction search are not run but marked
//! [`Finding::undecided`], which makes the mesh unacceptable: never a wrong "acceptable".
//!
//! The T-junction search is skipped when the pairwise test ran and found no intersecting
//! pair, no face has zero area and every corner is finite: a T-junction makes one of the two
//! (the faces at the vertex meet the edge's face away from what they share unless one of
//! them is degenerate).
//!
//! ```
//! use envelope_check::{check, CheckOptions, DegeneracyClass};
//! use envelope_mesh::generate;
//! let report = check(&generate::torus(1.0, 0.3, 24, 12), &CheckOptions::default());
//! assert!(report.acceptable());
//! assert_eq!(report.genus, Some(1));
//! assert_eq!(report.finding(DegeneracyClass::IntersectingTriangles).count, 0);
//! ```
#![forbid(unsafe_code)]

mod classes;
mod geometric;
mod json;

use std::collections::BTreeMap;

use envelope_mesh::{FaceId, Topology, TriangleSoup, VertexId, analyze, degeneracy};
use envelope_predicates::bvh::Bvh;
use glam::DVec3;

pub use classes::{DegeneracyClass, Severity};

/// What [`check`] looks for and how much it reports.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckOptions {
    /// How many offending elements to keep per class (the count is always complete).
    pub max_examples: usize,
    /// A triangle of non-zero area whose shape quality `4 sqrt(3) area / (sum of squared edge
    /// lengths)` (1 for equilateral, 0 for degenerate) is below this is a sliver.
    pub sliver_quality: f64,
    /// Run the exact pairwise tests (intersecting and coincident triangles).
    pub pairwise: bool,
}

impl Default for CheckOptions {
    fn default() -> Self {
        Self {
            max_examples: 5,
            sliver_quality: 1e-3,
            pairwise: true,
        }
    }
}

/// One offending element (or group of elements), as a finding names it.
#[derive(Clone, Debug, PartialEq)]
pub enum Element {
    /// A vertex.
    Vertex {
        /// Its id.
        vertex: VertexId,
        /// Its position.
        position: DVec3,
    },
    /// Vertices at the same position.
    VertexGroup {
        /// Their ids, increasing.
        vertices: Vec<VertexId>,
        /// The shared position.
        position: DVec3,
    },
    /// A triangle.
    Face {
        /// Its id.
        face: FaceId,
        /// Its corners.
        vertices: [VertexId; 3],
        /// Its shape quality, for slivers.
        quality: Option<f64>,
    },
    /// Two triangles.
    FacePair {
        /// Smaller id first.
        faces: [FaceId; 2],
    },
    /// An edge and its faces (non-manifold edges, orientation conflicts).
    Edge {
        /// Its endpoints.
        edge: [VertexId; 2],
        /// The faces involved.
        faces: Vec<FaceId>,
    },
    /// A vertex lying in the open interior of an edge it is not an endpoint of.
    VertexOnEdge {
        /// The vertex.
        vertex: VertexId,
        /// Its position.
        position: DVec3,
        /// The edge.
        edge: [VertexId; 2],
    },
}

/// Every offending element of one class: the full count and the first few.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Finding {
    /// How many elements (or pairs, or groups) of the class the mesh has.
    pub count: usize,
    /// The first [`CheckOptions::max_examples`] of them, in a deterministic order.
    pub examples: Vec<Element>,
    /// The class could not be decided within the checker's budget (the pairwise classes on
    /// faces stacked so densely that testing every pair would take quadratic time): `count`
    /// is then 0 and means nothing, and an undecided error class makes the mesh unacceptable.
    pub undecided: bool,
}

impl Finding {
    fn from_iter(items: impl IntoIterator<Item = Element>, max_examples: usize) -> Self {
        let mut finding = Finding::default();
        for item in items {
            if finding.examples.len() < max_examples {
                finding.examples.push(item);
            }
            finding.count += 1;
        }
        finding
    }
}

/// The result of [`check`]: counts, topology and every degeneracy class.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckReport {
    /// Vertex slots, referenced or not.
    pub vertices: usize,
    /// Triangles.
    pub faces: usize,
    /// Undirected edges.
    pub edges: usize,
    /// Border loops (closed cycles and open chains).
    pub border_loops: usize,
    /// Edge-connected components.
    pub components: usize,
    /// Euler characteristic, summed over components (unreferenced vertices excluded).
    pub euler: i64,
    /// Genus summed over components; `None` when some component is non-manifold or
    /// non-orientable.
    pub genus: Option<u32>,
    /// No non-manifold edge or vertex.
    pub manifold: bool,
    /// Every component orientable.
    pub orientable: bool,
    /// Every class, in [`DegeneracyClass::ALL`] order (classes not run are absent).
    pub degeneracies: BTreeMap<DegeneracyClass, Finding>,
}

impl CheckReport {
    /// The finding for one class (empty when the class was not run).
    #[must_use]
    pub fn finding(&self, class: DegeneracyClass) -> Finding {
        self.degeneracies.get(&class).cloned().unwrap_or_default()
    }

    /// Classes of [`Severity::Error`] with at least one element, or undecided.
    pub fn errors(&self) -> impl Iterator<Item = DegeneracyClass> + '_ {
        self.degeneracies
            .iter()
            .filter(|(c, f)| c.severity() == Severity::Error && (f.count > 0 || f.undecided))
            .map(|(c, _)| *c)
    }

    /// Whether the mesh is acceptable input for the simplifiers: no error-class finding.
    #[must_use]
    pub fn acceptable(&self) -> bool {
        self.errors().next().is_none()
    }

    /// The report as one JSON object with stable field names (see the `json` module docs:
    /// `vertices`, `faces`, `edges`, `border_loops`, `components`, `euler`, `genus`,
    /// `manifold`, `orientable`, `acceptable`, `degeneracies`).
    #[must_use]
    pub fn to_json(&self) -> serde_json::Value {
        json::value(self)
    }
}

/// Checks a triangle soup: topology counts and every degeneracy class.
///
/// Runs in O(n log n) plus the exact tests on candidate pairs from a bounding-volume
/// hierarchy. Faces with a repeated index are reported as zero-area triangles and ignored by
/// the topology counts (see `envelope_mesh::analyze`).
#[must_use]
pub fn check(soup: &TriangleSoup, options: &CheckOptions) -> CheckReport {
    check_with_topology(soup, options).0
}

/// [`check`], and the soup's topology it computed on the way (`envelope_mesh::analyze`), for
/// a caller that needs both (the simplify driver: border walls and its report).
///
/// ```
/// use envelope_check::{check_with_topology, CheckOptions};
/// use envelope_mesh::generate;
/// let (report, topology) = check_with_topology(&generate::icosphere(1, 1.0), &CheckOptions::default());
/// assert!(report.acceptable());
/// assert_eq!(topology.genus, Some(0));
/// ```
#[must_use]
pub fn check_with_topology(soup: &TriangleSoup, options: &CheckOptions) -> (CheckReport, Topology) {
    let topology = analyze(soup);
    (check_with_shared(soup, options, &topology, None), topology)
}

/// [`check`] with what a caller computed already and shares with other work on the same
/// soup (the simplify driver gives both to the envelopes too): `topology` must be
/// `envelope_mesh::analyze(soup)`, and `face_tree`, when given,
/// `Bvh::from_triangles(&soup.positions, faces)` over all of the soup's faces in order
/// (`[u32; 3]`). The tree serves the pairwise test when every face is usable (finite,
/// in-range corners; else a tree over the usable ones is built); a tree of another length
/// is ignored.
///
/// ```
/// use envelope_check::{check, check_with_shared, CheckOptions};
/// use envelope_mesh::{analyze, generate};
/// use envelope_predicates::bvh::Bvh;
/// let soup = generate::icosphere(1, 1.0);
/// let faces: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
/// let tree = Bvh::from_triangles(&soup.positions, &faces);
/// let options = CheckOptions::default();
/// let shared = check_with_shared(&soup, &options, &analyze(&soup), Some(&tree));
/// assert_eq!(shared, check(&soup, &options));
/// ```
#[must_use]
pub fn check_with_shared(
    soup: &TriangleSoup,
    options: &CheckOptions,
    topology: &Topology,
    face_tree: Option<&Bvh>,
) -> CheckReport {
    use DegeneracyClass as C;
    let n = options.max_examples;
    let vertex = |v: VertexId| Element::Vertex {
        vertex: v,
        position: soup.position(v),
    };
    let face = |f: FaceId| Element::Face {
        face: f,
        vertices: soup.faces[f.index()],
        quality: None,
    };
    let referenced = referenced_vertices(soup);
    let edges = degeneracy::edge_findings(soup);

    let mut d = BTreeMap::new();
    d.insert(
        C::NonManifoldVertices,
        Finding::from_iter(edges.non_manifold_vertices.into_iter().map(vertex), n),
    );
    d.insert(
        C::NonManifoldEdges,
        Finding::from_iter(
            edges.non_manifold_edges.into_iter().map(|e| Element::Edge {
                edge: e.vertices,
                faces: e.faces,
            }),
            n,
        ),
    );
    let zero_area = geometric::zero_area_faces(soup);
    d.insert(
        C::ZeroAreaTriangles,
        Finding::from_iter(zero_area.iter().map(|&f| face(f)), n),
    );
    d.insert(
        C::SliverTriangles,
        Finding::from_iter(
            geometric::slivers(soup, &zero_area, options.sliver_quality)
                .into_iter()
                .map(|(f, q)| Element::Face {
                    face: f,
                    vertices: soup.faces[f.index()],
                    quality: Some(q),
                }),
            n,
        ),
    );
    d.insert(
        C::DuplicateTriangles,
        Finding::from_iter(
            degeneracy::duplicate_faces(soup)
                .into_iter()
                .map(|faces| Element::FacePair { faces }),
            n,
        ),
    );
    d.insert(
        C::UnreferencedVertices,
        Finding::from_iter(topology.unreferenced_vertices.iter().map(|&v| vertex(v)), n),
    );
    d.insert(
        C::DuplicateVertices,
        Finding::from_iter(
            degeneracy::duplicate_vertices(soup)
                .into_iter()
                .map(|g| {
                    g.into_iter()
                        .filter(|v| referenced[v.index()])
                        .collect::<Vec<_>>()
                })
                .filter(|g| g.len() > 1)
                .map(|g| Element::VertexGroup {
                    position: soup.position(g[0]),
                    vertices: g,
                }),
            n,
        ),
    );
    d.insert(
        C::InconsistentOrientation,
        Finding::from_iter(
            edges
                .inconsistent_orientations
                .into_iter()
                .map(|c| Element::Edge {
                    edge: c.edge,
                    faces: c.faces.to_vec(),
                }),
            n,
        ),
    );
    let pairs = options
        .pairwise
        .then(|| geometric::PairwiseFindings::compute(soup, face_tree));
    // A T-junction (a vertex strictly inside an edge it is not on) makes a zero-area face or
    // an intersecting pair: the vertex's faces meet the edge's face away from what they
    // share, unless one of the two is degenerate. So with every face usable (finite
    // corners) and neither class found, there is none to look for.
    let no_t_junction = pairs.as_ref().is_some_and(|p| p.intersecting.is_empty())
        && zero_area.is_empty()
        && soup.faces.iter().all(|&f| geometric::usable(soup, f));
    // Undecided pairwise classes already make the mesh unacceptable; the T-junction search
    // would walk the same dense stack.
    let t_junctions_undecided = pairs.as_ref().is_some_and(|p| p.undecided);
    let t_junctions = if no_t_junction || t_junctions_undecided {
        Vec::new()
    } else {
        geometric::t_junctions(soup, &referenced)
    };
    d.insert(
        C::TJunctions,
        Finding {
            undecided: t_junctions_undecided,
            ..Finding::from_iter(
                t_junctions
                    .into_iter()
                    .map(|(v, edge)| Element::VertexOnEdge {
                        vertex: v,
                        position: soup.position(v),
                        edge,
                    }),
                n,
            )
        },
    );
    if let Some(pairs) = pairs {
        let pair = |(a, b): (u32, u32)| Element::FacePair {
            faces: [FaceId(a), FaceId(b)],
        };
        let undecided = pairs.undecided;
        for (class, list) in [
            (C::CoincidentTriangles, pairs.coincident),
            (C::IntersectingTriangles, pairs.intersecting),
        ] {
            d.insert(
                class,
                Finding {
                    undecided,
                    ..Finding::from_iter(list.into_iter().map(pair), n)
                },
            );
        }
    }

    CheckReport {
        vertices: topology.num_vertices,
        faces: topology.num_faces,
        edges: topology.num_edges,
        border_loops: topology.num_border_loops(),
        components: topology.components.len(),
        euler: topology.euler,
        genus: topology.genus,
        manifold: topology.manifold,
        orientable: topology.orientable,
        degeneracies: d,
    }
}

/// `referenced[v]`: some face names `v` (faces with out-of-range indices are skipped).
fn referenced_vertices(soup: &TriangleSoup) -> Vec<bool> {
    let mut referenced = vec![false; soup.num_vertices()];
    for v in soup.faces.iter().flatten() {
        if let Some(r) = referenced.get_mut(v.index()) {
            *r = true;
        }
    }
    referenced
}

#[cfg(test)]
mod tests;

/// Every pair of faces of `soup` that meet away from what they share (the pairs behind
/// [`DegeneracyClass::IntersectingTriangles`], coincident and T-junction pairs among them),
/// `(i, j)` with `i < j`, sorted; `None` when the faces' boxes overlap in more pairs than the
/// checker's budget allows (the class is then undecided). Exact. `face_tree`: as in
/// [`check_with_shared`].
///
/// ```
/// use envelope_check::intersecting_pairs;
/// use envelope_mesh::{FaceId, TriangleSoup};
/// let crossing = TriangleSoup::from_raw(
///     &[[0., 0., 0.], [2., 0., 0.], [0., 2., 0.], [0.5, 0.5, -1.], [0.5, 0.5, 1.], [1.5, 1.5, 0.]],
///     &[[0, 1, 2], [3, 4, 5]],
/// );
/// assert_eq!(intersecting_pairs(&crossing, None), Some(vec![(FaceId(0), FaceId(1))]));
/// ```
#[must_use]
pub fn intersecting_pairs(
    soup: &TriangleSoup,
    face_tree: Option<&Bvh>,
) -> Option<Vec<(FaceId, FaceId)>> {
    let found = geometric::PairwiseFindings::compute(soup, face_tree);
    (!found.undecided).then(|| {
        let mut pairs: Vec<(FaceId, FaceId)> = found
            .intersecting
            .into_iter()
            .map(|(i, j)| (FaceId(i.min(j)), FaceId(i.max(j))))
            .collect();
        pairs.sort_unstable();
        pairs
    })
}
