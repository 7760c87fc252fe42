//! Step 2: faces on the same three vertices (in either orientation) after the weld: the
//! first of each group is kept, the others dropped.
//!
//! The point set is unchanged: a dropped face is the same closed triangle as the one kept.
//! A pair written in opposite orientations (a two-sided sheet) keeps the first face's
//! orientation; the orientation step may flip it later.

use crate::report::{Change, RepairReport, Step};
use crate::work::Work;

pub(crate) fn drop_duplicates(work: &mut Work, report: &mut RepairReport) {
    let mut keys: Vec<([u32; 3], u32)> = work
        .faces
        .iter()
        .enumerate()
        .map(|(f, t)| {
            let mut k = *t;
            k.sort_unstable();
            (k, f as u32)
        })
        .collect();
    keys.sort_unstable();
    let mut keep = vec![true; work.faces.len()];
    let mut pairs = Vec::new();
    for group in keys.chunk_by(|a, b| a.0 == b.0) {
        for g in &group[1..] {
            keep[g.1 as usize] = false;
            pairs.push((g.1, group[0].1));
        }
    }
    pairs.sort_unstable();
    for (dropped, kept) in pairs {
        report.record(Step::DuplicateFaces, 1, || Change::DuplicateFace {
            kept: work.face_origin[kept as usize],
            dropped: work.face_origin[dropped as usize],
        });
    }
    work.retain_faces(&keep);
}
