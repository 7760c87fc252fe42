//! Candidates from the whole surface (section 5.3): "all 3-tuples of the input vertices which
//! do not intersect either of the offset surfaces", ranked by how many vertices they cover,
//! each cutting the largest hole it can stand for.
//!
//! ```text
//! FiberIndex::new            a uniform grid over the fibers of the live vertices
//! surface_candidates(seed)   triples (seed, b, c), b and c among the live vertices within
//!                            `rings` edges of the seed (the nearest `max_corners`)
//!   cover                    the live interior vertices whose fiber the triangle meets
//!                            (grid query, then exact segment_triangle), corners excluded
//!   prune                    cover below `min_cover`: dropped; the best `per_seed` kept
//!   screen                   the triangle touches an envelope or wall: dropped (exact)
//!   maximal hole             the covered vertices connected to a corner through covered
//!                            vertices; their faces must form a disk whose boundary holds
//!                            the three corners
//! ```
//!
//! The hole of a candidate is every face around a vertex it covers ("removing all triangles
//! which overlap this candidate triangle"), not a ball of a few rings around a seed: the
//! candidate is placed, the sub-holes between it and the hole's boundary are filled by the
//! greedy filling, every triangle through the exact 5.1 filter, and every removed vertex's
//! fiber meets the candidate itself (the projection condition holds by construction).
//!
//! *The pruning.* All triples of all vertices is cubic in the mesh; corners are taken within
//! `rings` edges of a seed on the *current* approximation, so as the passes simplify the
//! mesh, the same rings reach farther on the input (the candidates grow with the holes
//! already cut). Per pass this is linear in the live vertices (at most `max_corners^2 / 2`
//! triples per seed, each a grid query); the passes are bounded. The pruning only removes
//! candidates; nothing it keeps is accepted without the exact filter.

use crate::candidates::{Candidate, Fibers, Generated, covers};
use crate::region::{ball_any, region};
use envelope_mesh::{HalfEdgeMesh, VertexId};
use envelope_simplify::policy::{Barriers, aspect_ratio};
use glam::DVec3;
use std::collections::{HashMap, HashSet};

/// Bounds of the whole-surface candidate generation (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SurfaceReach {
    /// Corners within this many edges of the seed (on the current approximation).
    pub rings: usize,
    /// At most this many corners besides the seed (the nearest, breadth-first).
    pub max_corners: usize,
    /// Candidates kept per seed.
    pub per_seed: usize,
    /// Fewest covered vertices a candidate must remove.
    pub min_cover: u32,
}

/// Barrier screens per kept candidate at most (the screen is the costly test of a large
/// triangle; a seed whose best triples keep touching the envelopes gives up).
const SCREENS_PER_KEPT: usize = 4;

impl Default for SurfaceReach {
    /// Corners within 3 edges, at most 20 of them, 4 candidates per seed, covering 2 or more.
    fn default() -> Self {
        SurfaceReach {
            rings: 3,
            max_corners: 20,
            per_seed: 4,
            min_cover: 2,
        }
    }
}

/// The `rings` marker of a whole-surface candidate ([`Candidate::rings`]).
pub const SURFACE_RINGS: u8 = u8::MAX;

/// A uniform grid over the fibers (prism edges) of the live vertices of a mesh: which fibers
/// may meet a box. The exact test is [`covers`]; the grid only narrows the search (f64 boxes,
/// widened by one cell, so a fiber that meets a triangle is always among those returned).
#[derive(Clone, Debug)]
pub struct FiberIndex {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<VertexId>>,
}

