//! Per-corner attributes carried from an input mesh to a simplified or repaired one.
//!
//! **Seams.** An input edge is a *seam* when its two faces give different texture coordinates
//! or colours (values compared, not indices) at one of its ends; its vertices are *seam
//! vertices*. The simplifiers are told to keep seam vertices (never removed nor moved,
//! `SimplifyOptions::keep`), so every seam edge survives: a vertex removal, a slide or an
//! edge collapse only deletes edges at the vertex it removes or moves, and a global region
//! (a disk around connected removed vertices) only edges with a removed end. This is a
//! first, sound step: the issue's "seam edges removed only along the seam, within border
//! tubes" would need tubes around seam polylines and is not done; seams cost their vertices.
//! Normal creases are *not* kept (flat-shaded meshes would not simplify at all).
//!
//! **Values**, decided combinatorially, then by one f64 construction:
//! * the output edges that join two input vertices along an input seam edge cut the output
//!   into *output charts*; each takes the input chart (faces connected across non-seam edges)
//!   of its first corner at an input vertex;
//! * a corner at an input vertex (its f64 position bitwise equal to one: kept and unmoved
//!   vertices keep their positions exactly) gets that vertex's value **exactly**: the only one
//!   when it is no seam vertex, else the one of the input face on the same side of the first
//!   seam edge met turning around it in the output (the input face with the same directed
//!   edge is on the same side, orientations agreeing);
//! * any other corner (a moved vertex) gets the value interpolated barycentrically at the
//!   closest point of its output chart's input chart (an f64 construction; a tree per chart,
//!   built only for charts with moved vertices). A chart whose seam does not cut it apart (a
//!   cylinder's seam line) may give a moved vertex next to its seam the far side's value: a
//!   smear inside one face, not a tear, since every corner of a moved vertex in one output
//!   chart gets the same value.
//!
//! **Normals**: a corner of an output face that is an input face (the same three vertices in
//! the same turn) keeps its input normal exactly; any other corner gets the area-weighted
//! normal of the output faces around its vertex up to the nearest *sharp* output edges, an
//! output edge being sharp when it joins two input vertices along a path of input edges
//! whose inner vertices are all gone from the output (an input edge itself, or a crease whose
//! middle vertices were removed; at most [`SHARP_PATH_LIMIT`] vertices are visited), every
//! edge of the path one whose faces gave different normals at either end.
//!
//! No guarantee rests on anything here (the certificate is about positions only), so nothing
//! here needs an exact predicate.

use std::collections::{HashMap, HashSet};

use envelope_mesh::{Attributes, FaceId, TriangleSoup, Wedges};
use envelope_predicates::bvh::{Bvh, NodeKind};
use glam::DVec3;

use crate::Mesh;

/// Directed edge `a -> b` to the face holding it and the corner of `a` in that face.
type Edges = HashMap<(u32, u32), (u32, u8)>;

fn directed_edges(faces: &[[u32; 3]]) -> Edges {
    let mut out = HashMap::with_capacity(faces.len() * 3);
    for (f, t) in faces.iter().enumerate() {
        for k in 0..3 {
            // The first face wins on a non-manifold input (which the check refuses anyway).
            out.entry((t[k], t[(k + 1) % 3]))
                .or_insert((f as u32, k as u8));
        }
    }
    out
}

