//! Attributes carried through simplification, levels of detail and repair: exact on kept
//! vertices, interpolated on moved ones, no tears along texture seams.

use std::collections::{HashMap, HashSet};

use envelope::{
    Attributes, Epsilon, Lod, Mesh, Method, Placement, Simplifier, Wedges, carry_attributes,
    seam_vertices,
};

const N: u32 = 24;
const M: u32 = 12;

/// An open cylinder, `N` around and `M` rows high, with u = i / N, v = j / M per corner and
/// the seam at column 0 (the last column's faces give it u = 1), and radial normals.
fn cylinder() -> Mesh {
    let mut positions = Vec::new();
    for j in 0..=M {
        for i in 0..N {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(N);
            positions.push([a.cos(), a.sin(), 2.0 * f64::from(j) / f64::from(M)]);
        }
    }
    let id = |i: u32, j: u32| j * N + i % N;
    let mut faces = Vec::new();
    let mut uv = Wedges::default();
    let mut normals = Wedges::default();
    for j in 0..M {
        for i in 0..N {
            let quad = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            for tri in [[0, 1, 2], [0, 2, 3]] {
                let corners = tri.map(|c| quad[c]);
                faces.push(corners.map(|(i, j)| id(i, j)));
                let mut t = [0; 3];
                let mut n = [0; 3];
                for (k, &(i, j)) in corners.iter().enumerate() {
                    uv.values
                        .push([f64::from(i) / f64::from(N), f64::from(j) / f64::from(M)]);
                    t[k] = (uv.values.len() - 1) as u32;
                    let p = positions[id(i, j) as usize];
                    normals.values.push([p[0], p[1], 0.0]);
                    n[k] = (normals.values.len() - 1) as u32;
                }
                uv.corners.push(t);
                normals.corners.push(n);
            }
        }
    }
    Mesh::new(positions, faces)
        .unwrap()
        .with_attributes(Attributes {
            texcoords: Some(uv),
            normals: Some(normals),
            colors: None,
            quality: None,
        })
        .unwrap()
}

fn key(p: [f64; 3]) -> [u64; 3] {
    p.map(f64::to_bits)
}

/// The input vertex of each output vertex at an input position.
fn origins(input: &Mesh, output: &Mesh) -> Vec<Option<u32>> {
    let at: HashMap<[u64; 3], u32> = input
        .positions()
        .enumerate()
        .map(|(v, p)| (key(p), v as u32))
        .collect();
    output
        .positions()
        .map(|p| at.get(&key(p)).copied())
        .collect()
}

/// (a): every output corner at an input vertex has its chart's input value exactly: u = i / N,
/// or 1 at the seam for faces on the last column's side (their centroid's angle is past pi).
fn check_exact_on_input_vertices(input: &Mesh, output: &Mesh) -> usize {
    let uv = output.attributes().texcoords.as_ref().unwrap();
    let origin = origins(input, output);
    let positions: Vec<[f64; 3]> = output.positions().collect();
    let mut checked = 0;
    for (f, tri) in output.triangles().enumerate() {
        let centroid = tri.iter().fold([0.0; 2], |c, &v| {
            [
                c[0] + positions[v as usize][0],
                c[1] + positions[v as usize][1],
            ]
        });
        let far_side = centroid[1] < 0.0;
        for (k, &v) in tri.iter().enumerate() {
            let Some(iv) = origin[v as usize] else {
                continue;
            };
            let (i, j) = (iv % N, iv / N);
            let u = if i == 0 && far_side {
                1.0
            } else {
                f64::from(i) / f64::from(N)
            };
            let ids: Vec<_> = tri
                .iter()
                .map(|&w| origin[w as usize].map(|x| (x % N, x / N)))
                .collect();
            assert_eq!(
                uv.value(f, k),
                [u, f64::from(j) / f64::from(M)],
                "face {f} corner {k} {ids:?} {:?}",
                (0..3).map(|c| uv.value(f, c)).collect::<Vec<_>>()
            );
            checked += 1;
        }
    }
    checked
}

