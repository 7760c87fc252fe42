//! Shared combinatorial machinery behind [`crate::analyze`], the degeneracy finders and
//! [`crate::HalfEdgeMesh::from_soup`]: an undirected edge table built by a counting sort on the
//! smaller endpoint (expected O(n)), and union-find structures for fans and components.
//!
//! Face `f`'s corner `i` is the *slot* `3f + i`; slot `3f + i` also names the directed half-edge
//! `faces[f][i] -> faces[f][(i + 1) % 3]`.

use crate::{TriangleSoup, VertexId};

/// "No element" in the `u32` tables below.
pub(crate) const NONE: u32 = u32::MAX;

/// Whether face `f` takes part in the topology: all indices in range, three distinct vertices.
pub(crate) fn face_is_valid(f: &[VertexId; 3], num_vertices: usize) -> bool {
    f.iter().all(|v| v.index() < num_vertices) && f[0] != f[1] && f[1] != f[2] && f[0] != f[2]
}

/// `valid[f]` for every face.
pub(crate) fn valid_faces(soup: &TriangleSoup) -> Vec<bool> {
    let n = soup.positions.len();
    soup.faces.iter().map(|f| face_is_valid(f, n)).collect()
}

/// The directed half-edge of slot `s` as `(origin, target)`.
#[inline]
pub(crate) fn slot_ends(faces: &[[VertexId; 3]], s: u32) -> (u32, u32) {
    let f = &faces[(s / 3) as usize];
    let i = (s % 3) as usize;
    (f[i].0, f[(i + 1) % 3].0)
}

/// The corner slot at the target of slot `s` (the next corner of the same face).
#[inline]
pub(crate) fn next_slot(s: u32) -> u32 {
    s - s % 3 + (s % 3 + 1) % 3
}

/// Undirected edges of the valid faces, sorted by `(lo, hi)` endpoint ids.
pub(crate) struct EdgeTable {
    /// Edge of each slot (`NONE` for slots of excluded faces).
    pub slot_edge: Vec<u32>,
    /// Slots grouped by edge, each group in increasing slot order.
    slots: Vec<u32>,
    /// Edge `e` owns `slots[start[e]..start[e + 1]]`.
    start: Vec<u32>,
    /// `(lo, hi)` endpoints of each edge, `lo < hi`.
    pub ends: Vec<[u32; 2]>,
}

impl EdgeTable {
    /// Builds the table over the faces with `valid[f]`.
    pub fn build(soup: &TriangleSoup, valid: &[bool]) -> Self {
        let n = soup.positions.len();
        let nf = soup.faces.len();
        assert!(
            nf <= (NONE as usize - 1) / 3,
            "too many faces for u32 slots"
        );
        let mut start_v = vec![0u32; n + 1];
        for (f, tri) in soup.faces.iter().enumerate() {
            if valid[f] {
                for i in 0..3 {
                    let (a, b) = (tri[i].0, tri[(i + 1) % 3].0);
                    start_v[a.min(b) as usize + 1] += 1;
                }
            }
        }
        for v in 0..n {
            start_v[v + 1] += start_v[v];
        }
        let total = start_v[n] as usize;
        // Counting sort by the smaller endpoint; each entry packs (hi << 32 | slot).
        let mut packed = vec![0u64; total];
        let mut fill = start_v.clone();
        for (f, tri) in soup.faces.iter().enumerate() {
            if valid[f] {
                for i in 0..3 {
                    let (a, b) = (tri[i].0, tri[(i + 1) % 3].0);
                    let lo = a.min(b) as usize;
                    packed[fill[lo] as usize] = (u64::from(a.max(b)) << 32) | (3 * f + i) as u64;
                    fill[lo] += 1;
                }
            }
        }
        drop(fill);
        let mut slot_edge = vec![NONE; 3 * nf];
        let mut slots = Vec::with_capacity(total);
        let mut start = Vec::new();
        let mut ends = Vec::new();
        for v in 0..n {
            let bucket = &mut packed[start_v[v] as usize..start_v[v + 1] as usize];
            bucket.sort_unstable();
            let mut prev_hi = u64::MAX;
            for &p in bucket.iter() {
                let hi = p >> 32;
                let s = p as u32;
                if hi != prev_hi {
                    start.push(slots.len() as u32);
                    ends.push([v as u32, hi as u32]);
                    prev_hi = hi;
                }
                slot_edge[s as usize] = (ends.len() - 1) as u32;
                slots.push(s);
            }
        }
        start.push(slots.len() as u32);
        Self {
            slot_edge,
            slots,
            start,
            ends,
        }
    }

    /// Number of undirected edges.
    pub fn num_edges(&self) -> usize {
        self.ends.len()
    }

    /// The slots (directed face half-edges) on edge `e`, increasing.
    pub fn edge_slots(&self, e: usize) -> &[u32] {
        &self.slots[self.start[e] as usize..self.start[e + 1] as usize]
    }
}

/// Union-find over `0..n` whose representative is always the smallest member.
pub(crate) struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    pub fn new(n: usize) -> Self {
        Self {
            parent: (0..n as u32).collect(),
        }
    }

    pub fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let p = self.parent[x as usize];
            let gp = self.parent[p as usize];
            self.parent[x as usize] = gp;
            x = gp;
        }
        x
    }

    pub fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = (ra.min(rb), ra.max(rb));
            self.parent[hi as usize] = lo;
        }
    }

    /// Points every element straight at its representative, so [`Self::root`] is O(1).
    pub fn flatten(&mut self) {
        for x in 0..self.parent.len() {
            // Representatives are the smallest members, so parents come first.
            let p = self.parent[x];
            self.parent[x] = self.parent[p as usize];
        }
    }

    /// Representative after [`Self::flatten`].
    pub fn root(&self, x: u32) -> u32 {
        self.parent[x as usize]
    }
}

/// Union-find over corner slots: two corners at the same vertex are joined when their faces
/// share an edge at that vertex with exactly two incident faces (either orientation). The
/// classes at a vertex are its fans (umbrellas); a corner's class representative is the
/// smallest slot in its fan. Flattened.
pub(crate) fn corner_fans(soup: &TriangleSoup, table: &EdgeTable) -> UnionFind {
    let mut uf = UnionFind::new(3 * soup.faces.len());
    for e in 0..table.num_edges() {
        let sl = table.edge_slots(e);
        if let [s, t] = *sl {
            let (a, _) = slot_ends(&soup.faces, s);
            let (c, _) = slot_ends(&soup.faces, t);
            if a == c {
                uf.union(s, t);
                uf.union(next_slot(s), next_slot(t));
            } else {
                uf.union(s, next_slot(t));
                uf.union(next_slot(s), t);
            }
        }
    }
    uf.flatten();
    uf
}

/// Number of fans at every vertex (0 for vertices of no valid face).
pub(crate) fn fan_counts(soup: &TriangleSoup, valid: &[bool], fans: &UnionFind) -> Vec<u32> {
    let mut count = vec![0u32; soup.positions.len()];
    for (f, tri) in soup.faces.iter().enumerate() {
        if valid[f] {
            for i in 0..3 {
                let c = (3 * f + i) as u32;
                if fans.root(c) == c {
                    count[tri[i].index()] += 1;
                }
            }
        }
    }
    count
}
