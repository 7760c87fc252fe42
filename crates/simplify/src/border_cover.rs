//! The other half of a border tube (6.2): the input's border stays within epsilon of the
//! approximation's.
//!
//! A new border edge that touches no tube lies inside the tubes, so it is within epsilon of
//! the old border. That is one direction only. Inside a tube wider than the loop it
//! surrounds, an edge can cut across the loop and leave a removed border vertex farther
//! than epsilon from everything (a two-face component of `b9_mesh.off` at 1 %: 2.05 against
//! 1.46). So a border vertex is removed only when its new border edge passes through the
//! ring of every input border vertex that edge stands for: the removed one and those its
//! two old edges stood for. Those are the input border vertices strictly between the edge's
//! ends along the tube's loop on the side of the removed vertex (a border vertex is never
//! moved, so the approximation's border visits the input's in order).
//!
//! *Passes through the ring*: the closed segment meets one of the triangles `r_0 r_j
//! r_(j+1)` over the ring's vertices, decided exactly ([`segment_triangle`]). Those lie in
//! the convex hull of the ring, whose vertices are at the ring's radius from the border
//! vertex (f64 constructions of `envelope-offset`), at most the epsilon there. So every
//! input border vertex ends within its epsilon of the approximation's border, and every
//! point of an input border edge too (the distance to a segment is convex along a segment).
//! A vertex on no tube, or whose edge's ends are not found on its loop, is refused: the
//! test only refuses.
use std::collections::HashMap;

use envelope_mesh::{TriangleSoup, VertexId};
use envelope_predicates::segment_triangle;
use glam::DVec3;

/// The rings of the border tubes, by border vertex.
#[derive(Clone, Debug, Default)]
pub struct BorderCover {
    loops: Vec<Loop>,
    /// Border vertex id -> (loop, index on it).
    at: HashMap<u32, (u32, u32)>,
}

#[derive(Clone, Debug)]
struct Loop {
    border: Vec<VertexId>,
    closed: bool,
    /// Ring vertices, `k` per border vertex in border order (the tube mesh's positions).
    rings: Vec<DVec3>,
    k: usize,
}

impl BorderCover {
    /// The rings of tubes given as `(border, closed, tube mesh)`: the mesh's positions are
    /// `k` per border vertex, ring after ring (as `envelope-offset` builds them). A tube
    /// whose vertex count is not a multiple of its border's length is left out (its border
    /// vertices are then never removed).
    ///
    /// ```
    /// use envelope_mesh::{TriangleSoup, VertexId};
    /// use envelope_simplify::policy::BorderCover;
    /// use glam::DVec3;
    /// // A loop 0 .. 4 (vertex 1 a little off the line from 0 to 2), rings of radius 0.25
    /// // (4 vertices each, across the x axis) around its vertices.
    /// let at = [[0.0, 0.0], [0.5, 0.05], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    ///     .map(|[x, y]| DVec3::new(x, y, 0.0));
    /// let ring = |c: DVec3| [DVec3::Z, DVec3::Y, -DVec3::Z, -DVec3::Y].map(|d| c + d * 0.25);
    /// let rings: Vec<DVec3> = at.iter().flat_map(|&c| ring(c)).collect();
    /// let border: Vec<VertexId> = (0..5).map(VertexId).collect();
    /// let tube = TriangleSoup::new(rings, vec![]);
    /// let cover = BorderCover::new(&[(&border[..], true, &tube)]);
    /// let end = |v: u32| (VertexId(v), at[v as usize]);
    /// // Removing 1: the edge 0-2 passes 0.05 from it, through its ring.
    /// assert!(cover.covers(VertexId(1), [end(0), end(2)]));
    /// // Removing 3: the edge 2-4 passes 0.71 from it, outside its ring.
    /// assert!(!cover.covers(VertexId(3), [end(2), end(4)]));
    /// ```
    #[must_use]
    pub fn new(tubes: &[(&[VertexId], bool, &TriangleSoup)]) -> Self {
        let mut cover = Self::default();
        for (border, closed, mesh) in tubes {
            let n = border.len();
            if n == 0 || mesh.num_vertices() % n != 0 || mesh.num_vertices() < 3 * n {
                continue;
            }
            let id = cover.loops.len() as u32;
            for (i, v) in border.iter().enumerate() {
                cover.at.insert(v.0, (id, i as u32));
            }
            cover.loops.push(Loop {
                border: border.to_vec(),
                closed: *closed,
                rings: mesh.positions.clone(),
                k: mesh.num_vertices() / n,
            });
        }
        cover
    }

    /// Whether the new border edge between `ends` (ids and positions), which replaces the
    /// border vertex `removed` and its two border edges, passes through the ring of every
    /// input border vertex it stands for (see the module docs). Exact.
    #[must_use]
    pub fn covers(&self, removed: VertexId, ends: [(VertexId, DVec3); 2]) -> bool {
        let Some(&(id, i)) = self.at.get(&removed.0) else {
            return false;
        };
        let l = &self.loops[id as usize];
        let n = l.border.len();
        let is_end = |v: VertexId| ends.iter().any(|e| e.0 == v);
        // From the removed vertex both ways along the loop to the first end, every vertex
        // passed is one the new edge stands for.
        let mut stands_for = vec![i as usize];
        let mut found = Vec::with_capacity(2);
        for step in [n - 1, 1] {
            let mut j = i as usize;
            loop {
                if !l.closed && ((step == 1 && j + 1 == n) || (step != 1 && j == 0)) {
                    return false;
                }
                j = (j + step) % n;
                if j == i as usize {
                    return false;
                }
                if is_end(l.border[j]) {
                    found.push(l.border[j]);
                    break;
                }
                stands_for.push(j);
            }
        }
        if found[0] == found[1] {
            return false;
        }
        let (p, q) = (ends[0].1, ends[1].1);
        stands_for.iter().all(|&j| {
            let ring = &l.rings[j * l.k..(j + 1) * l.k];
            (1..l.k - 1)
                .any(|m| segment_triangle(p, q, [ring[0], ring[m], ring[m + 1]]).intersects())
        })
    }
}
