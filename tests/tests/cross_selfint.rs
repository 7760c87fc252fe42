//! Meshes built to self-intersect (and clean ones), written to temporary OFF files: the
//! intersecting face pairs `envelope_check::check` reports must equal CGAL's
//! `self_intersections` exactly (degenerate faces compared as described in
//! `envelope_tests::gen::compare_self_intersections`). The only hand-known expectations are
//! "some pairs" for the built-to-intersect meshes and "none" for the clean ones.
//!
//! Skips loudly without the oracle, fails under `CI=true`.

use std::path::{Path, PathBuf};

use envelope_io::{Format, read_path, write_path};
use envelope_mesh::{TriangleSoup, VertexId, generate};
use envelope_tests::r#gen::{SelfIntersectionAgreement, compare_self_intersections};
use envelope_tests::oracle::{Oracle, oracle_or_skip};
use glam::DVec3;

/// Writes `soup` as OFF, reads it back (so both sides see the file's doubles) and compares.
fn compare(o: &Oracle, dir: &Path, name: &str, soup: &TriangleSoup) -> SelfIntersectionAgreement {
    let path: PathBuf = dir.join(format!("{name}.off"));
    write_path(&path, soup, Format::Off).unwrap_or_else(|e| panic!("{name}: write: {e}"));
    let (back, _) = read_path(&path).unwrap_or_else(|e| panic!("{name}: read back: {e}"));
    assert_eq!(
        back.positions, soup.positions,
        "{name}: OFF round trip changed positions"
    );
    match compare_self_intersections(o, &path, &back) {
        Ok(a) => {
            eprintln!(
                "{name}: {} faces, {} intersecting pairs, {} degenerate faces, CGAL {:?} path: agree",
                back.faces.len(),
                a.pairs.len(),
                a.degenerate.len(),
                a.kind
            );
            a
        }
        Err(e) => panic!("{name}: ours and CGAL disagree:\n{e}"),
    }
}

fn merge(a: &TriangleSoup, b: &TriangleSoup) -> TriangleSoup {
    let off = a.positions.len() as u32;
    let mut positions = a.positions.clone();
    positions.extend_from_slice(&b.positions);
    let mut faces = a.faces.clone();
    faces.extend(b.faces.iter().map(|f| f.map(|v| VertexId(v.0 + off))));
    TriangleSoup::new(positions, faces)
}

fn translated(s: &TriangleSoup, d: DVec3) -> TriangleSoup {
    TriangleSoup::new(
        s.positions.iter().map(|&p| p + d).collect(),
        s.faces.clone(),
    )
}

/// A strip of `2n` quads along x in the plane z = 0, folded back onto itself at x = n: the
/// second half lies exactly on the first (coplanar overlap), and the faces at the fold share
/// an edge and lie on the same side of it.
fn folded_strip(n: u32) -> TriangleSoup {
    let mut pos = Vec::new();
    for i in 0..=2 * n {
        let x = if i <= n { i } else { 2 * n - i } as f64 * 0.5;
        // The returning half is shifted a quarter in y so the overlap is partial.
        let y0 = if i <= n { 0.0 } else { 0.25 };
        pos.push([x, y0, 0.0]);
        pos.push([x, y0 + 1.0, 0.0]);
    }
    let mut faces = Vec::new();
    for i in 0..2 * n {
        let (a, b, c, d) = (2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1);
        faces.push([a, b, c]);
        faces.push([a, c, d]);
    }
    TriangleSoup::from_raw(&pos, &faces)
}

fn with_oracle(f: impl FnOnce(&Oracle, &Path)) {
    let Some(o) = oracle_or_skip() else { return };
    let dir = tempfile::tempdir().expect("temp dir");
    f(&o, dir.path());
}

#[test]
fn spindle_torus_pushed_through_itself() {
    with_oracle(|o, dir| {
        // Tube radius larger than the centre radius: the inner side passes through the axis.
        let a = compare(o, dir, "spindle_torus", &generate::torus(0.2, 0.5, 32, 16));
        assert!(!a.pairs.is_empty(), "a spindle torus self-intersects");
    });
}

#[test]
fn two_interpenetrating_spheres() {
    with_oracle(|o, dir| {
        let s = generate::icosphere(2, 1.0);
        let both = merge(&s, &translated(&s, DVec3::new(1.0, 0.1, 0.05)));
        let a = compare(o, dir, "two_spheres", &both);
        assert!(!a.pairs.is_empty());
    });
}