/// (c): an output edge whose faces' texture coordinates differ at an end joins two input
/// vertices along an input seam edge, and every input seam edge is an output edge.
fn check_no_tears(input: &Mesh, output: &Mesh) {
    let uv = output.attributes().texcoords.as_ref().unwrap();
    let origin = origins(input, output);
    let tris: Vec<[u32; 3]> = output.triangles().collect();
    let mut edges: HashMap<(u32, u32), (usize, usize)> = HashMap::new();
    for (f, t) in tris.iter().enumerate() {
        for k in 0..3 {
            edges.insert((t[k], t[(k + 1) % 3]), (f, k));
        }
    }
    let seam = |a: u32, b: u32| a % N == 0 && b % N == 0 && a.abs_diff(b) == N;
    let mut output_edges = HashSet::new();
    for (&(a, b), &(f, k)) in &edges {
        let (ia, ib) = (origin[a as usize], origin[b as usize]);
        if let (Some(ia), Some(ib)) = (ia, ib) {
            output_edges.insert((ia.min(ib), ia.max(ib)));
        }
        let Some(&(g, j)) = edges.get(&(b, a)) else {
            continue;
        };
        let differ = uv.value(f, k) != uv.value(g, (j + 1) % 3)
            || uv.value(f, (k + 1) % 3) != uv.value(g, j);
        if differ {
            assert!(
                matches!((ia, ib), (Some(x), Some(y)) if seam(x, y)),
                "tear along output edge {a}-{b} ({ia:?}-{ib:?})"
            );
        }
    }
    for j in 0..M {
        assert!(
            output_edges.contains(&(j * N, (j + 1) * N)),
            "seam edge at row {j} lost"
        );
    }
}

#[test]
fn seam_vertices_are_the_seam_column() {
    let mesh = cylinder();
    let keep = seam_vertices(&mesh);
    for (v, &k) in keep.iter().enumerate() {
        assert_eq!(k, v as u32 % N == 0, "vertex {v}");
    }
}

#[test]
fn simplified_cylinder_keeps_values_and_seams() {
    let mesh = cylinder();
    for method in [Method::Local, Method::Hybrid, Method::Global] {
        let done = Simplifier::new(Epsilon::percent(1.0))
            .method(method)
            .placement(Placement::Subset)
            .threads(1)
            .run(&mesh)
            .unwrap();
        assert!(done.is_certified());
        let out = done.mesh();
        assert!(
            out.num_faces() < mesh.num_faces() / 2,
            "{method:?}: {}",
            out.num_faces()
        );
        assert!(out.attributes().is_valid_for(out.num_faces()));
        let checked = check_exact_on_input_vertices(&mesh, out);
        assert_eq!(checked, 3 * out.num_faces());
        check_no_tears(&mesh, out);
        // Normals: unchanged input faces keep theirs exactly, the rest point outwards.
        let normals = out.attributes().normals.as_ref().unwrap();
        let positions: Vec<[f64; 3]> = out.positions().collect();
        for (f, tri) in out.triangles().enumerate() {
            for (k, &v) in tri.iter().enumerate() {
                let n = normals.value(f, k);
                let p = positions[v as usize];
                assert!(
                    n[0] * p[0] + n[1] * p[1] > 0.9,
                    "face {f} corner {k}: {n:?}"
                );
            }
        }
    }
}

#[test]
fn moving_placements_keep_seams_and_values_at_input_vertices() {
    let mesh = cylinder();
    for placement in [Placement::Slide, Placement::Collapse] {
        let done = Simplifier::new(Epsilon::percent(1.0))
            .placement(placement)
            .threads(1)
            .run(&mesh)
            .unwrap();
        let out = done.mesh();
        check_exact_on_input_vertices(&mesh, out);
        check_no_tears(&mesh, out);
        // Moved vertices are never seam vertices, and they take v = z / 2 (linear in z on
        // every chart face) and u of a point of the surface near them.
        let uv = out.attributes().texcoords.as_ref().unwrap();
        let origin = origins(&mesh, out);
        let positions: Vec<[f64; 3]> = out.positions().collect();
        let mut moved = 0;
        for (f, tri) in out.triangles().enumerate() {
            for (k, &v) in tri.iter().enumerate() {
                if origin[v as usize].is_none() {
                    let t = uv.value(f, k);
                    assert!((t[1] - positions[v as usize][2] / 2.0).abs() < 1e-9);
                    moved += 1;
                }
            }
        }
        // (None move on this cylinder today; the height field below has moves.)
        let _ = moved;
    }
}

