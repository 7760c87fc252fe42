//! End-to-end tests of `envelope genus` and `envelope pipeline`.

use std::path::Path;

mod common;
use common::{assert_ok, envelope, read_json};
use envelope_io::{Format, read_path, write_path};
use envelope_mesh::{analyze, generate};

/// Runs `envelope pipeline INPUT OUT_DIR --steps STEPS`, asserts exit 0, and returns the
/// summary's stages.
fn pipeline(input: &Path, out_dir: &Path, steps: &str) -> Vec<serde_json::Value> {
    let out = envelope()
        .args([
            "pipeline",
            input.to_str().unwrap(),
            out_dir.to_str().unwrap(),
        ])
        .args(["--steps", steps])
        .output()
        .unwrap();
    assert_ok(&out);
    let s: serde_json::Value = read_json(&out_dir.join("summary.json"));
    s["stages"].as_array().unwrap().clone()
}

/// Runs `envelope genus INPUT OUTPUT --alpha ALPHA --report REPORT FLAGS`, asserts exit 0,
/// and returns the report.
fn genus_report(
    input: &Path,
    output: &Path,
    report: &Path,
    alpha: &str,
    flags: &[&str],
) -> serde_json::Value {
    let out = envelope()
        .args(["genus", input.to_str().unwrap(), output.to_str().unwrap()])
        .args(["--alpha", alpha, "--report", report.to_str().unwrap()])
        .args(flags)
        .output()
        .unwrap();
    assert_ok(&out);
    read_json(report)
}

