//! [`HalfEdgeMesh::sanity_check`]: every adjacency invariant, always compiled, and the
//! `debug-checks` hook that runs it after every edit.

use super::HalfEdgeMesh;
use crate::HalfedgeId;

impl HalfEdgeMesh {
    #[inline]
    pub(super) fn debug_check(&self) {
        #[cfg(all(feature = "debug-checks", debug_assertions))]
        if let Err(e) = self.sanity_check() {
            panic!("HalfEdgeMesh::sanity_check failed: {e}");
        }
    }

    /// Verifies every adjacency invariant; `Err` names the first violation. O(n log n).
    ///
    /// Checked: array lengths; face cycles of length 3 with consistent face links; twin
    /// targets differ (no loops); `prev(next(h)) == h`; `origin(next(h)) == target(h)`; border
    /// half-edges link to border half-edges; no edge without a face; no two edges with the
    /// same endpoints; targets are live vertices; each live vertex's outgoing half-edge leaves
    /// it, is a border one when the vertex has any, and the counter-clockwise rotation from it
    /// visits every outgoing half-edge exactly once (one umbrella, gaps linked in one cycle);
    /// isolated vertices have no edge; free lists hold exactly the dead ids, once each.
    pub fn sanity_check(&self) -> Result<(), String> {
        let nv = self.positions.len();
        let nh = self.he_to.len();
        let nf = self.f_he.len();
        if self.v_out.len() != nv || self.v_alive.len() != nv {
            return Err("vertex array lengths differ".into());
        }
        if nh % 2 != 0
            || self.he_next.len() != nh
            || self.he_prev.len() != nh
            || self.he_face.len() != nh
        {
            return Err("half-edge array lengths differ".into());
        }
        let live_h = |h: HalfedgeId| h.index() < nh && self.he_to[h.index()].is_valid();
        // Free lists.
        let mut free_v = vec![false; nv];
        for &v in &self.free_vertices {
            if v.index() >= nv || self.v_alive[v.index()] || free_v[v.index()] {
                return Err(format!(
                    "free vertex list entry {v} is live, out of range or repeated"
                ));
            }
            free_v[v.index()] = true;
        }
        if let Some(v) = (0..nv).find(|&v| !self.v_alive[v] && !free_v[v]) {
            return Err(format!("dead vertex v{v} is not on the free list"));
        }
        let mut free_e = vec![false; nh / 2];
        for &e in &self.free_edges {
            if e.index() >= nh / 2 || self.he_to[2 * e.index()].is_valid() || free_e[e.index()] {
                return Err(format!(
                    "free edge list entry {e} is live, out of range or repeated"
                ));
            }
            free_e[e.index()] = true;
        }
        for e in 0..nh / 2 {
            let (a, b) = (
                self.he_to[2 * e].is_valid(),
                self.he_to[2 * e + 1].is_valid(),
            );
            if a != b {
                return Err(format!("edge e{e} is half dead"));
            }
            if !a && !free_e[e] {
                return Err(format!("dead edge e{e} is not on the free list"));
            }
        }
        let mut free_f = vec![false; nf];
        for &f in &self.free_faces {
            if f.index() >= nf || self.f_he[f.index()].is_valid() || free_f[f.index()] {
                return Err(format!(
                    "free face list entry {f} is live, out of range or repeated"
                ));
            }
            free_f[f.index()] = true;
        }
        if let Some(f) = (0..nf).find(|&f| !self.f_he[f].is_valid() && !free_f[f]) {
            return Err(format!("dead face f{f} is not on the free list"));
        }
        // Faces.
        for f in self.faces() {
            let h = self.f_he[f.index()];
            if !live_h(h) {
                return Err(format!("face {f} points at dead half-edge {h}"));
            }
            let mut g = h;
            for _ in 0..3 {
                if self.he_face[g.index()] != f {
                    return Err(format!(
                        "half-edge {g} in the cycle of {f} has another face"
                    ));
                }
                g = self.he_next[g.index()];
                if !live_h(g) {
                    return Err(format!("face {f}'s cycle reaches a dead half-edge"));
                }
            }
            if g != h {
                return Err(format!("face {f}'s cycle is not of length 3"));
            }
        }
        // Half-edges.
        let mut out_count = vec![0u32; nv];
        let mut keys = Vec::new();
        for h in (0..nh).map(HalfedgeId::from_index).filter(|&h| live_h(h)) {
            let (to, next, prev) = (self.target(h), self.next(h), self.prev(h));
            if to.index() >= nv || !self.v_alive[to.index()] {
                return Err(format!("half-edge {h} points at dead vertex {to}"));
            }
            if to == self.origin(h) {
                return Err(format!("half-edge {h} is a loop at {to}"));
            }
            if !live_h(next) || !live_h(prev) {
                return Err(format!("half-edge {h} links to a dead half-edge"));
            }
            if self.he_prev[next.index()] != h || self.he_next[prev.index()] != h {
                return Err(format!("half-edge {h}: next/prev not inverse"));
            }
            if self.origin(next) != to {
                return Err(format!("half-edge {h}: next does not leave its target"));
            }
            let f = self.he_face[h.index()];
            if f.is_valid() {
                if !self.contains_face(f) {
                    return Err(format!("half-edge {h} has dead face {f}"));
                }
            } else {
                if self.he_face[next.index()].is_valid() {
                    return Err(format!("border half-edge {h} links to a face half-edge"));
                }
                if self.is_border_halfedge(self.twin(h)) {
                    return Err(format!("edge {} has no face", self.edge(h)));
                }
            }
            out_count[self.origin(h).index()] += 1;
            if h.0 % 2 == 0 {
                let (a, b) = (to.0.min(self.origin(h).0), to.0.max(self.origin(h).0));
                keys.push(((u64::from(a) << 32) | u64::from(b), h));
            }
        }
        keys.sort_unstable();
        if let Some(w) = keys.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(format!(
                "half-edges {} and {} duplicate an edge",
                w[0].1, w[1].1
            ));
        }
        // Vertices.
        for v in self.vertices() {
            let h = self.v_out[v.index()];
            let deg = out_count[v.index()] as usize;
            if !h.is_valid() {
                if deg != 0 {
                    return Err(format!("vertex {v} has edges but no outgoing half-edge"));
                }
                continue;
            }
            if !live_h(h) || self.origin(h) != v {
                return Err(format!(
                    "vertex {v}'s outgoing half-edge {h} does not leave it"
                ));
            }
            let mut g = h;
            let mut seen = 0usize;
            let mut any_border = false;
            loop {
                if self.origin(g) != v {
                    return Err(format!("rotation around {v} leaves the vertex at {g}"));
                }
                seen += 1;
                any_border |= self.is_border_halfedge(g);
                if seen > deg {
                    return Err(format!("rotation around {v} does not return"));
                }
                g = self.rotate_ccw(g);
                if g == h {
                    break;
                }
            }
            if seen != deg {
                return Err(format!(
                    "vertex {v}: rotation visits {seen} of {deg} outgoing half-edges (split umbrella)"
                ));
            }
            if any_border && !self.is_border_halfedge(h) {
                return Err(format!(
                    "vertex {v} is on the border but its half-edge {h} is not"
                ));
            }
        }
        Ok(())
    }
}