fn undirected(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

fn faces_of(soup: &TriangleSoup) -> Vec<[u32; 3]> {
    soup.faces.iter().map(|f| f.map(|v| v.0)).collect()
}

/// Whether the edge from corner `k` to corner `k + 1` of face `f` and its twin (corner `j`
/// of face `g` holding the reverse edge) give `w` different values at either end.
fn differs<const N: usize>(w: &Wedges<N>, f: usize, k: usize, g: usize, j: usize) -> bool {
    w.value(f, k) != w.value(g, (j + 1) % 3) || w.value(f, (k + 1) % 3) != w.value(g, j)
}

/// The input edges (undirected) whose two faces give different values of the chosen
/// attributes at an end.
fn split_edges(
    edges: &Edges,
    differ: impl Fn(usize, usize, usize, usize) -> bool,
) -> HashSet<(u32, u32)> {
    let mut out = HashSet::new();
    for (&(a, b), &(f, k)) in edges {
        if a < b
            && let Some(&(g, j)) = edges.get(&(b, a))
            && differ(f as usize, k as usize, g as usize, j as usize)
        {
            out.insert((a, b));
        }
    }
    out
}

fn seam_edges(a: &Attributes, edges: &Edges) -> HashSet<(u32, u32)> {
    split_edges(edges, |f, k, g, j| {
        a.texcoords.as_ref().is_some_and(|w| differs(w, f, k, g, j))
            || a.colors.as_ref().is_some_and(|w| differs(w, f, k, g, j))
    })
}

/// The vertices on a texture-coordinate or colour seam, by input vertex id: what the
/// simplifiers must keep (`SimplifyOptions::keep`).
///
/// ```
/// use envelope::{seam_vertices, Attributes, Mesh, Wedges};
/// // Two triangles of a square whose shared edge 0-2 has u 0 on one side and 1 on the other.
/// let square = Mesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let uv = Wedges {
///     values: vec![[0.0, 0.0], [1.0, 0.0]],
///     corners: vec![[0, 0, 0], [1, 1, 1]],
/// };
/// let square = square.with_attributes(Attributes { texcoords: Some(uv), ..Attributes::default() })?;
/// assert_eq!(seam_vertices(&square), [true, false, true, false]);
/// # Ok::<(), envelope::MeshError>(())
/// ```
#[must_use]
pub fn seam_vertices(mesh: &Mesh) -> Vec<bool> {
    let soup = mesh.soup();
    let mut keep = vec![false; soup.num_vertices()];
    let a = mesh.attributes();
    if a.texcoords.is_none() && a.colors.is_none() {
        return keep;
    }
    let edges = directed_edges(&faces_of(soup));
    for (u, v) in seam_edges(a, &edges) {
        keep[u as usize] = true;
        keep[v as usize] = true;
    }
    keep
}

/// The input's tables for carrying.
struct Source<'a> {
    soup: &'a TriangleSoup,
    faces: Vec<[u32; 3]>,
    edges: Edges,
    seams: HashSet<(u32, u32)>,
    sharp: HashSet<(u32, u32)>,
    /// Per vertex, its neighbours across sharp edges.
    sharp_neighbours: HashMap<u32, Vec<u32>>,
    seam_vertex: Vec<bool>,
    /// A corner (face, index) of each vertex (`u32::MAX` for an unused one).
    corner_of: Vec<(u32, u8)>,
    /// The chart of each face: faces connected across non-seam edges.
    chart: Vec<u32>,
    /// Input vertex of each position (bits).
    by_position: HashMap<[u64; 3], u32>,
}

fn bits(p: DVec3) -> [u64; 3] {
    p.to_array().map(f64::to_bits)
}

impl<'a> Source<'a> {
    fn new(soup: &'a TriangleSoup, attributes: &'a Attributes) -> Self {
        let faces = faces_of(soup);
        let edges = directed_edges(&faces);
        let seams = seam_edges(attributes, &edges);
        let sharp = match &attributes.normals {
            Some(n) => split_edges(&edges, |f, k, g, j| differs(n, f, k, g, j)),
            None => HashSet::new(),
        };
        let mut seam_vertex = vec![false; soup.num_vertices()];
        for &(a, b) in &seams {
            seam_vertex[a as usize] = true;
            seam_vertex[b as usize] = true;
        }
        let mut corner_of = vec![(u32::MAX, 0u8); soup.num_vertices()];
        for (f, t) in faces.iter().enumerate() {
            for (k, &v) in t.iter().enumerate() {
                if corner_of[v as usize].0 == u32::MAX {
                    corner_of[v as usize] = (f as u32, k as u8);
                }
            }
        }
        let mut by_position = HashMap::with_capacity(soup.num_vertices());
        for (v, &(f, _)) in corner_of.iter().enumerate() {
            if f != u32::MAX {
                by_position
                    .entry(bits(soup.positions[v]))
                    .or_insert(v as u32);
            }
        }
        let chart = components(faces.len(), |f, out| {
            let t = faces[f];
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if !seams.contains(&undirected(a, b))
                    && let Some(&(g, _)) = edges.get(&(b, a))
                {
                    out.push(g as usize);
                }
            }
        });
        Source {
            soup,
            faces,
            edges,
            seams,
            sharp_neighbours: {
                let mut m: HashMap<u32, Vec<u32>> = HashMap::new();
                for &(a, b) in &sharp {
                    m.entry(a).or_default().push(b);
                    m.entry(b).or_default().push(a);
                }
                for list in m.values_mut() {
                    list.sort_unstable();
                }
                m
            },
            sharp,
            seam_vertex,
            corner_of,
            chart,
            by_position,
        }
    }
}

