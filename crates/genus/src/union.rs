//! Tessellation rims from the union of alpha-prisms (El-Sana and Varshney 1997, sections 3.3
//! and 4: "tessellation edges ... as an option, from the full union of alpha-prisms").
//!
//! The paper computes the union of the alpha-prisms of all faces; the parts of the surface
//! inside the union's interior become interior and are removed, and the curves where the
//! union's boundary meets the surface bound the regions to retriangulate. Building that union
//! exactly is out of reach here, so we use a pragmatic reading that reuses the exact
//! machinery of [`crate::reduce_genus`] and keeps its guarantees:
//!
//! 1. **Bridges.** A pair of faces `(f, g)` is a *bridge* when their alpha-prisms meet
//!    ([`crate::alpha_close_pairs`], exact: L-infinity distance at most `2 alpha`), each
//!    face lies strictly in front of the other's plane (exact orient3d, "front" taken from
//!    the sign of the signed volume, as for convex rims): the gap between them is empty space,
//!    not material, and their normals are more than 120 degrees apart ([`OPPOSED_COS`], f64
//!    unit normals): they are the two sides of a passage, not neighbours in a gently concave
//!    region (we first tried a geodesic-to-straight distance ratio over the face graph; on
//!    anisotropic meshes such as a fine torus the centroid path zigzags and every concave
//!    neighbour looked far). A face with a bridge is *swallowed*: the other side of a narrow
//!    passage is within `2 alpha`, so the face is inside the union of the two sides' prisms.
//! 2. **Regions.** The surface is cut along the edges between swallowed and other faces
//!    ([`crate::details::patches`]). A swallowed patch with at least two boundary loops
//!    (the wall of a tunnel, the inner band of a torus) is a tessellation region; each of its
//!    loops, run the other way (the kept side on the left), is a candidate rim. Unswallowed
//!    disk islands inside a swallowed patch (single-loop patches smaller than the patch
//!    around them) are swallowed too, so they do not come back as separate shells.
//! 3. **Levels.** A loop at the edge of a `2 alpha` bridge can be too wide for a cap whose
//!    triangles lie in the alpha-cubes of their corners, so the regions are also computed
//!    with the bridges that still hold at radii `0.75 alpha` and `0.5 alpha` (exact prism
//!    intersections at the smaller radius); all levels' rims are candidates and the
//!    enclosure test of [`crate::reduce_genus`] keeps a consistent set.
//!
//! Every candidate then goes through exactly the same acceptance as a sharp-edge rim (exact
//! diagonal and corner-cube tests, enclosure spread, `envelope-check` validation), so
//! everything stated there holds: added triangles lie in the union of alpha-prisms, the
//! output is validated and a refusal only keeps the input. The bridge test, the geodesic
//! ratio and the levels are heuristics (f64 centroids and lengths): a wrong answer can only
//! propose a rim that is then refused, or miss a narrow passage.
//!
//! **What it fills and what it cannot.** Narrow tunnels and holes through smooth (non-sharp)
//! surfaces whose two sides face each other within `2 alpha`: the smooth torus whose central
//! hole is narrower than about `2 alpha`, drilled tunnels. It does not fill a passage whose
//! swallowed wall is a single disk (a blind pocket: one loop, nothing to cut), a passage
//! whose rim cannot be capped inside its corners' cubes at any level, or thin walls of
//! material (the faces face away from each other): an alpha-hull never removes material.

use std::collections::{HashMap, HashSet};

use envelope_mesh::{FaceId, TriangleSoup, VertexId};
use envelope_predicates::{Orientation, orient3d};
use rayon::prelude::*;

use crate::neighbourhood::alpha_close_pairs_where;
use crate::tessellation::{EdgeMap, Patches, face_normals, patches};
use crate::{AlphaPrism, GenusError};

/// Where the tessellation rims come from. The default is [`TessellationSource::Closing`]: it
/// fills what the cube cannot pass, as the method promises, where the sharp-edge step alone
/// leaves networks of tunnels whose junctions are not sharp (issue 37).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TessellationSource {
    /// Sharp edges (dihedral angle above `beta`) and border edges only: the paper's
    /// heuristic step alone.
    SharpEdges,
    /// Sharp and border edges, plus the rims of the regions swallowed by the union of
    /// alpha-prisms (see the [`crate::union`] module docs).
    PrismUnion,
    /// The sharp-edge step, then the regions the L-infinity closing by the cube of side
    /// `2 alpha` swallows (estimated on voxels) replaced by caps over their loops, with
    /// peeling where a loop cannot be capped (see the crate README, issue 37). On inputs with
    /// borders (no solid) the sharp-edge step alone.
    #[default]
    Closing,
}

