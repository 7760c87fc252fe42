use super::*;
use crate::{TriangleSoup, generate};

fn mesh(s: &TriangleSoup) -> HalfEdgeMesh {
    let m = HalfEdgeMesh::from_soup(s).unwrap();
    m.sanity_check().unwrap();
    m
}

#[test]
fn round_trips_every_generator() {
    for s in [
        generate::tetrahedron(),
        generate::icosphere(2, 1.0),
        generate::uv_sphere(7, 4, 1.0),
        generate::torus(2.0, 0.5, 9, 5),
        generate::open_cylinder(1.0, 1.0, 6, 3),
        generate::box_mesh(DVec3::ONE, 2),
        generate::plate_with_holes(2),
        generate::box_with_tunnel(),
        generate::block_with_pocket(),
        generate::disk_with_holes(3),
    ] {
        let m = mesh(&s);
        assert_eq!(m.to_soup(), s);
        assert_eq!(m.topology(), crate::analyze(&s));
        let t = crate::analyze(&s);
        assert_eq!(
            (m.num_vertices(), m.num_faces(), m.num_edges()),
            (s.num_vertices(), s.num_faces(), t.num_edges)
        );
    }
}

#[test]
fn build_errors_name_the_element() {
    use BuildError::*;
    assert_eq!(
        HalfEdgeMesh::from_soup(&generate::three_triangles_on_edge()),
        Err(NonManifoldEdge {
            vertices: [VertexId(0), VertexId(1)],
            faces: [FaceId(0), FaceId(1), FaceId(2)]
        })
    );
    assert!(matches!(
        HalfEdgeMesh::from_soup(&generate::moebius_strip(6)),
        Err(InconsistentOrientation { .. })
    ));
    let s = TriangleSoup::from_raw(&[[0.0; 3]; 3], &[[0, 1, 2], [0, 2, 2]]);
    assert_eq!(
        HalfEdgeMesh::from_soup(&s),
        Err(DegenerateFace { face: FaceId(1) })
    );
    let s = TriangleSoup::from_raw(&[[0.0; 3]; 3], &[[0, 1, 3]]);
    assert_eq!(
        HalfEdgeMesh::from_soup(&s),
        Err(IndexOutOfRange {
            face: FaceId(0),
            vertex: VertexId(3)
        })
    );
    let s = TriangleSoup::from_raw(&[[0.0; 3]; 4], &[[0, 1, 2], [0, 1, 3]]);
    assert_eq!(
        HalfEdgeMesh::from_soup(&s),
        Err(InconsistentOrientation {
            edge: [VertexId(0), VertexId(1)],
            faces: [FaceId(0), FaceId(1)]
        })
    );
}

#[test]
fn one_ring_is_ordered_counter_clockwise() {
    let m = mesh(&generate::icosphere(1, 1.0));
    let v = VertexId(0);
    let n: Vec<VertexId> = m.vertex_neighbors(v).collect();
    let f: Vec<FaceId> = m.vertex_faces(v).collect();
    assert_eq!((n.len(), f.len(), m.valence(v)), (5, 5, 5));
    for i in 0..5 {
        // Face i is (v, n[i], n[i+1]) up to rotation.
        let fv = m.face_vertices(f[i]);
        let k = fv.iter().position(|&x| x == v).unwrap();
        assert_eq!([fv[(k + 1) % 3], fv[(k + 2) % 3]], [n[i], n[(i + 1) % 5]]);
    }
    assert!(!m.is_border_vertex(v) && m.is_manifold_vertex(v));
}

#[test]
fn border_vertices_start_at_their_border_halfedge() {
    let m = mesh(&generate::open_cylinder(1.0, 1.0, 6, 2));
    let v = VertexId(0);
    assert!(m.is_border_vertex(v));
    let h = m.vertex_halfedge(v).unwrap();
    assert!(m.is_border_halfedge(h) && m.is_border_edge(m.edge(h)));
    assert_eq!(m.vertex_faces(v).count(), m.valence(v) - 1);
    assert_eq!(m.find_halfedge(v, m.target(h)), Some(h));
    assert_eq!(m.origin(h), v);
    assert_eq!(m.twin(m.twin(h)), h);
    assert_eq!(m.edge_halfedge(m.edge(h), h.0 & 1), h);
}