/// Connected components of `n` items under `neighbours`, numbered in order of their first
/// item.
fn components(n: usize, neighbours: impl Fn(usize, &mut Vec<usize>)) -> Vec<u32> {
    let mut id = vec![u32::MAX; n];
    let mut next = 0u32;
    let (mut stack, mut around) = (Vec::new(), Vec::new());
    for s in 0..n {
        if id[s] != u32::MAX {
            continue;
        }
        id[s] = next;
        stack.push(s);
        while let Some(f) = stack.pop() {
            around.clear();
            neighbours(f, &mut around);
            for &g in &around {
                if id[g] == u32::MAX {
                    id[g] = next;
                    stack.push(g);
                }
            }
        }
        next += 1;
    }
    id
}

/// The output's tables: faces, directed edges, and each vertex's input vertex.
struct Target<'a> {
    soup: &'a TriangleSoup,
    faces: Vec<[u32; 3]>,
    edges: Edges,
    origin: Vec<Option<u32>>,
    /// Per input vertex, whether an output vertex is at its position.
    present: Vec<bool>,
}

impl<'a> Target<'a> {
    fn new(soup: &'a TriangleSoup, source: &Source<'_>) -> Self {
        let faces = faces_of(soup);
        let edges = directed_edges(&faces);
        let origin: Vec<Option<u32>> = soup
            .positions
            .iter()
            .map(|&p| source.by_position.get(&bits(p)).copied())
            .collect();
        let mut present = vec![false; source.soup.num_vertices()];
        for &v in origin.iter().flatten() {
            present[v as usize] = true;
        }
        Target {
            soup,
            faces,
            edges,
            origin,
            present,
        }
    }

    /// Whether output edge `v-w` lies on an input edge of `set`.
    fn on(&self, set: &HashSet<(u32, u32)>, v: u32, w: u32) -> bool {
        match (self.origin[v as usize], self.origin[w as usize]) {
            (Some(a), Some(b)) => set.contains(&undirected(a, b)),
            _ => false,
        }
    }

    /// Turns around the vertex of corner `k` of face `f`, first across outgoing edges then
    /// across incoming ones, until an edge `cut` says stops it (or the border, or the start).
    /// Returns the corners met and the first stopping edge each way (`v -> w` outgoing,
    /// `w -> v` incoming), as the far vertex `w`.
    fn fan(&self, f: usize, k: usize, cut: impl Fn(u32, u32) -> bool) -> Fan {
        let v = self.faces[f][k];
        let mut fan = Fan {
            corners: vec![(f as u32, k as u8)],
            outgoing: None,
            incoming: None,
        };
        let limit = self.faces.len();
        let (mut g, mut j) = (f, k);
        for _ in 0..limit {
            let a = self.faces[g][(j + 1) % 3];
            if cut(v, a) {
                fan.outgoing = Some(a);
                break;
            }
            match self.edges.get(&(a, v)) {
                Some(&(h, ja)) if h as usize != f => {
                    (g, j) = (h as usize, (ja as usize + 1) % 3);
                    fan.corners.push((g as u32, j as u8));
                }
                _ => break,
            }
        }
        if fan.outgoing.is_none() && fan.corners.len() > 1 && self.closes(&fan, f, v) {
            // Around an inner vertex without a stop: the whole fan is met.
            return fan;
        }
        let (mut g, mut j) = (f, k);
        for _ in 0..limit {
            let b = self.faces[g][(j + 2) % 3];
            if cut(b, v) {
                fan.incoming = Some(b);
                break;
            }
            match self.edges.get(&(v, b)) {
                Some(&(h, jv)) if h as usize != f => {
                    (g, j) = (h as usize, jv as usize);
                    fan.corners.push((g as u32, j as u8));
                }
                _ => break,
            }
        }
        fan
    }
}

