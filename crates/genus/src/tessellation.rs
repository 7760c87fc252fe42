//! Tessellation edges, chains and regions (El-Sana and Varshney 1997, section 3.3).
//!
//! * **Tessellation edges**: the sharp edges (the angle between the two face normals exceeds
//!   `beta`, default 70 degrees) and the border edges. Face normals are f64 constructions;
//!   this is the paper's heuristic and no guarantee rests on it. Edges next to a zero-area
//!   face are never sharp (their normal is undefined).
//! * **Chains**: the paper's linear-time depth-first linking of the edge soup: a chain
//!   continues through vertices with exactly two tessellation edges and ends at the others;
//!   what is left are closed chains.
//! * **Regions and orientation.** The paper orients each chain "so that the region lies on the
//!   left" by the heuristic that tessellation regions have the larger normal variation. Our
//!   reading, made concrete: cutting the surface along the tessellation edges gives
//!   *patches*; a boundary loop of a patch, run the way the patch's faces run it, has the
//!   patch on its left. A loop is a candidate rim when its patch has at least two boundary
//!   loops (it is a hole *in* the patch: capping the only loop of a disk would duplicate the
//!   disk). When the same edge cycle is a candidate from both sides, the side with the smaller
//!   normal variation is kept as the surface and the other side is the region to fill (the
//!   paper's heuristic); a tie is ambiguous and both sides are tried, the interior test of
//!   [`crate::reduce`] deciding (our stand-in for "the union where ambiguous").

use std::collections::{HashMap, HashSet};

use envelope_mesh::{FaceId, TriangleSoup, VertexId};
use glam::DVec3;
use rustc_hash::FxHashMap;

/// Edge adjacency of a soup: undirected edge -> the faces using it and the direction.
#[derive(Clone, Debug, Default)]
pub struct EdgeMap {
    /// `(min, max)` -> `(face, runs min -> max)`; a fast hasher (the lookups dominate the
    /// cuts of a large surface into patches).
    pub faces: FxHashMap<(VertexId, VertexId), Vec<(FaceId, bool)>>,
    /// The face across edge `k` (from corner `k` to `k + 1`) of face `f`, at `3 f + k`:
    /// `u32::MAX` where the edge does not have exactly two faces. The floods of [`patches`]
    /// read this instead of the map (a large map's lookups miss the cache).
    pub across_at: Vec<u32>,
}

impl EdgeMap {
    /// Builds the map (faces with a repeated index are skipped).
    #[must_use]
    pub fn new(soup: &TriangleSoup) -> Self {
        let mut faces: FxHashMap<(VertexId, VertexId), Vec<(FaceId, bool)>> = FxHashMap::default();
        for f in soup.face_ids() {
            let t = soup.faces[f.index()];
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                continue;
            }
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                faces
                    .entry((a.min(b), a.max(b)))
                    .or_default()
                    .push((f, a < b));
            }
        }
        let mut across_at = vec![u32::MAX; 3 * soup.num_faces()];
        for (&(a, b), fs) in &faces {
            if let [(f, _), (g, _)] = fs.as_slice() {
                for (x, y) in [(*f, *g), (*g, *f)] {
                    let t = soup.faces[x.index()];
                    // The corner of x where the edge a-b starts.
                    let k = (0..3).find(|&k| {
                        let (p, q) = (t[k], t[(k + 1) % 3]);
                        (p.min(q), p.max(q)) == (a, b)
                    });
                    if let Some(k) = k {
                        across_at[3 * x.index() + k] = y.0;
                    }
                }
            }
        }
        EdgeMap { faces, across_at }
    }

    /// The face across the edge `a-b` from `f` (when exactly two faces use it).
    #[must_use]
    pub fn across(&self, f: FaceId, a: VertexId, b: VertexId) -> Option<FaceId> {
        let v = self.faces.get(&(a.min(b), a.max(b)))?;
        if v.len() != 2 {
            return None;
        }
        v.iter().map(|x| x.0).find(|&g| g != f)
    }
}

/// Unit face normals (f64 construction; `None` for zero-area faces).
#[must_use]
pub fn face_normals(soup: &TriangleSoup) -> Vec<Option<DVec3>> {
    soup.face_ids()
        .map(|f| {
            let [a, b, c] = soup.triangle(f);
            (b - a).cross(c - a).try_normalize()
        })
        .collect()
}

