//! Property tests: random sequences of the simplifier's local edits (remove a vertex's fan,
//! then roll back or refill the hole) keep every adjacency invariant and the topology, and
//! rollback restores an identical mesh.

use envelope_mesh::{HalfEdgeMesh, TriangleSoup, VertexId, analyze, generate};
use proptest::prelude::*;

fn base(i: u8) -> TriangleSoup {
    match i % 6 {
        0 => generate::icosphere(1, 1.0),
        1 => generate::torus(2.0, 0.5, 8, 6),
        2 => generate::open_cylinder(1.0, 1.0, 7, 3),
        3 => generate::plate_with_holes(2),
        4 => generate::disk_with_holes(2),
        _ => generate::box_with_tunnel(),
    }
}

/// (euler, genus, border loops, components)
fn invariants(m: &HalfEdgeMesh) -> (i64, Option<u32>, usize, usize) {
    let t = m.topology();
    (t.euler, t.genus, t.num_border_loops(), t.components.len())
}

/// `genus_and_border_loops` (the half-edge count) against the soup analysis.
fn counts_agree(m: &HalfEdgeMesh) -> Result<(), TestCaseError> {
    let t = m.topology();
    prop_assert_eq!(m.genus_and_border_loops(), (t.genus, t.num_border_loops()));
    Ok(())
}

#[derive(Clone, Debug)]
struct Op {
    vertex: u32,
    action: u8,
    start: u32,
    then_rollback: bool,
}

fn op() -> impl Strategy<Value = Op> {
    (
        any::<u32>(),
        0u8..3,
        any::<u32>(),
        proptest::bool::weighted(0.2),
    )
        .prop_map(|(vertex, action, start, then_rollback)| Op {
            vertex,
            action,
            start,
            then_rollback,
        })
}

/// Refills the hole of a removed fan at `v` with a fan from a fresh vertex.
fn refill_from_new_vertex(m: &mut HalfEdgeMesh, v: VertexId, hole: &[VertexId], closed: bool) {
    let p = m.position(v);
    m.remove_vertex(v).unwrap();
    let c = m.add_vertex(p);
    let pairs = if closed { hole.len() } else { hole.len() - 1 };
    let fan: Vec<[VertexId; 3]> = (0..pairs)
        .map(|i| [c, hole[i], hole[(i + 1) % hole.len()]])
        .collect();
    m.add_faces(&fan)
        .expect("refilling the same fan cannot fail");
}

/// Refills a closed hole with a triangle fan from boundary vertex `hole[s]`; `false` (and
/// nothing added) when a diagonal already exists elsewhere in the mesh.
fn refill_from_boundary_vertex(m: &mut HalfEdgeMesh, hole: &[VertexId], s: usize) -> bool {
    let k = hole.len();
    let at = |i: usize| hole[(s + i) % k];
    if (2..k - 1).any(|i| m.find_halfedge(at(0), at(i)).is_some()) {
        return false;
    }
    let fan: Vec<[VertexId; 3]> = (1..k - 1).map(|i| [at(0), at(i), at(i + 1)]).collect();
    m.add_faces(&fan)
        .expect("a fan over a simple hole with fresh diagonals cannot fail");
    true
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn local_edits_keep_invariants(mesh in 0u8..6, ops in proptest::collection::vec(op(), 1..24)) {
        let soup = base(mesh);
        let mut m = HalfEdgeMesh::from_soup(&soup).unwrap();
        let expected = invariants(&m);
        for o in ops {
            let live: Vec<VertexId> = m.vertices().collect();
            let v = live[o.vertex as usize % live.len()];
            if m.is_isolated(v) || !m.is_manifold_vertex(v) {
                continue;
            }
            let was_border = m.is_border_vertex(v);
            let before = m.clone();
            let t = m.begin();
            let hole = m.remove_vertex_fan(v).unwrap();
            m.sanity_check().unwrap();
            counts_agree(&m)?;
            prop_assert!(m.is_isolated(v));
            let ok = match o.action {
                0 => false,
                1 => {
                    refill_from_new_vertex(&mut m, v, &hole, !was_border);
                    true
                }
                _ if was_border || hole.len() < 3 => false,
                _ => {
                    let s = o.start as usize % hole.len();
                    refill_from_boundary_vertex(&mut m, &hole, s) && m.remove_vertex(v).is_ok()
                }
            };
            m.sanity_check().unwrap();
            if !ok || o.then_rollback {
                m.rollback(t);
                prop_assert_eq!(&m, &before);
                prop_assert_eq!(m.to_soup(), before.to_soup());
            } else {
                m.commit(t);
                prop_assert_eq!(invariants(&m), expected);
                prop_assert!(m.vertices().all(|x| m.is_manifold_vertex(x)));
            }
            m.sanity_check().unwrap();
        }
        // The compacted soup is a valid input again, with the same topology.
        let again = HalfEdgeMesh::from_soup(&m.to_soup()).unwrap();
        again.sanity_check().unwrap();
        counts_agree(&m)?;
        prop_assert_eq!(invariants(&again), expected);
        prop_assert_eq!(analyze(&m.to_soup()).genus, expected.1);
    }

    #[test]
    fn removing_random_face_sets_then_rollback(mesh in 0u8..6, picks in proptest::collection::vec(any::<u32>(), 1..12)) {
        let mut m = HalfEdgeMesh::from_soup(&base(mesh)).unwrap();
        let before = m.clone();
        let t = m.begin();
        let faces: Vec<_> = m.faces().collect();
        let mut chosen: Vec<_> = picks.iter().map(|&p| faces[p as usize % faces.len()]).collect();
        chosen.sort_unstable();
        chosen.dedup();
        m.remove_faces(&chosen).unwrap();
        m.sanity_check().unwrap();
        counts_agree(&m)?;
        prop_assert_eq!(m.num_faces(), before.num_faces() - chosen.len());
        // Holes may pinch vertices (several gaps); the adjacency must stay valid anyway, and
        // the soup analysis must agree on the face count.
        prop_assert_eq!(m.topology().num_faces, m.num_faces());
        m.rollback(t);
        prop_assert_eq!(&m, &before);
    }
}
