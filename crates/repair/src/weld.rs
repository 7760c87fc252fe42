//! Step 1: referenced vertices at bitwise-equal positions become one.
//!
//! The point set is unchanged: a corner moves to another vertex at exactly the same position.
//! `-0.0` welds with `0.0` (the same point). Unreferenced vertices are left to the last step,
//! so the count here is that of `envelope check`'s duplicate vertices.
//!
//! Attribute seams: attributes (normals, texture coordinates) will be corner data beside the
//! position index, so welding positions never merges two attribute values; a seam stays a
//! seam in the corners' attributes while its positions become one vertex. The weld key stays
//! the position alone.

use crate::report::{Change, RepairReport, Step};
use crate::work::Work;

pub(crate) fn weld(work: &mut Work, report: &mut RepairReport) {
    let mut referenced = vec![false; work.positions.len()];
    for &v in work.faces.iter().flatten() {
        referenced[v as usize] = true;
    }
    // `x + 0.0` maps -0.0 to +0.0 and leaves every finite value unchanged.
    let key = |v: u32| work.pos(v).to_array().map(|x| (x + 0.0).to_bits());
    let mut ids: Vec<u32> = (0..work.positions.len() as u32)
        .filter(|&v| referenced[v as usize])
        .collect();
    ids.sort_unstable_by_key(|&v| (key(v), v));
    let mut to: Vec<u32> = (0..work.positions.len() as u32).collect();
    let mut groups: Vec<&[u32]> = ids
        .chunk_by(|&a, &b| key(a) == key(b))
        .filter(|g| g.len() > 1)
        .collect();
    groups.sort_unstable_by_key(|g| g[0]);
    for g in groups {
        for &v in &g[1..] {
            to[v as usize] = g[0];
            work.welded_away[v as usize] = true;
        }
        report.record(Step::Weld, g.len() - 1, || Change::Weld {
            kept: work.input_vertex(g[0]),
            merged: g[1..].iter().map(|&v| work.input_vertex(v)).collect(),
            position: work.pos(g[0]),
        });
    }
    for v in work.faces.iter_mut().flatten() {
        *v = to[*v as usize];
    }
}
