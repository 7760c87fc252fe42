//! The geometric classes: each decision through the exact predicates, except slivers.

use envelope_mesh::{FaceId, TriangleSoup, VertexId};
use envelope_predicates::bvh::{Aabb, Bvh};
use envelope_predicates::{
    PreparedFace, collinear, point_strictly_inside_segment, prepared_faces_intersect,
    triangles_overlap_with_area,
};
use glam::DVec3;

/// Faces the geometric tests can look at: indices in range and distinct positions finite.
/// (Readers guarantee both; a hand-built soup may not, and must not make the checker panic.)
pub(crate) fn usable(soup: &TriangleSoup, f: [VertexId; 3]) -> bool {
    f.iter()
        .all(|v| soup.positions.get(v.index()).is_some_and(|p| p.is_finite()))
}

/// Faces with a repeated index or exactly collinear corners, increasing.
pub(crate) fn zero_area_faces(soup: &TriangleSoup) -> Vec<FaceId> {
    soup.face_ids()
        .filter(|&f| {
            let [a, b, c] = soup.faces[f.index()];
            if a == b || b == c || a == c {
                return true;
            }
            usable(soup, [a, b, c]) && {
                let [p, q, r] = soup.triangle(f);
                collinear(p, q, r)
            }
        })
        .collect()
}

/// Shape quality `4 sqrt(3) area / (|e0|^2 + |e1|^2 + |e2|^2)`: 1 for an equilateral
/// triangle, towards 0 for needles and caps. Plain f64: it only grades, it decides nothing the
/// guarantee rests on.
pub(crate) fn quality(t: [DVec3; 3]) -> f64 {
    let [a, b, c] = t;
    let area2 = (b - a).cross(c - a).length(); // twice the area
    let sum = (b - a).length_squared() + (c - b).length_squared() + (a - c).length_squared();
    if sum == 0.0 {
        0.0
    } else {
        2.0 * 3f64.sqrt() * area2 / sum
    }
}

/// Faces of non-zero area with quality below `threshold`, with their quality.
pub(crate) fn slivers(
    soup: &TriangleSoup,
    zero_area: &[FaceId],
    threshold: f64,
) -> Vec<(FaceId, f64)> {
    soup.face_ids()
        .filter(|f| zero_area.binary_search(f).is_err() && usable(soup, soup.faces[f.index()]))
        .map(|f| (f, quality(soup.triangle(f))))
        .filter(|&(_, q)| q < threshold)
        .collect()
}

/// `(vertex, edge)` for every referenced vertex lying exactly in the open interior of an edge
/// it is not an endpoint of, sorted.
pub(crate) fn t_junctions(
    soup: &TriangleSoup,
    referenced: &[bool],
) -> Vec<(VertexId, [VertexId; 2])> {
    let mut edges: Vec<[VertexId; 2]> = soup
        .faces
        .iter()
        .filter(|f| usable(soup, **f))
        .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
        .filter(|[a, b]| a != b)
        .map(|[a, b]| if a < b { [a, b] } else { [b, a] })
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let boxes: Vec<Aabb> = edges
        .iter()
        .map(|e| Aabb::from_points(&e.map(|v| soup.position(v))))
        .collect();
    let tree = Bvh::new(&boxes);
    let mut out = Vec::new();
    for (i, p) in soup.positions.iter().enumerate() {
        if !referenced[i] || !p.is_finite() {
            continue;
        }
        let v = VertexId::from_index(i);
        tree.for_each_overlapping(&Aabb::from_points(&[*p]), |e| {
            let [a, b] = edges[e as usize];
            if v != a
                && v != b
                && point_strictly_inside_segment(*p, soup.position(a), soup.position(b))
            {
                out.push((v, [a, b]));
            }
        });
    }
    out.sort_unstable();
    out
}

/// The pairwise classes, from one bounding-volume hierarchy over the faces.
pub(crate) struct PairwiseFindings {
    /// Faces meeting away from what they share, `(i, j)` with `i < j`, sorted.
    pub intersecting: Vec<(u32, u32)>,
    /// Intersecting pairs that are not duplicates and overlap with positive area.
    pub coincident: Vec<(u32, u32)>,
    /// The face boxes overlap in more pairs than the budget: nothing was tested, both lists
    /// are empty and the classes undecided.
    pub undecided: bool,
}

impl PairwiseFindings {
    /// `face_tree`: see [`crate::check_with_shared`].
    pub(crate) fn compute(soup: &TriangleSoup, face_tree: Option<&Bvh>) -> Self {
        // Face ids of the usable faces, and those faces as raw indices.
        let ids: Vec<u32> = soup
            .face_ids()
            .filter(|f| usable(soup, soup.faces[f.index()]))
            .map(|f| f.0)
            .collect();
        let faces: Vec<[u32; 3]> = ids
            .iter()
            .map(|&f| soup.faces[f as usize].map(|v| v.0))
            .collect();
        // With every face usable, `faces` is all of them in order: the given tree's items.
        let built;
        let tree = match face_tree {
            Some(t) if ids.len() == soup.num_faces() && t.len() == ids.len() => t,
            _ => {
                built = Bvh::from_triangles(&soup.positions, &faces);
                &built
            }
        };
        // Above the shared budget the pairwise classes are left undecided (and the mesh
        // unacceptable): testing every pair of a dense stack would take quadratic time.
        let budget = envelope_predicates::bvh::pair_budget(faces.len());
        if tree.self_pair_count_up_to(budget) >= budget {
            return Self {
                intersecting: Vec::new(),
                coincident: Vec::new(),
                undecided: true,
            };
        }
        // Each face's plane once (a face meets about a dozen candidates), stored in the
        // tree's leaf order: the pairs come leaf by leaf, so the faces they read are then
        // near each other in memory (in a scanned mesh's own order they are not).
        let order = tree.leaf_order();
        let mut rank = vec![0u32; order.len()];
        for (k, &i) in order.iter().enumerate() {
            rank[i as usize] = k as u32;
        }
        let prepared: Vec<PreparedFace> = order
            .iter()
            .map(|&i| PreparedFace::new(&soup.positions, faces[i as usize]))
            .collect();
        let prepared_of = |i: u32| &prepared[rank[i as usize] as usize];
        let intersecting: Vec<(u32, u32)> = tree
            .self_pairs_where(|i, j| prepared_faces_intersect(prepared_of(i), prepared_of(j)))
            .into_iter()
            .map(|(i, j)| (ids[i as usize], ids[j as usize]))
            .collect();
        let same_indices = |f: FaceId, g: FaceId| {
            let mut a = soup.faces[f.index()];
            let mut b = soup.faces[g.index()];
            a.sort_unstable();
            b.sort_unstable();
            a == b
        };
        let coincident = intersecting
            .iter()
            .copied()
            .filter(|&(i, j)| {
                !same_indices(FaceId(i), FaceId(j))
                    && triangles_overlap_with_area(
                        soup.triangle(FaceId(i)),
                        soup.triangle(FaceId(j)),
                    )
            })
            .collect();
        Self {
            intersecting,
            coincident,
            undecided: false,
        }
    }
}
