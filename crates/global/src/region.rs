//! Regions of the current approximation that one candidate replaces (section 5.3, "cut the
//! hole of all current triangles it overlaps").
//!
//! A region is a set `S` of interior vertices (a ball of `k` rings around a seed, grown
//! through interior vertices only) and the faces `R` around them. It is usable when `R` is a
//! topological disk whose boundary is one simple cycle `C` of vertices outside `S`, with a
//! face on the far side of every boundary edge (so cutting it never opens the mesh's
//! border): then removing `R` and the vertices of `S` leaves one closed hole on `C`, and any
//! triangulation of that polygon keeps the genus (the fill's topology guards refuse edges
//! that already exist elsewhere). All decisions here are combinatorial.

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
}

/// The interior vertices within `rings` edges of `seed`, along paths through interior
/// vertices, in breadth-first order (seed first). Empty when `seed` is a border vertex.
#[must_use]
pub fn ball(mesh: &HalfEdgeMesh, seed: VertexId, rings: usize) -> Vec<VertexId> {
    if !mesh.contains_vertex(seed) || mesh.is_isolated(seed) || mesh.is_border_vertex(seed) {
        return Vec::new();
    }
    let mut out = vec![seed];
    let mut seen: HashSet<VertexId> = HashSet::from([seed]);
    let mut start = 0;
    for _ in 0..rings {
        let end = out.len();
        for i in start..end {
            for w in mesh.vertex_neighbors(out[i]) {
                if !mesh.is_border_vertex(w) && seen.insert(w) {
                    out.push(w);
                }
            }
        }
        start = end;
    }
    out
}

/// The region of `inside` (see the module docs), or `None` when it is not a disk with one
/// simple boundary cycle away from the mesh's border.
///
/// ```
/// use envelope_global::{ball, region};
/// use envelope_mesh::{generate, HalfEdgeMesh, VertexId};
/// let m = HalfEdgeMesh::from_soup(&generate::icosphere(1, 1.0)).unwrap();
/// let fan = region(&m, &[VertexId(0)]).unwrap();
/// assert_eq!(fan.cycle.len(), m.valence(VertexId(0)));
/// let all: Vec<VertexId> = m.vertices().collect();
/// assert!(region(&m, &all).is_none()); // a sphere is no disk
/// assert_eq!(ball(&m, VertexId(0), 1).len(), 1 + m.valence(VertexId(0)));
/// ```
#[must_use]
pub fn region(mesh: &HalfEdgeMesh, inside: &[VertexId]) -> Option<Region> {
    let set: HashSet<VertexId> = inside.iter().copied().collect();
    if set.len() != inside.len() || inside.is_empty() {
        return None;
    }
    let mut faces: Vec<FaceId> = Vec::new();
    let mut face_set: HashSet<FaceId> = HashSet::new();
    for &v in inside {
        if !mesh.contains_vertex(v) || !mesh.is_manifold_vertex(v) || mesh.is_border_vertex(v) {
            return None;
        }
        for f in mesh.vertex_faces(v) {
            if face_set.insert(f) {
                faces.push(f);
            }
        }
    }
    // Boundary edges: face half-edges whose twin's face is not in the region.
    let mut next: HashMap<VertexId, VertexId> = HashMap::new();
    let mut vertices: HashSet<VertexId> = HashSet::new();
    for &f in &faces {
        let h0 = mesh.face_halfedge(f);
        let mut h = h0;
        loop {
            vertices.insert(mesh.origin(h));
            match mesh.face(mesh.twin(h)) {
                None => return None, // the region touches the mesh's border
                Some(g) if !face_set.contains(&g) => {
                    let (u, w) = (mesh.origin(h), mesh.target(h));
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
    // One simple cycle through every boundary edge.
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
    // A disk: V - E + F = 1, and no vertex other than `inside` and the cycle.
    let (l, nf) = (cycle.len(), faces.len());
    if vertices.len() != inside.len() + l || (3 * nf + l) % 2 != 0 {
        return None;
    }
    let edges = (3 * nf + l) / 2;
    if vertices.len() + nf != edges + 1 {
        return None;
    }
    Some(Region {
        inside: inside.to_vec(),
        faces,
        cycle,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::generate;

    #[test]
    fn one_ring_is_the_fan() {
        let m = HalfEdgeMesh::from_soup(&generate::icosphere(2, 1.0)).unwrap();
        let v = VertexId(0);
        let r = region(&m, &ball(&m, v, 1)[..1]).unwrap();
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
        let r = region(&m, &[v]).unwrap();
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
        let r = region(&m, &b).unwrap();
        assert!(r.cycle.len() > m.valence(VertexId(0)));
        let all: Vec<VertexId> = m.vertices().collect();
        assert_eq!(region(&m, &all), None);
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
