use super::*;
use envelope_mesh::generate;
use proptest::prelude::*;

fn run(soup: &TriangleSoup) -> CheckReport {
    check(soup, &CheckOptions::default())
}

fn count(r: &CheckReport, c: DegeneracyClass) -> usize {
    r.finding(c).count
}

/// Every class except `except` is empty.
fn only(r: &CheckReport, except: &[DegeneracyClass]) {
    for c in DegeneracyClass::ALL {
        if !except.contains(&c) {
            assert_eq!(count(r, c), 0, "unexpected {c}: {:?}", r.finding(c));
        }
    }
}

#[test]
fn range_constants_agree_with_predicates() {
    assert_eq!(
        envelope_mesh::MAX_ALLOWED_MAGNITUDE,
        envelope_predicates::MAX_ALLOWED_MAGNITUDE
    );
    assert_eq!(
        envelope_mesh::MIN_ALLOWED_MAGNITUDE,
        envelope_predicates::MIN_ALLOWED_MAGNITUDE
    );
}

#[test]
fn clean_meshes_with_known_topology() {
    let cases: Vec<(&str, TriangleSoup, Option<u32>, usize, usize)> = vec![
        ("tetrahedron", generate::tetrahedron(), Some(0), 0, 1),
        ("icosphere", generate::icosphere(2, 1.0), Some(0), 0, 1),
        ("torus", generate::torus(1.0, 0.3, 24, 12), Some(1), 0, 1),
        ("double torus", generate::plate_with_holes(2), Some(2), 0, 1),
        (
            "open cylinder",
            generate::open_cylinder(1.0, 2.0, 16, 4),
            Some(0),
            2,
            1,
        ),
        (
            "disk with 3 holes",
            generate::disk_with_holes(3),
            Some(0),
            4,
            1,
        ),
        (
            "box with tunnel",
            generate::box_with_tunnel(),
            Some(1),
            0,
            1,
        ),
    ];
    for (name, soup, genus, borders, components) in cases {
        let r = run(&soup);
        assert!(
            r.acceptable(),
            "{name}: {:?}",
            r.errors().collect::<Vec<_>>()
        );
        only(&r, &[]);
        assert_eq!(r.genus, genus, "{name}");
        assert_eq!(r.border_loops, borders, "{name}");
        assert_eq!(r.components, components, "{name}");
        assert_eq!(
            r.euler,
            2 * components as i64 - 2 * genus.unwrap() as i64 - borders as i64,
            "{name}"
        );
    }
}

#[test]
fn tetrahedron_counts() {
    let r = run(&generate::tetrahedron());
    assert_eq!((r.vertices, r.faces, r.edges, r.euler), (4, 4, 6, 2));
    assert!(r.manifold && r.orientable);
}