/// Six times the signed volume (f64 heuristic): negative when the faces are oriented inward.
pub(crate) fn signed_volume(soup: &TriangleSoup) -> f64 {
    soup.face_ids()
        .map(|f| {
            let [a, b, c] = soup.triangle(f);
            a.dot(b.cross(c))
        })
        .sum()
}

/// The edges with one face (a loop left open), each as `(min, max)`.
pub(crate) fn border_edges(edges: &EdgeMap) -> Vec<(VertexId, VertexId)> {
    edges
        .faces
        .iter()
        .filter(|(_, fs)| fs.len() == 1)
        .map(|(&e, _)| e)
        .collect()
}

/// The tessellation edges (sharp or border), each as `(min, max)`, sorted.
#[must_use]
pub fn tessellation_edges(
    edges: &EdgeMap,
    normals: &[Option<DVec3>],
    beta_degrees: f64,
) -> Vec<(VertexId, VertexId)> {
    let cos_beta = beta_degrees.to_radians().cos();
    let mut out: Vec<(VertexId, VertexId)> = edges
        .faces
        .iter()
        .filter(|(_, fs)| match fs.as_slice() {
            [_] => true,
            [(f, _), (g, _)] => match (normals[f.index()], normals[g.index()]) {
                (Some(n), Some(m)) => n.dot(m) < cos_beta,
                _ => false,
            },
            _ => false,
        })
        .map(|(k, _)| *k)
        .collect();
    out.sort_unstable();
    out
}

/// A tessellation chain: a path of tessellation edges.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Chain {
    /// Its vertices in order (a closed chain does not repeat its first vertex).
    pub vertices: Vec<VertexId>,
    /// Closed (every vertex has exactly two tessellation edges).
    pub closed: bool,
}

/// Links the edge soup into chains by depth-first scanning, in time linear in the number of
/// edges: open chains start at vertices whose tessellation degree is not two, closed chains
/// are what remains.
///
/// ```
/// use envelope_genus::details::link_chains;
/// use envelope_mesh::VertexId;
/// let v = VertexId;
/// // A triangle loop 0-1-2 and a path 3-4-5.
/// let chains = link_chains(&[(v(0), v(1)), (v(1), v(2)), (v(0), v(2)), (v(3), v(4)), (v(4), v(5))]);
/// assert_eq!(chains.iter().filter(|c| c.closed).count(), 1);
/// assert_eq!(chains.iter().filter(|c| !c.closed).count(), 1);
/// ```
#[must_use]
pub fn link_chains(edges: &[(VertexId, VertexId)]) -> Vec<Chain> {
    let mut adj: HashMap<VertexId, Vec<(VertexId, usize)>> = HashMap::new();
    for (i, &(a, b)) in edges.iter().enumerate() {
        adj.entry(a).or_default().push((b, i));
        adj.entry(b).or_default().push((a, i));
    }
    let mut used = vec![false; edges.len()];
    let mut chains = Vec::new();
    let mut starts: Vec<VertexId> = adj.keys().copied().collect();
    starts.sort_unstable();
    let walk = |start: VertexId, first: (VertexId, usize), used: &mut Vec<bool>| {
        let mut vertices = vec![start];
        let (mut cur, mut e) = first;
        loop {
            used[e] = true;
            if cur == start {
                return Chain {
                    vertices,
                    closed: true,
                };
            }
            vertices.push(cur);
            let nb = &adj[&cur];
            if nb.len() != 2 {
                return Chain {
                    vertices,
                    closed: false,
                };
            }
            match nb.iter().find(|&&(_, f)| !used[f]) {
                Some(&(next, f)) => {
                    cur = next;
                    e = f;
                }
                None => {
                    return Chain {
                        vertices,
                        closed: false,
                    };
                }
            }
        }
    };
    for &s in &starts {
        if adj[&s].len() == 2 {
            continue;
        }
        for k in 0..adj[&s].len() {
            let (n, e) = adj[&s][k];
            if !used[e] {
                chains.push(walk(s, (n, e), &mut used));
            }
        }
    }
    for &s in &starts {
        for k in 0..adj[&s].len() {
            let (n, e) = adj[&s][k];
            if !used[e] {
                chains.push(walk(s, (n, e), &mut used));
            }
        }
    }
    chains
}

/// Faces joined across non-tessellation edges.
#[derive(Clone, Debug)]
pub struct Patches {
    /// Patch index of every face (`usize::MAX` for skipped degenerate-index faces).
    pub of_face: Vec<usize>,
    /// Number of patches.
    pub count: usize,
    /// Boundary loops of each patch, as directed vertex cycles run the way the patch runs
    /// them (the patch on the left), with the face owning each edge.
    pub loops: Vec<Vec<PatchLoop>>,
}

