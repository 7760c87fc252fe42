//! Step 7: each component is oriented consistently; a non-orientable one refuses the repair.
//!
//! After the sheet split every edge has at most two faces. Faces are joined through those
//! edges; across an edge run the same way by both faces, one of them must flip. A breadth-
//! first walk from each component's first face assigns flips; a face reached with two
//! different answers proves the component non-orientable (a Möbius band), named by that face.
//! Of the two consistent orientations, the one flipping fewer faces is taken (on a tie, the
//! one keeping the component's first face). Choosing outward normals for closed components
//! would need a signed volume, which is not an exact predicate; it is not attempted.
//!
//! The point set is unchanged: a flip reverses a triangle's corner order.

use std::collections::VecDeque;

use crate::error::RepairError;
use crate::report::{Change, RepairReport, Step};
use crate::work::{Edges, Work};

pub(crate) fn orient(work: &mut Work, report: &mut RepairReport) -> Result<(), RepairError> {
    let n = work.faces.len();
    let edges = Edges::build(work);
    // Neighbours of each face through two-face edges: (other face, same direction).
    let mut adjacency: Vec<Vec<(u32, bool)>> = vec![Vec::new(); n];
    for g in edges.groups() {
        if let [s, t] = *g {
            let same = Edges::from(work, s) == Edges::from(work, t);
            adjacency[s.face as usize].push((t.face, same));
            adjacency[t.face as usize].push((s.face, same));
        }
    }
    const UNSEEN: u8 = 2;
    let mut flip = vec![UNSEEN; n];
    let mut flipped = Vec::new();
    let mut queue = VecDeque::new();
    for first in 0..n {
        if flip[first] != UNSEEN {
            continue;
        }
        flip[first] = 0;
        queue.push_back(first);
        let mut component = Vec::new();
        while let Some(f) = queue.pop_front() {
            component.push(f);
            for &(g, same) in &adjacency[f] {
                let want = flip[f] ^ u8::from(same);
                match flip[g as usize] {
                    UNSEEN => {
                        flip[g as usize] = want;
                        queue.push_back(g as usize);
                    }
                    x if x != want => {
                        return Err(RepairError::NonOrientable {
                            face: work.face_origin[g as usize],
                            first: work.face_origin[first],
                        });
                    }
                    _ => {}
                }
            }
        }
        let ones = component.iter().filter(|&&f| flip[f] == 1).count();
        let invert = 2 * ones > component.len();
        flipped.extend(component.into_iter().filter(|&f| (flip[f] == 1) != invert));
    }
    flipped.sort_unstable();
    for f in flipped {
        work.faces[f].swap(1, 2);
        report.record(Step::Orientation, 1, || Change::FaceFlipped {
            face: work.face_origin[f],
        });
    }
    Ok(())
}
