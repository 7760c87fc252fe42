//! Regions of the current approximation that one candidate replaces (section 5.3, "cut the
//! hole of all current triangles it overlaps"; open holes at the border as in 5.2 and 6.2).
//!
//! A region is a set `S` of vertices (a ball of `k` rings around a seed, a short chain, ...)
//! and the faces `R` around them. It is usable when `R` is a topological disk (`V - E + F =
//! 1`) and either
//!
//! * *closed*: `S` has interior vertices only and the boundary of `R` is one simple cycle `C`
//!   of vertices outside `S`, with a face on the far side of every boundary edge (cutting it
//!   never opens the mesh's border); removing `R` and `S` leaves one closed hole on `C`; or
//! * *open* (only when asked, i.e. with border tubes): the boundary of `R` is one simple
//!   chain `C = c_0 .. c_m` of vertices outside `S` (edges with a face beyond) followed by
//!   one simple path of mesh border edges from `c_m` back to `c_0` whose inner vertices are
//!   all in `S`. Removing `R` and `S` leaves the open hole of the local algorithm: the chain,
//!   closed by the new border edge `c_m -> c_0` (which the fill's guards refuse when it
//!   already exists, so a border loop never disappears, and the filter tests against the
//!   border tubes).
//!
//! Any triangulation of such a polygon keeps the genus and the number of border loops (the
//! fill's topology guards refuse edges that already exist elsewhere). All decisions here are
//! combinatorial.

use envelope_mesh::{FaceId, HalfEdgeMesh, VertexId};
use std::collections::{HashMap, HashSet};

/// A region: removed vertices, the faces around them, and the hole boundary they leave.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Region {
    /// The vertices the region removes (interior vertices, seed first).
    pub inside: Vec<VertexId>,
    /// The faces around them.
    pub faces: Vec<FaceId>,
    /// The hole boundary in the direction the removed faces run it (the order of
    /// `HalfEdgeMesh::remove_vertex_fan`, so a triangle on increasing positions is oriented
    /// as the faces were).
    pub cycle: Vec<VertexId>,
    /// An open region (it removes border vertices): `cycle` is a chain, closed by the new
    /// border edge from its last vertex to its first (the local algorithm's open hole).
    pub open: bool,
}

/// The interior vertices within `rings` edges of `seed`, along paths through interior
/// vertices, in breadth-first order (seed first). Empty when `seed` is a border vertex.
#[must_use]
pub fn ball(mesh: &HalfEdgeMesh, seed: VertexId, rings: usize) -> Vec<VertexId> {
    if mesh.contains_vertex(seed) && mesh.is_border_vertex(seed) {
        return Vec::new();
    }
    breadth_first(mesh, seed, rings, |w| !mesh.is_border_vertex(w))
}

/// All vertices (interior and border) within `rings` edges of `seed`, in breadth-first
/// order (seed first): the candidate sets of regions that may touch the border.
#[must_use]
pub fn ball_any(mesh: &HalfEdgeMesh, seed: VertexId, rings: usize) -> Vec<VertexId> {
    breadth_first(mesh, seed, rings, |_| true)
}

/// The vertices within `rings` edges of `seed` along paths whose vertices after the seed all
/// satisfy `through`, in breadth-first order (seed first); empty for a dead or isolated seed.
fn breadth_first(
    mesh: &HalfEdgeMesh,
    seed: VertexId,
    rings: usize,
    through: impl Fn(VertexId) -> bool,
) -> Vec<VertexId> {
    if !mesh.contains_vertex(seed) || mesh.is_isolated(seed) {
        return Vec::new();
    }
    let mut out = vec![seed];
    let mut seen: HashSet<VertexId> = HashSet::from([seed]);
    let mut start = 0;
    for _ in 0..rings {
        let end = out.len();
        for i in start..end {
            for w in mesh.vertex_neighbors(out[i]) {
                if through(w) && seen.insert(w) {
                    out.push(w);
                }
            }
        }
        start = end;
    }
    out
}

/// The next vertex along the border loop from border vertex `v` (the target of its outgoing
/// border half-edge), or `None` for an interior vertex.
#[must_use]
pub fn border_next(mesh: &HalfEdgeMesh, v: VertexId) -> Option<VertexId> {
    mesh.outgoing_halfedges(v)
        .find(|&h| mesh.is_border_halfedge(h))
        .map(|h| mesh.target(h))
}

