//! End-to-end tests of `envelope simplify --method local|global|hybrid`: the output is
//! certified, the report names the method and carries the candidate counts, a bad method is
//! refused.

use std::path::Path;
use std::process::Output;

use envelope_io::{Format, read_path, write_path};
use envelope_mesh::{TriangleSoup, analyze, generate};

mod common;
use common::{assert_ok, read_json};

fn envelope(args: &[&str]) -> Output {
    common::envelope()
        .args(args)
        .output()
        .expect("run envelope")
}

fn write(dir: &Path, name: &str, soup: &TriangleSoup) -> String {
    let p = dir.join(name);
    write_path(&p, soup, Format::Off).unwrap();
    p.to_str().unwrap().to_string()
}

fn run(input: &str, dir: &Path, method: &str) -> (TriangleSoup, serde_json::Value) {
    let output = dir.join(format!("out-{method}.off"));
    let report = dir.join(format!("report-{method}.json"));
    let out = envelope(&[
        "simplify",
        input,
        output.to_str().unwrap(),
        "--epsilon",
        "1%",
        "--method",
        method,
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_ok(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("certificate holds"), "{stdout}");
    assert!(stdout.contains(&format!("({method})")), "{stdout}");
    let (soup, _) = read_path(&output).unwrap();
    let r: serde_json::Value = read_json(&report);
    (soup, r)
}

#[test]
fn each_method_writes_a_certified_output_and_says_what_ran() {
    let dir = tempfile::tempdir().unwrap();
    let torus = generate::torus(1.0, 0.3, 32, 12);
    let input = write(dir.path(), "torus.off", &torus);
    let mut faces = Vec::new();
    for method in ["local", "global", "hybrid"] {
        let (soup, r) = run(&input, dir.path(), method);
        assert_eq!(r["method"], method, "{r:#}");
        assert_eq!(r["output_faces"], soup.num_faces());
        assert_eq!(r["verify"]["verdict"], "holds", "{r:#}");
        assert_eq!(analyze(&soup).genus, Some(1));
        assert!(soup.num_faces() < torus.num_faces(), "{method}: {r:#}");
        faces.push(soup.num_faces());
        match method {
            "local" => assert!(r["method_details"].is_null()),
            "global" => {
                let d = &r["method_details"];
                assert!(d["candidates_ranked"].as_u64().unwrap() > 0, "{d:#}");
                assert!(d["candidate_triples"].as_u64() >= d["candidates_ranked"].as_u64());
                // The global stage on the input removes vertices; on what local left
                // (a torus at 1 %), it may find nothing more.
                assert!(d["global_first"]["accepted"].as_u64().unwrap() > 0, "{d:#}");
                assert!(d["chosen"].is_string(), "{d:#}");
                assert!(d["local"]["faces_after"].is_u64(), "{d:#}");
            }
            _ => {
                let d = &r["method_details"];
                assert!(d["global"]["candidates_ranked"].is_u64(), "{d:#}");
                assert!(d["local"]["faces_after"].is_u64(), "{d:#}");
            }
        }
    }
    // The global and hybrid methods start with the local algorithm and only remove more.
    assert!(faces[1] <= faces[0] && faces[2] <= faces[0], "{faces:?}");
}

#[test]
fn an_unknown_method_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let input = write(dir.path(), "s.off", &generate::icosphere(1, 1.0));
    let out = envelope(&[
        "simplify",
        &input,
        dir.path().join("o.off").to_str().unwrap(),
        "--epsilon",
        "1%",
        "--method",
        "magic",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!dir.path().join("o.off").exists());
}
