//! Topology of any [`TriangleSoup`]: edges, border loops, connected components, Euler
//! characteristic, genus, manifoldness and orientability.
//!
//! The paper (Cohen et al. 1996, section 3) assumes an oriented 2-manifold, possibly with
//! borders, and promises to preserve its topology; this module states which soups satisfy that
//! and measures what must be preserved.
//!
//! Conventions, chosen once and used throughout:
//!
//! * **Excluded faces.** A face with an out-of-range index or a repeated index (`[a, a, b]`) is
//!   listed in [`Topology::excluded_faces`] and otherwise ignored: it adds no edge, no
//!   component, nothing to the Euler characteristic.
//! * **Unreferenced vertices** (named by no face at all) are listed and counted nowhere else.
//! * **Components** are classes of faces connected through shared edges (CGAL's
//!   `connected_components` convention): two faces touching at a single vertex (a bow-tie) are
//!   two components, and the pinch vertex counts once in each component's `V`.
//! * **Fans.** At a vertex, two incident faces are in the same fan when a chain of incident
//!   faces joins them, consecutive ones sharing an edge at that vertex that has exactly two
//!   incident faces. A vertex with more than one fan is non-manifold; this always includes both
//!   endpoints of every non-manifold edge (an edge with three or more faces).
//! * **Orientability** is decided through the edges with exactly two faces: a component is
//!   orientable when some choice of flips makes every such edge run in opposite directions in
//!   its two faces.
//! * **Genus** of a component follows from `chi = 2 - 2g - b` (b = border loops) and is
//!   defined only for a manifold, orientable component.

use crate::analysis::{
    EdgeTable, NONE, UnionFind, corner_fans, face_is_valid, fan_counts, next_slot, slot_ends,
    valid_faces,
};
use crate::{FaceId, TriangleSoup, VertexId};

/// One connected component (faces joined through shared edges).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Component {
    /// The smallest face id in the component.
    pub first_face: FaceId,
    /// Number of faces `F`.
    pub faces: usize,
    /// Number of distinct vertices `V` of its faces.
    pub vertices: usize,
    /// Number of undirected edges `E` of its faces.
    pub edges: usize,
    /// Number of border loops and open border chains `b`.
    pub border_loops: usize,
    /// Euler characteristic `V - E + F`.
    pub euler: i64,
    /// No border edge.
    pub closed: bool,
    /// No non-manifold edge and no vertex with two fans inside this component.
    pub manifold: bool,
    /// Orientable through its two-face edges (see the module docs).
    pub orientable: bool,
    /// `g` from `chi = 2 - 2g - b`; `None` unless manifold and orientable.
    pub genus: Option<u32>,
}

/// Everything [`analyze`] measures.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Topology {
    /// Number of vertex slots (referenced or not).
    pub num_vertices: usize,
    /// Number of vertices of at least one non-excluded face.
    pub num_referenced_vertices: usize,
    /// Number of faces, excluded ones included.
    pub num_faces: usize,
    /// Number of undirected edges of the non-excluded faces.
    pub num_edges: usize,
    /// Faces ignored because of an out-of-range or repeated index, increasing.
    pub excluded_faces: Vec<FaceId>,
    /// Vertices no face names, increasing.
    pub unreferenced_vertices: Vec<VertexId>,
    /// Edges with exactly one incident face, directed as that face runs them, sorted by their
    /// undirected `(min, max)` key.
    pub border_edges: Vec<[VertexId; 2]>,
    /// Closed border cycles, each listed without repeating its first vertex.
    ///
    /// A loop starts at the first vertex of its smallest border edge (in `(min, max)` order)
    /// and runs the way that edge's face runs it. At a vertex with several border edges
    /// (a pinch), a border edge continues with the border edge at the other end of the same
    /// fan; border edges whose fan ends at a non-manifold edge instead are paired, within one
    /// component, in order of `(other endpoint, edge key)`. On a consistently oriented
    /// component every loop therefore runs as its half-edges do.
    pub border_loops: Vec<Vec<VertexId>>,
    /// Border paths that could not be closed (only possible next to a non-manifold edge with
    /// an odd number of faces), from one dead end to the other.
    pub border_chains: Vec<Vec<VertexId>>,
    /// Components in order of their smallest face id.
    pub components: Vec<Component>,
    /// Sum of the components' Euler characteristics.
    pub euler: i64,
    /// Sum of the components' genera, `None` when one is undefined.
    pub genus: Option<u32>,
    /// No non-manifold edge and no non-manifold vertex (pinches between components count).
    pub manifold: bool,
    /// Every component orientable.
    pub orientable: bool,
    /// No edge is traversed in the same direction by two faces.
    pub consistently_oriented: bool,
}

