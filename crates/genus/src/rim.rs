//! A rim and its cap (El-Sana and Varshney 1997, section 3.4): the candidate loop, its cap
//! and the alpha test every cap passes, whichever way the loop was found (sharp edges, the
//! union of prisms, the closing's regions).
//!
//! **Acceptance of a cap (our exact reading of "the L-infinity cube cannot pass").** Every
//! cap edge that is not a loop edge must be a diagonal in the paper's sense: a cube of side
//! `2 alpha` holds both endpoints (`|p - q|_inf <= 2 alpha`, exact). Every cap triangle must
//! lie in the union of the alpha-cubes of its three corners (exact), and no cap triangle on
//! a loop edge may fold back over that edge's kept face (exact). The Delaunay or
//! shortest-diagonal cap is tried first, then the least-area cap whose every triangle passes.
//! [`cap_avoiding`] also keeps diagonals off the edges a caller names (edges the output
//! keeps).

use std::collections::{BTreeSet, HashMap, HashSet};

use envelope_mesh::{FaceId, TriangleSoup, VertexId};
use envelope_predicates::{orient2d, orient3d};
use glam::DVec3;

use crate::exact::{covered_by_corner_cubes, linf_close};
use crate::triangulate::{constrained_triangulation, triangulate_loop};

/// A candidate rim and its cap.
#[derive(Clone, Debug)]
pub(crate) struct Candidate {
    /// Loop vertices, run as the kept patch runs them.
    pub(crate) vertices: Vec<VertexId>,
    /// The kept patch's face on each loop edge.
    pub(crate) keep: Vec<FaceId>,
    /// Key of the undirected edge cycle (for the two-sided ambiguity).
    pub(crate) key: Vec<(VertexId, VertexId)>,
    /// Normal variation of the kept patch.
    pub(crate) variation: f64,
    /// A plug: another candidate run the other way (its cap reversed), never preferred, so
    /// never the reason a region is filled; it only closes a filled region off from a kept
    /// cell whose own side has no candidate on these edges (see the selection in `reduce`).
    pub(crate) plug: bool,
    /// The cap.
    pub(crate) cap: Vec<[VertexId; 3]>,
}

impl Candidate {
    /// A rim that is not a plug, with its key and no cap yet.
    pub(crate) fn rim(vertices: Vec<VertexId>, keep: Vec<FaceId>) -> Self {
        let n = vertices.len();
        let mut key: Vec<Edge> = (0..n)
            .map(|i| {
                let (a, b) = (vertices[i], vertices[(i + 1) % n]);
                (a.min(b), a.max(b))
            })
            .collect();
        key.sort_unstable();
        Candidate {
            vertices,
            keep,
            key,
            variation: 0.0,
            plug: false,
            cap: Vec::new(),
        }
    }
}

/// A cap, or what was built and whether it was refused for its shape (see [`cap_of`]).
pub(crate) type Capped = Result<Vec<[VertexId; 3]>, (Vec<[VertexId; 3]>, bool)>;

/// The cap of `c` if the alpha test accepts it (see the module docs); otherwise what was
/// built and whether it was refused for its shape (repeated vertex, no triangulation, folding
/// back over its kept face) rather than as wider than the cube.
pub(crate) fn cap_of(soup: &TriangleSoup, c: &Candidate, alpha: f64) -> Capped {
    cap_avoiding(soup, c, alpha, &|_, _| false)
}