impl Target<'_> {
    /// Whether turning across outgoing edges from face `f` came back to it.
    fn closes(&self, fan: &Fan, f: usize, v: u32) -> bool {
        let &(g, j) = fan.corners.last().unwrap_or(&(f as u32, 0));
        let a = self.faces[g as usize][(j as usize + 1) % 3];
        self.edges
            .get(&(a, v))
            .is_some_and(|&(h, _)| h as usize == f)
    }
}

/// How many input vertices a search for a sharp path between two output vertices visits at
/// most (keeps the normals' cost linear; a longer merged crease is then not sharp).
const SHARP_PATH_LIMIT: usize = 256;

/// Whether output edge `v-w` is sharp (see the module docs): its ends are input vertices
/// joined by a path of sharp input edges through input vertices the output no longer has.
fn sharp_between(s: &Source<'_>, t: &Target<'_>, v: u32, w: u32) -> bool {
    let (Some(a), Some(b)) = (t.origin[v as usize], t.origin[w as usize]) else {
        return false;
    };
    if s.sharp.contains(&undirected(a, b)) {
        return true;
    }
    let mut seen: HashSet<u32> = HashSet::from([a]);
    let mut stack = vec![a];
    while let Some(x) = stack.pop() {
        for &y in s.sharp_neighbours.get(&x).map_or(&[][..], Vec::as_slice) {
            if y == b {
                return true;
            }
            if !t.present[y as usize] && seen.len() < SHARP_PATH_LIMIT && seen.insert(y) {
                stack.push(y);
            }
        }
    }
    false
}

/// What [`Target::fan`] found.
struct Fan {
    corners: Vec<(u32, u8)>,
    outgoing: Option<u32>,
    incoming: Option<u32>,
}

/// The input corner (face, index) whose value an output corner takes exactly, when it is at
/// an input vertex and its side of the seams is found.
fn exact_corner(s: &Source<'_>, t: &Target<'_>, f: usize, k: usize) -> Option<(u32, u8)> {
    let v = t.faces[f][k];
    let iv = t.origin[v as usize]?;
    if !s.seam_vertex[iv as usize] {
        return Some(s.corner_of[iv as usize]);
    }
    let fan = t.fan(f, k, |a, b| t.on(&s.seams, a, b));
    if let Some(w) = fan.outgoing
        && let Some(iw) = t.origin[w as usize]
        && let Some(&(g, j)) = s.edges.get(&(iv, iw))
    {
        return Some((g, j));
    }
    if let Some(w) = fan.incoming
        && let Some(iw) = t.origin[w as usize]
        && let Some(&(g, j)) = s.edges.get(&(iw, iv))
    {
        return Some((g, (j + 1) % 3));
    }
    None
}

/// The closest point of triangle `abc` to `p`, as barycentric weights (Ericson 5.1.5).
fn closest_weights(p: DVec3, [a, b, c]: [DVec3; 3]) -> [f64; 3] {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return [0.0, 1.0, 0.0];
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return [1.0 - v, v, 0.0];
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return [0.0, 0.0, 1.0];
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return [1.0 - w, 0.0, w];
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return [0.0, 1.0 - w, w];
    }
    let denom = va + vb + vc;
    if denom.abs() < f64::MIN_POSITIVE || !denom.is_finite() {
        // A zero-area face: its first corner.
        return [1.0, 0.0, 0.0];
    }
    let (v, w) = (vb / denom, vc / denom);
    [1.0 - v - w, v, w]
}

