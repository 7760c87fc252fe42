//! End-to-end tests of the `envelope` program: exit codes, counts, JSON, bad input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use envelope_io::{Format, PlyEncoding, StlEncoding, write_path};
use envelope_mesh::{TriangleSoup, generate};

fn envelope(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_envelope"))
        .args(args)
        .output()
        .expect("run envelope")
}

fn write(dir: &Path, name: &str, soup: &TriangleSoup, format: Format) -> PathBuf {
    let p = dir.join(name);
    write_path(&p, soup, format).unwrap();
    p
}

fn check_json(path: &Path) -> (i32, serde_json::Value) {
    let out = envelope(&["check", "--json", path.to_str().unwrap()]);
    let v = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "bad JSON ({e}): {}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    });
    (out.status.code().unwrap(), v)
}

#[test]
fn known_topology_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    // (name, mesh, genus, border loops, components)
    let cases = [
        ("sphere", generate::icosphere(3, 1.0), 0, 0, 1),
        ("torus", generate::torus(2.0, 0.5, 40, 20), 1, 0, 1),
        ("double-torus", generate::plate_with_holes(2), 2, 0, 1),
        (
            "open-cylinder",
            generate::open_cylinder(1.0, 1.0, 24, 6),
            0,
            2,
            1,
        ),
    ];
    let formats = [
        Format::Obj,
        Format::Off,
        Format::Ply(PlyEncoding::Ascii),
        Format::Ply(PlyEncoding::BinaryBigEndian),
        Format::Stl(StlEncoding::Binary),
        Format::Stl(StlEncoding::Ascii),
    ];
    for (name, soup, genus, borders, components) in cases {
        for format in formats {
            // STL stores f32: round the positions so the file holds the same mesh.
            let soup = if matches!(format, Format::Stl(_)) {
                let mut s = soup.clone();
                s.positions
                    .iter_mut()
                    .for_each(|p| *p = p.as_vec3().as_dvec3());
                s
            } else {
                soup.clone()
            };
            let file = write(
                dir.path(),
                &format!("{name}.{}", format.extension()),
                &soup,
                format,
            );
            let (code, v) = check_json(&file);
            let ctx = format!("{name} as {format}");
            assert_eq!(code, 0, "{ctx}: {v}");
            assert_eq!(v["genus"], genus, "{ctx}");
            assert_eq!(v["border_loops"], borders, "{ctx}");
            assert_eq!(v["components"], components, "{ctx}");
            assert_eq!(v["faces"], soup.num_faces(), "{ctx}");
            assert_eq!(v["vertices"], soup.num_vertices(), "{ctx}");
            assert_eq!(v["acceptable"], true, "{ctx}");
        }
    }
}

#[test]
fn degeneracies_give_exit_1_and_name_the_elements() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "bowtie.off", &generate::bow_tie(), Format::Off);
    let (code, v) = check_json(&file);
    assert_eq!(code, 1);
    assert_eq!(v["degeneracies"]["non_manifold_vertices"]["count"], 1);
    assert_eq!(
        v["degeneracies"]["non_manifold_vertices"]["examples"][0]["vertex"],
        0
    );

    let out = envelope(&["check", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("non_manifold_vertices") && text.contains("not acceptable"),
        "{text}"
    );
}

#[test]
fn warnings_keep_exit_0() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = generate::tetrahedron();
    s.positions.push(glam::DVec3::splat(7.0));
    let file = write(dir.path(), "extra-vertex.obj", &s, Format::Obj);
    let (code, v) = check_json(&file);
    assert_eq!(code, 0);
    assert_eq!(v["degeneracies"]["unreferenced_vertices"]["count"], 1);
    assert_eq!(
        v["degeneracies"]["unreferenced_vertices"]["severity"],
        "warning"
    );
}

#[test]
fn polygons_are_triangulated_and_reported() {
    let dir = tempfile::tempdir().unwrap();
    let cube = "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n\
                4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
    let file = dir.path().join("cube.off");
    std::fs::write(&file, cube).unwrap();
    let (code, v) = check_json(&file);
    assert_eq!(code, 0, "{v}");
    assert_eq!(
        (v["faces"].as_u64(), v["polygons_triangulated"].as_u64()),
        (Some(12), Some(6))
    );
    assert_eq!(v["genus"], 0);
}

#[test]
fn unreadable_input_gives_exit_2_and_a_message_naming_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("truncated.off", b"OFF\n4 4 0\n0 0 0\n1 0 0\n".to_vec(), "truncated.off"),
        ("nan.obj", b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n".to_vec(), "line 2"),
        ("inf.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n".to_vec(), "inf.off"),
        ("huge.obj", b"v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n".to_vec(), "line 2"),
        ("index.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n".to_vec(), "line 4"),
        ("empty.off", b"OFF\n0 0 0\n".to_vec(), "empty.off"),
        ("garbage.ply", vec![0xff, 0x00, 0x13, 0x37, 0x42, 0x99, 0x01], "garbage.ply"),
        ("header.ply", b"ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\nend_header\n".to_vec(), "header.ply"),
    ];
    for (name, bytes, mention) in cases {
        let file = dir.path().join(name);
        std::fs::write(&file, &bytes).unwrap();
        let out = envelope(&["check", file.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.contains(mention),
            "{name}: message should mention {mention:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{name}: {err}");
    }
    // A directory and a missing file.
    for p in [dir.path().to_path_buf(), dir.path().join("missing.off")] {
        let out = envelope(&["check", p.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2));
        assert!(!String::from_utf8_lossy(&out.stderr).contains("panicked"));
    }
    // Wrong arguments.
    assert_eq!(envelope(&["check"]).status.code(), Some(2));
}

/// A reader that closes stdout early (`| head`) ends the program quietly with status 141,
/// not with a panic: a check whose JSON is far larger than a pipe's buffer, read for a few
/// bytes.
#[test]
fn closed_stdout_ends_quietly() {
    use std::io::Read;
    use std::process::Stdio;
    let dir = tempfile::tempdir().unwrap();
    // 20,000 separate triangles each doubled: as many duplicate-face examples to print.
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for i in 0..20_000u32 {
        let x = f64::from(i);
        positions.extend([[x, 0.0, 0.0], [x + 0.5, 0.0, 0.0], [x, 0.5, 0.0]]);
        faces.extend([[3 * i, 3 * i + 1, 3 * i + 2], [3 * i, 3 * i + 1, 3 * i + 2]]);
    }
    let path = write(
        dir.path(),
        "doubled.off",
        &TriangleSoup::from_raw(&positions, &faces),
        Format::Off,
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_envelope"))
        .args(["check", "--json", "--examples", "10000"])
        .arg(&path)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child
        .stdout
        .as_mut()
        .unwrap()
        .read_exact(&mut first)
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(out.status.code(), Some(141), "{err}");
}
