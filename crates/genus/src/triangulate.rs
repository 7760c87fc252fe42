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

/// Longest loop [`constrained_triangulation`] takes (its tables are quadratic in the loop's
/// length).
pub(crate) const MAX_CONSTRAINED_LOOP: usize = 400;

/// Most triangles [`constrained_triangulation`] asks `allowed` about (exact tests cost), per
/// loop; past it the loop gets no triangulation.
pub(crate) const MAX_TRIANGLE_TESTS: usize = 4000;

/// The least-area triangulation of the closed loop `loop_` (no new vertex) among the
/// triangulations whose diagonals `diagonal(i, j)` accepts and whose triangles `allowed(i, k,
/// j)` accepts (`i < k < j`, loop positions), by dynamic programming over the loop's
/// sub-chains; `None` when there is none or the loop is longer than
/// [`MAX_CONSTRAINED_LOOP`] or needs more than [`MAX_TRIANGLE_TESTS`] tests. Triangles are
/// oriented against the loop. Areas are f64 and only
/// rank the choices; acceptance is the callers' (exact) `diagonal` and `allowed`, and each
/// sub-chain tries its splits cheapest first, so `allowed` is asked as little as possible.
pub(crate) fn constrained_triangulation(
    pts: &[DVec3],
    loop_: &[VertexId],
    diagonal: impl Fn(usize, usize) -> bool,
    mut allowed: impl FnMut(usize, usize, usize) -> bool,
) -> Option<Vec<[VertexId; 3]>> {
    let n = pts.len();
    if !(3..=MAX_CONSTRAINED_LOOP).contains(&n) || loop_.len() != n {
        return None;
    }
    let at = |i: usize, j: usize| i * n + j;
    let mut edge = vec![false; n * n];
    for i in 0..n {
        for j in i + 1..n {
            edge[at(i, j)] = j == i + 1 || (i == 0 && j == n - 1) || diagonal(i, j);
        }
    }
    let mut cost = vec![f64::INFINITY; n * n];
    let mut split = vec![usize::MAX; n * n];
    for i in 0..n - 1 {
        cost[at(i, i + 1)] = 0.0;
    }
    let area = |i: usize, k: usize, j: usize| (pts[k] - pts[i]).cross(pts[j] - pts[i]).length();
    let mut options: Vec<(f64, usize)> = Vec::new();
    let mut tests = 0;
    for d in 2..n {
        for i in 0..n - d {
            let j = i + d;
            if !edge[at(i, j)] {
                continue;
            }
            options.clear();
            for k in i + 1..j {
                if edge[at(i, k)] && edge[at(k, j)] {
                    let c = cost[at(i, k)] + cost[at(k, j)];
                    if c.is_finite() {
                        options.push((c + area(i, k, j), k));
                    }
                }
            }
            options.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut found = None;
            for &(c, k) in &options {
                tests += 1;
                if tests > MAX_TRIANGLE_TESTS {
                    return None;
                }
                if allowed(i, k, j) {
                    found = Some((c, k));
                    break;
                }
            }
            if let Some((c, k)) = found {
                cost[at(i, j)] = c;
                split[at(i, j)] = k;
            }
        }
    }
    if !cost[at(0, n - 1)].is_finite() {
        return None;
    }
    let mut out = Vec::with_capacity(n - 2);
    let mut stack = vec![(0, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j <= i + 1 {
            continue;
        }
        let k = split[at(i, j)];
        out.push([loop_[j], loop_[k], loop_[i]]);
        stack.push((i, k));
        stack.push((k, j));
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// Every loop edge once, run against the loop; every diagonal twice, once each way.
    fn assert_closes_the_loop(loop_: &[VertexId], cap: &[[VertexId; 3]]) {
        let n = loop_.len();
        assert_eq!(cap.len(), n - 2);
        let mut runs: HashMap<(VertexId, VertexId), i32> = HashMap::new();
        for t in cap {
            for k in 0..3 {
                *runs.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        for i in 0..n {
            let (a, b) = (loop_[i], loop_[(i + 1) % n]);
            assert_eq!(runs.get(&(b, a)), Some(&1), "loop edge {a:?}-{b:?}");
            assert_eq!(
                runs.get(&(a, b)),
                None,
                "loop edge {a:?}-{b:?} run the loop's way"
            );
        }
        for (&(a, b), &k) in &runs {
            assert_eq!(k, 1);
            let on_loop = (0..n).any(|i| (loop_[(i + 1) % n], loop_[i]) == (a, b));
            assert!(
                on_loop || runs.get(&(b, a)) == Some(&1),
                "diagonal {a:?}-{b:?} once"
            );
        }
    }

    #[test]
    fn least_area_among_the_allowed_triangles() {
        // A bent strip: two rows of 6 points, the second row lifted out of the plane.
        let pts: Vec<DVec3> = (0..6)
            .map(|i| DVec3::new(f64::from(i), 0.0, 0.0))
            .chain(
                (0..6)
                    .rev()
                    .map(|i| DVec3::new(f64::from(i), 1.0, 0.3 * f64::from(i))),
            )
            .collect();
        let ids: Vec<VertexId> = (0..12).map(VertexId).collect();
        let cap = constrained_triangulation(&pts, &ids, |_, _| true, |_, _, _| true).unwrap();
        assert_closes_the_loop(&ids, &cap);
        // Only "rungs" between the rows within one step in x: the strip triangulation.
        let near = |i: usize, j: usize| (pts[i].x - pts[j].x).abs() <= 1.0;
        let strip = constrained_triangulation(&pts, &ids, near, |_, _, _| true).unwrap();
        assert_closes_the_loop(&ids, &strip);
        let area = |c: &[[VertexId; 3]]| -> f64 {
            c.iter()
                .map(|t| {
                    let [a, b, d] = t.map(|v| pts[v.index()]);
                    (b - a).cross(d - a).length()
                })
                .sum()
        };
        assert!(area(&cap) <= area(&strip) + 1e-12);
        // No triangle allowed: no triangulation; and a loop too long is refused.
        assert!(constrained_triangulation(&pts, &ids, near, |_, _, _| false).is_none());
        let many: Vec<DVec3> = (0..=MAX_CONSTRAINED_LOOP)
            .map(|i| DVec3::new((i as f64).cos(), (i as f64).sin(), 0.0))
            .collect();
        let many_ids: Vec<VertexId> = (0..many.len() as u32).map(VertexId).collect();
        assert!(constrained_triangulation(&many, &many_ids, |_, _| true, |_, _, _| true).is_none());
    }
}
