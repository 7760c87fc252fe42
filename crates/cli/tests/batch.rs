//! `envelope batch`: one bad item never stops the others, a rerun does no work, a killed run
//! resumes, shards and thread counts give the same files, a bad manifest runs nothing.

mod common;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use common::envelope;
use envelope_io::{Format, write_path};
use envelope_mesh::generate;

/// A folder with two meshes, a broken file and a manifest naming them (and a missing one).
fn setup() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::create_dir(d.join("in")).unwrap();
    write_path(
        d.join("in/sphere.off"),
        &generate::uv_sphere(16, 8, 1.0),
        Format::Off,
    )
    .unwrap();
    write_path(
        d.join("in/torus.obj"),
        &generate::torus(2.0, 0.5, 16, 8),
        Format::Obj,
    )
    .unwrap();
    fs::write(d.join("in/broken.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n").unwrap();
    let manifest = d.join("in/manifest.jsonl");
    fs::write(
        &manifest,
        [
            r#"{"id": "sphere", "input": "sphere.off", "epsilon": "2%"}"#,
            r#"{"id": "broken", "input": "broken.off", "epsilon": "1%"}"#,
            "",
            r#"{"id": "torus", "input": "torus.obj", "lod": ["1%", "4%"], "format": "ply"}"#,
            r#"{"id": "missing", "input": "missing.off"}"#,
            r#"{"id": "plain", "input": "sphere.off", "placement": "subset", "method": "hybrid"}"#,
        ]
        .join("\n"),
    )
    .unwrap();
    (dir, manifest)
}

fn batch(manifest: &Path, out: &Path, extra: &[&str]) -> Output {
    envelope()
        .arg("batch")
        .arg(manifest)
        .arg(out)
        .args(["--epsilon", "3%"])
        .args(extra)
        .output()
        .unwrap()
}