#[test]
fn t_junction_is_found_exactly() {
    // Two triangles below the edge (0,2); one above split at vertex 4, which lies exactly
    // in the middle of the edge (0,2) it does not belong to.
    let s = TriangleSoup::from_raw(
        &[
            [0.0, 0.0, 0.0],
            [1.0, -1.0, 0.0],
            [2.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
        ],
        &[[0, 1, 2], [0, 4, 3], [4, 2, 3]],
    );
    let r = run(&s);
    assert_eq!(count(&r, DegeneracyClass::TJunctions), 1);
    assert_eq!(
        r.finding(DegeneracyClass::TJunctions).examples[0],
        Element::VertexOnEdge {
            vertex: VertexId(4),
            position: DVec3::new(1.0, 0.0, 0.0),
            edge: [VertexId(0), VertexId(2)]
        }
    );
    assert!(!r.acceptable());

    // Moved off the edge by the smallest accepted magnitude: no T-junction any more.
    let mut moved = s.clone();
    moved.positions[4].y = envelope_mesh::MIN_ALLOWED_MAGNITUDE;
    assert_eq!(count(&run(&moved), DegeneracyClass::TJunctions), 0);
}

#[test]
fn zero_area_by_collinear_positions_and_by_repeated_index() {
    let s = TriangleSoup::from_raw(
        &[
            [0.0, 0.0, 0.0],
            [0.1, 0.1, 0.1],
            [0.3, 0.3, 0.3],
            [1.0, 0.0, 0.0],
        ],
        // 0.1 and 0.3 are not exact in binary, but 0.1*3 != 0.3: check what exact says.
        &[[0, 1, 2], [0, 0, 3], [0, 3, 1]],
    );
    let r = run(&s);
    let zero: Vec<_> = r.finding(DegeneracyClass::ZeroAreaTriangles).examples;
    // Face 1 repeats an index. Face 0's corners are collinear only if the doubles are.
    let collinear_exact =
        envelope_predicates::collinear(s.positions[0], s.positions[1], s.positions[2]);
    let expected = if collinear_exact { 2 } else { 1 };
    assert_eq!(zero.len(), expected);

    // Exactly representable collinear points: always zero area.
    let s = TriangleSoup::from_raw(&[[0.0; 3], [0.25, 0.5, 1.0], [0.5, 1.0, 2.0]], &[[0, 1, 2]]);
    assert_eq!(count(&run(&s), DegeneracyClass::ZeroAreaTriangles), 1);
}

#[test]
fn sliver_is_a_warning() {
    let s = TriangleSoup::from_raw(&[[0.0; 3], [1.0, 0.0, 0.0], [0.5, 1e-6, 0.0]], &[[0, 1, 2]]);
    let r = run(&s);
    assert_eq!(count(&r, DegeneracyClass::SliverTriangles), 1);
    assert_eq!(count(&r, DegeneracyClass::ZeroAreaTriangles), 0);
    assert!(r.acceptable());
}

#[test]
fn duplicate_and_coincident_triangles() {
    let mut s = generate::tetrahedron();
    let f0 = s.faces[0];
    s.faces.push([f0[1], f0[0], f0[2]]); // same indices, flipped
    let r = run(&s);
    assert_eq!(count(&r, DegeneracyClass::DuplicateTriangles), 1);
    assert_eq!(
        count(&r, DegeneracyClass::CoincidentTriangles),
        0,
        "duplicates are not double-counted"
    );
    assert!(count(&r, DegeneracyClass::IntersectingTriangles) >= 1);

    // A copy of face 0 on new vertices at the same positions: coincident, and duplicate
    // vertices, but not a duplicate triangle.
    let mut s = generate::tetrahedron();
    let base = s.positions.len() as u32;
    for v in f0 {
        s.positions.push(s.position(v));
    }
    s.faces
        .push([VertexId(base), VertexId(base + 1), VertexId(base + 2)]);
    let r = run(&s);
    assert_eq!(count(&r, DegeneracyClass::CoincidentTriangles), 1);
    assert_eq!(count(&r, DegeneracyClass::DuplicateTriangles), 0);
    assert_eq!(count(&r, DegeneracyClass::DuplicateVertices), 3);
    assert_eq!(r.components, 2);
}

#[test]
fn intersecting_triangles_named_by_pair() {
    // Two tetrahedra, the second pushed through a face of the first.
    let a = generate::tetrahedron();
    let mut s = a.clone();
    let off = a.positions.len() as u32;
    let c = a.positions.iter().sum::<DVec3>() / 4.0;
    s.positions
        .extend(a.positions.iter().map(|p| *p + (c - a.positions[0]) * 0.9));
    s.faces
        .extend(a.faces.iter().map(|f| f.map(|v| VertexId(v.0 + off))));
    let r = run(&s);
    let expected = envelope_predicates::self_intersections(
        &s.positions,
        &s.faces.iter().map(|f| f.map(|v| v.0)).collect::<Vec<_>>(),
    );
    assert!(!expected.is_empty());
    assert_eq!(
        count(&r, DegeneracyClass::IntersectingTriangles),
        expected.len()
    );
    for (e, (i, j)) in r
        .finding(DegeneracyClass::IntersectingTriangles)
        .examples
        .iter()
        .zip(&expected)
    {
        assert_eq!(
            *e,
            Element::FacePair {
                faces: [FaceId(*i), FaceId(*j)]
            }
        );
    }
    assert!(!r.acceptable());
}

#[test]
fn non_manifold_classes() {
    let r = run(&generate::bow_tie());
    assert_eq!(count(&r, DegeneracyClass::NonManifoldVertices), 1);
    assert!(!r.acceptable());
    let r = run(&generate::three_triangles_on_edge());
    assert_eq!(count(&r, DegeneracyClass::NonManifoldEdges), 1);
    assert!(!r.manifold);
}

#[test]
fn orientation_conflict_and_moebius() {
    let mut s = generate::icosphere(1, 1.0);
    s.faces[3].swap(0, 1);
    let r = run(&s);
    assert_eq!(count(&r, DegeneracyClass::InconsistentOrientation), 3);
    let r = run(&generate::moebius_strip(12));
    assert!(count(&r, DegeneracyClass::InconsistentOrientation) >= 1);
    assert!(!r.orientable);
    assert_eq!(r.genus, None);
}

#[test]
fn unreferenced_vertex_is_only_a_warning() {
    let mut s = generate::tetrahedron();
    s.positions.push(DVec3::new(9.0, 9.0, 9.0));
    let r = run(&s);
    assert_eq!(count(&r, DegeneracyClass::UnreferencedVertices), 1);
    assert!(r.acceptable());
    assert_eq!(r.euler, 2, "unreferenced vertices are not counted");
}

#[test]
fn hand_built_soups_with_bad_values_do_not_panic() {
    let s = TriangleSoup::from_raw(
        &[
            [0.0; 3],
            [f64::NAN, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [f64::INFINITY, 1.0, 1.0],
        ],
        &[[0, 1, 2], [0, 2, 3], [0, 2, 7]],
    );
    let r = run(&s);
    assert_eq!(r.faces, 3);
}

#[test]
fn json_has_the_stable_fields() {
    let v = run(&generate::bow_tie()).to_json();
    for key in [
        "vertices",
        "faces",
        "edges",
        "border_loops",
        "components",
        "euler",
        "genus",
        "manifold",
        "orientable",
        "acceptable",
        "degeneracies",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    for c in DegeneracyClass::ALL {
        let d = &v["degeneracies"][c.key()];
        assert!(d["count"].is_u64() && d["examples"].is_array(), "{c}");
    }
    assert_eq!(v["degeneracies"]["non_manifold_vertices"]["count"], 1);
    assert_eq!(
        v["degeneracies"]["non_manifold_vertices"]["examples"][0]["vertex"],
        0
    );
    assert_eq!(v["acceptable"], false);
}

#[test]
fn examples_are_capped_but_counts_are_not() {
    let mut s = generate::icosphere(2, 1.0);
    for _ in 0..20 {
        s.positions.push(DVec3::ZERO);
    }
    let r = check(
        &s,
        &CheckOptions {
            max_examples: 3,
            ..CheckOptions::default()
        },
    );
    let f = r.finding(DegeneracyClass::UnreferencedVertices);
    assert_eq!((f.count, f.examples.len()), (20, 3));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Splitting an edge of a clean mesh by inserting its midpoint into only one of the two
    /// faces makes exactly one T-junction (midpoints of dyadic coordinates are exact).
    #[test]
    fn one_sided_edge_split_makes_one_t_junction(face in 0usize..80, corner in 0usize..3) {
        let mut s = generate::icosphere(1, 1.0);
        // Snap to a dyadic grid so the midpoint is exactly on the edge.
        for p in &mut s.positions {
            *p = (*p * 1024.0).round() / 1024.0;
        }
        prop_assume!(run(&s).acceptable());
        let f = face % s.faces.len();
        let [a, b, c] = [s.faces[f][corner], s.faces[f][(corner + 1) % 3], s.faces[f][(corner + 2) % 3]];
        let m = VertexId(s.positions.len() as u32);
        s.positions.push((s.position(a) + s.position(b)) / 2.0);
        s.faces[f] = [a, m, c];
        s.faces.push([m, b, c]);
        let r = run(&s);
        prop_assert_eq!(count(&r, DegeneracyClass::TJunctions), 1);
        prop_assert_eq!(&r.finding(DegeneracyClass::TJunctions).examples[0],
            &Element::VertexOnEdge { vertex: m, position: s.position(m), edge: if a < b { [a, b] } else { [b, a] } });
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The check skips the T-junction search when no zero-area face and no intersecting
    /// pair was found (a T-junction makes one of the two): its count is the search's on
    /// clean meshes and on meshes with a vertex moved onto the midpoint of an edge
    /// elsewhere (a T-junction and intersections), and with the pairwise test off.
    #[test]
    fn t_junction_count_is_the_search_s(face in 0usize..80, corner in 0usize..3, vertex in 0usize..42, snap in any::<bool>()) {
        let mut s = generate::icosphere(1, 1.0);
        for p in &mut s.positions {
            *p = (*p * 1024.0).round() / 1024.0;
        }
        let f = s.faces[face % s.faces.len()];
        let (a, b) = (f[corner], f[(corner + 1) % 3]);
        let v = VertexId((vertex % s.positions.len()) as u32);
        if snap && v != a && v != b {
            s.positions[v.index()] = (s.position(a) + s.position(b)) / 2.0;
        }
        let search = geometric::t_junctions(&s, &referenced_vertices(&s)).len();
        for pairwise in [true, false] {
            let r = check(&s, &CheckOptions { pairwise, ..CheckOptions::default() });
            prop_assert_eq!(count(&r, DegeneracyClass::TJunctions), search);
        }
        if snap && v != a && v != b {
            prop_assert!(search > 0);
        }
    }
}

/// The check with a shared topology and face tree answers what it answers alone: on a clean
/// mesh, on one with intersecting faces, with an unusable (non-finite) face, where the
/// given tree is then not the usable faces' and must be left aside, and with a tree of
/// another length.
#[test]
fn shared_topology_and_tree_give_the_same_report() {
    use envelope_mesh::analyze;
    use envelope_predicates::bvh::Bvh;
    let clean = generate::icosphere(2, 1.0);
    let mut crossing = clean.clone();
    crossing.positions[0] = -crossing.positions[0];
    let mut broken = crossing.clone();
    broken.positions[5] = DVec3::new(f64::NAN, 0.0, 0.0);
    let other = generate::icosphere(1, 1.0);
    let tree_of = |s: &TriangleSoup| {
        let faces: Vec<[u32; 3]> = s.faces.iter().map(|f| f.map(|v| v.0)).collect();
        Bvh::from_triangles(&s.positions, &faces)
    };
    let options = CheckOptions::default();
    for s in [&clean, &crossing, &broken] {
        let alone = check(s, &options);
        let topology = analyze(s);
        for tree in [Some(tree_of(s)), Some(tree_of(&other)), None] {
            assert_eq!(
                check_with_shared(s, &options, &topology, tree.as_ref()),
                alone
            );
        }
    }
    assert!(
        count(
            &check(&crossing, &options),
            DegeneracyClass::IntersectingTriangles
        ) > 0
    );
}

#[test]
fn a_dense_stack_of_faces_is_undecided_not_quadratic() {
    use envelope_mesh::{TriangleSoup, VertexId};
    use glam::DVec3;
    // 4,000 copies of one triangle over distinct vertices: 8 million overlapping box pairs,
    // above the budget of 48 per face plus 2^22.
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for i in 0..4000u32 {
        positions.extend([DVec3::ZERO, DVec3::X, DVec3::Y]);
        faces.push([VertexId(3 * i), VertexId(3 * i + 1), VertexId(3 * i + 2)]);
    }
    let report = check(
        &TriangleSoup::new(positions, faces),
        &CheckOptions::default(),
    );
    let f = report.finding(DegeneracyClass::IntersectingTriangles);
    assert!(f.undecided);
    assert_eq!(f.count, 0);
    assert!(!report.acceptable());
    assert!(
        report
            .errors()
            .any(|c| c == DegeneracyClass::IntersectingTriangles)
    );
    assert_eq!(
        report.to_json()["degeneracies"]["intersecting_triangles"]["undecided"],
        true
    );
    // Below the budget the pairs are counted as before.
    let small = generate::icosphere(2, 1.0);
    assert!(
        !check(&small, &CheckOptions::default())
            .finding(DegeneracyClass::IntersectingTriangles)
            .undecided
    );
}