/// One boundary loop of a patch.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PatchLoop {
    /// Vertices in order (the edge `vertices[i] -> vertices[i + 1]` is run by `faces[i]`).
    pub vertices: Vec<VertexId>,
    /// The patch face on each edge.
    pub faces: Vec<FaceId>,
}

/// Cuts the surface along `tess` and returns the patches with their boundary loops.
#[must_use]
pub fn patches(
    soup: &TriangleSoup,
    edges: &EdgeMap,
    tess: &HashSet<(VertexId, VertexId)>,
) -> Patches {
    let n = soup.num_faces();
    let mut of_face = vec![usize::MAX; n];
    // Per face corner: the edge from it is cut (in `tess`, or not shared by exactly two faces).
    let cut: Vec<bool> = (0..3 * n)
        .map(|i| {
            let t = soup.faces[i / 3];
            let (a, b) = (t[i % 3], t[(i % 3 + 1) % 3]);
            edges.across_at.get(i).is_none_or(|&g| g == u32::MAX)
                || tess.contains(&(a.min(b), a.max(b)))
        })
        .collect();
    let across = |f: FaceId, k: usize| FaceId(edges.across_at[3 * f.index() + k]);
    let mut count = 0;
    for f in soup.face_ids() {
        let t = soup.faces[f.index()];
        if of_face[f.index()] != usize::MAX || t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            continue;
        }
        let mut stack = vec![f];
        of_face[f.index()] = count;
        while let Some(g) = stack.pop() {
            for k in 0..3 {
                if cut[3 * g.index() + k] {
                    continue;
                }
                let h = across(g, k);
                if of_face[h.index()] == usize::MAX {
                    of_face[h.index()] = count;
                    stack.push(h);
                }
            }
        }
        count += 1;
    }
    // Directed boundary half-edges per patch, linked by rotating around the end vertex.
    let mut loops: Vec<Vec<PatchLoop>> = vec![Vec::new(); count];
    // Boundary half-edges already on a loop, by face and corner.
    let mut visited = vec![false; 3 * n];
    let corner = |f: FaceId, v: VertexId| soup.faces[f.index()].iter().position(|&x| x == v);
    for f in soup.face_ids() {
        let p = of_face[f.index()];
        if p == usize::MAX {
            continue;
        }
        for k in 0..3 {
            if !cut[3 * f.index() + k] || visited[3 * f.index() + k] {
                continue;
            }
            let mut lp = PatchLoop {
                vertices: Vec::new(),
                faces: Vec::new(),
            };
            let (mut g, mut e) = (f, k);
            let mut ok = true;
            loop {
                if std::mem::replace(&mut visited[3 * g.index() + e], true) {
                    ok = (g, e) == (f, k);
                    break;
                }
                let t = soup.faces[g.index()];
                lp.vertices.push(t[e]);
                lp.faces.push(g);
                let b = t[(e + 1) % 3];
                // Rotate around b inside the patch until the next cut edge out of b.
                let (mut h, mut out) = (g, (e + 1) % 3);
                let mut guard = 0;
                loop {
                    if cut[3 * h.index() + out] {
                        break;
                    }
                    let x = across(h, out);
                    match corner(x, b).map(|i| (x, i)) {
                        Some((x, i)) => {
                            h = x;
                            out = i;
                        }
                        None => {
                            ok = false;
                            break;
                        }
                    }
                    guard += 1;
                    if guard > n {
                        ok = false;
                        break;
                    }
                }
                if !ok {
                    break;
                }
                g = h;
                e = out;
            }
            if ok && lp.vertices.len() >= 3 {
                loops[p].push(lp);
            }
        }
    }
    Patches {
        of_face,
        count,
        loops,
    }
}

/// Normal variation of a set of faces: `1 - |sum area * n| / sum area` (0 for a flat patch,
/// towards 1 for a closed or strongly curved one). f64 heuristic.
#[must_use]
pub fn normal_variation(soup: &TriangleSoup, faces: impl Iterator<Item = FaceId>) -> f64 {
    let (mut sum, mut area) = (DVec3::ZERO, 0.0);
    for f in faces {
        let [a, b, c] = soup.triangle(f);
        let n = (b - a).cross(c - a);
        sum += n;
        area += n.length();
    }
    if area > 0.0 {
        1.0 - sum.length() / area
    } else {
        0.0
    }
}