/// Two facing faces are on opposite sides of a passage when the cosine of the angle between
/// their normals is below this (the normals more than 120 degrees apart; across a round
/// hole they are opposite).
pub const OPPOSED_COS: f64 = -0.5;

/// Fractions of `alpha` at which the swallowed regions are computed.
const LEVELS: [f64; 3] = [1.0, 0.75, 0.5];

/// A candidate rim from the union: vertices run as the kept side runs them, the kept face on
/// each edge.
pub(crate) type UnionRim = (Vec<VertexId>, Vec<FaceId>);

/// What the union step found.
#[derive(Clone, Debug, Default)]
pub(crate) struct UnionRims {
    /// The candidate rims, all levels.
    pub rims: Vec<UnionRim>,
    /// Faces swallowed at the full `alpha` level.
    pub swallowed: usize,
}

/// Whether every vertex of `g` is strictly in front of `f` (exact orient3d).
fn in_front(soup: &TriangleSoup, f: FaceId, g: FaceId, front: Orientation) -> bool {
    let t = soup.triangle(f);
    soup.triangle(g)
        .iter()
        .all(|&p| orient3d(t[0], t[1], t[2], p) == front)
}

/// Bridges `(f, g)`, `f < g`, at radius `alpha` (see the module docs).
fn bridges(
    soup: &TriangleSoup,
    alpha: f64,
    outward: bool,
) -> Result<Vec<(FaceId, FaceId)>, GenusError> {
    let front = if outward {
        Orientation::Positive
    } else {
        Orientation::Negative
    };
    let normals = face_normals(soup);
    // The cheap tests (normals, then exact orient3d) run before the exact prism
    // intersection.
    let far = alpha_close_pairs_where(soup, alpha, None, |f, g| {
        let opposed = match (normals[f.index()], normals[g.index()]) {
            (Some(n), Some(m)) => n.dot(m) < OPPOSED_COS,
            _ => false,
        };
        opposed && in_front(soup, f, g, front) && in_front(soup, g, f, front)
    })?;
    Ok(far)
}

/// The candidate rims of the swallowed regions at every level (see the module docs).
pub(crate) fn union_rims(
    soup: &TriangleSoup,
    edges: &EdgeMap,
    alpha: f64,
    outward: bool,
) -> Result<UnionRims, GenusError> {
    let all = bridges(soup, alpha, outward)?;
    let mut out = UnionRims::default();
    let mut prisms: HashMap<(FaceId, usize), AlphaPrism> = HashMap::new();
    for (level, &frac) in LEVELS.iter().enumerate() {
        let kept: Vec<(FaceId, FaceId)> = if level == 0 {
            all.clone()
        } else {
            let rho = alpha * frac;
            let mut faces: Vec<FaceId> = all.iter().flat_map(|&(f, g)| [f, g]).collect();
            faces.sort_unstable();
            faces.dedup();
            let built: Vec<(FaceId, AlphaPrism)> = faces
                .par_iter()
                .map(|&f| AlphaPrism::new(soup.triangle(f), rho).map(|p| (f, p)))
                .collect::<Result<_, _>>()?;
            for (f, p) in built {
                prisms.insert((f, level), p);
            }
            all.iter()
                .copied()
                .filter(|&(f, g)| prisms[&(f, level)].intersects(&prisms[&(g, level)]))
                .collect()
        };
        let mut swallowed = vec![false; soup.num_faces()];
        for &(f, g) in &kept {
            swallowed[f.index()] = true;
            swallowed[g.index()] = true;
        }
        if level == 0 {
            out.swallowed = swallowed.iter().filter(|&&s| s).count();
        }
        if !swallowed.iter().any(|&s| s) {
            break;
        }
        fill_islands(soup, edges, &mut swallowed, false);
        out.rims.extend(region_rims(soup, edges, &swallowed));
    }
    Ok(out)
}

/// The edges between swallowed and other faces.
pub(crate) fn cut_edges(edges: &EdgeMap, swallowed: &[bool]) -> HashSet<(VertexId, VertexId)> {
    edges
        .faces
        .iter()
        .filter(|(_, fs)| fs.len() == 2 && swallowed[fs[0].0.index()] != swallowed[fs[1].0.index()])
        .map(|(k, _)| *k)
        .collect()
}