#[test]
fn sphere_with_vertex_pulled_through() {
    with_oracle(|o, dir| {
        let mut s = generate::icosphere(2, 1.0);
        s.positions[0] *= -1.5; // through the centre and out of the opposite side
        let a = compare(o, dir, "pulled_vertex", &s);
        assert!(!a.pairs.is_empty());
    });
}

#[test]
fn folded_strip_with_coplanar_overlap() {
    with_oracle(|o, dir| {
        let a = compare(o, dir, "folded_strip", &folded_strip(4));
        assert!(!a.pairs.is_empty());
    });
}

#[test]
fn touching_with_different_vertex_indices() {
    with_oracle(|o, dir| {
        let base = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let cases: [(&str, Vec<[f64; 3]>, bool); 6] = [
            // Corner to corner, unwelded: one common point.
            (
                "point_corner",
                vec![[0.0, 0.0, 0.0], [-1.0, 0.0, 1.0], [0.0, -1.0, 1.0]],
                true,
            ),
            // A corner of the second exactly in the interior of the first.
            (
                "point_interior",
                vec![[0.25, 0.25, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]],
                true,
            ),
            // A corner on the open edge of the first.
            (
                "point_on_edge",
                vec![[0.5, 0.5, 0.0], [1.0, 1.0, 1.0], [1.0, 1.0, -1.0]],
                true,
            ),
            // Along a whole edge, unwelded (a crack that is not one).
            (
                "along_edge",
                vec![[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
                true,
            ),
            // Coplanar, on the other side of the edge, unwelded: touch along the edge.
            (
                "coplanar_edge",
                vec![[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.5, -1.0, 0.0]],
                true,
            ),
            // Like `point_interior`, but the corner is 2^-120 above the plane (the smallest
            // magnitude the writer accepts).
            (
                "tiny_gap",
                vec![
                    [0.25, 0.25, 2f64.powi(-120)],
                    [0.0, 0.0, 1.0],
                    [1.0, 1.0, 1.0],
                ],
                false,
            ),
        ];
        for (name, other, touching) in cases {
            let mut pos = base.to_vec();
            pos.extend(other);
            let s = TriangleSoup::from_raw(&pos, &[[0, 1, 2], [3, 4, 5]]);
            let a = compare(o, dir, name, &s);
            assert_eq!(!a.pairs.is_empty(), touching, "{name}");
        }
        // The same touching configurations welded (shared indices) are not intersections,
        // except a fold: coplanar on the same side of a shared edge.
        // (name, extra vertices 3.., second face, intersects)
        type Welded = (&'static str, Vec<[f64; 3]>, [u32; 3], bool);
        let welded: [Welded; 4] = [
            (
                "welded_corner",
                vec![[-1.0, 0.0, 1.0], [0.0, -1.0, 1.0]],
                [0, 3, 4],
                false,
            ),
            ("welded_edge", vec![[0.0, 0.0, 1.0]], [1, 0, 3], false),
            ("welded_fold", vec![[0.25, 0.25, 0.0]], [1, 0, 3], true),
            (
                "welded_corner_pierce",
                vec![[0.2, 0.2, -1.0], [0.2, 0.2, 1.0]],
                [0, 3, 4],
                true,
            ),
        ];
        for (name, extra, f2, hit) in welded {
            let mut pos = base.to_vec();
            pos.extend(extra);
            let s = TriangleSoup::from_raw(&pos, &[[0, 1, 2], f2]);
            let a = compare(o, dir, name, &s);
            assert_eq!(!a.pairs.is_empty(), hit, "{name}");
        }
    });
}

#[test]
fn degenerate_faces_are_reported_alike() {
    with_oracle(|o, dir| {
        // A collinear face crossing a good one: CGAL reports (1, 1) and tests it no further.
        let s = TriangleSoup::from_raw(
            &[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.2, 0.2, -1.0],
                [0.2, 0.2, 0.0],
                [0.2, 0.2, 1.0],
            ],
            &[[0, 1, 2], [3, 4, 5]],
        );
        let a = compare(o, dir, "collinear_face", &s);
        assert_eq!(a.degenerate, vec![1]);
    });
}

#[test]
fn clean_generated_meshes_have_none() {
    with_oracle(|o, dir| {
        let meshes = [
            ("torus", generate::torus(1.0, 0.3, 48, 24)),
            ("icosphere", generate::icosphere(3, 1.0)),
            ("plate_with_holes", generate::plate_with_holes(3)),
        ];
        for (name, s) in meshes {
            let a = compare(o, dir, name, &s);
            assert!(a.pairs.is_empty() && a.degenerate.is_empty(), "{name}");
        }
    });
}
