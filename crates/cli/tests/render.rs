//! End-to-end tests of `envelope render`, `lod --picture` and the pictures of `demo`.

use std::path::Path;

use envelope_io::{Format, write_path};
use envelope_mesh::generate;

mod common;
use common::{assert_ok, envelope};

/// Width and height of a PNG file, decoded.
fn png_size(path: &Path) -> (u32, u32) {
    let file = std::fs::File::open(path).unwrap();
    let reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap();
    (reader.info().width, reader.info().height)
}

fn meshes(dir: &Path) -> (String, String) {
    let a = dir.join("sphere.off");
    let b = dir.join("torus.obj");
    write_path(&a, &generate::icosphere(2, 1.0), Format::Off).unwrap();
    write_path(&b, &generate::torus(1.0, 0.3, 24, 12), Format::Obj).unwrap();
    (a.display().to_string(), b.display().to_string())
}

#[test]
fn render_writes_one_panel_per_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = meshes(dir.path());
    let out = dir.path().join("pair.png");
    let render = || {
        envelope()
            .args(["render", &a, &b, out.to_str().unwrap()])
            .args([
                "--size",
                "96x64",
                "--view",
                "-20,35",
                "--wire",
                "--same-scale",
            ])
            .args(["--caption", "sphere"])
            .output()
            .unwrap()
    };
    assert_ok(&render());
    assert_eq!(png_size(&out), (192, 64));
    let first = std::fs::read(&out).unwrap();
    // Same arguments, same bytes.
    assert_ok(&render());
    assert_eq!(std::fs::read(&out).unwrap(), first);
}

#[test]
fn bad_arguments_exit_2_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (a, _) = meshes(dir.path());
    let out = dir.path().join("out.png");
    let cases: [&[&str]; 7] = [
        &["--size", "8x100"],
        &["--size", "100x9000"],
        &["--size", "100"],
        &["--view", "30"],
        &["--view", "0,95"],
        &["--perspective", "180"],
        &["--color-by", "quality"],
    ];
    for args in cases {
        let run = envelope()
            .args(["render", &a, out.to_str().unwrap()])
            .args(args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(!out.exists(), "{args:?} wrote OUT");
        if args[0] == "--color-by" {
            assert!(stderr.contains("no per-vertex quality"), "{stderr}");
        }
    }
    let run = envelope()
        .args(["render", &a, dir.path().join("out.jpg").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains(".png"));
}

#[test]
fn lod_picture_writes_the_strip_and_the_plots() {
    let dir = tempfile::tempdir().unwrap();
    let (a, _) = meshes(dir.path());
    let out_dir = dir.path().join("lod");
    let run = envelope()
        .args(["lod", &a, out_dir.to_str().unwrap()])
        .args(["--epsilons", "1%,4%", "--picture", "--quiet"])
        .output()
        .unwrap();
    assert_ok(&run);
    // Level 0 and two levels, 240 pixels each.
    assert_eq!(png_size(&out_dir.join("lod.png")), (3 * 240, 240));
    let svg = std::fs::read_to_string(out_dir.join("faces-vs-epsilon.svg")).unwrap();
    assert!(
        svg.starts_with("<svg") && svg.contains("sphere.off"),
        "{svg}"
    );
    assert!(png_size(&out_dir.join("faces-vs-epsilon.png")).0 > 0);
}

#[test]
fn lod_without_picture_writes_none() {
    let dir = tempfile::tempdir().unwrap();
    let (a, _) = meshes(dir.path());
    let out_dir = dir.path().join("lod");
    let run = envelope()
        .args(["lod", &a, out_dir.to_str().unwrap()])
        .args(["--epsilons", "4%", "--quiet"])
        .output()
        .unwrap();
    assert_ok(&run);
    assert!(out_dir.join("summary.json").is_file());
    assert!(!out_dir.join("lod.png").exists());
}

/// All pixels of a PNG as RGB triples.
fn png_pixels(path: &Path) -> Vec<[u8; 3]> {
    let file = std::fs::File::open(path).unwrap();
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    buf[..info.buffer_size()]
        .chunks(channels)
        .map(|c| [c[0], c[1], c[2]])
        .collect()
}

/// The error map of `verify --map` renders coloured by its quality: the colour bar's ends
/// are the ramp's, which the uncoloured render of the same file lacks.
#[test]
fn an_error_map_renders_by_quality() {
    let dir = tempfile::tempdir().unwrap();
    let orig = dir.path().join("sphere.off");
    write_path(&orig, &generate::icosphere(3, 1.0), Format::Off).unwrap();
    let approx = dir.path().join("approx.off");
    let map = dir.path().join("map.ply");
    let path = |p: &Path| p.to_str().unwrap().to_string();
    assert_ok(
        &envelope()
            .args(["simplify", &path(&orig), &path(&approx), "--epsilon", "2%"])
            .output()
            .unwrap(),
    );
    assert_ok(
        &envelope()
            .args(["verify", &path(&orig), &path(&approx), "--epsilon", "2%"])
            .args(["--map", &path(&map)])
            .output()
            .unwrap(),
    );
    let render = |by: &str, out: &Path| {
        envelope()
            .args(["render", &path(&map), &path(out), "--size", "160x120"])
            .args(["--color-by", by])
            .output()
            .unwrap()
    };
    let (coloured, plain) = (dir.path().join("q.png"), dir.path().join("n.png"));
    assert_ok(&render("quality", &coloured));
    assert_ok(&render("none", &plain));
    let top = envelope_render::ramp::viridis(1.0);
    let bottom = envelope_render::ramp::viridis(0.0);
    // The bar samples the ramp at pixel centres: its ends are within a few steps of them.
    let near = |pixels: &[[u8; 3]], c: [u8; 3]| {
        pixels
            .iter()
            .any(|p| (0..3).all(|k| p[k].abs_diff(c[k]) <= 8))
    };
    let q = png_pixels(&coloured);
    assert!(near(&q, top) && near(&q, bottom), "no colour bar");
    assert!(!near(&png_pixels(&plain), top));
}
