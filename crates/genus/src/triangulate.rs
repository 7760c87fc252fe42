//! Triangulating a tessellation region from its chain and the diagonal edges (El-Sana and
//! Varshney 1997, section 3.4).
//!
//! * A loop whose vertices are exactly coplanar (orient3d) is triangulated by `spade`'s
//!   constrained Delaunay triangulation of its projection on the coordinate plane the loop's
//!   (f64 Newell) normal is most aligned with; dropping a coordinate is exact, so the
//!   projected problem is the loop itself. Triangles inside the loop are found by parity
//!   across constraint edges. A projected loop that self-intersects, repeats a point or has a
//!   vertex on another edge (spade splits the constraint) is refused.
//! * A non-planar loop is triangulated by the surface-from-contours rule the paper cites:
//!   shortest diagonal first, here as ear clipping that always cuts the ear whose new
//!   diagonal is shortest (f64 lengths only order the choices).
//!
//! Either way the triangles are oriented against the loop (the loop runs as the kept patch
//! runs it, so the cap must run each loop edge the other way). Whether a triangulation is
//! accepted (diagonals alpha-close, triangles inside the prism union) is decided by the caller
//! with exact tests.

use envelope_mesh::{TriangleSoup, VertexId};
use envelope_predicates::{orient2d, orient3d};
use glam::{DVec2, DVec3};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// Triangulates the closed loop `loop_` (vertex ids of `soup`, no repeats), returning the cap
/// triangles oriented against the loop; `None` when the loop cannot be triangulated.
#[must_use]
pub fn triangulate_loop(soup: &TriangleSoup, loop_: &[VertexId]) -> Option<Vec<[VertexId; 3]>> {
    let n = loop_.len();
    if n < 3 {
        return None;
    }
    let pts: Vec<DVec3> = loop_.iter().map(|&v| soup.position(v)).collect();
    // A non-collinear triple.
    let mut triple = None;
    'outer: for j in 1..n {
        for k in j + 1..n {
            if !crate::exact::collinear(pts[0], pts[j], pts[k]) {
                triple = Some((j, k));
                break 'outer;
            }
        }
    }
    let (j, k) = triple?;
    let planar = pts
        .iter()
        .all(|&p| orient3d(pts[0], pts[j], pts[k], p).is_degenerate());
    if planar {
        planar_cdt(&pts, loop_)
    } else {
        ear_clip(&pts, loop_)
    }
}

fn planar_cdt(pts: &[DVec3], loop_: &[VertexId]) -> Option<Vec<[VertexId; 3]>> {
    let n = pts.len();
    let mut normal = DVec3::ZERO;
    for i in 0..n {
        let (p, q) = (pts[i], pts[(i + 1) % n]);
        normal += DVec3::new(
            (p.y - q.y) * (p.z + q.z),
            (p.z - q.z) * (p.x + q.x),
            (p.x - q.x) * (p.y + q.y),
        );
    }
    let proj = crate::exact::dominant_projection(normal);
    let p2: Vec<DVec2> = pts.iter().map(|&p| proj(p)).collect();
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::new();
    let mut handles = Vec::with_capacity(n);
    let mut loop_index = Vec::new();
    for (i, p) in p2.iter().enumerate() {
        let h = cdt.insert(Point2::new(p.x, p.y)).ok()?;
        if h.index() != i {
            return None; // a repeated projected point
        }
        handles.push(h);
        loop_index.push(i);
    }
    for i in 0..n {
        let (a, b) = (handles[i], handles[(i + 1) % n]);
        if !cdt.can_add_constraint(a, b) {
            return None;
        }
        cdt.add_constraint(a, b);
    }
    if cdt.num_constraints() != n {
        return None;
    }
    for i in 0..n {
        let (a, b) = (handles[i], handles[(i + 1) % n]);
        let e = cdt.get_edge_from_neighbors(a, b)?;
        if !cdt.is_constraint_edge(e.as_undirected().fix()) {
            return None;
        }
    }
    // Inside by parity across constraint edges, seeded at the convex hull.
    let faces: Vec<_> = cdt.inner_faces().map(|f| f.fix()).collect();
    let mut inside: std::collections::HashMap<usize, bool> = std::collections::HashMap::new();
    let mut queue = std::collections::VecDeque::new();
    for f in cdt.inner_faces() {
        for e in f.adjacent_edges() {
            if e.rev().face().as_inner().is_none() {
                let v = cdt.is_constraint_edge(e.as_undirected().fix());
                if inside.insert(f.fix().index(), v).is_none() {
                    queue.push_back(f.fix());
                }
            }
        }
    }
    while let Some(fh) = queue.pop_front() {
        let f = cdt.face(fh);
        let mine = inside[&fh.index()];
        for e in f.adjacent_edges() {
            if let Some(g) = e.rev().face().as_inner() {
                let flip = cdt.is_constraint_edge(e.as_undirected().fix());
                let v = mine ^ flip;
                match inside.get(&g.fix().index()) {
                    None => {
                        inside.insert(g.fix().index(), v);
                        queue.push_back(g.fix());
                    }
                    Some(&w) if w != v => return None,
                    Some(_) => {}
                }
            }
        }
    }
    // Loop orientation in the projection, at its lexicographically smallest vertex.
    let m = (0..n).min_by(|&i, &j| {
        p2[i]
            .x
            .total_cmp(&p2[j].x)
            .then(p2[i].y.total_cmp(&p2[j].y))
    })?;
    let loop_orient = orient2d(p2[(m + n - 1) % n], p2[m], p2[(m + 1) % n]);
    if loop_orient.is_degenerate() {
        return None;
    }
    let mut out = Vec::new();
    for fh in faces {
        if !inside.get(&fh.index()).copied().unwrap_or(false) {
            continue;
        }
        let vs = cdt.face(fh).vertices().map(|v| loop_index[v.fix().index()]);
        let o = orient2d(p2[vs[0]], p2[vs[1]], p2[vs[2]]);
        if o.is_degenerate() {
            return None;
        }
        let t = if o == loop_orient {
            [vs[0], vs[2], vs[1]]
        } else {
            vs
        };
        out.push(t.map(|i| loop_[i]));
    }
    (out.len() == n - 2).then_some(out)
}

fn ear_clip(pts: &[DVec3], loop_: &[VertexId]) -> Option<Vec<[VertexId; 3]>> {
    let mut idx: Vec<usize> = (0..pts.len()).collect();
    let mut out = Vec::new();
    while idx.len() > 3 {
        let m = idx.len();
        let best = (0..m)
            .filter(|&i| {
                let (a, b, c) = (idx[(i + m - 1) % m], idx[i], idx[(i + 1) % m]);
                !crate::exact::collinear(pts[a], pts[b], pts[c])
            })
            .min_by(|&i, &j| {
                let d =
                    |i: usize| pts[idx[(i + m - 1) % m]].distance_squared(pts[idx[(i + 1) % m]]);
                d(i).total_cmp(&d(j))
            })?;
        let (a, b, c) = (idx[(best + m - 1) % m], idx[best], idx[(best + 1) % m]);
        out.push([loop_[c], loop_[b], loop_[a]]);
        idx.remove(best);
    }
    let (a, b, c) = (idx[0], idx[1], idx[2]);
    if crate::exact::collinear(pts[a], pts[b], pts[c]) {
        return None;
    }
    out.push([loop_[c], loop_[b], loop_[a]]);
    Some(out)
}
