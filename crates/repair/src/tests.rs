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

/// A xorshift generator (seeded, reproducible).
fn xorshift(mut state: u64) -> impl FnMut(usize) -> usize {
    move |n| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % n as u64) as usize
    }
}

#[test]
fn random_damage_to_a_clean_mesh_is_undone_exactly() {
    for seed in 1..40u64 {
        let clean = if seed % 2 == 0 {
            generate::icosphere(2, 1.0)
        } else {
            generate::torus(1.0, 0.3, 16, 8)
        };
        let mut rand = xorshift(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let mut s = clean.clone();
        let n = s.num_faces();
        // Unwelded corners: a copy of the vertex at the end.
        let mut corners: Vec<(usize, usize)> = (0..rand(20)).map(|_| (rand(n), rand(3))).collect();
        corners.sort_unstable();
        corners.dedup();
        let copies = corners.len();
        for (f, i) in corners {
            s.faces[f][i] = envelope_mesh::VertexId::from_index(s.positions.len());
            s.positions.push(s.position(clean.faces[f][i]));
        }
        // Flipped faces, fewer than half of the component.
        let mut flipped: Vec<usize> = (0..rand(10)).map(|_| rand(n)).collect();
        flipped.sort_unstable();
        flipped.dedup();
        for &f in &flipped {
            s.faces[f].swap(1, 2);
        }
        // Duplicates, rotated or reversed, at the end.
        let duplicates = rand(6);
        for _ in 0..duplicates {
            let mut t = s.faces[rand(n)];
            t.rotate_left(rand(3));
            if rand(2) == 1 {
                t.swap(0, 1);
            }
            s.faces.push(t);
        }
        // Vertices no face uses.
        let extra = rand(4);
        for k in 0..extra {
            s.positions
                .push(glam::DVec3::new(10.0 + k as f64, 0.0, 0.0));
        }
        let (out, report) = repair(&s, &RepairOptions::default()).unwrap();
        assert_eq!(out, clean, "seed {seed}");
        let counts: Vec<usize> = Step::ALL.iter().map(|&st| report.step(st).count).collect();
        assert_eq!(
            counts,
            [copies, duplicates, 0, 0, 0, 0, flipped.len(), extra],
            "seed {seed}: {report}"
        );
    }
}

#[test]
fn a_dense_stack_leaves_the_geometric_steps_undecided() {
    // 3,000 distinct triangles over one edge, all boxes overlapping: about 4.5 million pairs.
    let mut p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
    let mut f = vec![[0, 0, 1]]; // a zero-area face, left as it is
    for i in 0..3000u32 {
        p.push([0.5, 1.0, f64::from(i) / 3000.0]);
        f.push([0, 1, i + 2]);
        f.last_mut().unwrap().swap(0, (i % 2) as usize);
    }
    let (out, report) = run(&p, &f);
    assert_eq!(out.faces[0], [0, 0, 1].map(envelope_mesh::VertexId));
    assert!(report.step(Step::DegenerateFaces).undecided);
    assert!(report.step(Step::TJunctions).undecided);
    assert!(!report.step(Step::Weld).undecided);
    assert_eq!(report.to_json()["steps"][3]["undecided"], true);
}
