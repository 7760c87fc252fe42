//! End-to-end tests of `envelope verify`: exit codes 0/1/2/3, JSON fields, witnesses.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use envelope_io::{Format, write_path};
use envelope_mesh::{TriangleSoup, generate};

fn envelope(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_envelope"))
        .args(args)
        .output()
        .expect("run envelope")
}

fn write(dir: &Path, name: &str, soup: &TriangleSoup) -> PathBuf {
    let p = dir.join(name);
    write_path(&p, soup, Format::Off).unwrap();
    p
}

fn verify_json(orig: &Path, approx: &Path, extra: &[&str]) -> (i32, serde_json::Value) {
    let mut args = vec![
        "verify",
        orig.to_str().unwrap(),
        approx.to_str().unwrap(),
        "--json",
    ];
    args.extend_from_slice(extra);
    let out = envelope(&args);
    let v = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "bad JSON ({e}): {}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    });
    (out.status.code().unwrap(), v)
}

/// The sphere and a copy with vertex 0 pushed outward by 0.01.
fn pair(dir: &Path) -> (PathBuf, PathBuf) {
    let orig = generate::icosphere(2, 1.0);
    let mut approx = orig.clone();
    approx.positions[0] *= 1.01;
    (
        write(dir, "orig.off", &orig),
        write(dir, "approx.off", &approx),
    )
}

#[test]
fn holds_exits_0_with_intervals() {
    let dir = tempfile::tempdir().unwrap();
    let (o, a) = pair(dir.path());
    let (code, v) = verify_json(&o, &a, &["--epsilon", "0.0101"]);
    assert_eq!(code, 0, "{v:#}");
    assert_eq!(v["verdict"], "holds");
    assert_eq!(v["violations"].as_array().unwrap().len(), 0);
    let side = &v["approx_to_orig"];
    assert_eq!(side["verdict"], "holds");
    let (lo, hi) = (
        side["lower"].as_f64().unwrap(),
        side["upper"].as_f64().unwrap(),
    );
    assert!(
        lo <= 0.01 + 1e-12 && (0.01 - 1e-12..=0.0101).contains(&hi),
        "{side:#}"
    );
    assert!(side["upper_relative"].as_f64().unwrap() > 0.0);
    assert_eq!(v["self_intersections"]["count"], 0);
    assert_eq!(v["topology"]["matches"], true);
    assert_eq!(v["topology"]["orig"]["genus"], 0);
}

