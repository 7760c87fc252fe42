//! Steps 5 and 6: non-manifold edges and vertices are separated into manifold sheets.
//!
//! At each vertex the faces form fans: two corners at the vertex are in one fan when a chain
//! of its faces joins them, consecutive faces sharing an edge at the vertex that has exactly
//! two faces (either orientation; the orientation step comes after). A vertex with several
//! fans keeps its index for the fan of its first corner and gets one new vertex, at the same
//! position, for each other fan (appended after the input's vertices). An edge with three or
//! more faces joins no fan, so its faces end up on different copies of at least one end: each
//! fan at a vertex holds at most two of them (the two ends of the fan's chain), so every edge
//! afterwards has at most two faces, and every vertex one fan.
//!
//! The point set is unchanged: every triangle keeps its corner positions. The sheets still
//! touch where they were joined (a point, an edge); `envelope check` reports that contact
//! (the copies as duplicate vertices, the faces as intersecting), which this repair cannot
//! move apart without moving the surface. Pairing the faces around a
//! non-manifold edge by their angular order, to keep two of them as one sheet, is not done:
//! any pairing leaves the same contact.

use crate::report::{Change, RepairReport, Step};
use crate::work::{Edges, Work};

/// Union-find over corner slots; the representative is the smallest slot.
struct Fans(Vec<u32>);

impl Fans {
    fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let p = self.0[x as usize];
            self.0[x as usize] = self.0[p as usize];
            x = p;
        }
        x
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        self.0[ra.max(rb) as usize] = ra.min(rb);
    }
}

pub(crate) fn split_sheets(work: &mut Work, report: &mut RepairReport) {
    let edges = Edges::build(work);
    let mut fans = Fans((0..3 * work.faces.len() as u32).collect());
    for g in edges.groups() {
        match *g {
            [s, t] => {
                if Edges::from(work, s) == Edges::from(work, t) {
                    fans.union(s.slot(), t.slot());
                    fans.union(s.next_slot(), t.next_slot());
                } else {
                    fans.union(s.slot(), t.next_slot());
                    fans.union(s.next_slot(), t.slot());
                }
            }
            [s, ..] if g.len() > 2 => {
                let mut faces: Vec<_> = g
                    .iter()
                    .map(|x| work.face_origin[x.face as usize])
                    .collect();
                faces.sort_unstable();
                faces.dedup();
                report.record(Step::NonManifoldEdges, 1, || Change::NonManifoldEdge {
                    edge: [work.input_vertex(s.lo), work.input_vertex(s.hi)],
                    faces,
                });
            }
            _ => {}
        }
    }
    // The vertex of each fan (by its representative slot), first come first served.
    const NONE: u32 = u32::MAX;
    let mut fan_vertex = vec![NONE; 3 * work.faces.len()];
    let mut taken = vec![false; work.positions.len()];
    let mut sheets = vec![0usize; work.positions.len()];
    for f in 0..work.faces.len() {
        let [a, b, c] = work.faces[f];
        if a == b || b == c || a == c {
            // Left by an undecided zero-area step: joins no fan, keeps its vertices.
            continue;
        }
        for i in 0..3 {
            let slot = (3 * f + i) as u32;
            let root = fans.find(slot) as usize;
            let v = work.faces[f][i];
            if fan_vertex[root] == NONE {
                fan_vertex[root] = if taken[v as usize] {
                    let copy = work.positions.len() as u32;
                    work.positions.push(work.pos(v));
                    work.vertex_origin.push(work.input_vertex(v));
                    work.welded_away.push(false);
                    copy
                } else {
                    taken[v as usize] = true;
                    v
                };
                sheets[v as usize] += 1;
            }
            work.faces[f][i] = fan_vertex[root];
        }
    }
    for (v, &n) in sheets.iter().enumerate() {
        if n > 1 {
            report.record(Step::NonManifoldVertices, 1, || Change::VertexSplit {
                vertex: work.input_vertex(v as u32),
                sheets: n,
            });
        }
    }
}
