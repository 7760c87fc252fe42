//! Step 8: vertices no face uses are dropped and the rest renumbered, in order.
//!
//! The point set (of the surface: the union of the faces) is unchanged: an unreferenced
//! vertex is no part of it. Vertices merged away by the weld are dropped here too but were
//! counted there; vertices left unused by a dropped zero-area face are counted here (their
//! positions lie on the faces that covered it).

use crate::report::{Change, RepairReport, Step};
use crate::work::Work;

pub(crate) fn drop_unreferenced(work: &mut Work, report: &mut RepairReport) {
    let mut referenced = vec![false; work.positions.len()];
    for &v in work.faces.iter().flatten() {
        referenced[v as usize] = true;
    }
    let mut new_id = vec![u32::MAX; work.positions.len()];
    let mut kept = 0u32;
    for v in 0..work.positions.len() {
        if referenced[v] {
            new_id[v] = kept;
            kept += 1;
        } else if !work.welded_away[v] {
            report.record(Step::UnreferencedVertices, 1, || Change::VertexDropped {
                vertex: work.vertex_origin[v],
                position: work.positions[v],
            });
        }
    }
    let keep = |v: &usize| referenced[*v];
    work.positions = (0..work.positions.len())
        .filter(keep)
        .map(|v| work.positions[v])
        .collect();
    work.vertex_origin = (0..work.vertex_origin.len())
        .filter(keep)
        .map(|v| work.vertex_origin[v])
        .collect();
    work.welded_away = vec![false; work.positions.len()];
    for v in work.faces.iter_mut().flatten() {
        *v = new_id[*v as usize];
    }
}
