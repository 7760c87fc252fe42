//! Topology of a [`HalfEdgeMesh`]: the full [`Topology`] report through a soup, and genus and
//! border loops counted on the half-edges.

use super::HalfEdgeMesh;
use crate::Topology;

impl HalfEdgeMesh {
    /// [`crate::analyze`] of this mesh, with ids renamed back to the mesh's.
    #[must_use]
    pub fn topology(&self) -> Topology {
        let (soup, vids, fids) = self.to_soup_with_ids();
        let mut t = crate::analyze(&soup);
        t.rename(&vids, &fids);
        t
    }

    /// The genus and the number of border loops of [`Self::topology`] (`genus`,
    /// `num_border_loops()`), counted on the half-edges in linear time, without the soup,
    /// when every vertex is manifold (each component's vertices, edges and faces by a walk
    /// over the faces, its border loops by the border cycles; consistent orientation makes
    /// every component orientable); from [`Self::topology`] otherwise. For a report on a
    /// simplifier's output, where `topology` builds and sorts an edge table.
    ///
    /// ```
    /// use envelope_mesh::{generate, HalfEdgeMesh};
    /// let m = HalfEdgeMesh::from_soup(&generate::torus(1.0, 0.3, 12, 8)).unwrap();
    /// assert_eq!(m.genus_and_border_loops(), (Some(1), 0));
    /// let m = HalfEdgeMesh::from_soup(&generate::open_cylinder(1.0, 2.0, 12, 4)).unwrap();
    /// assert_eq!(m.genus_and_border_loops(), (Some(0), 2));
    /// ```
    #[must_use]
    pub fn genus_and_border_loops(&self) -> (Option<u32>, usize) {
        let from_topology = || {
            let t = self.topology();
            (t.genus, t.num_border_loops())
        };
        if self.vertices().any(|v| !self.is_manifold_vertex(v)) {
            return from_topology();
        }
        // Per component: vertices, edges, faces, border loops.
        let mut counts: Vec<[i64; 4]> = Vec::new();
        let mut comp = vec![u32::MAX; self.f_he.len()];
        let mut seen = vec![false; self.positions.len()];
        let mut stack = Vec::new();
        for f in self.faces() {
            if comp[f.index()] != u32::MAX {
                continue;
            }
            let c = counts.len() as u32;
            let mut k = [0i64; 4];
            comp[f.index()] = c;
            stack.push(f);
            while let Some(g) = stack.pop() {
                k[2] += 1;
                let mut h = self.face_halfedge(g);
                for _ in 0..3 {
                    let v = self.origin(h);
                    k[0] += i64::from(!std::mem::replace(&mut seen[v.index()], true));
                    let t = self.twin(h);
                    match self.face(t) {
                        Some(o) => {
                            k[1] += i64::from(h.0 < t.0);
                            if comp[o.index()] == u32::MAX {
                                comp[o.index()] = c;
                                stack.push(o);
                            }
                        }
                        None => k[1] += 1,
                    }
                    h = self.next(h);
                }
            }
            counts.push(k);
        }
        let mut walked = vec![false; self.he_face.len()];
        for e in self.edges() {
            for i in 0..2 {
                let h = self.edge_halfedge(e, i);
                if !self.is_border_halfedge(h) || walked[h.index()] {
                    continue;
                }
                let Some(f) = self.face(self.twin(h)) else {
                    return from_topology(); // an edge with no face at all
                };
                let mut x = h;
                for _ in 0..self.he_face.len() {
                    walked[x.index()] = true;
                    x = self.next(x);
                    if x == h || !self.is_border_halfedge(x) {
                        break;
                    }
                }
                if x != h {
                    return from_topology();
                }
                counts[comp[f.index()] as usize][3] += 1;
            }
        }
        let genus = counts.iter().try_fold(0u32, |sum, &[v, e, f, b]| {
            Some(sum + crate::topology::genus_of(v - e + f, b)?)
        });
        let loops = counts.iter().map(|k| k[3] as usize).sum();
        (genus, loops)
    }
}