/// The region of `inside` (see the module docs), or `None` when it is not a disk with one
/// simple boundary cycle away from the mesh's border, and (with `border`) not an open region
/// either.
///
/// ```
/// use envelope_global::{ball, region};
/// use envelope_mesh::{generate, HalfEdgeMesh, VertexId};
/// let m = HalfEdgeMesh::from_soup(&generate::icosphere(1, 1.0)).unwrap();
/// let fan = region(&m, &[VertexId(0)], false).unwrap();
/// assert_eq!(fan.cycle.len(), m.valence(VertexId(0)));
/// let all: Vec<VertexId> = m.vertices().collect();
/// assert!(region(&m, &all, true).is_none()); // a sphere is no disk
/// assert_eq!(ball(&m, VertexId(0), 1).len(), 1 + m.valence(VertexId(0)));
/// ```
#[must_use]
pub fn region(mesh: &HalfEdgeMesh, inside: &[VertexId], border: bool) -> Option<Region> {
    let set: HashSet<VertexId> = inside.iter().copied().collect();
    if set.len() != inside.len() || inside.is_empty() {
        return None;
    }
    let mut faces: Vec<FaceId> = Vec::new();
    let mut face_set: HashSet<FaceId> = HashSet::new();
    for &v in inside {
        if !mesh.contains_vertex(v)
            || mesh.is_isolated(v)
            || !mesh.is_manifold_vertex(v)
            || (!border && mesh.is_border_vertex(v))
        {
            return None;
        }
        for f in mesh.vertex_faces(v) {
            if face_set.insert(f) {
                faces.push(f);
            }
        }
    }
    // Boundary edges: face half-edges whose twin's face is not in the region (`next`), or
    // which lie on the mesh's border (`along`: they must touch a removed vertex).
    let mut next: HashMap<VertexId, VertexId> = HashMap::new();
    let mut along: HashMap<VertexId, VertexId> = HashMap::new();
    let mut vertices: HashSet<VertexId> = HashSet::new();
    for &f in &faces {
        let h0 = mesh.face_halfedge(f);
        let mut h = h0;
        loop {
            vertices.insert(mesh.origin(h));
            let (u, w) = (mesh.origin(h), mesh.target(h));
            match mesh.face(mesh.twin(h)) {
                None => {
                    if !border
                        || !(set.contains(&u) || set.contains(&w))
                        || along.insert(u, w).is_some()
                    {
                        return None;
                    }
                }
                Some(g) if !face_set.contains(&g) => {
                    if set.contains(&u) || set.contains(&w) || next.insert(u, w).is_some() {
                        return None;
                    }
                }
                Some(_) => {}
            }
            h = mesh.next(h);
            if h == h0 {
                break;
            }
        }
    }
    let open = !along.is_empty();
    let cycle = if open {
        open_chain(&set, &next, &along)?
    } else {
        closed_cycle(&next)?
    };
    // A disk: V - E + F = 1, and no vertex other than `inside` and the cycle.
    let (l, nf) = (cycle.len(), faces.len());
    let boundary = next.len() + along.len();
    if vertices.len() != inside.len() + l || (3 * nf + boundary) % 2 != 0 {
        return None;
    }
    let edges = (3 * nf + boundary) / 2;
    if vertices.len() + nf != edges + 1 {
        return None;
    }
    Some(Region {
        inside: inside.to_vec(),
        faces,
        cycle,
        open,
    })
}

/// One simple cycle through every boundary edge.
fn closed_cycle(next: &HashMap<VertexId, VertexId>) -> Option<Vec<VertexId>> {
    let &first = next.keys().min()?;
    let mut cycle = vec![first];
    let mut v = next[&first];
    while v != first {
        if cycle.len() > next.len() {
            return None;
        }
        cycle.push(v);
        v = *next.get(&v)?;
    }
    if cycle.len() != next.len() || cycle.len() < 3 {
        return None;
    }
    Some(cycle)
}