#[test]
fn remove_and_refill_interior_fan() {
    let s = generate::icosphere(1, 1.0);
    let mut m = mesh(&s);
    let before = m.clone();
    let v = VertexId(0);
    let p = m.position(v);
    let hole = m.remove_vertex_fan(v).unwrap();
    m.sanity_check().unwrap();
    assert_eq!(hole.len(), 5);
    assert!(m.is_isolated(v));
    let t = m.topology();
    assert_eq!((t.border_loops.len(), t.genus), (1, Some(0)));
    assert_eq!(t.unreferenced_vertices, vec![v]);
    // The soup loop runs as the surrounding faces run it: the hole cycle reversed.
    let l = &t.border_loops[0];
    let k = l.iter().position(|&x| x == hole[0]).unwrap();
    assert!((0..5).all(|i| l[(k + 5 - i) % 5] == hole[i]));
    m.remove_vertex(v).unwrap();
    let c = m.add_vertex(p);
    assert_eq!(c, v, "the freed id is reused");
    for i in 0..5 {
        m.add_face([c, hole[i], hole[(i + 1) % 5]]).unwrap();
        m.sanity_check().unwrap();
    }
    assert_eq!(m.topology(), before.topology());
    assert_eq!(m.num_faces(), before.num_faces());
}

#[test]
fn remove_border_fan_gives_open_chain() {
    let mut m = mesh(&generate::open_cylinder(1.0, 1.0, 6, 2));
    let v = VertexId(0);
    let ring: Vec<VertexId> = m.vertex_neighbors(v).collect();
    let chain = m.remove_vertex_fan(v).unwrap();
    m.sanity_check().unwrap();
    assert_eq!(chain.len(), ring.len());
    assert_eq!(chain.last(), ring.first());
    // The chain's consecutive pairs are border half-edges.
    for w in chain.windows(2) {
        let h = m.find_halfedge(w[0], w[1]).unwrap();
        assert!(m.is_border_halfedge(h));
    }
    for w in chain.windows(2) {
        m.add_face([v, w[0], w[1]]).unwrap();
    }
    m.sanity_check().unwrap();
    assert_eq!(
        m.topology(),
        crate::analyze(&generate::open_cylinder(1.0, 1.0, 6, 2))
    );
}

#[test]
fn several_gaps_and_relinking() {
    // Open a hole at vertex 0 of an icosphere, then remove the fan of the middle
    // neighbour of a hole vertex x: x is left with two fans (two border gaps). Refilling
    // in an interleaved order exercises OpenMesh's patch relinking.
    let s = generate::icosphere(1, 1.0);
    let mut m = mesh(&s);
    let hole0 = m.remove_vertex_fan(VertexId(0)).unwrap();
    let x = hole0[0];
    let ring: Vec<VertexId> = m.vertex_neighbors(x).collect();
    assert_eq!(ring.len(), 5);
    let v = ring[3]; // faces at x: (x, r1, r2) .. (x, r4, r0); r3 is the middle
    assert!(!m.is_border_vertex(v));
    let hole = m.remove_vertex_fan(v).unwrap();
    m.sanity_check().unwrap();
    assert!(!m.is_manifold_vertex(x));
    assert_eq!(m.remove_vertex_fan(x), Err(EditError::NonManifoldVertex(x)));
    assert_eq!(m.topology().components[0].genus, None);
    let k = hole.len();
    let order: Vec<usize> = (0..k).step_by(2).chain((1..k).step_by(2)).collect();
    let mut refused = Vec::new();
    for &i in &order {
        if m.add_face([v, hole[i], hole[(i + 1) % k]]).is_err() {
            refused.push(i);
        }
        m.sanity_check().unwrap();
    }
    for &i in &refused {
        m.add_face([v, hole[i], hole[(i + 1) % k]]).unwrap();
        m.sanity_check().unwrap();
    }
    assert!(m.vertices().all(|x| m.is_manifold_vertex(x)));
    for i in 0..hole0.len() {
        m.add_face([VertexId(0), hole0[i], hole0[(i + 1) % hole0.len()]])
            .unwrap();
    }
    m.sanity_check().unwrap();
    assert_eq!(m.topology(), crate::analyze(&s));
}