impl Topology {
    /// Number of border loops plus open border chains.
    #[must_use]
    pub fn num_border_loops(&self) -> usize {
        self.border_loops.len() + self.border_chains.len()
    }

    /// Renames vertex and face ids (used by [`crate::HalfEdgeMesh::topology`]).
    pub(crate) fn rename(&mut self, vmap: &[VertexId], fmap: &[FaceId]) {
        let v = |x: &mut VertexId| *x = vmap[x.index()];
        self.unreferenced_vertices.iter_mut().for_each(v);
        self.border_edges.iter_mut().flatten().for_each(v);
        self.border_loops.iter_mut().flatten().for_each(v);
        self.border_chains.iter_mut().flatten().for_each(v);
        for f in &mut self.excluded_faces {
            *f = fmap[f.index()];
        }
        for c in &mut self.components {
            c.first_face = fmap[c.first_face.index()];
        }
    }
}

/// Union-find with parity, for orientability: `flip(a) xor flip(b) == parity` constraints.
struct ParityUnionFind {
    parent: Vec<u32>,
    parity: Vec<bool>,
}

impl ParityUnionFind {
    fn new(n: usize) -> Self {
        Self {
            parent: (0..n as u32).collect(),
            parity: vec![false; n],
        }
    }

    /// Root of `x` and the parity of `x` relative to it (full path compression, iterative,
    /// without a stack: one walk up for the root and the parity, one more to point the
    /// path at the root with each node's parity relative to it).
    fn find(&mut self, x: u32) -> (u32, bool) {
        let mut r = x;
        let mut total = false;
        while self.parent[r as usize] != r {
            total ^= self.parity[r as usize];
            r = self.parent[r as usize];
        }
        // `acc`: the parity of `y` relative to the root, peeled off node by node.
        let (mut y, mut acc) = (x, total);
        while self.parent[y as usize] != r && y != r {
            let (next, own) = (self.parent[y as usize], self.parity[y as usize]);
            self.parent[y as usize] = r;
            self.parity[y as usize] = acc;
            acc ^= own;
            y = next;
        }
        (r, total)
    }

    /// Adds the constraint; returns false on a contradiction.
    fn relate(&mut self, a: u32, b: u32, differ: bool) -> bool {
        let (ra, pa) = self.find(a);
        let (rb, pb) = self.find(b);
        if ra == rb {
            return (pa ^ pb) == differ;
        }
        self.parent[rb as usize] = ra;
        self.parity[rb as usize] = pa ^ pb ^ differ;
        true
    }
}

/// For every vertex, the faces around it (compressed rows: the faces of `v` are
/// `of(v)`, in increasing face order). A face naming a vertex out of range is left out of
/// that vertex's row, and a vertex out of range has no faces.
///
/// ```
/// use envelope_mesh::{generate, VertexFaces};
/// let t = generate::tetrahedron();
/// let vf = VertexFaces::new(t.num_vertices(), &t.faces);
/// assert_eq!(vf.of(0).len(), 3);
/// assert!(vf.of(0).windows(2).all(|w| w[0] < w[1]));
/// assert!(vf.of(99).is_empty());
/// ```
#[derive(Clone, Debug)]
pub struct VertexFaces {
    start: Vec<u32>,
    faces: Vec<u32>,
}

