//! End-to-end: a textured OBJ keeps its texture coordinates through `simplify` and
//! `repair`, without tears; formats without attributes say what they drop.

mod common;

use std::collections::HashMap;
use std::fmt::Write as _;
use std::process::Output;

use common::envelope;
use envelope_io::read_path_with_attributes;

fn run(args: &[&str]) -> Output {
    envelope().args(args).output().expect("run envelope")
}

/// An open cylinder, 24 around and 12 high, with u = i / 24 (1 on the seam's far side) and
/// v = j / 12, as OBJ text with `vt` per column and row.
fn textured_cylinder() -> String {
    let (n, m) = (24u32, 12u32);
    let mut s = String::new();
    for j in 0..=m {
        for i in 0..n {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
            writeln!(s, "v {:?} {:?} {:?}", a.cos(), a.sin(), f64::from(j) / 6.0).unwrap();
        }
    }
    for j in 0..=m {
        for i in 0..=n {
            writeln!(
                s,
                "vt {:?} {:?}",
                f64::from(i) / f64::from(n),
                f64::from(j) / f64::from(m)
            )
            .unwrap();
        }
    }
    let v = |i: u32, j: u32| j * n + i % n + 1;
    let t = |i: u32, j: u32| j * (n + 1) + i + 1;
    for j in 0..m {
        for i in 0..n {
            let c = |i, j| format!("{}/{}", v(i, j), t(i, j));
            writeln!(
                s,
                "f {} {} {} {}",
                c(i, j),
                c(i + 1, j),
                c(i + 1, j + 1),
                c(i, j + 1)
            )
            .unwrap();
        }
    }
    s
}

#[test]
fn a_textured_obj_keeps_its_texture_coordinates_without_tears() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("cyl.obj");
    std::fs::write(&input, textured_cylinder()).unwrap();
    let output = dir.path().join("out.obj");
    let out = run(&[
        "simplify",
        input.to_str().unwrap(),
        output.to_str().unwrap(),
        "--epsilon",
        "1%",
        "--quiet",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (soup, attributes, _) = read_path_with_attributes(&output).unwrap();
    assert!(soup.num_faces() < 24 * 12 * 2 / 2, "{}", soup.num_faces());
    let uv = attributes.texcoords.expect("texture coordinates written");
    // No tears: across every output edge both faces agree at both ends, except along the
    // seam (x = 1, y = 0), where u is 0 on one side and 1 on the other.
    let mut edges = HashMap::new();
    for (f, t) in soup.faces.iter().enumerate() {
        for k in 0..3 {
            edges.insert((t[k].0, t[(k + 1) % 3].0), (f, k));
        }
    }
    let mut seam_edges = 0;
    for (&(a, b), &(f, k)) in &edges {
        let Some(&(g, j)) = edges.get(&(b, a)) else {
            continue;
        };
        let ends = [
            (uv.value(f, k), uv.value(g, (j + 1) % 3)),
            (uv.value(f, (k + 1) % 3), uv.value(g, j)),
        ];
        for (x, y) in ends {
            if x != y {
                let (pa, pb) = (soup.positions[a as usize], soup.positions[b as usize]);
                assert!(
                    pa.x == 1.0 && pa.y == 0.0 && pb.x == 1.0 && pb.y == 0.0,
                    "tear at {pa} {pb}"
                );
                assert_eq!((x[0] - y[0]).abs(), 1.0);
                seam_edges += 1;
            }
        }
    }
    assert!(seam_edges >= 12, "{seam_edges}");
    // STL holds none: one note.
    let stl = dir.path().join("out.stl");
    let out = run(&[
        "simplify",
        input.to_str().unwrap(),
        stl.to_str().unwrap(),
        "--epsilon",
        "1%",
    ]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("holds no texture coordinates; not written"),
        "{err}"
    );
    // Repair carries them too.
    let repaired = dir.path().join("repaired.ply");
    let out = run(&[
        "repair",
        input.to_str().unwrap(),
        repaired.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (_, attributes, _) = read_path_with_attributes(&repaired).unwrap();
    assert!(attributes.texcoords.is_some());
}

/// `envelope batch` carries texture coordinates too: a simplified item and every level of a
/// chain come out with `vt`.
#[test]
fn batch_items_keep_their_texture_coordinates() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("cyl.obj"), textured_cylinder()).unwrap();
    let manifest = d.join("manifest.jsonl");
    std::fs::write(
        &manifest,
        [
            r#"{"id": "one", "input": "cyl.obj", "epsilon": "1%"}"#,
            r#"{"id": "chain", "input": "cyl.obj", "lod": ["1%", "4%"]}"#,
        ]
        .join("\n"),
    )
    .unwrap();
    let out = d.join("out");
    let done = run(&[
        "batch",
        manifest.to_str().unwrap(),
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(
        done.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    for file in [
        "one/simplified.obj",
        "chain/level-1.obj",
        "chain/level-2.obj",
    ] {
        let (soup, attributes, _) = read_path_with_attributes(out.join(file)).unwrap();
        let uv = attributes.texcoords.expect(file);
        assert_eq!(uv.corners.len(), soup.num_faces(), "{file}");
        assert!(
            soup.num_faces() < 24 * 12 * 2,
            "{file}: {}",
            soup.num_faces()
        );
    }
}