/// The input faces of one chart with a tree over them, for closest points.
struct ChartTree {
    faces: Vec<u32>,
    tree: Bvh,
}

impl ChartTree {
    fn new(s: &Source<'_>, faces: Vec<u32>) -> Self {
        let tris: Vec<[u32; 3]> = faces.iter().map(|&f| s.faces[f as usize]).collect();
        ChartTree {
            tree: Bvh::from_triangles(&s.soup.positions, &tris),
            faces,
        }
    }

    /// The input face closest to `p` and the weights of the closest point in it.
    fn closest(&self, s: &Source<'_>, p: DVec3) -> Option<(u32, [f64; 3])> {
        let mut best: Option<(f64, u32, [f64; 3])> = None;
        let mut stack = vec![self.tree.root()?];
        while let Some(n) = stack.pop() {
            if best.is_some_and(|b| self.tree.bounds(n).sq_distance_lower_bound(p) > b.0) {
                continue;
            }
            match self.tree.kind(n) {
                NodeKind::Leaf(items) => {
                    for &i in items {
                        let f = self.faces[i as usize];
                        let tri = s.faces[f as usize].map(|v| s.soup.positions[v as usize]);
                        let w = closest_weights(p, tri);
                        let q = tri[0] * w[0] + tri[1] * w[1] + tri[2] * w[2];
                        let d = q.distance_squared(p);
                        if best.is_none_or(|b| d < b.0 || (d == b.0 && f < b.1)) {
                            best = Some((d, f, w));
                        }
                    }
                }
                NodeKind::Interior(a, b) => {
                    let (da, db) = (
                        self.tree.bounds(a).sq_distance_lower_bound(p),
                        self.tree.bounds(b).sq_distance_lower_bound(p),
                    );
                    // The nearer child is visited first.
                    if da <= db {
                        stack.extend([b, a]);
                    } else {
                        stack.extend([a, b]);
                    }
                }
            }
        }
        best.map(|(_, f, w)| (f, w))
    }
}

/// Per-corner values collected into a table without repeats (bitwise).
struct Collect<const N: usize> {
    index: HashMap<[u64; N], u32>,
    wedges: Wedges<N>,
}

impl<const N: usize> Collect<N> {
    fn new(faces: usize) -> Self {
        Collect {
            index: HashMap::new(),
            wedges: Wedges {
                values: Vec::new(),
                corners: vec![[0; 3]; faces],
            },
        }
    }

    fn set(&mut self, f: usize, k: usize, value: [f64; N]) {
        let values = &mut self.wedges.values;
        let i = *self
            .index
            .entry(value.map(f64::to_bits))
            .or_insert_with(|| {
                values.push(value);
                (values.len() - 1) as u32
            });
        self.wedges.corners[f][k] = i;
    }
}

fn interpolate<const N: usize>(w: &Wedges<N>, f: usize, weights: [f64; 3]) -> [f64; N] {
    let mut out = [0.0; N];
    for (k, &wk) in weights.iter().enumerate() {
        for (o, x) in out.iter_mut().zip(w.value(f, k)) {
            *o += wk * x;
        }
    }
    out
}

/// Where an output corner's texture coordinate and colour come from.
#[derive(Clone, Copy)]
enum Origin {
    /// Exactly an input corner's.
    Corner(u32, u8),
    /// Interpolated in an input face.
    Inside(u32, [f64; 3]),
}

