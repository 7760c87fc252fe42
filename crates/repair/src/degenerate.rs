//! Step 3: zero-area faces whose points are proved to lie on the other faces are dropped;
//! any other zero-area face refuses the repair, named.
//!
//! A face is of zero area when two corners are the same vertex (after the weld: the same
//! position) or its corners are exactly collinear (`collinear`, exact). Its point set is then
//! a segment, between its two extreme corners, or a point. The segment is cut at every vertex
//! of a non-degenerate face, and at its own middle corner, lying exactly in its open interior
//! (`point_strictly_inside_segment`), and each piece between consecutive cuts must lie in one
//! closed non-degenerate face: both its ends located in that face by the exact
//! `point_in_triangle` (a closed triangle is convex, so the piece between them is in it too).
//! So a sliver along a chain of edges (a crack filled with zero-area faces) is covered piece
//! by piece. Candidates come from a bounding-volume hierarchy over the non-degenerate faces,
//! so the search is bounded by the faces near the segment, not by all faces.
//!
//! Only non-degenerate faces cover, so no proof leans on a face dropped by another. This is a
//! sufficient test, not a complete one: a segment covered only where it crosses faces at
//! points that are no vertex is refused, which never drops geometry.

use envelope_predicates::bvh::{Aabb, Bvh};
use envelope_predicates::{
    TriangleLocation, collinear, point_in_triangle, point_strictly_inside_segment,
};
use glam::DVec3;

use crate::error::RepairError;
use crate::report::{Change, RepairReport, Step};
use crate::work::{Work, sort_along};

/// Whether working triangle `t` has zero area (repeated vertex or exactly collinear corners).
pub(crate) fn zero_area(work: &Work, t: [u32; 3]) -> bool {
    let [a, b, c] = t;
    a == b || b == c || a == c || collinear(work.pos(a), work.pos(b), work.pos(c))
}

pub(crate) fn drop_covered(work: &mut Work, report: &mut RepairReport) -> Result<(), RepairError> {
    let degenerate: Vec<bool> = work.faces.iter().map(|&t| zero_area(work, t)).collect();
    if !degenerate.contains(&true) {
        return Ok(());
    }
    let good: Vec<u32> = (0..work.faces.len() as u32)
        .filter(|&f| !degenerate[f as usize])
        .collect();
    let good_faces: Vec<[u32; 3]> = good.iter().map(|&f| work.faces[f as usize]).collect();
    let tree = Bvh::from_triangles(&work.positions, &good_faces);
    // The smallest non-degenerate face holding both `p` and `q` (closed triangles).
    let cover = |p: DVec3, q: DVec3| {
        let mut best: Option<u32> = None;
        tree.for_each_overlapping(&Aabb::from_points(&[p, q]), |i| {
            let f = good[i as usize];
            if best.is_some_and(|b| b <= f) {
                return;
            }
            let t = work.triangle(f as usize);
            if point_in_triangle(p, t) != TriangleLocation::Outside
                && point_in_triangle(q, t) != TriangleLocation::Outside
            {
                best = Some(f);
            }
        });
        best
    };
    // The vertices of non-degenerate faces strictly inside segment `uw`.
    let cuts = |u: u32, w: u32| {
        let (p, q) = (work.pos(u), work.pos(w));
        let mut out = Vec::new();
        tree.for_each_overlapping(&Aabb::from_points(&[p, q]), |i| {
            for v in good_faces[i as usize] {
                if point_strictly_inside_segment(work.pos(v), p, q) {
                    out.push(v);
                }
            }
        });
        out
    };
    for f in (0..work.faces.len()).filter(|&f| degenerate[f]) {
        let mut d = work.faces[f].to_vec();
        d.sort_unstable();
        d.dedup();
        let inside = |m: u32, x: u32, y: u32| {
            point_strictly_inside_segment(work.pos(m), work.pos(x), work.pos(y))
        };
        // The extreme corners, and the middle one (collinear and distinct: one is between).
        let (u, w, middle) = match d[..] {
            [u] => (u, u, None),
            [u, w] => (u, w, None),
            [a, b, c] if inside(a, b, c) => (b, c, Some(a)),
            [a, b, c] if inside(b, a, c) => (a, c, Some(b)),
            [a, b, c] => (a, b, Some(c)),
            _ => continue,
        };
        let mut points = if u == w { Vec::new() } else { cuts(u, w) };
        points.extend(middle);
        points.sort_unstable();
        points.dedup();
        sort_along(work, u, w, &mut points);
        let mut chain = vec![u];
        chain.extend(points);
        chain.push(w);
        let pieces: Vec<(u32, u32)> = chain.windows(2).map(|p| (p[0], p[1])).collect();
        let mut covered_by = Vec::new();
        for (u, w) in pieces {
            match cover(work.pos(u), work.pos(w)) {
                Some(g) => covered_by.push(work.face_origin[g as usize]),
                None => {
                    return Err(RepairError::UncoveredDegenerateFace {
                        face: work.face_origin[f],
                        corners: work.input_corners(f),
                    });
                }
            }
        }
        report.record(Step::DegenerateFaces, 1, || Change::DegenerateFace {
            face: work.face_origin[f],
            corners: work.input_corners(f),
            covered_by,
        });
    }
    let keep: Vec<bool> = degenerate.iter().map(|d| !d).collect();
    work.retain_faces(&keep);
    Ok(())
}
