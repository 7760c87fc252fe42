//! Step 4: a face is split at every border vertex lying exactly in the open interior of one
//! of its border edges (a T-junction: the crack between a long edge and the chain of short
//! ones along it; El-Sana and Varshney accept such input, Cohen et al. 7.1 do not).
//!
//! Decided exactly: `point_strictly_inside_segment` (exact collinearity and betweenness).
//! Candidates come from a bounding-volume hierarchy over the border edges' boxes, queried
//! with each border vertex, so the search is bounded by the edges near each vertex.
//!
//! The point set is unchanged: a triangle `abc` with `v` exactly inside `ab` is the union of
//! `avc` and `vbc` (same orientation), neither of zero area since `c` is not on the line
//! `ab` (zero-area faces were dropped by the previous step). A face with several such
//! vertices, on one or more edges, is split one vertex at a time, each piece taking the
//! vertices on its own sides. Only border edges (one face) and border vertices are
//! considered: a vertex inside an edge with two faces is where two sheets cross, which no
//! split repairs (`envelope check` names it).

use envelope_predicates::bvh::{Aabb, Bvh};
use envelope_predicates::point_strictly_inside_segment;

use crate::report::{Change, RepairReport, Step};
use crate::work::{Edges, Side, Work, sort_along};

pub(crate) fn split_t_junctions(work: &mut Work, report: &mut RepairReport) {
    let edges = Edges::build(work);
    let border: Vec<Side> = edges
        .groups()
        .filter(|g| g.len() == 1)
        .map(|g| g[0])
        .collect();
    if border.is_empty() {
        return;
    }
    let mut on_border = vec![false; work.positions.len()];
    for s in &border {
        on_border[s.lo as usize] = true;
        on_border[s.hi as usize] = true;
    }
    let boxes: Vec<Aabb> = border
        .iter()
        .map(|s| Aabb::from_points(&[work.pos(s.lo), work.pos(s.hi)]))
        .collect();
    let tree = Bvh::new(&boxes);
    // (face, corner, vertex): `vertex` inside the face's edge from `corner`.
    let mut found: Vec<(u32, u8, u32)> = Vec::new();
    for v in (0..work.positions.len() as u32).filter(|&v| on_border[v as usize]) {
        let p = work.pos(v);
        tree.for_each_overlapping(&Aabb::from_points(&[p]), |e| {
            let s = border[e as usize];
            if v != s.lo
                && v != s.hi
                && point_strictly_inside_segment(p, work.pos(s.lo), work.pos(s.hi))
            {
                found.push((s.face, s.corner, v));
            }
        });
    }
    if found.is_empty() {
        return;
    }
    found.sort_unstable();
    for &(f, corner, v) in &found {
        let t = work.faces[f as usize];
        let edge = [t[corner as usize], t[(corner as usize + 1) % 3]];
        report.record(Step::TJunctions, 1, || Change::TJunction {
            vertex: work.input_vertex(v),
            edge: edge.map(|x| work.input_vertex(x)),
            face: work.face_origin[f as usize],
        });
    }
    let mut faces = Vec::with_capacity(work.faces.len() + found.len());
    let mut origin = Vec::with_capacity(faces.capacity());
    let mut next = found.iter().peekable();
    for f in 0..work.faces.len() {
        let t = work.faces[f];
        let mut sides: [Vec<u32>; 3] = Default::default();
        while let Some(&&(g, corner, v)) = next.peek() {
            if g as usize != f {
                break;
            }
            sides[corner as usize].push(v);
            next.next();
        }
        for (i, side) in sides.iter_mut().enumerate() {
            sort_along(work, t[i], t[(i + 1) % 3], side);
        }
        let before = faces.len();
        split(t, sides, &mut faces);
        origin.extend(std::iter::repeat_n(
            work.face_origin[f],
            faces.len() - before,
        ));
    }
    work.faces = faces;
    work.face_origin = origin;
}

/// Splits triangle `t` at the vertices inside its sides (`sides[i]`: inside the side from
/// corner `i`, ordered from that corner), pushing the pieces in order.
fn split(t: [u32; 3], sides: [Vec<u32>; 3], out: &mut Vec<[u32; 3]>) {
    let mut stack = vec![(t, sides)];
    while let Some((t, mut sides)) = stack.pop() {
        let Some(i) = (0..3).find(|&i| !sides[i].is_empty()) else {
            out.push(t);
            continue;
        };
        // Rotate so that the side to split runs from corner 0 to corner 1.
        let [a, b, c] = [t[i], t[(i + 1) % 3], t[(i + 2) % 3]];
        let ab = std::mem::take(&mut sides[i]);
        let bc = std::mem::take(&mut sides[(i + 1) % 3]);
        let ca = std::mem::take(&mut sides[(i + 2) % 3]);
        let k = ab.len() / 2;
        let v = ab[k];
        let first = ([a, v, c], [ab[..k].to_vec(), Vec::new(), ca]);
        let second = ([v, b, c], [ab[k + 1..].to_vec(), bc, Vec::new()]);
        // Popped first, pushed last: pieces come out in order from `a` to `b`.
        stack.push(second);
        stack.push(first);
    }
}