/// The attributes of `output`, a simplification of `input` whose kept and unmoved vertices
/// keep their input positions bitwise (as `Simplifier` and `Lod` outputs do; moved vertices
/// are the others): see the module docs. Empty when `input` has none. `Simplifier::run`
/// and `Lod::level_mesh` call it; it is public for outputs made by other means. A
/// [`quality`](Attributes::quality) is dropped: it is a value derived from the input's surface
/// (an error map's bounds), which the output no longer has.
///
/// ```
/// use envelope::{carry_attributes, Attributes, Mesh, Wedges};
/// let square = Mesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let uv = Wedges {
///     values: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
///     corners: vec![[0, 1, 2], [0, 2, 3]],
/// };
/// let square = square.with_attributes(Attributes { texcoords: Some(uv), ..Attributes::default() })?;
/// // The same square cut along the other diagonal: every corner is an input vertex.
/// let other = Mesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 3], [1, 2, 3]],
/// )?;
/// let carried = carry_attributes(&square, other.soup());
/// assert_eq!(carried.texcoords.unwrap().value(1, 1), [1.0, 1.0]);
/// # Ok::<(), envelope::MeshError>(())
/// ```
#[must_use]
pub fn carry_attributes(input: &Mesh, output: &TriangleSoup) -> Attributes {
    let a = input.attributes();
    if a.is_empty() {
        return Attributes::default();
    }
    let s = Source::new(input.soup(), a);
    let t = Target::new(output, &s);
    let n = t.faces.len();
    let need_charts = a.texcoords.is_some() || a.colors.is_some();
    let mut from: Vec<[Option<Origin>; 3]> = vec![[None; 3]; n];
    if need_charts {
        carry_charts(&s, &t, &mut from);
    }
    let mut out = Attributes::default();
    if let Some(w) = &a.texcoords {
        out.texcoords = Some(values_from(w, &from));
    }
    if let Some(w) = &a.colors {
        out.colors = Some(values_from(w, &from));
    }
    if let Some(w) = &a.normals {
        out.normals = Some(normals(&s, &t, w));
    }
    out
}

/// Decides where each output corner's chart-bound values come from.
fn carry_charts(s: &Source<'_>, t: &Target<'_>, from: &mut [[Option<Origin>; 3]]) {
    let n = t.faces.len();
    for (f, corners) in from.iter_mut().enumerate() {
        for (k, c) in corners.iter_mut().enumerate() {
            *c = exact_corner(s, t, f, k).map(|(g, j)| Origin::Corner(g, j));
        }
    }
    // Output charts: faces connected across output edges that are not on input seams.
    let component = components(n, |f, out| {
        let tri = t.faces[f];
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if !t.on(&s.seams, a, b)
                && let Some(&(g, _)) = t.edges.get(&(b, a))
            {
                out.push(g as usize);
            }
        }
    });
    let count = component.iter().map(|&c| c as usize + 1).max().unwrap_or(0);
    let mut chart_of: Vec<Option<u32>> = vec![None; count];
    for (f, corners) in from.iter().enumerate() {
        let c = &mut chart_of[component[f] as usize];
        if c.is_none()
            && let Some(Origin::Corner(g, _)) = corners.iter().flatten().next()
        {
            *c = Some(s.chart[*g as usize]);
        }
    }
    // A tree per chart that has a moved corner, over the chart's input faces.
    let mut by_chart: Vec<Vec<u32>> = Vec::new();
    let mut trees: HashMap<Option<u32>, ChartTree> = HashMap::new();
    for f in 0..n {
        for k in 0..3 {
            if from[f][k].is_some() {
                continue;
            }
            if by_chart.is_empty() {
                let charts = s.chart.iter().map(|&c| c as usize + 1).max().unwrap_or(0);
                by_chart = vec![Vec::new(); charts];
                for (g, &c) in s.chart.iter().enumerate() {
                    by_chart[c as usize].push(g as u32);
                }
            }
            let chart = chart_of[component[f] as usize];
            let tree = trees.entry(chart).or_insert_with(|| {
                let faces = match chart {
                    Some(c) => std::mem::take(&mut by_chart[c as usize]),
                    None => (0..s.faces.len() as u32).collect(),
                };
                ChartTree::new(s, faces)
            });
            let p = t.soup.positions[t.faces[f][k] as usize];
            from[f][k] = tree.closest(s, p).map(|(g, w)| Origin::Inside(g, w));
        }
    }
}

