//! The density test that bounds the geometric steps (zero-area faces, T-junctions).
//!
//! Both steps query a bounding-volume hierarchy with boxes that lie inside one face's box (a
//! degenerate face's segment; a border vertex, a corner of its faces), and every candidate
//! they test lies inside another face's box: so each candidate comes from a pair of faces
//! with overlapping boxes (or a face with itself), at most nine per pair. When the faces'
//! boxes overlap in fewer pairs than `envelope_predicates::bvh::pair_budget` allows (the
//! budget the input checker and the certificate share), the steps' work is linear in the
//! input; above it (a dense stack of distinct faces) they are not run, and the report marks
//! them undecided; the checker then refuses the mesh too.

use envelope_predicates::bvh::{Bvh, pair_budget};

use crate::work::Work;

/// Whether the faces' boxes overlap in at least the shared pair budget.
pub(crate) fn too_dense(work: &Work) -> bool {
    let tree = Bvh::from_triangles(&work.positions, &work.faces);
    let budget = pair_budget(work.faces.len());
    tree.self_pair_count_up_to(budget) >= budget
}