/// A planar grid `n` by `n` with the linear field u = 0.3 x + 0.2 y + 0.1, v = 0.5 y - 0.1 x.
fn plane(n: u32) -> Mesh {
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            positions.push([
                f64::from(i) / f64::from(n),
                f64::from(j) / f64::from(n),
                0.0,
            ]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let v = j * (n + 1) + i;
            faces.push([v, v + 1, v + n + 2]);
            faces.push([v, v + n + 2, v + n + 1]);
        }
    }
    let field = |p: [f64; 3]| [0.3 * p[0] + 0.2 * p[1] + 0.1, 0.5 * p[1] - 0.1 * p[0]];
    let uv = Wedges {
        values: positions.iter().map(|&p| field(p)).collect(),
        corners: faces.clone(),
    };
    Mesh::new(positions, faces)
        .unwrap()
        .with_attributes(Attributes {
            texcoords: Some(uv),
            ..Attributes::default()
        })
        .unwrap()
}

fn linear(p: [f64; 3]) -> [f64; 2] {
    [0.3 * p[0] + 0.2 * p[1] + 0.1, 0.5 * p[1] - 0.1 * p[0]]
}

fn assert_linear(mesh: &Mesh) -> usize {
    let uv = mesh.attributes().texcoords.as_ref().unwrap();
    let positions: Vec<[f64; 3]> = mesh.positions().collect();
    let mut moved = 0;
    for (f, tri) in mesh.triangles().enumerate() {
        for (k, &v) in tri.iter().enumerate() {
            let p = positions[v as usize];
            let (got, want) = (uv.value(f, k), linear(p));
            for c in 0..2 {
                assert!(
                    (got[c] - want[c]).abs() <= 1e-9 * want[c].abs().max(1e-3),
                    "face {f} corner {k} at {p:?}: {got:?} vs {want:?}"
                );
            }
            let on_grid = |x: f64| x * 8.0 == (x * 8.0).round();
            moved += usize::from(!(on_grid(p[0]) && on_grid(p[1])));
        }
    }
    moved
}

#[test]
fn a_moved_vertex_takes_the_linear_fields_value() {
    let mesh = plane(8);
    // By hand: vertex 40 (4, 4) moved to an inside point of its star, the output otherwise
    // the input.
    let mut positions: Vec<[f64; 3]> = mesh.positions().collect();
    positions[40] = [0.52, 0.47, 0.0];
    let moved = Mesh::new(positions, mesh.triangles().collect()).unwrap();
    let carried = carry_attributes(&mesh, moved.soup());
    let moved = moved.with_attributes(carried).unwrap();
    assert!(assert_linear(&moved) > 0);
    // And through the simplifier with moving placements.
    for placement in [Placement::Slide, Placement::Collapse] {
        let done = Simplifier::new(Epsilon::percent(1.0))
            .placement(placement)
            .threads(1)
            .run(&mesh)
            .unwrap();
        assert_linear(done.mesh());
    }
}

#[test]
fn levels_keep_exact_values_and_seams() {
    let mesh = cylinder();
    let levels = Lod::new(vec![Epsilon::percent(0.5), Epsilon::percent(1.0)])
        .threads(1)
        .run(&mesh)
        .unwrap();
    for level in &levels {
        let out = Lod::level_mesh(&mesh, level);
        assert_eq!(
            check_exact_on_input_vertices(&mesh, &out),
            3 * out.num_faces()
        );
        check_no_tears(&mesh, &out);
    }
}

