//! Hand-made meshes, one per step, with the counts known by hand.

use envelope_mesh::{TriangleSoup, generate};

use crate::{RepairError, RepairOptions, Step, repair};

fn run(positions: &[[f64; 3]], faces: &[[u32; 3]]) -> (TriangleSoup, crate::RepairReport) {
    repair(
        &TriangleSoup::from_raw(positions, faces),
        &RepairOptions::default(),
    )
    .unwrap()
}

const SQUARE: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];

#[test]
fn a_clean_mesh_is_returned_as_it_is() {
    let soup = generate::torus(1.0, 0.3, 12, 8);
    let (out, report) = repair(&soup, &RepairOptions::default()).unwrap();
    assert_eq!(out, soup);
    assert!(!report.changed());
}

#[test]
fn weld_joins_bitwise_equal_positions() {
    let mut p = SQUARE.to_vec();
    p.push([1.0, 1.0, -0.0]); // v4 = v2
    let (out, report) = run(&p, &[[0, 1, 2], [0, 4, 3]]);
    assert_eq!(report.step(Step::Weld).count, 1);
    assert_eq!(out.num_vertices(), 4);
    assert_eq!(report.step(Step::UnreferencedVertices).count, 0);
}

#[test]
fn non_manifold_edge_with_three_faces_is_split() {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.5, 1.0, 0.0],
        [0.5, -1.0, 0.0],
        [0.5, 0.0, 1.0],
    ];
    let (out, report) = run(&p, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    assert_eq!(report.step(Step::NonManifoldEdges).count, 1);
    assert!(report.step(Step::NonManifoldVertices).count >= 1);
    assert_eq!(out.num_faces(), 3);
}

#[test]
fn moebius_is_refused_naming_a_face() {
    // A strip of 4 quads closed with a half twist.
    let n = 4;
    let mut p = Vec::new();
    for i in 0..n {
        let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        let t = a / 2.0;
        for s in [-1.0, 1.0] {
            let r = 2.0 + 0.5 * s * t.cos();
            p.push([r * a.cos(), r * a.sin(), 0.5 * s * t.sin()]);
        }
    }
    let mut f = Vec::new();
    for i in 0..n {
        let (a, b) = (2 * i, 2 * i + 1);
        let (c, d) = if i + 1 < n {
            (2 * i + 2, 2 * i + 3)
        } else {
            (1, 0)
        };
        f.push([a, c, b]);
        f.push([b, c, d]);
    }
    let err = repair(&TriangleSoup::from_raw(&p, &f), &RepairOptions::default()).unwrap_err();
    assert!(matches!(err, RepairError::NonOrientable { .. }), "{err}");
}

#[test]
fn an_uncovered_zero_area_face_is_refused() {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
    ];
    let err = repair(
        &TriangleSoup::from_raw(&p, &[[0, 1, 2], [1, 3, 4]]),
        &RepairOptions::default(),
    )
    .unwrap_err();
    assert_eq!(
        err,
        RepairError::UncoveredDegenerateFace {
            face: envelope_mesh::FaceId(1),
            corners: [1, 3, 4].map(envelope_mesh::VertexId)
        }
    );
}

#[test]
fn t_junction_on_two_sides_of_one_face() {
    // Triangle 0-1-2 with v3 inside 0-1 and v4 inside 1-2, each met by a fan on the other side.
    let p = [
        [0.0, 0.0, 0.0],
        [4.0, 0.0, 0.0],
        [0.0, 4.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 2.0, 0.0],
        [2.0, -2.0, 0.0],
        [4.0, 4.0, 0.0],
    ];
    let (out, report) = run(&p, &[[0, 1, 2], [0, 5, 3], [3, 5, 1], [1, 6, 4], [4, 6, 2]]);
    assert_eq!(report.step(Step::TJunctions).count, 2);
    assert_eq!(out.num_faces(), 7);
    let t = envelope_mesh::analyze(&out);
    assert_eq!((t.border_loops.len(), t.manifold), (1, true));
}