fn values_from<const N: usize>(w: &Wedges<N>, from: &[[Option<Origin>; 3]]) -> Wedges<N> {
    let mut out = Collect::new(from.len());
    for (f, corners) in from.iter().enumerate() {
        for (k, c) in corners.iter().enumerate() {
            let value = match *c {
                Some(Origin::Corner(g, j)) => w.value(g as usize, j as usize),
                Some(Origin::Inside(g, weights)) => interpolate(w, g as usize, weights),
                // Only for an input without faces, which no simplifier accepts.
                None => [0.0; N],
            };
            out.set(f, k, value);
        }
    }
    out.wedges
}

/// Output normals (see the module docs).
fn normals(s: &Source<'_>, t: &Target<'_>, w: &Wedges<3>) -> Wedges<3> {
    let mut out = Collect::new(t.faces.len());
    let face_normal = |f: usize| {
        let [a, b, c] = t.faces[f].map(|v| t.soup.positions[v as usize]);
        (b - a).cross(c - a)
    };
    for (f, tri) in t.faces.iter().enumerate() {
        // An input face, unchanged: its corners' normals exactly.
        let same = match tri.map(|v| t.origin[v as usize]) {
            [Some(a), Some(b), Some(c)] => s
                .edges
                .get(&(a, b))
                .filter(|&&(g, j)| s.faces[g as usize][(j as usize + 2) % 3] == c),
            _ => None,
        };
        if let Some(&(g, j)) = same {
            for k in 0..3 {
                out.set(f, k, w.value(g as usize, (j as usize + k) % 3));
            }
            continue;
        }
        for k in 0..3 {
            let fan = t.fan(f, k, |a, b| sharp_between(s, t, a, b));
            let sum: DVec3 = fan
                .corners
                .iter()
                .map(|&(g, _)| face_normal(g as usize))
                .sum();
            let n = sum
                .try_normalize()
                .or_else(|| face_normal(f).try_normalize())
                .unwrap_or(DVec3::Z);
            out.set(f, k, n.to_array());
        }
    }
    out.wedges
}

/// The attributes of `output`, made by `envelope_repair` from `input` with `face_origin[f]`
/// the input face of output face `f`: a corner at one of its input face's corner positions
/// (bitwise) takes that corner's value exactly (a kept or flipped face, a split vertex's
/// copy), any other (a T-junction piece's new corner, on an edge of its input face) the
/// value interpolated at its position in that face.
pub(crate) fn carry_through_repair(
    input: &Mesh,
    output: &TriangleSoup,
    face_origin: &[FaceId],
) -> Attributes {
    let a = input.attributes();
    if a.is_empty() {
        return Attributes::default();
    }
    let soup = input.soup();
    let from: Vec<[Option<Origin>; 3]> = output
        .faces
        .iter()
        .zip(face_origin)
        .map(|(tri, g)| {
            let corners = soup.faces[g.index()].map(|v| soup.positions[v.index()]);
            tri.map(|v| {
                let p = output.positions[v.index()];
                let g = g.index() as u32;
                Some(match corners.iter().position(|&q| bits(q) == bits(p)) {
                    Some(j) => Origin::Corner(g, j as u8),
                    None => Origin::Inside(g, closest_weights(p, corners)),
                })
            })
        })
        .collect();
    Attributes {
        texcoords: a.texcoords.as_ref().map(|w| values_from(w, &from)),
        normals: a.normals.as_ref().map(|w| values_from(w, &from)),
        colors: a.colors.as_ref().map(|w| values_from(w, &from)),
        // A derived value of the input (an error map's bounds): not carried, like in
        // `carry_attributes`.
        quality: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_weights_of_inside_edge_and_corner_points() {
        let tri = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let w = closest_weights(DVec3::new(0.25, 0.25, 3.0), tri);
        assert!((w[0] - 0.5).abs() < 1e-15 && (w[1] - 0.25).abs() < 1e-15);
        assert_eq!(
            closest_weights(DVec3::new(-1.0, -1.0, 0.0), tri),
            [1.0, 0.0, 0.0]
        );
        let w = closest_weights(DVec3::new(0.5, -2.0, 0.0), tri);
        assert_eq!(w, [0.5, 0.5, 0.0]);
    }
}