impl FiberIndex {
    /// The index of the fibers of `mesh`'s live vertices.
    #[must_use]
    pub fn new(mesh: &HalfEdgeMesh, fibers: &Fibers<'_>) -> Self {
        let segments: Vec<(VertexId, DVec3, DVec3)> = mesh
            .vertices()
            .filter_map(|v| {
                let (a, b) = (*fibers.inner.get(v.index())?, *fibers.outer.get(v.index())?);
                (a.is_finite() && b.is_finite()).then_some((v, a.min(b), a.max(b)))
            })
            .collect();
        // Cell: twice the mean edge length of the mesh (or the mean fiber extent, if longer).
        let (mut sum, mut n) = (0.0, 0usize);
        for v in mesh.vertices() {
            let p = mesh.position(v);
            for w in mesh.vertex_neighbors(v) {
                sum += (mesh.position(w) - p).length();
                n += 1;
            }
        }
        let edge = if n > 0 { sum / n as f64 } else { 1.0 };
        let fiber = segments
            .iter()
            .map(|(_, lo, hi)| (*hi - *lo).max_element())
            .sum::<f64>()
            / segments.len().max(1) as f64;
        let mut cell = (2.0 * edge).max(fiber);
        if !(cell.is_finite() && cell > 0.0) {
            cell = 1.0;
        }
        let mut index = FiberIndex {
            cell,
            cells: HashMap::new(),
        };
        for (v, lo, hi) in segments {
            let (a, b) = (index.key(lo), index.key(hi));
            // A fiber far longer than the cells (a degenerate input) goes in one cell of each
            // end and is found by the widened queries only near them: bound the work.
            if (0..3)
                .map(|k| b[k].saturating_sub(a[k]).saturating_add(1))
                .fold(1i64, i64::saturating_mul)
                > 4096
            {
                for key in [a, b] {
                    index.cells.entry(key).or_default().push(v);
                }
                continue;
            }
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        index.cells.entry([x, y, z]).or_default().push(v);
                    }
                }
            }
        }
        index
    }

    fn key(&self, p: DVec3) -> [i64; 3] {
        let q = (p / self.cell).floor();
        // Saturating casts: a huge coordinate lands in an outer cell, never panics.
        [q.x as i64, q.y as i64, q.z as i64]
    }

    /// The vertices whose fibers may meet the box `lo..hi` (each once, sorted).
    #[must_use]
    pub fn query(&self, lo: DVec3, hi: DVec3) -> Vec<VertexId> {
        let (a, b) = (self.key(lo), self.key(hi));
        let mut out = Vec::new();
        if (0..3)
            .map(|k| b[k].saturating_sub(a[k]).saturating_add(3))
            .fold(1i64, i64::saturating_mul)
            > 1 << 16
        {
            // A box larger than the grid is worth: every fiber.
            for list in self.cells.values() {
                out.extend_from_slice(list);
            }
        } else {
            let (a, b) = (
                a.map(|k| k.saturating_sub(1)),
                b.map(|k| k.saturating_add(1)),
            );
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        if let Some(list) = self.cells.get(&[x, y, z]) {
                            out.extend_from_slice(list);
                        }
                    }
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }
}

/// The live interior vertices other than the corners whose fibers the triangle `t` meets
/// (exact), sorted.
#[must_use]
pub fn covered(
    mesh: &HalfEdgeMesh,
    fibers: &Fibers<'_>,
    index: &FiberIndex,
    corners: [VertexId; 3],
) -> Vec<VertexId> {
    let p = corners.map(|v| mesh.position(v));
    let lo = p[0].min(p[1]).min(p[2]);
    let hi = p[0].max(p[1]).max(p[2]);
    index
        .query(lo, hi)
        .into_iter()
        .filter(|&v| {
            !corners.contains(&v)
                && mesh.contains_vertex(v)
                && !mesh.is_isolated(v)
                && !mesh.is_border_vertex(v)
                && covers(fibers, v, p)
        })
        .collect()
}

/// The maximal hole of a candidate with corners `corners`: the vertices of `cover` connected
/// to a corner through vertices of `cover` (breadth-first from the corners' neighbours).
#[must_use]
pub fn maximal_hole(
    mesh: &HalfEdgeMesh,
    cover: &[VertexId],
    corners: [VertexId; 3],
) -> Vec<VertexId> {
    let set: HashSet<VertexId> = cover.iter().copied().collect();
    let mut seen: HashSet<VertexId> = HashSet::new();
    let mut out = Vec::new();
    for c in corners {
        for w in mesh.vertex_neighbors(c) {
            if set.contains(&w) && seen.insert(w) {
                out.push(w);
            }
        }
    }
    let mut i = 0;
    while i < out.len() {
        let v = out[i];
        for w in mesh.vertex_neighbors(v) {
            if set.contains(&w) && seen.insert(w) {
                out.push(w);
            }
        }
        i += 1;
    }
    out
}