/// [`cap_of`] with no diagonal on a pair of vertices `kept` names (an edge the output keeps
/// elsewhere: a cap edge there would be non-manifold).
pub(crate) fn cap_avoiding(
    soup: &TriangleSoup,
    c: &Candidate,
    alpha: f64,
    kept: &dyn Fn(VertexId, VertexId) -> bool,
) -> Capped {
    let distinct: BTreeSet<VertexId> = c.vertices.iter().copied().collect();
    if distinct.len() != c.vertices.len() {
        return Err((Vec::new(), true));
    }
    let loop_edges: HashSet<(VertexId, VertexId)> = c.key.iter().copied().collect();
    let accepted = |cap: &[[VertexId; 3]]| {
        cap.iter().all(|t| {
            (0..3).all(|k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                loop_edges.contains(&(a.min(b), a.max(b)))
                    || (linf_close(soup.position(a), soup.position(b), alpha) && !kept(a, b))
            }) && covered_by_corner_cubes(t.map(|v| soup.position(v)), alpha)
        })
    };
    let first = match triangulate_loop(soup, &c.vertices) {
        Some(cap) if folds_onto_kept(soup, c, &cap) => Err((cap, true)),
        Some(cap) if accepted(&cap) => return Ok(cap),
        Some(cap) => Err((cap, false)),
        None => Err((Vec::new(), true)),
    };
    // The least-area cap among those the alpha test accepts triangle by triangle (the
    // Delaunay or shortest-diagonal cap may have failed where another succeeds).
    let n = c.vertices.len();
    let pts: Vec<DVec3> = c.vertices.iter().map(|&v| soup.position(v)).collect();
    let rim_edge = |i: usize, j: usize| j == i + 1 || (i == 0 && j == n - 1);
    let cap = constrained_triangulation(
        &pts,
        &c.vertices,
        |i, j| linf_close(pts[i], pts[j], alpha) && !kept(c.vertices[i], c.vertices[j]),
        |i, k, j| {
            // A triangle on a rim edge must not fold over that edge's kept face.
            let folds = [(i, k, j), (k, j, i), (i, j, k)].iter().any(|&(p, q, x)| {
                let (lo, hi) = (p.min(q), p.max(q));
                if !rim_edge(lo, hi) {
                    return false;
                }
                // The loop runs lo -> hi, except its closing edge, which runs n-1 -> 0.
                let (a, b) = if lo == 0 && hi == n - 1 {
                    (n - 1, 0)
                } else {
                    (lo, hi)
                };
                folds_over(soup, c.vertices[a], c.vertices[b], c.vertices[x], c.keep[a])
            });
            !folds && covered_by_corner_cubes([pts[i], pts[k], pts[j]], alpha)
        },
    );
    match cap {
        Some(cap) if accepted(&cap) && !folds_onto_kept(soup, c, &cap) => Ok(cap),
        _ => first,
    }
}

/// An undirected edge `(min, max)`.
pub(crate) type Edge = (VertexId, VertexId);

/// Splits a closed loop through a vertex more than once into simple loops (each keeps its
/// edges' faces); pieces with fewer than three vertices (slits run both ways) are dropped.
pub(crate) fn split_simple(
    vertices: &[VertexId],
    faces: &[FaceId],
) -> Vec<(Vec<VertexId>, Vec<FaceId>)> {
    let mut out = Vec::new();
    let mut path: Vec<(VertexId, FaceId)> = Vec::new();
    let mut pos: HashMap<VertexId, usize> = HashMap::new();
    for (&v, &f) in vertices.iter().zip(faces) {
        if let Some(&i) = pos.get(&v) {
            let cycle: Vec<(VertexId, FaceId)> = path.drain(i..).collect();
            for (w, _) in &cycle {
                pos.remove(w);
            }
            if cycle.len() >= 3 {
                out.push(cycle.into_iter().unzip());
            }
        }
        pos.insert(v, path.len());
        path.push((v, f));
    }
    // The rest closes back to path[0] (the loop's first vertex).
    if path.len() >= 3 {
        out.push(path.into_iter().unzip());
    }
    out
}

/// Whether a cap triangle on a rim edge lies in the plane of the kept face on that edge and
/// on the same side of the edge (exact orient3d, then orient2d in a projection that is exact
/// for coplanar points): the cap would fold back over the kept patch, as the cap of a planar
/// face's outer loop does. Such a cap always overlaps a kept face, so it is refused before
/// the selection (the validation would refuse it later, after it had filled its region).
pub(crate) fn folds_onto_kept(soup: &TriangleSoup, c: &Candidate, cap: &[[VertexId; 3]]) -> bool {
    let n = c.vertices.len();
    let mut third: HashMap<Edge, VertexId> = HashMap::new();
    for t in cap {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            third.insert((a.min(b), a.max(b)), t[(k + 2) % 3]);
        }
    }
    (0..n).any(|i| {
        let (a, b) = (c.vertices[i], c.vertices[(i + 1) % n]);
        third
            .get(&(a.min(b), a.max(b)))
            .is_some_and(|&x| folds_over(soup, a, b, x, c.keep[i]))
    })
}

