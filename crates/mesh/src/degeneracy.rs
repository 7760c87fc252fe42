//! Combinatorial degeneracy finders: each returns the offending elements, so a checker can
//! name them. Geometric degeneracies (zero-area faces, intersections) are `envelope-check`'s.
//!
//! Faces with an out-of-range or repeated index are skipped by every finder except
//! [`degenerate_faces`] and [`unreferenced_vertices`], as in [`crate::analyze`]. All run in
//! O(n log n) or expected O(n).
//!
//! ```
//! use envelope_mesh::{degeneracy, generate, VertexId};
//! let bow_tie = generate::bow_tie();
//! assert_eq!(degeneracy::non_manifold_vertices(&bow_tie), vec![VertexId(0)]);
//! assert!(degeneracy::non_manifold_edges(&bow_tie).is_empty());
//! ```

use crate::analysis::{EdgeTable, corner_fans, fan_counts, slot_ends, valid_faces};
use crate::{FaceId, TriangleSoup, VertexId};

/// An edge with more than two incident faces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NonManifoldEdge {
    /// Its endpoints, smaller id first.
    pub vertices: [VertexId; 2],
    /// Its incident faces, increasing.
    pub faces: Vec<FaceId>,
}

/// Two faces traversing an edge in the same direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OrientationConflict {
    /// The edge, directed as both faces run it.
    pub edge: [VertexId; 2],
    /// The two faces, smaller id first.
    pub faces: [FaceId; 2],
}

/// What [`non_manifold_vertices`], [`non_manifold_edges`] and [`inconsistent_orientations`]
/// find, from one edge table (each of them builds its own).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct EdgeFindings {
    /// [`non_manifold_vertices`].
    pub non_manifold_vertices: Vec<VertexId>,
    /// [`non_manifold_edges`].
    pub non_manifold_edges: Vec<NonManifoldEdge>,
    /// [`inconsistent_orientations`].
    pub inconsistent_orientations: Vec<OrientationConflict>,
}

/// [`non_manifold_vertices`], [`non_manifold_edges`] and [`inconsistent_orientations`] at
/// once: the same answers for one edge table instead of three.
///
/// ```
/// use envelope_mesh::{degeneracy, generate};
/// let bow_tie = generate::bow_tie();
/// let all = degeneracy::edge_findings(&bow_tie);
/// assert_eq!(all.non_manifold_vertices, degeneracy::non_manifold_vertices(&bow_tie));
/// assert_eq!(all.non_manifold_edges, degeneracy::non_manifold_edges(&bow_tie));
/// ```
#[must_use]
pub fn edge_findings(soup: &TriangleSoup) -> EdgeFindings {
    let valid = valid_faces(soup);
    let table = EdgeTable::build(soup, &valid);
    EdgeFindings {
        non_manifold_vertices: non_manifold_vertices_of(soup, &valid, &table),
        non_manifold_edges: non_manifold_edges_of(&table),
        inconsistent_orientations: inconsistent_orientations_of(soup, &table),
    }
}

/// Edges with three or more incident faces, in `(min, max)` order.
///
/// ```
/// use envelope_mesh::{degeneracy, generate};
/// let e = degeneracy::non_manifold_edges(&generate::three_triangles_on_edge());
/// assert_eq!(e.len(), 1);
/// assert_eq!(e[0].faces.len(), 3);
/// ```
#[must_use]
pub fn non_manifold_edges(soup: &TriangleSoup) -> Vec<NonManifoldEdge> {
    non_manifold_edges_of(&EdgeTable::build(soup, &valid_faces(soup)))
}

fn non_manifold_edges_of(table: &EdgeTable) -> Vec<NonManifoldEdge> {
    (0..table.num_edges())
        .filter(|&e| table.edge_slots(e).len() > 2)
        .map(|e| NonManifoldEdge {
            vertices: table.ends[e].map(VertexId),
            faces: table.edge_slots(e).iter().map(|&s| FaceId(s / 3)).collect(),
        })
        .collect()
}

/// Vertices whose incident faces form more than one fan (see [`crate::analyze`]'s module docs:
/// fans are joined only through edges with exactly two faces, so both endpoints of every
/// non-manifold edge are reported too), increasing.
#[must_use]
pub fn non_manifold_vertices(soup: &TriangleSoup) -> Vec<VertexId> {
    let valid = valid_faces(soup);
    non_manifold_vertices_of(soup, &valid, &EdgeTable::build(soup, &valid))
}

fn non_manifold_vertices_of(
    soup: &TriangleSoup,
    valid: &[bool],
    table: &EdgeTable,
) -> Vec<VertexId> {
    let fans = corner_fans(soup, table);
    fan_counts(soup, valid, &fans)
        .iter()
        .enumerate()
        .filter(|&(_, &n)| n > 1)
        .map(|(v, _)| VertexId::from_index(v))
        .collect()
}