#[test]
fn violated_exits_1_with_witness() {
    let dir = tempfile::tempdir().unwrap();
    let (o, a) = pair(dir.path());
    let (code, v) = verify_json(&o, &a, &["--epsilon", "0.0099"]);
    assert_eq!(code, 1, "{v:#}");
    assert_eq!(v["violations"][0], "approx_to_orig");
    let w = &v["approx_to_orig"]["witness"];
    assert_eq!(w["exact_f64"], true);
    assert!(w["distance_at_least"].as_f64().unwrap() > 0.0099);
    // Text form names the witness too.
    let out = envelope(&[
        "verify",
        o.to_str().unwrap(),
        a.to_str().unwrap(),
        "--epsilon",
        "0.0099",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("witness: face") && text.contains("verdict: violated"),
        "{text}"
    );
}

#[test]
fn topology_and_self_intersection_violations() {
    let dir = tempfile::tempdir().unwrap();
    let orig = generate::icosphere(2, 1.0);
    // Fold one vertex through the sphere: far outside epsilon too, but also intersecting.
    let mut folded = orig.clone();
    folded.positions[0] *= -1.5;
    let (o, a) = (
        write(dir.path(), "o.off", &orig),
        write(dir.path(), "a.off", &folded),
    );
    let (code, v) = verify_json(&o, &a, &["--epsilon", "10"]);
    assert_eq!(code, 1);
    assert_eq!(v["approx_to_orig"]["verdict"], "holds");
    assert!(v["self_intersections"]["count"].as_u64().unwrap() > 0);
    // A torus against a sphere: topology differs (and distance is not asked to fail).
    let t = write(dir.path(), "t.off", &generate::torus(0.7, 0.2, 24, 12));
    let (code, v) = verify_json(&o, &t, &["--epsilon", "100", "--no-self-intersections"]);
    assert_eq!(code, 1);
    assert_eq!(v["violations"], serde_json::json!(["topology"]));
    assert_eq!(v["topology"]["approx"]["genus"], 1);
}

#[test]
fn undecided_exits_3() {
    // orig: two points (as point-triangles) below a square; approx: the square [-1, 1]^2.
    // approx -> orig peaks on the bisector x = 0.1 at the square's border, sqrt(3.21): not a
    // dyadic subdivision point, so at epsilon = the nearest double the bounds meet within
    // the resolution without deciding.
    let dir = tempfile::tempdir().unwrap();
    let orig = TriangleSoup::from_raw(&[[-1., 0., -1.], [1.2, 0., -1.]], &[[0, 0, 0], [1, 1, 1]]);
    let approx = TriangleSoup::from_raw(
        &[[-1., -1., 0.], [1., -1., 0.], [1., 1., 0.], [-1., 1., 0.]],
        &[[0, 1, 2], [0, 2, 3]],
    );
    let (o, a) = (
        write(dir.path(), "o.off", &orig),
        write(dir.path(), "a.off", &approx),
    );
    let skip = ["--no-topology", "--no-self-intersections"];
    let peak = 3.21f64.sqrt();
    let run = |eps: f64| {
        verify_json(
            &o,
            &a,
            &[&["--epsilon", &eps.to_string()], &skip[..]].concat(),
        )
    };
    let (code, v) = run(peak);
    assert_eq!(code, 3, "{v:#}");
    assert_eq!(v["approx_to_orig"]["verdict"], "undecided");
    assert_eq!(v["orig_to_approx"]["verdict"], "holds");
    let (lo, hi) = (
        v["approx_to_orig"]["lower"].as_f64().unwrap(),
        v["approx_to_orig"]["upper"].as_f64().unwrap(),
    );
    assert!(lo <= peak && peak <= hi && hi - lo < 1e-5, "{v:#}");
    assert_eq!(run(peak - 1e-3).0, 1);
    assert_eq!(run(peak + 1e-3).0, 0);
}

#[test]
fn unreadable_input_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let (o, _) = pair(dir.path());
    let bad = dir.path().join("bad.off");
    std::fs::write(&bad, "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n").unwrap();
    let out = envelope(&[
        "verify",
        o.to_str().unwrap(),
        bad.to_str().unwrap(),
        "--epsilon",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("bad.off"));
    let out = envelope(&[
        "verify",
        o.to_str().unwrap(),
        o.to_str().unwrap(),
        "--epsilon",
        "-1",
    ]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn envelope_of_and_stop_at_first() {
    let dir = tempfile::tempdir().unwrap();
    let (o, a) = pair(dir.path());
    // Vertex 0 moved by 0.01: inside the 0.0101-envelope, outside the 0.0099 one.
    let (code, v) = verify_json(&o, &a, &["--epsilon", "0.0101", "--envelope-of"]);
    assert_eq!(code, 0, "{v:#}");
    assert_eq!(v["envelope_of"], "holds");
    assert_eq!(v["two_sided"], false);
    assert!(v["orig_to_approx"].is_null());
    let (code, v) = verify_json(
        &o,
        &a,
        &["--epsilon", "0.0099", "--envelope-of", "--stop-at-first"],
    );
    assert_eq!(code, 1, "{v:#}");
    assert_eq!(v["envelope_of"], "violated");
    assert_eq!(v["self_intersections"]["complete"], false);
    let out = envelope(&[
        "verify",
        o.to_str().unwrap(),
        a.to_str().unwrap(),
        "--epsilon",
        "0.0101",
        "--envelope-of",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("envelope_of: holds"), "{text}");
    assert!(text.contains("not checked"), "{text}");
}

/// `--map`: the PLY is written whatever the verdict (holds: exit 0; violated: exit 1), with
/// per-vertex quality and colours, and the JSON gains the per-face bounds; a non-PLY path is
/// refused before any work (exit 2) and nothing is written.
#[test]
fn map_is_written_holds_or_not_and_refused_when_not_ply() {
    let dir = tempfile::tempdir().unwrap();
    let (o, a) = pair(dir.path());
    let map = dir.path().join("map.ply");
    let m = map.to_str().unwrap();
    let (code, v) = verify_json(&o, &a, &["--epsilon", "0.0101", "--map", m]);
    assert_eq!(code, 0, "{v:#}");
    let (back, attributes, _) = envelope_io::read_path_with_attributes(&map).unwrap();
    let q = attributes.quality.expect("quality");
    assert!(attributes.colors.is_some());
    assert_eq!(
        back.faces.len(),
        v["map"]["approx_faces"]["upper"].as_array().unwrap().len()
    );
    assert_eq!(
        v["map"]["orig_faces"]["lower"].as_array().unwrap().len(),
        generate::icosphere(2, 1.0).faces.len()
    );
    // Vertex 0 moved by 0.01 (within 0.0101): it carries the largest bound.
    let worst = q.values.iter().map(|x| x[0]).fold(0.0, f64::max);
    assert!((0.0099..=0.0102).contains(&worst), "{worst}");
    assert!(v["map"]["approx_vertices"][0].as_f64().unwrap() >= 0.0099);
    let text = std::fs::read(&map).unwrap();
    let text = String::from_utf8_lossy(&text);
    assert!(text.contains("comment ramp viridis 0 0.0101\n"));

    // Violated: exit 1, and the map is written all the same.
    std::fs::remove_file(&map).unwrap();
    let out = envelope(&[
        "verify",
        o.to_str().unwrap(),
        a.to_str().unwrap(),
        "--epsilon",
        "0.005",
        "--map",
        m,
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stdout).contains("error map: "));
    assert!(map.exists());

    // Not a .ply: exit 2 before any work, nothing written.
    let off = dir.path().join("map.off");
    let out = envelope(&[
        "verify",
        o.to_str().unwrap(),
        a.to_str().unwrap(),
        "--epsilon",
        "0.0101",
        "--map",
        off.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("PLY"));
    assert!(!off.exists());
    // Even with an unreadable input: the path is refused first.
    let out = envelope(&[
        "verify",
        "missing.off",
        a.to_str().unwrap(),
        "--epsilon",
        "0.0101",
        "--map",
        off.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--map"));
    let entries: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(
        entries.len(),
        3,
        "orig, approx, map.ply only: no temporaries"
    );
}