#[test]
fn repair_carries_corners_through_flips_and_welds() {
    // A square whose second triangle uses a copy of vertex 2 and the wrong winding.
    let mesh = Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 3, 4]],
    )
    .unwrap();
    let uv = Wedges {
        values: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]],
        corners: vec![[0, 1, 2], [0, 3, 4]],
    };
    let mesh = mesh
        .with_attributes(Attributes {
            texcoords: Some(uv),
            ..Attributes::default()
        })
        .unwrap();
    let repaired = envelope::repair(&mesh).unwrap();
    let out = repaired.mesh();
    let uv = out.attributes().texcoords.as_ref().unwrap();
    let positions: Vec<[f64; 3]> = out.positions().collect();
    // Each corner keeps the value its face gave that position.
    let expect = |f: usize, p: [f64; 3]| match (f, p) {
        (_, [0.0, 0.0, 0.0]) => [0.0, 0.0],
        (_, [1.0, 0.0, 0.0]) => [1.0, 0.0],
        (_, [0.0, 1.0, 0.0]) => [0.0, 1.0],
        (0, _) => [1.0, 1.0],
        _ => [0.5, 0.5],
    };
    for (f, tri) in out.triangles().enumerate() {
        for (k, &v) in tri.iter().enumerate() {
            assert_eq!(uv.value(f, k), expect(f, positions[v as usize]), "face {f}");
        }
    }
}

#[test]
fn a_mesh_without_attributes_gets_none() {
    let done = Simplifier::new(Epsilon::percent(1.0))
        .threads(1)
        .run(&Mesh::demo())
        .unwrap();
    assert!(done.mesh().attributes().is_empty());
}

/// The closest point of triangle `t` to `p`, by brute force over the inside, the edges and
/// the corners (independent of the library's region test).
fn closest_on(p: [f64; 3], t: [[f64; 3]; 3]) -> [f64; 3] {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let lerp = |a: [f64; 3], b: [f64; 3], s: f64| {
        [
            a[0] + s * (b[0] - a[0]),
            a[1] + s * (b[1] - a[1]),
            a[2] + s * (b[2] - a[2]),
        ]
    };
    let on_segment = |a: [f64; 3], b: [f64; 3]| {
        let d = sub(b, a);
        lerp(a, b, (dot(sub(p, a), d) / dot(d, d)).clamp(0.0, 1.0))
    };
    let mut candidates = vec![
        on_segment(t[0], t[1]),
        on_segment(t[1], t[2]),
        on_segment(t[2], t[0]),
    ];
    // The projection on the plane, when inside (barycentric weights all positive).
    let (e1, e2, w) = (sub(t[1], t[0]), sub(t[2], t[0]), sub(p, t[0]));
    let (a, b, c, d, e) = (
        dot(e1, e1),
        dot(e1, e2),
        dot(e2, e2),
        dot(w, e1),
        dot(w, e2),
    );
    let det = a * c - b * b;
    let (s, r) = ((c * d - b * e) / det, (a * e - b * d) / det);
    if s >= 0.0 && r >= 0.0 && s + r <= 1.0 {
        candidates.push([
            t[0][0] + s * e1[0] + r * e2[0],
            t[0][1] + s * e1[1] + r * e2[1],
            t[0][2] + s * e1[2] + r * e2[2],
        ]);
    }
    let dist = |q: [f64; 3]| dot(sub(q, p), sub(q, p));
    candidates
        .into_iter()
        .min_by(|x, y| dist(*x).total_cmp(&dist(*y)))
        .unwrap()
}