/// Whether the cap triangle `(b, a, x)` on the rim edge `a -> b` lies in the plane of the
/// kept face `keep` on that edge and on the same side of the edge (exact; see
/// [`folds_onto_kept`]).
fn folds_over(soup: &TriangleSoup, a: VertexId, b: VertexId, x: VertexId, keep: FaceId) -> bool {
    let Some(&d) = soup.faces[keep.index()].iter().find(|&&v| v != a && v != b) else {
        return false;
    };
    let [pa, pb, px, pd] = [a, b, x, d].map(|v| soup.position(v));
    if !orient3d(pa, pb, pd, px).is_degenerate() {
        return false;
    }
    let proj = crate::exact::dominant_projection((pb - pa).cross(pd - pa));
    let (sa, sb) = (proj(pa), proj(pb));
    let (ox, od) = (orient2d(sa, sb, proj(px)), orient2d(sa, sb, proj(pd)));
    !ox.is_degenerate() && ox == od
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tessellation::{EdgeMap, face_normals, patches, tessellation_edges};

    #[test]
    fn caps_folding_back_over_their_planar_patch_are_told_apart_from_hole_caps() {
        // A planar disk with one square hole: its patch has the outer loop and the hole loop.
        let disk = crate::testmeshes::disk_with_square_holes(&[1], 1.0);
        let edges = EdgeMap::new(&disk);
        let normals = face_normals(&disk);
        let tess: HashSet<Edge> = tessellation_edges(&edges, &normals, 70.0)
            .into_iter()
            .collect();
        let pat = patches(&disk, &edges, &tess);
        let loops = &pat.loops[0];
        assert_eq!((pat.count, loops.len()), (1, 2));
        let verdicts: Vec<bool> = loops
            .iter()
            .map(|lp| {
                let c = Candidate {
                    vertices: lp.vertices.clone(),
                    keep: lp.faces.clone(),
                    key: Vec::new(),
                    variation: 0.0,
                    plug: false,
                    cap: Vec::new(),
                };
                let cap = triangulate_loop(&disk, &c.vertices).unwrap();
                folds_onto_kept(&disk, &c, &cap)
            })
            .collect();
        // The outer loop's cap lies over the disk; the hole's cap fills the hole.
        let outer = usize::from(loops[1].vertices.len() > loops[0].vertices.len());
        assert!(verdicts[outer], "outer cap folds: {verdicts:?}");
        assert!(!verdicts[1 - outer], "hole cap does not: {verdicts:?}");
    }

    #[test]
    fn figure_eight_loops_split_at_the_repeated_vertex() {
        let v = |i: u32| VertexId(i);
        let f = |i: u32| FaceId(i);
        // 0-1-2-0-3-4 closes back to 0: two triangles through vertex 0.
        let loops = split_simple(
            &[v(0), v(1), v(2), v(0), v(3), v(4)],
            &[f(10), f(11), f(12), f(13), f(14), f(15)],
        );
        assert_eq!(loops.len(), 2);
        assert_eq!(
            loops[0],
            (vec![v(0), v(1), v(2)], vec![f(10), f(11), f(12)])
        );
        assert_eq!(
            loops[1],
            (vec![v(0), v(3), v(4)], vec![f(13), f(14), f(15)])
        );
        // A slit 5-6-5 inside a loop is dropped, the rest kept.
        let loops = split_simple(
            &[v(0), v(1), v(5), v(6), v(5), v(2)],
            &[f(0), f(1), f(2), f(3), f(4), f(5)],
        );
        assert_eq!(
            loops,
            vec![(vec![v(0), v(1), v(5), v(2)], vec![f(0), f(1), f(4), f(5)])]
        );
        // Simple loops pass through unchanged.
        assert_eq!(
            split_simple(&[v(0), v(1), v(2)], &[f(0), f(1), f(2)]).len(),
            1
        );
    }
}
