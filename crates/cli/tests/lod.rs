//! End-to-end tests of `envelope lod`: nested vertex sets, monotone face counts, summary.

use std::collections::HashSet;

use envelope_io::{Format, read_path, write_path};
use envelope_mesh::generate;

mod common;
use common::{assert_ok, envelope, read_json};

fn key(p: glam::DVec3) -> [u64; 3] {
    p.to_array().map(f64::to_bits)
}

#[test]
fn torus_chain_is_nested_monotone_and_certified() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("torus.off");
    write_path(&input, &generate::torus(1.0, 0.35, 48, 24), Format::Off).unwrap();
    let out_dir = dir.path().join("lod");
    let out = envelope()
        .args(["lod", input.to_str().unwrap(), out_dir.to_str().unwrap()])
        .args([
            "--epsilons",
            "1/8%, 1/4%,1/2%,1%",
            "--pixels",
            "2",
            "--resolution",
            "1000",
            "--fov",
            "90",
        ])
        .output()
        .unwrap();
    assert_ok(&out);
    let s: serde_json::Value = read_json(&out_dir.join("summary.json"));
    let levels = s["levels"].as_array().unwrap();
    assert_eq!(levels.len(), 4);
    assert_eq!(s["rule"], "cumulative");
    let diag = s["diagonal"].as_f64().unwrap();
    let mut previous = read_path(out_dir.join("level-0.off")).unwrap().0;
    assert_eq!(previous.num_faces(), 48 * 24 * 2);
    for (i, l) in levels.iter().enumerate() {
        let (mesh, _) = read_path(out_dir.join(format!("level-{}.off", i + 1))).unwrap();
        assert_eq!(l["faces"], mesh.num_faces());
        assert_eq!(l["vertices"], mesh.num_vertices());
        assert!(mesh.num_faces() <= previous.num_faces(), "level {}", i + 1);
        let before: HashSet<[u64; 3]> = previous.positions.iter().map(|&p| key(p)).collect();
        assert!(
            mesh.positions.iter().all(|&p| before.contains(&key(p))),
            "level {} not nested",
            i + 1
        );
        let bound = l["cumulative_bound"].as_f64().unwrap();
        let requested = l["epsilon_requested"].as_f64().unwrap();
        assert!((bound - requested).abs() <= 1e-15 * diag);
        // d = eps W / (2 P tan(fov/2)) with W = 1000, P = 2, fov = 90 degrees (tan 45 = 1).
        let d = l["switching_distance"].as_f64().unwrap();
        assert!((d - bound * 1000.0 / 4.0).abs() <= 1e-9 * d, "{l:#}");
        let c = &l["certified_vs_original"];
        assert_eq!(c["verdict"], "holds", "{c:#}");
        assert!(c["approx_to_orig"]["upper"].as_f64().unwrap() <= bound);
        assert!(c["orig_to_approx"]["upper"].as_f64().unwrap() <= bound);
        assert_eq!(l["genus"], 1);
        previous = mesh;
    }
    let first = levels[0]["faces"].as_u64().unwrap();
    let last = levels[3]["faces"].as_u64().unwrap();
    assert!(last < first, "{first} -> {last}");
}

#[test]
fn decreasing_epsilons_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("s.off");
    write_path(&input, &generate::icosphere(2, 1.0), Format::Off).unwrap();
    let out = envelope()
        .args([
            "lod",
            input.to_str().unwrap(),
            dir.path().join("o").to_str().unwrap(),
        ])
        .args(["--epsilons", "1%,1/2%"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("increasing"));
}

/// `--correspondences --to-original`: one file per level, every finer face covered, the
/// composed map onto level 0, and the lists within the face counts.
#[test]
fn correspondence_files_cover_every_finer_face() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("torus.off");
    write_path(&input, &generate::torus(1.0, 0.35, 32, 16), Format::Off).unwrap();
    let out_dir = dir.path().join("lod");
    let out = envelope()
        .args(["lod", input.to_str().unwrap(), out_dir.to_str().unwrap()])
        .args([
            "--epsilons",
            "1%,2%,4%",
            "--correspondences",
            "--to-original",
        ])
        .output()
        .unwrap();
    assert_ok(&out);
    let summary: serde_json::Value = read_json(&out_dir.join("summary.json"));
    let level_faces = |i: usize| -> u64 {
        if i == 0 {
            summary["level_0"]["faces"].as_u64().unwrap()
        } else {
            summary["levels"][i - 1]["faces"].as_u64().unwrap()
        }
    };
    let covered = |v: &serde_json::Value, fine: u64| {
        let mut hit = vec![false; fine as usize];
        for list in v["covers"].as_array().unwrap() {
            for f in list.as_array().unwrap() {
                hit[f.as_u64().unwrap() as usize] = true;
            }
        }
        hit.iter().all(|&h| h)
    };
    for i in 1..=3 {
        let c: serde_json::Value = read_json(&out_dir.join(format!("correspondence-{i}.json")));
        assert_eq!(c["level"], i);
        assert_eq!(c["coarse_faces"], level_faces(i));
        assert_eq!(c["fine_faces"], level_faces(i - 1));
        assert_eq!(c["covers"].as_array().unwrap().len() as u64, level_faces(i));
        assert!(covered(&c, level_faces(i - 1)), "level {i}");
        assert_eq!(c["by_nearest"].as_array().unwrap().len(), 0, "closed torus");
        let step = summary["levels"][i - 1]["epsilon_step"].as_f64().unwrap();
        for e in c["error"].as_array().unwrap() {
            assert!(e.as_f64().unwrap() <= step * (1.0 + 1e-9));
        }
        let down = &c["to_original"];
        assert_eq!(down["fine_faces"], level_faces(0));
        assert!(covered(down, level_faces(0)), "level {i} to level 0");
    }
    // Without --correspondences there are none; --to-original alone is refused (exit 2).
    let out = envelope()
        .args(["lod", input.to_str().unwrap(), out_dir.to_str().unwrap()])
        .args(["--epsilons", "1%", "--to-original"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}