#[test]
fn add_face_refusals() {
    let mut m = mesh(&generate::icosphere(0, 1.0));
    let n: Vec<VertexId> = m.vertex_neighbors(VertexId(0)).collect();
    assert_eq!(
        m.add_face([VertexId(0), n[1], n[0]]),
        Err(AddFaceError::InteriorVertex(VertexId(0)))
    );
    let hole = m.remove_vertex_fan(VertexId(0)).unwrap();
    let before = m.clone();
    // Flipped face on an existing border half-edge's twin side.
    assert_eq!(
        m.add_face([hole[1], hole[0], VertexId(0)]),
        Err(AddFaceError::HalfedgeOccupied {
            from: hole[1],
            to: hole[0]
        })
    );
    // A face touching a hole vertex through no edge.
    let far = m.add_vertex(DVec3::ZERO);
    let far2 = m.add_vertex(DVec3::ONE);
    assert_eq!(
        m.add_face([hole[0], far, far2]),
        Err(AddFaceError::NewFan(hole[0]))
    );
    assert_eq!(
        m.add_face([far, far, far2]),
        Err(AddFaceError::RepeatedVertex(far))
    );
    m.remove_vertex(far2).unwrap();
    assert_eq!(
        m.add_face([far, far2, hole[0]]),
        Err(AddFaceError::DeadVertex(far2))
    );
    m.remove_vertex(far).unwrap();
    // A free-standing triangle is fine.
    let a = m.add_vertex(DVec3::X);
    let b = m.add_vertex(DVec3::Y);
    let c = m.add_vertex(DVec3::Z);
    let f = m.add_face([a, b, c]).unwrap();
    assert_eq!(m.face_vertices(f), [a, b, c]);
    assert_eq!(m.topology().components.len(), 2);
    m.remove_faces(&[f]).unwrap();
    assert_eq!(m.remove_faces(&[f]), Err(EditError::DeadFace(f)));
    for x in [c, b, a] {
        m.remove_vertex(x).unwrap();
    }
    m.sanity_check().unwrap();
    assert_eq!(m.topology(), before.topology());
}

#[test]
fn rollback_restores_identical_mesh() {
    let mut m = mesh(&generate::torus(2.0, 0.5, 8, 6));
    let before = m.clone();
    let outer = m.begin();
    let hole = m.remove_vertex_fan(VertexId(3)).unwrap();
    let mid = m.clone();
    let inner = m.begin();
    m.remove_vertex(VertexId(3)).unwrap();
    let c = m.add_vertex(DVec3::ZERO);
    m.set_position(VertexId(5), DVec3::ONE);
    for i in 0..hole.len() {
        m.add_face([c, hole[i], hole[(i + 1) % hole.len()]])
            .unwrap();
    }
    m.remove_faces(&[FaceId(0), FaceId(7)]).unwrap();
    m.rollback(inner);
    assert_eq!(m, mid);
    let again = m.begin();
    m.remove_vertex_fan(VertexId(20)).unwrap();
    m.commit(again);
    m.rollback(outer);
    assert_eq!(m, before);
    m.sanity_check().unwrap();
    // No checkpoint open: edits are not logged.
    m.remove_vertex_fan(VertexId(1)).unwrap();
    assert!(m.log.is_empty());
}

#[test]
fn removing_an_isolated_triangle_kills_its_edges() {
    let mut m = mesh(&TriangleSoup::from_raw(&[[0.0; 3]; 3], &[[0, 1, 2]]));
    m.remove_faces(&[FaceId(0)]).unwrap();
    m.sanity_check().unwrap();
    assert_eq!((m.num_faces(), m.num_edges(), m.num_vertices()), (0, 0, 3));
    assert!((0..3).all(|v| m.is_isolated(VertexId(v))));
    m.add_face([VertexId(0), VertexId(1), VertexId(2)]).unwrap();
    m.sanity_check().unwrap();
    assert_eq!(m.topology().genus, Some(0));
}