fn summary(out: &Path) -> Vec<serde_json::Value> {
    fs::read_to_string(out.join("summary.jsonl"))
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

fn statuses(out: &Path) -> Vec<(String, String)> {
    summary(out)
        .iter()
        .map(|o| {
            (
                o["id"].as_str().unwrap().to_string(),
                o["status"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}

/// Every mesh file under `out`, with its bytes, by relative path.
fn meshes(out: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files = Vec::new();
    for item in fs::read_dir(out).unwrap() {
        let item = item.unwrap().path();
        if !item.is_dir() {
            continue;
        }
        for f in fs::read_dir(&item).unwrap() {
            let f = f.unwrap().path();
            if Format::from_path(&f).is_some() {
                let name = f.strip_prefix(out).unwrap().display().to_string();
                files.push((name, fs::read(&f).unwrap()));
            }
        }
    }
    files.sort();
    files
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn every_item_gets_a_status_and_a_rerun_does_no_work() {
    let (dir, manifest) = setup();
    let out = dir.path().join("out");
    let first = batch(&manifest, &out, &[]);
    assert_eq!(first.status.code(), Some(1), "{}", stdout(&first));
    let expected = [
        ("sphere", "ok"),
        ("broken", "bad_input"),
        ("torus", "ok"),
        ("missing", "bad_input"),
        ("plain", "ok"),
    ];
    let got = statuses(&out);
    assert_eq!(
        got,
        expected
            .iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect::<Vec<_>>()
    );
    let lines = summary(&out);
    assert!(
        lines[1]["message"]
            .as_str()
            .unwrap()
            .contains("broken.off: "),
        "{}",
        lines[1]
    );
    let sphere = &lines[0];
    assert!(sphere["faces"][0].as_u64().unwrap() < sphere["input_faces"].as_u64().unwrap());
    assert!(sphere["approx_to_orig"].as_f64().unwrap() <= sphere["epsilon"][0].as_f64().unwrap());
    assert!(out.join("sphere/simplified.off").exists());
    assert!(out.join("sphere/report.json").exists());
    assert!(out.join("torus/level-1.ply").exists() && out.join("torus/level-2.ply").exists());
    assert_eq!(lines[2]["faces"].as_array().unwrap().len(), 2);
    assert!(!out.join("broken").join("simplified.off").exists());
    let result = out.join("sphere/result.json");
    let written = fs::metadata(&result).unwrap().modified().unwrap();

    let second = batch(&manifest, &out, &[]);
    assert_eq!(second.status.code(), Some(1));
    assert!(
        stdout(&second).contains("(4 reused from earlier runs)"),
        "{}",
        stdout(&second)
    );
    assert_eq!(fs::metadata(&result).unwrap().modified().unwrap(), written);
    assert_eq!(statuses(&out), got);
}

#[test]
fn a_killed_run_resumes_and_a_changed_input_runs_again() {
    let (dir, manifest) = setup();
    let out = dir.path().join("out");
    batch(&manifest, &out, &[]);
    let before = meshes(&out);
    // A run killed while making `torus`: its folder never appeared, a partial one did.
    fs::remove_dir_all(out.join("torus")).unwrap();
    fs::create_dir(out.join(".torus.partial-1-0")).unwrap();
    let again = batch(&manifest, &out, &[]);
    let text = stdout(&again);
    assert!(text.contains("(3 reused from earlier runs)"), "{text}");
    assert_eq!(meshes(&out), before);
    // The missing input appears: that item runs, nothing else.
    write_path(
        dir.path().join("in/missing.off"),
        &generate::icosphere(2, 1.0),
        Format::Off,
    )
    .unwrap();
    let text = stdout(&batch(&manifest, &out, &[]));
    assert!(text.contains("(4 reused from earlier runs)"), "{text}");
    assert_eq!(statuses(&out)[3].1, "ok");
    // A changed input is a new key.
    write_path(
        dir.path().join("in/sphere.off"),
        &generate::uv_sphere(12, 6, 1.0),
        Format::Off,
    )
    .unwrap();
    let text = stdout(&batch(&manifest, &out, &[]));
    assert!(text.contains("(3 reused from earlier runs)"), "{text}");
}

#[test]
fn shards_and_thread_counts_make_the_same_files() {
    let (dir, manifest) = setup();
    let whole = dir.path().join("whole");
    batch(
        &manifest,
        &whole,
        &["--threads", "2", "--threads-per-item", "2"],
    );
    let sharded = dir.path().join("sharded");
    let one = batch(&manifest, &sharded, &["--shard", "1/2", "--threads", "1"]);
    assert!(stdout(&one).starts_with("3 items") || stdout(&one).contains("\n3 items"));
    let ids: Vec<String> = statuses(&sharded).into_iter().map(|(id, _)| id).collect();
    assert_eq!(ids, ["sphere", "torus", "plain"].map(String::from));
    batch(&manifest, &sharded, &["--shard", "2/2", "--threads", "1"]);
    assert_eq!(statuses(&sharded), statuses(&whole));
    assert_eq!(meshes(&sharded), meshes(&whole));
    assert!(!meshes(&whole).is_empty());
}

#[test]
fn a_bad_manifest_or_argument_runs_nothing() {
    let (dir, manifest) = setup();
    let out = dir.path().join("out");
    let mut text = fs::read_to_string(&manifest).unwrap();
    text.push_str("\n{\"id\": \"sphere\", \"input\": \"sphere.off\"}\n");
    fs::write(&manifest, &text).unwrap();
    let run = batch(&manifest, &out, &[]);
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        err.contains("manifest.jsonl: line 7: id \"sphere\" is already the id of line 1"),
        "{err}"
    );
    assert!(!out.exists());
    for shard in ["0/2", "3/2", "x", "1/0"] {
        let run = batch(&manifest, &out, &["--shard", shard]);
        assert_eq!(run.status.code(), Some(2), "--shard {shard}");
    }
    let run = batch(&dir.path().join("none.jsonl"), &out, &[]);
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("none.jsonl"));
}

#[test]
fn all_ok_exits_zero() {
    let dir = tempfile::tempdir().unwrap();
    write_path(
        dir.path().join("s.stl"),
        &generate::icosphere(2, 1.0),
        Format::from_extension("stl").unwrap(),
    )
    .unwrap();
    let manifest = dir.path().join("m.jsonl");
    fs::write(
        &manifest,
        r#"{"id": "s", "input": "s.stl", "epsilon": 0.05}"#,
    )
    .unwrap();
    let run = batch(&manifest, &dir.path().join("out"), &["--quiet"]);
    assert_eq!(run.status.code(), Some(0), "{}", stdout(&run));
    assert!(dir.path().join("out/s/simplified.stl").exists());
}

#[test]
fn repair_lets_an_unwelded_mesh_through() {
    let dir = tempfile::tempdir().unwrap();
    // Every face with corners of its own, as an STL-like export leaves it: refused as is.
    let sphere = generate::uv_sphere(16, 8, 1.0);
    let positions = sphere
        .faces
        .iter()
        .flat_map(|f| f.map(|v| sphere.positions[v.index()]))
        .collect();
    let faces = (0..sphere.faces.len() as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2].map(envelope_mesh::VertexId))
        .collect();
    let unwelded = envelope_mesh::TriangleSoup::new(positions, faces);
    write_path(dir.path().join("u.off"), &unwelded, Format::Off).unwrap();
    let manifest = dir.path().join("m.jsonl");
    fs::write(
        &manifest,
        "{\"id\": \"as-is\", \"input\": \"u.off\", \"epsilon\": \"2%\"}\n\
         {\"id\": \"repaired\", \"input\": \"u.off\", \"epsilon\": \"2%\", \"repair\": true}\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let run = batch(&manifest, &out, &[]);
    assert_eq!(run.status.code(), Some(1));
    assert_eq!(
        statuses(&out),
        [("as-is", "bad_input"), ("repaired", "ok")].map(|(a, b)| (a.to_string(), b.to_string()))
    );
    let lines = summary(&out);
    assert_eq!(lines[1]["input_faces"], sphere.faces.len());
    let repair: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("repaired/repair.json")).unwrap())
            .unwrap();
    assert_eq!(repair["acceptable"], true, "{repair}");
}