/// Swallows unswallowed patches bounded only by swallowed faces and smaller than the largest
/// swallowed patch around them (islands): with one loop only, or with any number of loops
/// when `any_loops` (a kept piece of wall inside a closed-off pocket, whose outer loop could
/// only be capped over the piece itself).
pub(crate) fn fill_islands(
    soup: &TriangleSoup,
    edges: &EdgeMap,
    swallowed: &mut [bool],
    any_loops: bool,
) {
    let cut = cut_edges(edges, swallowed);
    let pat = patches(soup, edges, &cut);
    let mut size = vec![0usize; pat.count];
    let mut first_face = vec![usize::MAX; pat.count];
    for (f, &p) in pat.of_face.iter().enumerate() {
        if p != usize::MAX {
            size[p] += 1;
            if first_face[p] == usize::MAX {
                first_face[p] = f;
            }
        }
    }
    // With any number of loops, the largest kept patch (the part's outside) is never an island.
    let main = (0..pat.count)
        .filter(|&p| first_face[p] != usize::MAX && !swallowed[first_face[p]])
        .max_by_key(|&p| size[p]);
    let mut island = vec![false; pat.count];
    for (p, loops) in pat.loops.iter().enumerate() {
        if any_loops && Some(p) == main {
            continue;
        }
        let first = first_face[p];
        if first == usize::MAX || swallowed[first] || loops.is_empty() {
            continue;
        }
        if loops.len() != 1 && !any_loops {
            continue;
        }
        let mut around: HashSet<usize> = HashSet::new();
        let enclosed = loops.iter().all(|lp| {
            let n = lp.vertices.len();
            (0..n).all(|i| {
                match edges.across(lp.faces[i], lp.vertices[i], lp.vertices[(i + 1) % n]) {
                    Some(g) if swallowed[g.index()] => {
                        around.insert(pat.of_face[g.index()]);
                        true
                    }
                    _ => false,
                }
            })
        });
        let largest = around
            .iter()
            .filter(|&&q| q != usize::MAX)
            .map(|&q| size[q])
            .max();
        if enclosed && (any_loops || around.len() == 1) && largest.is_some_and(|s| s > size[p]) {
            island[p] = true;
        }
    }
    for (f, s) in swallowed.iter_mut().enumerate() {
        let p = pat.of_face[f];
        if p != usize::MAX && island[p] {
            *s = true;
        }
    }
}

/// The loops of swallowed patches with at least two loops, reversed (kept side on the left),
/// with the kept face on each edge; loops with an edge lacking a kept face are skipped.
fn region_rims(soup: &TriangleSoup, edges: &EdgeMap, swallowed: &[bool]) -> Vec<UnionRim> {
    let cut = cut_edges(edges, swallowed);
    let pat = patches(soup, edges, &cut);
    patch_rims(edges, swallowed, &pat)
        .into_iter()
        .filter_map(|(_, _, rim)| rim)
        .collect()
}

/// Each loop of a swallowed patch with at least two loops: the patch, the loop's vertices,
/// and the loop reversed (kept side on the left) with the kept face on each edge, `None`
/// when an edge lacks a kept face.
pub(crate) fn patch_rims(
    edges: &EdgeMap,
    swallowed: &[bool],
    pat: &Patches,
) -> Vec<(usize, Vec<VertexId>, Option<UnionRim>)> {
    let mut first_face = vec![usize::MAX; pat.count];
    for (f, &p) in pat.of_face.iter().enumerate() {
        if p != usize::MAX && first_face[p] == usize::MAX {
            first_face[p] = f;
        }
    }
    let mut rims = Vec::new();
    for (p, loops) in pat.loops.iter().enumerate() {
        if first_face[p] == usize::MAX || !swallowed[first_face[p]] || loops.len() < 2 {
            continue;
        }
        for lp in loops {
            let n = lp.vertices.len();
            let across: Option<Vec<FaceId>> = (0..n)
                .map(|i| {
                    let (a, b) = (lp.vertices[i], lp.vertices[(i + 1) % n]);
                    edges
                        .across(lp.faces[i], a, b)
                        .filter(|g| !swallowed[g.index()])
                })
                .collect();
            let rim = across.map(|across| {
                let vertices: Vec<VertexId> = lp.vertices.iter().rev().copied().collect();
                let keep: Vec<FaceId> = (0..n).map(|j| across[(2 * n - 2 - j) % n]).collect();
                (vertices, keep)
            });
            rims.push((p, lp.vertices.clone(), rim));
        }
    }
    rims
}
