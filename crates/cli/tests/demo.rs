//! `envelope demo` runs end to end on the built-in cup and writes its chain.

mod common;
use common::{assert_ok, envelope, read_json};

#[test]
fn demo_writes_a_certified_chain() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("demo");
    let out = envelope()
        .args(["demo", "--out-dir", out_dir.to_str().unwrap()])
        .output()
        .unwrap();
    assert_ok(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("level"), "{stdout}");
    let s: serde_json::Value = read_json(&out_dir.join("summary.json"));
    let levels = s["levels"].as_array().unwrap();
    assert_eq!(levels.len(), 7);
    for l in levels {
        assert!(out_dir.join(l["file"].as_str().unwrap()).is_file());
        assert_eq!(l["certified_vs_original"]["verdict"], "holds", "{l:#}");
        assert_eq!(l["border_loops"], 1);
        assert_eq!(l["genus"], 0);
    }
    assert!(levels[6]["faces"].as_u64().unwrap() < 500);
    let picture = out_dir.join("lod.png");
    assert!(stdout.contains(&picture.display().to_string()), "{stdout}");
    let bytes = std::fs::read(&picture).unwrap();
    let reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    // The input and its seven levels side by side.
    assert_eq!((reader.info().width, reader.info().height), (8 * 240, 240));
    assert!(out_dir.join("faces-vs-epsilon.svg").is_file());
}