/// An open region: the boundary edges between the region and the rest form one simple chain
/// `first .. last` of kept vertices, and the region's border edges one simple path from
/// `last` back to `first` through removed vertices only. The hole is the chain; the new edge
/// `last -> first` closes it on the border.
fn open_chain(
    set: &HashSet<VertexId>,
    next: &HashMap<VertexId, VertexId>,
    along: &HashMap<VertexId, VertexId>,
) -> Option<Vec<VertexId>> {
    let targets: HashSet<VertexId> = next.values().copied().collect();
    let mut starts = next.keys().filter(|v| !targets.contains(v));
    let first = *starts.next()?;
    if starts.next().is_some() {
        return None;
    }
    let mut chain = vec![first];
    let mut v = first;
    while let Some(&w) = next.get(&v) {
        if chain.len() > next.len() {
            return None;
        }
        chain.push(w);
        v = w;
    }
    if chain.len() != next.len() + 1 || chain.len() < 3 {
        return None;
    }
    let last = v;
    // The border path from `last` to `first`, through removed vertices only.
    let mut steps = 0;
    let mut u = last;
    loop {
        let w = *along.get(&u)?;
        steps += 1;
        if w == first {
            break;
        }
        if !set.contains(&w) || steps > along.len() {
            return None;
        }
        u = w;
    }
    if steps != along.len() {
        return None;
    }
    Some(chain)
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::generate;

    #[test]
    fn one_ring_is_the_fan() {
        let m = HalfEdgeMesh::from_soup(&generate::icosphere(2, 1.0)).unwrap();
        let v = VertexId(0);
        let r = region(&m, &ball(&m, v, 1)[..1], false).unwrap();
        assert_eq!(r.faces.len(), m.valence(v));
        assert_eq!(r.cycle.len(), m.valence(v));
        let mut ring: Vec<VertexId> = m.vertex_neighbors(v).collect();
        let mut cyc = r.cycle.clone();
        ring.sort_unstable();
        cyc.sort_unstable();
        assert_eq!(ring, cyc);
    }

    #[test]
    fn cycle_runs_like_the_fan() {
        let mut m = HalfEdgeMesh::from_soup(&generate::icosphere(2, 1.0)).unwrap();
        let v = VertexId(5);
        let r = region(&m, &[v], false).unwrap();
        let ring = m.remove_vertex_fan(v).unwrap();
        let k = ring.iter().position(|&x| x == r.cycle[0]).unwrap();
        let mut rotated = ring.clone();
        rotated.rotate_left(k);
        assert_eq!(rotated, r.cycle);
    }

    #[test]
    fn two_rings_make_a_disk_and_a_whole_sphere_does_not() {
        let m = HalfEdgeMesh::from_soup(&generate::icosphere(2, 1.0)).unwrap();
        let b = ball(&m, VertexId(0), 2);
        let r = region(&m, &b, false).unwrap();
        assert!(r.cycle.len() > m.valence(VertexId(0)));
        let all: Vec<VertexId> = m.vertices().collect();
        assert_eq!(region(&m, &all, true), None);
    }

    #[test]
    fn border_vertices_make_open_regions_only_when_asked() {
        let m = HalfEdgeMesh::from_soup(&generate::open_cylinder(1.0, 1.0, 12, 4)).unwrap();
        let b = m.vertices().find(|&v| m.is_border_vertex(v)).unwrap();
        assert_eq!(region(&m, &[b], false), None);
        let r = region(&m, &[b], true).unwrap();
        assert!(r.open);
        // The chain runs from one border neighbour to the other through the interior ones.
        assert_eq!(r.cycle.len(), m.valence(b));
        let next = border_next(&m, b).unwrap();
        assert!(m.is_border_vertex(r.cycle[0]) && m.is_border_vertex(r.cycle[r.cycle.len() - 1]));
        assert!(r.cycle.contains(&next));
        // Two consecutive border vertices: one open region whose chain avoids both.
        let r2 = region(&m, &[b, next], true).unwrap();
        assert!(r2.open && !r2.cycle.contains(&b) && !r2.cycle.contains(&next));
        // A whole border loop is no open region (no chain ends to close).
        let mut lp = vec![b];
        while let Some(w) = border_next(&m, lp[lp.len() - 1]).filter(|w| !lp.contains(w)) {
            lp.push(w);
        }
        assert_eq!(lp.len(), 12);
        assert_eq!(region(&m, &lp, true), None);
        // A closed region stays closed with `border`.
        let inner = m.vertices().find(|&v| ball(&m, v, 1).len() == 7).unwrap();
        assert!(!region(&m, &[inner], true).unwrap().open);
    }

    #[test]
    fn border_vertices_are_never_inside() {
        let m = HalfEdgeMesh::from_soup(&generate::open_cylinder(1.0, 1.0, 12, 4)).unwrap();
        let border = m.vertices().find(|&v| m.is_border_vertex(v)).unwrap();
        assert!(ball(&m, border, 2).is_empty());
        let inner = m.vertices().find(|&v| !m.is_border_vertex(v)).unwrap();
        for v in ball(&m, inner, 3) {
            assert!(!m.is_border_vertex(v));
        }
    }
}
