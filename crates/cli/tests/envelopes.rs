//! End-to-end tests of `envelope envelopes`: outputs, JSON, exit codes, per-vertex files.

use std::process::Output;

use envelope_io::{Format, read_path, write_path};
use envelope_mesh::generate;

mod common;
use common::assert_ok;

fn envelope(args: &[&str]) -> Output {
    common::envelope()
        .args(args)
        .output()
        .expect("run envelope")
}

fn json(out: &Output) -> serde_json::Value {
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "bad JSON ({e}): {}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    })
}

#[test]
fn sphere_is_proved_with_both_methods() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("sphere.off");
    write_path(&input, &generate::icosphere(3, 1.0), Format::Off).unwrap();
    for method in ["numerical", "analytical"] {
        let out_dir = dir.path().join(method);
        let out = envelope(&[
            "envelopes",
            input.to_str().unwrap(),
            "--epsilon",
            "1/4%",
            "--method",
            method,
            "--out-dir",
            out_dir.to_str().unwrap(),
            "--json",
        ]);
        assert_ok(&out);
        let v = json(&out);
        assert_eq!(v["proved"], true);
        assert!(v["epsilon_fraction"]["median"].as_f64().unwrap() > 0.99);
        let (outer, _) = read_path(out_dir.join("outer.off")).unwrap();
        let (inner, _) = read_path(out_dir.join("inner.off")).unwrap();
        assert_eq!(outer.num_faces(), inner.num_faces());
    }
}

#[test]
fn bordered_mesh_writes_tubes_in_ply() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("cyl.obj");
    write_path(
        &input,
        &generate::open_cylinder(1.0, 1.0, 16, 4),
        Format::Obj,
    )
    .unwrap();
    let out_dir = dir.path().join("out");
    let out = envelope(&[
        "envelopes",
        input.to_str().unwrap(),
        "--epsilon",
        "0.02",
        "--format",
        "ply",
        "--out-dir",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("PROVED"), "{text}");
    assert!(out_dir.join("tube-0.ply").exists() && out_dir.join("tube-1.ply").exists());
}

#[test]
fn per_vertex_epsilon_file() {
    let dir = tempfile::tempdir().unwrap();
    let sphere = generate::icosphere(1, 1.0);
    let input = dir.path().join("s.off");
    write_path(&input, &sphere, Format::Off).unwrap();
    let mut text = String::from("# per-vertex epsilon\n");
    for i in 0..sphere.num_vertices() {
        text.push_str(if i % 2 == 0 {
            "0.01\n"
        } else {
            "1/64%  # a comment\n"
        });
    }
    let eps = dir.path().join("eps.txt");
    std::fs::write(&eps, &text).unwrap();
    let out_dir = dir.path().join("out");
    let args = [
        "envelopes",
        input.to_str().unwrap(),
        "--epsilon-file",
        eps.to_str().unwrap(),
        "--out-dir",
        out_dir.to_str().unwrap(),
        "--json",
    ];
    let out = envelope(&args);
    assert_ok(&out);
    // Wrong count: bad input.
    std::fs::write(&eps, "0.01\n").unwrap();
    let out = envelope(&args);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("epsilon values"));
}

#[test]
fn bad_input_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("bowtie.off");
    write_path(&input, &generate::bow_tie(), Format::Off).unwrap();
    let out = envelope(&[
        "envelopes",
        input.to_str().unwrap(),
        "--epsilon",
        "1%",
        "--out-dir",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("not manifold"));
    let sphere = dir.path().join("s.off");
    write_path(&sphere, &generate::icosphere(1, 1.0), Format::Off).unwrap();
    for bad in ["-1%", "abc", "1/0%"] {
        let out = envelope(&["envelopes", sphere.to_str().unwrap(), "--epsilon", bad]);
        assert_eq!(out.status.code(), Some(2), "{bad}");
    }
    let out = envelope(&[
        "envelopes",
        dir.path().join("missing.off").to_str().unwrap(),
        "--epsilon",
        "1%",
    ]);
    assert_eq!(out.status.code(), Some(2));
}