impl VertexFaces {
    /// The faces around each of the vertices `0..num_vertices`.
    #[must_use]
    pub fn new(num_vertices: usize, faces: &[[VertexId; 3]]) -> Self {
        let in_range = |v: &&VertexId| v.index() < num_vertices;
        let mut start = vec![0u32; num_vertices + 1];
        for f in faces {
            for v in f.iter().filter(in_range) {
                start[v.index() + 1] += 1;
            }
        }
        for i in 0..num_vertices {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut out = vec![0u32; start[num_vertices] as usize];
        for (fi, f) in (0u32..).zip(faces) {
            for v in f.iter().filter(in_range) {
                let slot = &mut fill[v.index()];
                out[*slot as usize] = fi;
                *slot += 1;
            }
        }
        VertexFaces { start, faces: out }
    }

    /// The faces around vertex `v` (empty for a vertex out of range).
    #[must_use]
    pub fn of(&self, v: usize) -> &[u32] {
        match (self.start.get(v), self.start.get(v + 1)) {
            (Some(&a), Some(&b)) => &self.faces[a as usize..b as usize],
            _ => &[],
        }
    }
}

/// The connected components of the vertices over `faces` (two vertices of one face are
/// connected): per vertex its component, numbered in order of the lowest vertex, `None` for a
/// vertex `0..num_vertices` that no face names; faces with an index out of range or a
/// repeated index are skipped (as [`analyze`] skips them). Also the number of components.
///
/// ```
/// use envelope_mesh::{generate, vertex_components};
/// let t = generate::tetrahedron();
/// let (comp, n) = vertex_components(t.num_vertices() + 1, &t.faces);
/// assert_eq!((n, comp[0], comp[4]), (1, Some(0), None));
/// ```
#[must_use]
pub fn vertex_components(
    num_vertices: usize,
    faces: &[[VertexId; 3]],
) -> (Vec<Option<u32>>, usize) {
    let mut uf = UnionFind::new(num_vertices);
    let mut used = vec![false; num_vertices];
    for f in faces.iter().filter(|f| face_is_valid(f, num_vertices)) {
        for v in f {
            used[v.index()] = true;
        }
        uf.union(f[0].0, f[1].0);
        uf.union(f[0].0, f[2].0);
    }
    uf.flatten();
    let mut id_of_root = vec![None; num_vertices];
    let mut count = 0;
    let comp = (0..num_vertices)
        .map(|v| {
            used[v].then(|| {
                let r = uf.root(v as u32) as usize;
                *id_of_root[r].get_or_insert_with(|| {
                    count += 1;
                    count as u32 - 1
                })
            })
        })
        .collect();
    (comp, count)
}

/// The genus of a connected, manifold, orientable surface with Euler characteristic
/// `euler` and `border_loops` border loops (`2 - 2g - b = euler`); `None` when that gives no
/// whole, non-negative genus. [`analyze`] and `HalfEdgeMesh::genus_and_border_loops` both
/// use it.
pub(crate) fn genus_of(euler: i64, border_loops: i64) -> Option<u32> {
    let twice = 2 - border_loops - euler;
    (twice >= 0 && twice % 2 == 0).then_some((twice / 2) as u32)
}

/// Analyses any soup; see the module docs for the conventions. O(n log n) worst case, expected
/// O(n) (a counting sort on edge keys, union-find with path compression).
///
/// ```
/// use envelope_mesh::{analyze, generate};
/// let t = analyze(&generate::torus(2.0, 0.5, 12, 8));
/// assert_eq!((t.euler, t.genus, t.components.len()), (0, Some(1), 1));
/// assert!(t.manifold && t.orientable && t.consistently_oriented && t.border_loops.is_empty());
/// ```
#[must_use]
pub fn analyze(soup: &TriangleSoup) -> Topology {
    let faces = &soup.faces;
    let nv = soup.positions.len();
    let nf = faces.len();
    let valid = valid_faces(soup);
    let table = EdgeTable::build(soup, &valid);
    let fans = corner_fans(soup, &table);
    let fan_count = fan_counts(soup, &valid, &fans);

    // Referenced vertices.
    let mut named = vec![false; nv];
    let mut in_valid = vec![false; nv];
    for (f, tri) in faces.iter().enumerate() {
        for v in tri {
            if v.index() < nv {
                named[v.index()] = true;
                if valid[f] {
                    in_valid[v.index()] = true;
                }
            }
        }
    }

    // Components, orientation.
    let mut comp_uf = UnionFind::new(nf);
    let mut parity = ParityUnionFind::new(nf);
    let mut nonorientable_faces = Vec::new();
    let mut consistently_oriented = true;
    let mut nonmanifold_edge_faces = Vec::new();
    for e in 0..table.num_edges() {
        let sl = table.edge_slots(e);
        for &t in &sl[1..] {
            comp_uf.union(sl[0] / 3, t / 3);
        }
        let first_dir = slot_ends(faces, sl[0]).0;
        if sl[1..].iter().any(|&t| slot_ends(faces, t).0 == first_dir) {
            consistently_oriented = false;
        }
        match *sl {
            [s, t] => {
                let same = slot_ends(faces, s).0 == slot_ends(faces, t).0;
                if !parity.relate(s / 3, t / 3, same) {
                    nonorientable_faces.push(s / 3);
                }
            }
            [s, _, _, ..] => nonmanifold_edge_faces.push(s / 3),
            _ => {}
        }
    }
    comp_uf.flatten();
    let mut comp_of_root = vec![NONE; nf];
    let mut face_comp = vec![NONE; nf];
    let mut components: Vec<Component> = Vec::new();
    for f in 0..nf {
        if !valid[f] {
            continue;
        }
        let r = comp_uf.root(f as u32) as usize;
        if comp_of_root[r] == NONE {
            comp_of_root[r] = components.len() as u32;
            components.push(Component {
                first_face: FaceId::from_index(f),
                faces: 0,
                vertices: 0,
                edges: 0,
                border_loops: 0,
                euler: 0,
                closed: true,
                manifold: true,
                orientable: true,
                genus: None,
            });
        }
        face_comp[f] = comp_of_root[r];
        components[face_comp[f] as usize].faces += 1;
    }
    // Distinct vertices per component: visit faces grouped by component.
    {
        let mut order: Vec<u32> = (0..nf as u32).filter(|&f| valid[f as usize]).collect();
        order.sort_unstable_by_key(|&f| face_comp[f as usize]);
        let mut last = vec![NONE; nv];
        for &f in &order {
            let c = face_comp[f as usize];
            for v in faces[f as usize] {
                if last[v.index()] != c {
                    last[v.index()] = c;
                    components[c as usize].vertices += 1;
                }
            }
        }
    }
    let mut border_edge_ids = Vec::new();
    for e in 0..table.num_edges() {
        let sl = table.edge_slots(e);
        let c = &mut components[face_comp[(sl[0] / 3) as usize] as usize];
        c.edges += 1;
        if sl.len() == 1 {
            c.closed = false;
            border_edge_ids.push(e);
        }
    }
    for f in nonorientable_faces {
        components[face_comp[f as usize] as usize].orientable = false;
    }
    for f in nonmanifold_edge_faces {
        components[face_comp[f as usize] as usize].manifold = false;
    }
    // A vertex with two fans in the same component makes that component non-manifold.
    let mut vertex_manifold = true;
    {
        let mut fan_roots: Vec<(u32, u32)> = Vec::new();
        for (f, tri) in faces.iter().enumerate() {
            if valid[f] {
                for i in 0..3 {
                    let c = (3 * f + i) as u32;
                    if fan_count[tri[i].index()] > 1 && fans.root(c) == c {
                        fan_roots.push((tri[i].0, face_comp[f]));
                    }
                }
            }
        }
        vertex_manifold &= fan_roots.is_empty();
        fan_roots.sort_unstable();
        for w in fan_roots.windows(2) {
            if w[0] == w[1] {
                components[w[0].1 as usize].manifold = false;
            }
        }
    }

    let (border_loops, border_chains, loop_comps) =
        trace_border(soup, &table, &fans, &face_comp, &border_edge_ids);
    for c in loop_comps {
        components[c as usize].border_loops += 1;
    }

    let mut total_genus = Some(0u32);
    let mut euler = 0i64;
    for c in &mut components {
        c.euler = c.vertices as i64 - c.edges as i64 + c.faces as i64;
        euler += c.euler;
        if c.manifold && c.orientable {
            c.genus = genus_of(c.euler, c.border_loops as i64);
        }
        total_genus = match (total_genus, c.genus) {
            (Some(a), Some(b)) => Some(a + b),
            _ => None,
        };
    }

    Topology {
        num_vertices: nv,
        num_referenced_vertices: in_valid.iter().filter(|&&b| b).count(),
        num_faces: nf,
        num_edges: table.num_edges(),
        excluded_faces: (0..nf)
            .filter(|&f| !valid[f])
            .map(FaceId::from_index)
            .collect(),
        unreferenced_vertices: (0..nv)
            .filter(|&v| !named[v])
            .map(VertexId::from_index)
            .collect(),
        border_edges: border_edge_ids
            .iter()
            .map(|&e| {
                let (a, b) = slot_ends(faces, table.edge_slots(e)[0]);
                [VertexId(a), VertexId(b)]
            })
            .collect(),
        border_loops,
        border_chains,
        manifold: vertex_manifold && components.iter().all(|c| c.manifold),
        orientable: components.iter().all(|c| c.orientable),
        consistently_oriented,
        components,
        euler,
        genus: total_genus,
    }
}

/// Loops, open chains, and the component of each (loops first, then chains).
type Borders = (Vec<Vec<VertexId>>, Vec<Vec<VertexId>>, Vec<u32>);

/// Pairs border edge ends at each vertex (same fan first) and walks the pairing.
fn trace_border(
    soup: &TriangleSoup,
    table: &EdgeTable,
    fans: &UnionFind,
    face_comp: &[u32],
    border: &[usize],
) -> Borders {
    let faces = &soup.faces;
    let nb = border.len();
    // End 2*i is the origin of border edge i (as its face runs it), end 2*i+1 the target.
    let end_vertex = |end: u32| -> u32 {
        let s = table.edge_slots(border[(end / 2) as usize])[0];
        let (a, b) = slot_ends(faces, s);
        if end % 2 == 0 { a } else { b }
    };
    let end_fan = |end: u32| -> u32 {
        let s = table.edge_slots(border[(end / 2) as usize])[0];
        fans.root(if end % 2 == 0 { s } else { next_slot(s) })
    };
    let mut ends: Vec<(u32, u32, u32)> = (0..2 * nb as u32)
        .map(|end| (end_vertex(end), end_fan(end), end))
        .collect();
    ends.sort_unstable();
    let mut partner = vec![NONE; 2 * nb];
    let mut i = 0;
    while i < ends.len() {
        let v = ends[i].0;
        let mut j = i;
        while j < ends.len() && ends[j].0 == v {
            j += 1;
        }
        // Same-fan pairs.
        let mut leftover = Vec::new();
        let mut k = i;
        while k < j {
            if k + 1 < j && ends[k + 1].1 == ends[k].1 && (k + 2 >= j || ends[k + 2].1 != ends[k].1)
            {
                let (a, b) = (ends[k].2, ends[k + 1].2);
                partner[a as usize] = b;
                partner[b as usize] = a;
                k += 2;
            } else {
                let end = ends[k].2;
                let comp =
                    face_comp[(table.edge_slots(border[(end / 2) as usize])[0] / 3) as usize];
                leftover.push((comp, end_vertex(end ^ 1), border[(end / 2) as usize], end));
                k += 1;
            }
        }
        leftover.sort_unstable();
        for w in leftover.chunk_by(|a, b| a.0 == b.0) {
            for p in w.chunks_exact(2) {
                partner[p[0].3 as usize] = p[1].3;
                partner[p[1].3 as usize] = p[0].3;
            }
        }
        i = j;
    }

    let mut used = vec![false; nb];
    let (mut loops, mut chains, mut loop_comps, mut chain_comps) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for start in 0..nb {
        if used[start] {
            continue;
        }
        used[start] = true;
        let comp = face_comp[(table.edge_slots(border[start])[0] / 3) as usize];
        let mut verts = vec![VertexId(end_vertex(2 * start as u32))];
        let mut at = 2 * start as u32 + 1;
        let closed = loop {
            let p = partner[at as usize];
            if p == 2 * start as u32 {
                break true;
            }
            verts.push(VertexId(end_vertex(at)));
            if p == NONE {
                break false;
            }
            used[(p / 2) as usize] = true;
            at = p ^ 1;
        };
        if closed {
            loops.push(verts);
            loop_comps.push(comp);
        } else {
            // Extend backwards from the start's origin.
            let mut back = Vec::new();
            let mut at = 2 * start as u32;
            while partner[at as usize] != NONE {
                let p = partner[at as usize];
                used[(p / 2) as usize] = true;
                at = p ^ 1;
                back.push(VertexId(end_vertex(at)));
            }
            back.reverse();
            back.extend(verts);
            chains.push(back);
            chain_comps.push(comp);
        }
    }
    loop_comps.extend(chain_comps);
    (loops, chains, loop_comps)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{degeneracy, generate};

    proptest::proptest! {
        /// The parity union-find against a brute force: each constraint `(a, b, differ)`
        /// is refused exactly when the constraints taken before force the opposite, and
        /// every `find` reports the parity a 2-colouring of the accepted ones gives.
        #[test]
        fn parity_union_find_is_the_brute_force(
            constraints in proptest::collection::vec((0u32..12, 0u32..12, proptest::bool::ANY), 0..40),
        ) {
            let mut uf = ParityUnionFind::new(12);
            let mut accepted: Vec<(u32, u32, bool)> = Vec::new();
            // Parity of every node relative to `start` through the accepted constraints
            // (`None`: not connected).
            let colour = |acc: &[(u32, u32, bool)], start: u32| {
                let mut c = vec![None; 12];
                c[start as usize] = Some(false);
                let mut changed = true;
                while changed {
                    changed = false;
                    for &(a, b, d) in acc {
                        for (x, y) in [(a, b), (b, a)] {
                            if let (Some(p), None) = (c[x as usize], c[y as usize]) {
                                c[y as usize] = Some(p ^ d);
                                changed = true;
                            }
                        }
                    }
                }
                c
            };
            for &(a, b, d) in &constraints {
                let forced = colour(&accepted, a)[b as usize];
                let ok = uf.relate(a, b, d);
                proptest::prop_assert_eq!(ok, forced.is_none_or(|p| p == d));
                if forced.is_none() {
                    accepted.push((a, b, d));
                }
                for x in 0..12 {
                    let (r, p) = uf.find(x);
                    proptest::prop_assert_eq!(colour(&accepted, r)[x as usize], Some(p));
                }
            }
        }
    }

    proptest::proptest! {
        /// `edge_findings` answers what the three finders answer one by one, on random
        /// soups (repeated, out-of-range and shared indices, any orientation).
        #[test]
        fn edge_findings_are_the_three_finders(
            faces in proptest::collection::vec(proptest::array::uniform3(0u32..9), 0..24),
        ) {
            let positions: Vec<[f64; 3]> = (0..8).map(|i| [f64::from(i), f64::from(i * i % 5), 0.0]).collect();
            let s = TriangleSoup::from_raw(&positions, &faces);
            let all = degeneracy::edge_findings(&s);
            proptest::prop_assert_eq!(all.non_manifold_vertices, degeneracy::non_manifold_vertices(&s));
            proptest::prop_assert_eq!(all.non_manifold_edges, degeneracy::non_manifold_edges(&s));
            proptest::prop_assert_eq!(all.inconsistent_orientations, degeneracy::inconsistent_orientations(&s));
        }
    }

    fn one(t: &Topology) -> &Component {
        assert_eq!(t.components.len(), 1, "{t:?}");
        &t.components[0]
    }

    /// A grid of unit squares in `z = 0` keeping the squares `keep(i, j)`.
    fn grid(nx: u32, ny: u32, keep: impl Fn(u32, u32) -> bool) -> TriangleSoup {
        let id = |i: u32, j: u32| j * (nx + 1) + i;
        let mut pos = Vec::new();
        for j in 0..=ny {
            for i in 0..=nx {
                pos.push([f64::from(i), f64::from(j), 0.0]);
            }
        }
        let mut faces = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                if keep(i, j) {
                    let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
                    faces.push([q[0], q[1], q[2]]);
                    faces.push([q[0], q[2], q[3]]);
                }
            }
        }
        TriangleSoup::from_raw(&pos, &faces)
    }

    #[test]
    fn tetrahedron_by_hand() {
        let t = analyze(&generate::tetrahedron());
        let c = one(&t);
        assert_eq!((c.vertices, c.edges, c.faces, c.euler), (4, 6, 4, 2));
        assert_eq!((t.num_vertices, t.num_edges, t.num_faces), (4, 6, 4));
        assert_eq!((c.genus, t.genus, t.euler), (Some(0), Some(0), 2));
        assert!(c.closed && c.manifold && c.orientable);
        assert!(t.manifold && t.orientable && t.consistently_oriented);
        assert!(t.border_edges.is_empty() && t.border_loops.is_empty());
    }

    #[test]
    fn closed_surfaces_have_expected_genus() {
        let cases: Vec<(&str, TriangleSoup, u32)> = vec![
            ("icosphere", generate::icosphere(2, 1.0), 0),
            ("uv_sphere", generate::uv_sphere(8, 5, 1.0), 0),
            (
                "box",
                generate::box_mesh(glam::DVec3::new(1.0, 2.0, 3.0), 3),
                0,
            ),
            ("pocket", generate::block_with_pocket(), 0),
            ("torus", generate::torus(2.0, 0.5, 10, 7), 1),
            ("tunnel", generate::box_with_tunnel(), 1),
            ("plate0", generate::plate_with_holes(0), 0),
            ("plate1", generate::plate_with_holes(1), 1),
            ("double torus", generate::plate_with_holes(2), 2),
            ("plate5", generate::plate_with_holes(5), 5),
        ];
        for (name, s, g) in cases {
            let t = analyze(&s);
            let c = one(&t);
            assert!(c.closed && t.manifold && t.consistently_oriented, "{name}");
            assert_eq!(t.genus, Some(g), "{name}");
            assert_eq!(t.euler, 2 - 2 * i64::from(g), "{name}");
            assert!(t.unreferenced_vertices.is_empty(), "{name}");
        }
    }

    #[test]
    fn open_cylinder_has_two_loops_running_with_the_faces() {
        let t = analyze(&generate::open_cylinder(1.0, 2.0, 9, 3));
        let c = one(&t);
        assert_eq!((c.border_loops, c.euler, c.genus), (2, 0, Some(0)));
        assert_eq!(t.border_loops.len(), 2);
        assert!(t.border_chains.is_empty());
        let directed: std::collections::HashSet<[VertexId; 2]> =
            t.border_edges.iter().copied().collect();
        for l in &t.border_loops {
            assert_eq!(l.len(), 9);
            for i in 0..l.len() {
                assert!(directed.contains(&[l[i], l[(i + 1) % l.len()]]));
            }
        }
    }

    #[test]
    fn disk_with_three_holes_has_four_loops() {
        let t = analyze(&generate::disk_with_holes(3));
        let c = one(&t);
        assert_eq!((c.border_loops, c.genus, c.euler), (4, Some(0), -2));
        let mut lens: Vec<usize> = t.border_loops.iter().map(Vec::len).collect();
        lens.sort_unstable();
        assert_eq!(lens, vec![4, 4, 4, 20]);
    }

    #[test]
    fn moebius_strip_is_non_orientable() {
        let t = analyze(&generate::moebius_strip(7));
        let c = one(&t);
        assert_eq!((c.euler, c.border_loops, c.genus), (0, 1, None));
        assert!(c.manifold && !c.orientable && !t.orientable && !t.consistently_oriented);
        assert_eq!(t.border_loops[0].len(), 14);
        assert_eq!(t.genus, None);
    }

    #[test]
    fn bow_tie_is_two_components_pinched() {
        let s = generate::bow_tie();
        let t = analyze(&s);
        assert_eq!(t.components.len(), 2);
        assert!(!t.manifold);
        assert!(
            t.components
                .iter()
                .all(|c| c.manifold && c.genus == Some(0))
        );
        assert_eq!(t.border_loops.len(), 2);
        assert_eq!(t.euler, 2);
        assert_eq!(degeneracy::non_manifold_vertices(&s), vec![VertexId(0)]);
    }

    #[test]
    fn three_triangles_on_one_edge() {
        let s = generate::three_triangles_on_edge();
        let t = analyze(&s);
        let c = one(&t);
        assert!(!c.manifold && !t.manifold && !t.consistently_oriented);
        assert_eq!(c.genus, None);
        let e = degeneracy::non_manifold_edges(&s);
        assert_eq!(e.len(), 1);
        assert_eq!(e[0].vertices, [VertexId(0), VertexId(1)]);
        assert_eq!(e[0].faces, vec![FaceId(0), FaceId(1), FaceId(2)]);
        assert_eq!(
            degeneracy::non_manifold_vertices(&s),
            vec![VertexId(0), VertexId(1)]
        );
        let o = degeneracy::inconsistent_orientations(&s);
        assert_eq!(o.len(), 1);
        assert_eq!(o[0].faces, [FaceId(0), FaceId(2)]);
        assert_eq!(o[0].edge, [VertexId(0), VertexId(1)]);
        // Six border edges; each apex's two pair up in its own fan; at 0 and at 1 three
        // single-edge fans remain: (2, 3) pair by other endpoint, 4 is left a dead end.
        assert_eq!(t.border_edges.len(), 6);
        assert_eq!(t.border_loops.len(), 1);
        assert_eq!(t.border_loops[0].len(), 4);
        assert_eq!(
            t.border_chains,
            vec![vec![VertexId(1), VertexId(4), VertexId(0)]]
        );
        assert_eq!(c.border_loops, 2);
    }

    #[test]
    fn pinched_border_loop_follows_the_fans() {
        // 3x3 squares without the centre and the top-right corner: squares (2,1) and (1,2) meet
        // only at lattice point (2,2) = vertex 10.
        let s = grid(3, 3, |i, j| !((i, j) == (1, 1) || (i, j) == (2, 2)));
        let t = analyze(&s);
        let c = one(&t);
        assert!(!c.manifold && c.genus.is_none());
        assert_eq!(degeneracy::non_manifold_vertices(&s), vec![VertexId(10)]);
        assert_eq!(t.border_loops.len(), 1);
        let l = &t.border_loops[0];
        assert_eq!(l.len(), 16);
        assert_eq!(l.iter().filter(|&&v| v == VertexId(10)).count(), 2);
    }

    #[test]
    fn excluded_and_unreferenced() {
        let s = TriangleSoup::from_raw(
            &[
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [9.0; 3],
                [0.0; 3],
            ],
            &[[0, 1, 2], [0, 0, 1], [1, 2, 7]],
        );
        let t = analyze(&s);
        assert_eq!(t.excluded_faces, vec![FaceId(1), FaceId(2)]);
        assert_eq!(t.unreferenced_vertices, vec![VertexId(3), VertexId(4)]);
        assert_eq!(t.num_referenced_vertices, 3);
        assert_eq!(degeneracy::degenerate_faces(&s), vec![FaceId(1)]);
        assert_eq!(
            degeneracy::unreferenced_vertices(&s),
            vec![VertexId(3), VertexId(4)]
        );
        assert_eq!(
            degeneracy::duplicate_vertices(&s),
            vec![vec![VertexId(0), VertexId(4)]]
        );
        assert_eq!(one(&t).genus, Some(0));
    }

    #[test]
    fn duplicate_faces_any_orientation() {
        let s = TriangleSoup::from_raw(
            &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            &[[0, 1, 2], [1, 2, 0], [2, 1, 0]],
        );
        assert_eq!(
            degeneracy::duplicate_faces(&s),
            vec![[FaceId(0), FaceId(1)], [FaceId(0), FaceId(2)]]
        );
        assert!(!analyze(&s).manifold);
    }

    #[test]
    fn empty_soup() {
        let t = analyze(&TriangleSoup::default());
        assert_eq!((t.euler, t.genus, t.components.len()), (0, Some(0), 0));
        assert!(t.manifold && t.orientable);
    }
}