/// The whole-surface candidates with `seed` as a corner (see the module docs), each with its
/// maximal hole as [`Candidate::inside`], oriented as the hole's faces, and its cover the
/// number of vertices that hole removes. `screen`: the barriers of the validity filter (a
/// candidate touching one is dropped and counted as blocked).
#[must_use]
pub fn surface_candidates(
    mesh: &HalfEdgeMesh,
    fibers: &Fibers<'_>,
    index: &FiberIndex,
    seed: VertexId,
    reach: &SurfaceReach,
    screen: Option<&Barriers>,
) -> (Generated, Vec<Candidate>) {
    let mut counts = Generated::default();
    if !mesh.contains_vertex(seed) || mesh.is_isolated(seed) {
        return (counts, Vec::new());
    }
    let mut near = ball_any(mesh, seed, reach.rings);
    near.retain(|&v| v != seed);
    near.truncate(reach.max_corners);
    // (cover, aspect, corners) of the triples that cover enough.
    let mut scored: Vec<(u32, f64, [VertexId; 3])> = Vec::new();
    for (i, &b) in near.iter().enumerate() {
        for &c in &near[i + 1..] {
            counts.triples += 1;
            let t = [seed, b, c];
            let p = t.map(|v| mesh.position(v));
            if envelope_predicates::collinear(p[0], p[1], p[2]) {
                continue;
            }
            let n = covered(mesh, fibers, index, t).len() as u32;
            if n >= reach.min_cover {
                counts.covering += 1;
                scored.push((n, aspect_ratio(p), t));
            }
        }
    }
    scored.sort_by(|x, y| y.0.cmp(&x.0).then(y.1.total_cmp(&x.1)).then(x.2.cmp(&y.2)));
    let mut out = Vec::new();
    for (_, aspect, t) in scored.into_iter().take(SCREENS_PER_KEPT * reach.per_seed) {
        if out.len() >= reach.per_seed {
            break;
        }
        if let Some(barriers) = screen {
            if barriers.refuses(t.map(|v| mesh.position(v)), [false; 3]) {
                counts.blocked += 1;
                continue;
            }
        }
        let cover = covered(mesh, fibers, index, t);
        let mut inside = maximal_hole(mesh, &cover, t);
        if (inside.len() as u32) < reach.min_cover {
            continue;
        }
        // A corner off the hole's boundary is beyond a vertex the triangle does not cover
        // (a fiber leaning away from it): take the vertices between it and the hole too,
        // twice at most; the projection condition then asks the filled patch, not the
        // candidate, to cover them.
        let mut found = None;
        for _ in 0..3 {
            let Some(r) = region(mesh, &inside, false) else {
                break;
            };
            let at: Vec<usize> = t
                .iter()
                .filter_map(|v| r.cycle.iter().position(|x| x == v))
                .collect();
            if at.len() == 3 {
                found = Some((r, at));
                break;
            }
            let before = inside.len();
            for c in t.into_iter().filter(|c| !r.cycle.contains(c)) {
                let between: Vec<VertexId> = mesh
                    .vertex_neighbors(c)
                    .filter(|&w| {
                        !t.contains(&w)
                            && !inside.contains(&w)
                            && !mesh.is_border_vertex(w)
                            && mesh.vertex_neighbors(w).any(|x| inside.contains(&x))
                    })
                    .collect();
                for w in between {
                    if !inside.contains(&w) {
                        inside.push(w);
                    }
                }
            }
            if inside.len() == before {
                break;
            }
        }
        let Some((r, mut at)) = found else {
            continue;
        };
        counts.regions += 1;
        at.sort_unstable();
        let triangle = [r.cycle[at[0]], r.cycle[at[1]], r.cycle[at[2]]];
        out.push(Candidate {
            triangle,
            cover: r.inside.len() as u32,
            faces_covered: r.faces.len() as u32,
            aspect,
            seed,
            rings: SURFACE_RINGS,
            inside: r.inside,
        });
    }
    counts.kept += out.len() as u64;
    (counts, out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::TriangleSoup;

    /// An `n x n` grid of unit squares in the plane z = 0, two triangles each.
    fn grid(n: u32) -> TriangleSoup {
        let mut positions = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                positions.push(DVec3::new(f64::from(i), f64::from(j), 0.0));
            }
        }
        let id = |i: u32, j: u32| VertexId(j * (n + 1) + i);
        let mut faces = Vec::new();
        for j in 0..n {
            for i in 0..n {
                faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        TriangleSoup::new(positions, faces)
    }

    /// On a flat grid with vertical fibers, a large triangle covers every vertex strictly
    /// inside it, its maximal hole is those vertices, and the index finds the same cover as
    /// testing every fiber.
    #[test]
    fn a_flat_grid_gives_large_holes() {
        let soup = grid(8);
        let mesh = HalfEdgeMesh::from_soup(&soup).unwrap();
        let inner: Vec<DVec3> = soup.positions.iter().map(|p| *p - DVec3::Z * 0.1).collect();
        let outer: Vec<DVec3> = soup.positions.iter().map(|p| *p + DVec3::Z * 0.1).collect();
        let fibers = Fibers {
            inner: &inner,
            outer: &outer,
        };
        let index = FiberIndex::new(&mesh, &fibers);
        let seed = mesh
            .vertices()
            .find(|&v| !mesh.is_border_vertex(v) && mesh.valence(v) == 6)
            .unwrap();
        let reach = SurfaceReach::default();
        let (counts, cands) = surface_candidates(&mesh, &fibers, &index, seed, &reach, None);
        assert!(!cands.is_empty(), "{counts:?}");
        for c in &cands {
            let p = c.triangle.map(|v| mesh.position(v));
            let brute: Vec<VertexId> = mesh
                .vertices()
                .filter(|&v| {
                    !c.triangle.contains(&v) && !mesh.is_border_vertex(v) && covers(&fibers, v, p)
                })
                .collect();
            assert_eq!(covered(&mesh, &fibers, &index, c.triangle), brute);
            assert!(c.cover >= 2 && c.inside.iter().any(|v| brute.contains(v)));
        }
        assert!(cands[0].cover >= cands[cands.len() - 1].cover);
    }
}