/// Pairs of faces with the same vertex set (any order or orientation): each face is paired
/// with the smallest face of its group, `[first, other]`, sorted.
///
/// ```
/// use envelope_mesh::{degeneracy, FaceId, TriangleSoup};
/// let s = TriangleSoup::from_raw(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2], [2, 1, 0]]);
/// assert_eq!(degeneracy::duplicate_faces(&s), vec![[FaceId(0), FaceId(1)]]);
/// ```
#[must_use]
pub fn duplicate_faces(soup: &TriangleSoup) -> Vec<[FaceId; 2]> {
    let valid = valid_faces(soup);
    let mut keys: Vec<([u32; 3], u32)> = soup
        .faces
        .iter()
        .enumerate()
        .filter(|&(f, _)| valid[f])
        .map(|(f, t)| {
            let mut k = t.map(|v| v.0);
            k.sort_unstable();
            (k, f as u32)
        })
        .collect();
    keys.sort_unstable();
    let mut out = Vec::new();
    for group in keys.chunk_by(|a, b| a.0 == b.0) {
        for g in &group[1..] {
            out.push([FaceId(group[0].1), FaceId(g.1)]);
        }
    }
    out.sort_unstable();
    out
}

/// Faces with a repeated vertex index (`[a, a, b]`, `[a, a, a]`), increasing.
#[must_use]
pub fn degenerate_faces(soup: &TriangleSoup) -> Vec<FaceId> {
    soup.face_ids()
        .filter(|&f| {
            let [a, b, c] = soup.faces[f.index()];
            a == b || b == c || a == c
        })
        .collect()
}

/// Vertices named by no face (excluded faces count as naming their in-range indices),
/// increasing.
#[must_use]
pub fn unreferenced_vertices(soup: &TriangleSoup) -> Vec<VertexId> {
    let mut named = vec![false; soup.positions.len()];
    for v in soup.faces.iter().flatten() {
        if let Some(n) = named.get_mut(v.index()) {
            *n = true;
        }
    }
    (0..named.len())
        .filter(|&v| !named[v])
        .map(VertexId::from_index)
        .collect()
}

/// Groups (two or more, increasing ids; groups ordered by first id) of vertices with
/// bitwise-equal positions, `-0.0` counting as `0.0`.
///
/// ```
/// use envelope_mesh::{degeneracy, TriangleSoup, VertexId};
/// let s = TriangleSoup::from_raw(&[[0.0, 1.0, 2.0], [5.0; 3], [-0.0, 1.0, 2.0]], &[]);
/// assert_eq!(degeneracy::duplicate_vertices(&s), vec![vec![VertexId(0), VertexId(2)]]);
/// ```
#[must_use]
pub fn duplicate_vertices(soup: &TriangleSoup) -> Vec<Vec<VertexId>> {
    // `x + 0.0` maps -0.0 to +0.0 and leaves every other value (NaN payloads aside) unchanged.
    let key = |v: u32| {
        soup.positions[v as usize]
            .to_array()
            .map(|x| (x + 0.0).to_bits())
    };
    let mut ids: Vec<u32> = (0..soup.positions.len() as u32).collect();
    ids.sort_unstable_by_key(|&v| (key(v), v));
    let mut out: Vec<Vec<VertexId>> = ids
        .chunk_by(|&a, &b| key(a) == key(b))
        .filter(|g| g.len() > 1)
        .map(|g| g.iter().map(|&v| VertexId(v)).collect())
        .collect();
    out.sort_unstable();
    out
}

/// Edges traversed in the same direction by two faces. On an edge with several faces, each
/// face is paired with the first (smallest) face running the edge its way; sorted.
///
/// ```
/// use envelope_mesh::{degeneracy, FaceId, TriangleSoup, VertexId};
/// let s = TriangleSoup::from_raw(
///     &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]],
///     &[[0, 1, 2], [0, 1, 3]],
/// );
/// let c = degeneracy::inconsistent_orientations(&s);
/// assert_eq!(c[0].faces, [FaceId(0), FaceId(1)]);
/// assert_eq!(c[0].edge, [VertexId(0), VertexId(1)]);
/// ```
#[must_use]
pub fn inconsistent_orientations(soup: &TriangleSoup) -> Vec<OrientationConflict> {
    inconsistent_orientations_of(soup, &EdgeTable::build(soup, &valid_faces(soup)))
}

fn inconsistent_orientations_of(
    soup: &TriangleSoup,
    table: &EdgeTable,
) -> Vec<OrientationConflict> {
    let mut out = Vec::new();
    for e in 0..table.num_edges() {
        let sl = table.edge_slots(e);
        if sl.len() < 2 {
            continue;
        }
        let mut first = [None, None];
        for &s in sl {
            let (a, b) = slot_ends(&soup.faces, s);
            let dir = usize::from(a > b);
            match first[dir] {
                None => first[dir] = Some(s / 3),
                Some(f) => out.push(OrientationConflict {
                    edge: [VertexId(a), VertexId(b)],
                    faces: [FaceId(f), FaceId(s / 3)],
                }),
            }
        }
    }
    out.sort_unstable_by_key(|c| (c.faces, c.edge));
    out
}
