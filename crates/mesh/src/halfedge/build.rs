//! Building a [`HalfEdgeMesh`] from a [`TriangleSoup`] and turning it back into one.

use super::{BuildError, HalfEdgeMesh, NO_F, NO_H, NO_V};
use crate::analysis::{EdgeTable, corner_fans, fan_counts, slot_ends};
use crate::{FaceId, HalfedgeId, TriangleSoup, VertexId};

impl HalfEdgeMesh {
    /// Builds the adjacency of a soup, keeping every vertex id and face id (unreferenced
    /// vertices become isolated vertices). Errors name the first offending element (faces in
    /// order, then edges in `(min, max)` order, then vertices).
    ///
    /// ```
    /// use envelope_mesh::{generate, BuildError, HalfEdgeMesh, VertexId};
    /// assert!(matches!(
    ///     HalfEdgeMesh::from_soup(&generate::bow_tie()),
    ///     Err(BuildError::NonManifoldVertex { vertex: VertexId(0) })
    /// ));
    /// ```
    pub fn from_soup(soup: &TriangleSoup) -> Result<Self, BuildError> {
        let nv = soup.positions.len();
        for (f, tri) in soup.faces.iter().enumerate() {
            let face = FaceId::from_index(f);
            if let Some(&vertex) = tri.iter().find(|v| v.index() >= nv) {
                return Err(BuildError::IndexOutOfRange { face, vertex });
            }
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
                return Err(BuildError::DegenerateFace { face });
            }
        }
        let valid = vec![true; soup.faces.len()];
        let table = EdgeTable::build(soup, &valid);
        for e in 0..table.num_edges() {
            let sl = table.edge_slots(e);
            if sl.len() > 2 {
                return Err(BuildError::NonManifoldEdge {
                    vertices: table.ends[e].map(VertexId),
                    faces: [FaceId(sl[0] / 3), FaceId(sl[1] / 3), FaceId(sl[2] / 3)],
                });
            }
            if let [s, t] = *sl {
                let (a, b) = slot_ends(&soup.faces, s);
                if slot_ends(&soup.faces, t).0 == a {
                    return Err(BuildError::InconsistentOrientation {
                        edge: [VertexId(a), VertexId(b)],
                        faces: [FaceId(s / 3), FaceId(t / 3)],
                    });
                }
            }
        }
        let fans = corner_fans(soup, &table);
        if let Some(v) = fan_counts(soup, &valid, &fans).iter().position(|&n| n > 1) {
            return Err(BuildError::NonManifoldVertex {
                vertex: VertexId::from_index(v),
            });
        }

        let ne = table.num_edges();
        let nf = soup.faces.len();
        let mut m = Self {
            positions: soup.positions.clone(),
            v_out: vec![NO_H; nv],
            v_alive: vec![true; nv],
            he_to: vec![NO_V; 2 * ne],
            he_next: vec![NO_H; 2 * ne],
            he_prev: vec![NO_H; 2 * ne],
            he_face: vec![NO_F; 2 * ne],
            f_he: vec![NO_H; nf],
            ..Self::default()
        };
        // Half-edge of slot s: 2e if it runs lo -> hi, else 2e + 1.
        let slot_he = |s: u32| -> HalfedgeId {
            let (a, b) = slot_ends(&soup.faces, s);
            HalfedgeId(2 * table.slot_edge[s as usize] + u32::from(a > b))
        };
        for e in 0..ne {
            let [lo, hi] = table.ends[e];
            m.he_to[2 * e] = VertexId(hi);
            m.he_to[2 * e + 1] = VertexId(lo);
        }
        for f in 0..nf {
            let hs = [0, 1, 2].map(|i| slot_he((3 * f + i) as u32));
            for i in 0..3 {
                let h = hs[i].index();
                m.he_face[h] = FaceId::from_index(f);
                m.he_next[h] = hs[(i + 1) % 3];
                m.he_prev[h] = hs[(i + 2) % 3];
                // Any outgoing half-edge for now; border ones override below.
                m.v_out[soup.faces[f][i].index()] = hs[i];
            }
            m.f_he[f] = hs[0];
        }
        // Border half-edges: next is the border half-edge leaving the target, found by
        // rotating counter-clockwise around the target from the twin.
        for h in 0..2 * ne {
            let h = HalfedgeId::from_index(h);
            if m.he_face[h.index()].is_valid() {
                continue;
            }
            let mut g = m.twin(h);
            while m.he_face[g.index()].is_valid() {
                g = m.twin(m.he_prev[g.index()]);
            }
            m.he_next[h.index()] = g;
            m.he_prev[g.index()] = h;
            let o = m.origin(g);
            m.v_out[o.index()] = g;
        }
        m.debug_check();
        Ok(m)
    }

    /// The live vertices in increasing id order and the live faces in increasing id order, as
    /// a soup with compacted ids (a face keeps its corner order, see [`Self::face_vertices`]).
    #[must_use]
    pub fn to_soup(&self) -> TriangleSoup {
        self.to_soup_with_ids().0
    }

    /// [`Self::to_soup`], plus the mesh id of each soup vertex and of each soup face.
    #[must_use]
    pub fn to_soup_with_ids(&self) -> (TriangleSoup, Vec<VertexId>, Vec<FaceId>) {
        let vids: Vec<VertexId> = self.vertices().collect();
        let fids: Vec<FaceId> = self.faces().collect();
        let mut new_of = vec![NO_V; self.positions.len()];
        for (i, v) in vids.iter().enumerate() {
            new_of[v.index()] = VertexId::from_index(i);
        }
        let soup = TriangleSoup {
            positions: vids.iter().map(|v| self.positions[v.index()]).collect(),
            faces: fids
                .iter()
                .map(|&f| self.face_vertices(f).map(|v| new_of[v.index()]))
                .collect(),
        };
        (soup, vids, fids)
    }
}
