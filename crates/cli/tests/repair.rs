//! End-to-end tests of `envelope repair` and of `--repair` on `simplify`, `lod` and
//! `verify`: exit codes, the report file, outputs written only on success.

mod common;

use std::path::Path;
use std::process::Output;

use common::{envelope, read_json};
use envelope_check::{CheckOptions, check};
use envelope_io::{Format, read_path, write_path};
use envelope_mesh::{TriangleSoup, generate};

fn run(args: &[&str]) -> Output {
    envelope().args(args).output().expect("run envelope")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn write(dir: &Path, name: &str, soup: &TriangleSoup) -> String {
    let p = dir.join(name);
    write_path(&p, soup, Format::Off).unwrap();
    p.to_str().unwrap().to_string()
}

/// An icosphere written with unshared corners (as STL has them), one face flipped and one
/// repeated: refused by `check`, repaired by the weld, the duplicate drop and the
/// orientation.
fn broken_sphere() -> TriangleSoup {
    let s = generate::icosphere(2, 1.0);
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for f in s.face_ids() {
        let n = positions.len() as u32;
        positions.extend(s.triangle(f).map(|p| p.to_array()));
        faces.push([n, n + 1, n + 2]);
    }
    faces[4].swap(1, 2);
    faces.push(faces[9]);
    TriangleSoup::from_raw(&positions, &faces)
}

#[test]
fn repair_writes_an_acceptable_mesh_and_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let input = write(dir.path(), "in.off", &broken_sphere());
    assert_eq!(run(&["check", &input]).status.code(), Some(1));
    let output = dir.path().join("out.ply");
    let report = dir.path().join("r.json");
    let out = run(&[
        "repair",
        &input,
        output.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("acceptable input"), "{stdout}");
    let (soup, _) = read_path(&output).unwrap();
    assert!(check(&soup, &CheckOptions::default()).acceptable());
    assert_eq!((soup.num_vertices(), soup.num_faces()), (162, 320));
    let r = read_json(&report);
    let steps = &r["repair"]["steps"];
    assert_eq!(steps[0]["step"], "weld");
    assert_eq!(steps[0]["count"], 3 * 320 - 162);
    assert_eq!(steps[1]["count"], 1);
    assert_eq!(steps[1]["examples"][0]["dropped"], 320);
    assert_eq!(steps[6]["step"], "orientation");
    assert_eq!(steps[6]["count"], 1);
    assert_eq!(steps[6]["examples"][0]["face"], 4);
    assert_eq!(r["repair"]["acceptable"], true);
    assert_eq!(r["check"]["acceptable"], true);
    assert_eq!(assert_only(dir.path()), 3);
}

/// Files in `dir` (no temporaries left behind).
fn assert_only(dir: &Path) -> usize {
    let names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.starts_with('.')), "{names:?}");
    names.len()
}

#[test]
fn repair_exits_1_when_what_is_left_is_not_repairable() {
    let dir = tempfile::tempdir().unwrap();
    let input = write(dir.path(), "bow.off", &generate::bow_tie());
    let output = dir.path().join("out.off");
    let report = dir.path().join("r.json");
    let out = run(&[
        "repair",
        &input,
        output.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("still not acceptable"), "{stdout}");
    assert!(stdout.contains("intersecting_triangles"), "{stdout}");
    assert!(output.exists());
    let r = read_json(&report);
    assert_eq!(r["repair"]["acceptable"], false);
    assert_eq!(r["repair"]["steps"][5]["count"], 1);
    assert!(
        r["repair"]["left"]
            .as_array()
            .unwrap()
            .iter()
            .any(|l| l["class"] == "intersecting_triangles")
    );
}

#[test]
fn refusals_name_the_element_and_replace_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let input = write(dir.path(), "moebius.off", &generate::moebius_strip(6));
    let output = dir.path().join("out.off");
    let report = dir.path().join("r.json");
    std::fs::write(&output, "KEEP").unwrap();
    let out = run(&[
        "repair",
        &input,
        output.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(
        err.contains("non-orientable") && err.contains("face f"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&output).unwrap(), "KEEP");
    assert!(!report.exists());
    assert_eq!(assert_only(dir.path()), 2);

    // A zero-area face sticking out of the surface.
    let mut soup = generate::tetrahedron();
    soup.positions.push(glam::DVec3::new(2.0, 0.0, 0.0));
    soup.positions.push(glam::DVec3::new(3.0, 0.0, 0.0));
    soup.faces.push([0, 4, 5].map(envelope_mesh::VertexId));
    let input = write(dir.path(), "stick.off", &soup);
    let out = run(&["repair", &input, output.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("face f4"), "{}", stderr(&out));
    assert_eq!(std::fs::read_to_string(&output).unwrap(), "KEEP");

    // Unreadable input, and a bad output path, before any work.
    let out = run(&["repair", "missing.off", output.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let out = run(&[
        "repair",
        &input,
        dir.path().join("out.xyz").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("unknown output format"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn simplify_with_repair_certifies_what_simplify_refuses() {
    let dir = tempfile::tempdir().unwrap();
    let input = write(dir.path(), "in.off", &broken_sphere());
    let output = dir.path().join("out.off");
    let report = dir.path().join("r.json");
    let out = run(&[
        "simplify",
        &input,
        output.to_str().unwrap(),
        "--epsilon",
        "2%",
    ]);
    assert_eq!(out.status.code(), Some(2), "refused without --repair");
    assert!(!output.exists());
    let out = run(&[
        "simplify",
        &input,
        output.to_str().unwrap(),
        "--epsilon",
        "2%",
        "--repair",
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let r = read_json(&report);
    assert_eq!(r["verify"]["verdict"], "holds", "{r:#}");
    assert_eq!(r["repair"]["steps"][0]["step"], "weld");
    assert_eq!(r["repair"]["acceptable"], true);
    // The certificate against the file itself, as written.
    let out = run(&[
        "verify",
        &input,
        output.to_str().unwrap(),
        "--epsilon",
        "2%",
        "--repair",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["verdict"], "holds");
    assert_eq!(v["repair"]["steps"][1]["count"], 1);
}

#[test]
fn lod_with_repair_records_it_in_the_summary() {
    let dir = tempfile::tempdir().unwrap();
    let input = write(dir.path(), "in.off", &broken_sphere());
    let out_dir = dir.path().join("levels");
    let out = run(&[
        "lod",
        &input,
        out_dir.to_str().unwrap(),
        "--epsilons",
        "1%,2%",
        "--repair",
        "--quiet",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let s = read_json(&out_dir.join("summary.json"));
    assert_eq!(s["repair"]["acceptable"], true);
    assert_eq!(s["levels"].as_array().unwrap().len(), 2);
}