#[test]
fn moved_vertices_take_the_fields_value_at_their_closest_input_point() {
    // A gently curved height field: the subset run gets stuck, collapses and slides move
    // vertices. u, v are linear in x and y on every face, so the carried value at a moved
    // vertex is the field at its closest input point.
    for (n, placement) in [(16, Placement::Collapse), (30, Placement::Slide)] {
        let flat = plane(n);
        let mut positions: Vec<[f64; 3]> = flat.positions().collect();
        for p in &mut positions {
            p[2] = 0.03 * (7.0 * p[0]).sin() * (5.0 * p[1]).cos();
        }
        let tris: Vec<[u32; 3]> = flat.triangles().collect();
        let bumpy = Mesh::new(positions.clone(), tris.clone())
            .unwrap()
            .with_attributes(flat.attributes().clone())
            .unwrap();
        let done = Simplifier::new(Epsilon::percent(0.2))
            .placement(placement)
            .threads(1)
            .run(&bumpy)
            .unwrap();
        let out = done.mesh();
        let origin = origins(&bumpy, out);
        let uv = out.attributes().texcoords.as_ref().unwrap();
        let out_positions: Vec<[f64; 3]> = out.positions().collect();
        let mut moved = 0;
        for (f, tri) in out.triangles().enumerate() {
            for (k, &v) in tri.iter().enumerate() {
                let p = out_positions[v as usize];
                let want = match origin[v as usize] {
                    Some(_) => linear(p),
                    None => {
                        moved += 1;
                        let sq = |q: [f64; 3]| (0..3).map(|c| (q[c] - p[c]).powi(2)).sum::<f64>();
                        let q = tris
                            .iter()
                            .map(|t| closest_on(p, t.map(|i| positions[i as usize])))
                            .min_by(|a, b| sq(*a).total_cmp(&sq(*b)))
                            .unwrap();
                        linear(q)
                    }
                };
                let got = uv.value(f, k);
                for c in 0..2 {
                    assert!(
                        (got[c] - want[c]).abs() <= 1e-9 * want[c].abs().max(1e-3),
                        "{placement:?} face {f} corner {k} at {p:?}: {got:?} vs {want:?}"
                    );
                }
            }
        }
        assert!(moved > 0, "{placement:?}: nothing moved");
    }
}

/// A roof: two planes meeting at a straight crease x = 1/2, flat-shaded (each plane's faces
/// carry its normal at every corner), so only the crease edges are sharp.
fn roof(n: u32) -> Mesh {
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let x = f64::from(i) / f64::from(n);
            positions.push([x, f64::from(j) / f64::from(n), 0.3 * (x - 0.5).abs()]);
        }
    }
    let mut faces = Vec::new();
    let mut corners = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let v = j * (n + 1) + i;
            let side = u32::from(i >= n / 2);
            faces.push([v, v + 1, v + n + 2]);
            faces.push([v, v + n + 2, v + n + 1]);
            corners.push([side; 3]);
            corners.push([side; 3]);
        }
    }
    let normals = Wedges {
        values: vec![[0.3, 0.0, 1.0], [-0.3, 0.0, 1.0]],
        corners,
    };
    Mesh::new(positions, faces)
        .unwrap()
        .with_attributes(Attributes {
            normals: Some(normals),
            ..Attributes::default()
        })
        .unwrap()
}

#[test]
fn normals_stay_flat_on_each_side_of_a_crease() {
    let mesh = roof(12);
    // Normal creases are not kept: the roof simplifies like an unshaded one.
    assert!(seam_vertices(&mesh).iter().all(|k| !k));
    let done = Simplifier::new(Epsilon::percent(1.0))
        .threads(1)
        .run(&mesh)
        .unwrap();
    let out = done.mesh();
    assert!(out.num_faces() < 40, "{}", out.num_faces());
    let normals = out.attributes().normals.as_ref().unwrap();
    let positions: Vec<[f64; 3]> = out.positions().collect();
    let unit = |n: [f64; 3]| {
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        n.map(|x| x / l)
    };
    for (f, tri) in out.triangles().enumerate() {
        let cx: f64 = tri.iter().map(|&v| positions[v as usize][0]).sum::<f64>() / 3.0;
        let want = unit(if cx < 0.5 {
            [0.3, 0.0, 1.0]
        } else {
            [-0.3, 0.0, 1.0]
        });
        for k in 0..3 {
            let got = unit(normals.value(f, k));
            for c in 0..3 {
                assert!(
                    (got[c] - want[c]).abs() < 1e-12,
                    "face {f} corner {k}: {got:?}"
                );
            }
        }
    }
}