#[test]
fn genus_fills_narrow_holes_and_reports() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("plate.off");
    write_path(&input, &generate::plate_with_holes(2), Format::Off).unwrap();
    let output = dir.path().join("out.obj");
    let report = dir.path().join("r.json");
    // Diagonal of the 5 x 3 x 1 plate is sqrt(35) = 5.92; 10% = 0.59 > 0.5 fills unit holes.
    let out = envelope()
        .args(["genus", input.to_str().unwrap(), output.to_str().unwrap()])
        .args(["--alpha", "10%", "--report", report.to_str().unwrap()])
        .output()
        .unwrap();
    assert_ok(&out);
    let (soup, _) = read_path(&output).unwrap();
    assert_eq!(analyze(&soup).genus, Some(0));
    let r: serde_json::Value = read_json(&report);
    assert_eq!(r["genus_in"], 2);
    assert_eq!(r["genus_out"], 0);
    assert_eq!(r["holes_filled"], 4);
    assert!(r["triangles_added"].as_u64().unwrap() > 0);
    assert!(r["triangles_removed"].as_u64().unwrap() > 0);
    assert!(r["seconds"].as_f64().unwrap() >= 0.0);

    // Absolute alpha too small: genus kept.
    let out = envelope()
        .args(["genus", input.to_str().unwrap(), output.to_str().unwrap()])
        .args(["--alpha", "0.25", "--beta", "60"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(analyze(&read_path(&output).unwrap().0).genus, Some(2));
}

#[test]
fn genus_bad_arguments_and_input_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("box.off");
    write_path(&input, &generate::box_with_tunnel(), Format::Off).unwrap();
    let output = dir.path().join("out.off");
    for alpha in ["-1", "abc", "0", "0%"] {
        let out = envelope()
            .args(["genus", input.to_str().unwrap(), output.to_str().unwrap()])
            .args(["--alpha", alpha])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "alpha {alpha}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("error"));
    }
    let out = envelope()
        .args(["genus", input.to_str().unwrap(), output.to_str().unwrap()])
        .args(["--alpha", "1", "--beta", "200"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("beta"));
    // A self-intersecting input: a typed, clear refusal.
    let mut two = generate::icosphere(1, 1.0);
    let other = generate::icosphere(1, 1.0);
    let off = two.positions.len() as u32;
    two.positions.extend(
        other
            .positions
            .iter()
            .map(|p| *p + glam::DVec3::new(0.5, 0.1, 0.05)),
    );
    two.faces.extend(
        other
            .faces
            .iter()
            .map(|t| t.map(|v| envelope_mesh::VertexId(v.0 + off))),
    );
    let bad = dir.path().join("bad.off");
    write_path(&bad, &two, Format::Off).unwrap();
    let out = envelope()
        .args([
            "genus",
            bad.to_str().unwrap(),
            output.to_str().unwrap(),
            "--alpha",
            "1%",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("intersecting"));
    assert!(!output.exists());
    // Missing input file.
    let out = envelope()
        .args([
            "genus",
            "/nonexistent/x.off",
            output.to_str().unwrap(),
            "--alpha",
            "1",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn pipeline_writes_every_stage_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("plate.off");
    write_path(&input, &generate::plate_with_holes(2), Format::Off).unwrap();
    let out_dir = dir.path().join("stages");
    let stages = pipeline(&input, &out_dir, "e1%,a10%,e2%");
    assert_eq!(stages.len(), 4);
    for (k, st) in stages.iter().enumerate() {
        let (soup, _) = read_path(out_dir.join(format!("stage-{k}.off"))).unwrap();
        assert_eq!(st["faces"].as_u64().unwrap() as usize, soup.num_faces());
        assert_eq!(st["genus"], serde_json::json!(analyze(&soup).genus));
    }
    assert_eq!(stages[1]["genus"], 2);
    assert_eq!(stages[2]["genus"], 0);
    assert_eq!(stages[3]["genus"], 0);
    // Bad step syntax exits 2.
    let out = envelope()
        .args([
            "pipeline",
            input.to_str().unwrap(),
            out_dir.to_str().unwrap(),
        ])
        .args(["--steps", "e1%,z2"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn genus_union_fills_the_smooth_torus_hole() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("torus.off");
    // Central hole of width 0.6, no sharp edge.
    write_path(&input, &generate::torus(1.0, 0.7, 32, 16), Format::Off).unwrap();
    let output = dir.path().join("out.off");
    let report = dir.path().join("r.json");
    let genus = |union: bool| {
        let flags: &[&str] = if union { &["--union"] } else { &["--sharp"] };
        let r = genus_report(&input, &output, &report, "0.5", flags);
        assert_eq!(r["union"], union);
        (analyze(&read_path(&output).unwrap().0).genus, r)
    };
    let (g, r) = genus(true);
    assert_eq!(g, Some(0));
    assert_eq!(
        (r["genus_in"].clone(), r["genus_out"].clone()),
        (1.into(), 0.into())
    );
    assert!(r["swallowed_faces"].as_u64().unwrap() > 0);
    assert!(r["holes_filled"].as_u64().unwrap() >= 2);
    let (g, r) = genus(false);
    assert_eq!(g, Some(1));
    assert_eq!(r["swallowed_faces"], 0);

    // The same as a pipeline step: `u` fills, `s` (sharp edges alone) does not.
    let out_dir = dir.path().join("stages");
    let stages = pipeline(&input, &out_dir, "s0.5,u0.5");
    assert_eq!(stages[1]["genus"], 1);
    assert_eq!(stages[2]["genus"], 0);
}

#[test]
fn genus_closing_fills_a_smooth_torus_and_pipeline_takes_c_steps() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("torus.off");
    // Central hole of radius 0.6, no sharp edge: only the closing's regions fill it.
    write_path(&input, &generate::torus(1.0, 0.4, 48, 24), Format::Off).unwrap();
    let output = dir.path().join("out.off");
    let report = dir.path().join("r.json");
    let run = |flags: &[&str]| genus_report(&input, &output, &report, "0.75", flags);
    let sharp = run(&["--sharp"]);
    assert_eq!(
        (&sharp["genus_out"], &sharp["closing"]),
        (&1.into(), &false.into())
    );
    // The closing is the default; --closing says so.
    for flags in [&[][..], &["--closing"][..]] {
        let closing = run(flags);
        assert_eq!(
            (&closing["genus_out"], &closing["closing"]),
            (&0.into(), &true.into()),
            "{flags:?}"
        );
        assert_eq!(analyze(&read_path(&output).unwrap().0).genus, Some(0));
    }
    // --sharp, --union and --closing are three answers to one question.
    for pair in [
        ["--union", "--closing"],
        ["--sharp", "--closing"],
        ["--sharp", "--union"],
    ] {
        let both = envelope()
            .args(["genus", input.to_str().unwrap(), output.to_str().unwrap()])
            .args(["--alpha", "0.75"])
            .args(pair)
            .output()
            .unwrap();
        assert_eq!(both.status.code(), Some(2), "{pair:?}");
    }

    for (steps, genus) in [("c0.75", 0), ("a0.75", 0), ("s0.75", 1)] {
        let stages = pipeline(&input, &dir.path().join(steps), steps);
        assert_eq!(stages.last().unwrap()["genus"], genus, "{steps}");
    }
}
