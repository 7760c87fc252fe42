//! The readers' defect classes: byte order marks, statements that must not be ignored,
//! polygons triangulated without overlaps, and error messages that quote the file.

use envelope_io::{Format, PlyEncoding, ReadErrorKind, StlEncoding, read};
use envelope_mesh::TriangleSoup;
use envelope_predicates::polygon::interiors_overlap;
use envelope_predicates::{Orientation, orient2d, triangles_intersect};
use glam::{DVec2, DVec3};

const BOM: &[u8] = b"\xEF\xBB\xBF";

fn with_bom(text: &str) -> Vec<u8> {
    [BOM, text.as_bytes()].concat()
}

fn soup(bytes: &[u8], format: Format) -> TriangleSoup {
    read(bytes, format).unwrap().0
}

fn kind(text: &str, format: Format) -> ReadErrorKind {
    read(text.as_bytes(), format).unwrap_err().kind
}

const OBJ_TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nf 1 2 3\nf 2 4 3\n";

#[test]
fn a_byte_order_mark_is_skipped_in_every_text_format() {
    let off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n\
        property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
        0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let stl = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
        vertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
    let cases = [
        (OBJ_TRI, Format::Obj),
        (off, Format::Off),
        (ply, Format::Ply(PlyEncoding::Ascii)),
        (stl, Format::Stl(StlEncoding::Binary)),
    ];
    for (text, format) in cases {
        let (plain, plain_report) = read(text.as_bytes(), format).unwrap();
        let (bommed, bom_report) = read(&with_bom(text)[..], format).unwrap();
        assert_eq!(bommed, plain, "{format}");
        assert_eq!(bom_report, plain_report, "{format}");
        // Sniffing sees through the mark too (an ascii STL stays ascii).
        let len = Some(with_bom(text).len() as u64);
        let sniffed = Format::sniff(&with_bom(text), len).unwrap();
        assert_eq!(
            std::mem::discriminant(&sniffed),
            std::mem::discriminant(&format),
            "{format}"
        );
    }
    let stl_bom = with_bom(stl);
    assert_eq!(
        Format::sniff(&stl_bom, Some(stl_bom.len() as u64)),
        Some(Format::Stl(StlEncoding::Ascii))
    );
    let (_, report) = read(&stl_bom[..], Format::Stl(StlEncoding::Binary)).unwrap();
    assert_eq!(report.format, Format::Stl(StlEncoding::Ascii));
}

#[test]
fn obj_skips_only_statements_that_cannot_change_the_mesh() {
    let skipped = [
        "vt 0 0",
        "vn 0 0 1",
        "vp 0.5",
        "o a",
        "g a b",
        "s 1",
        "s off",
        "mg 1 0.5",
        "mtllib a.mtl",
        "usemtl red",
        "maplib a.map",
        "usemap off",
        "l 1 2",
        "p 1",
        "lod 1",
        "bevel off",
        "c_interp on",
        "d_interp off",
        "shadow_obj s.obj",
        "trace_obj t.obj",
        "ctech cparm 1",
        "stech cparm 1 1",
    ];
    for st in skipped {
        let text = format!("v 0 0 0\nv 1 0 0\n{st}\nv 0 1 0\nf 1 2 3\n");
        let (s, report) = read(text.as_bytes(), Format::Obj).unwrap();
        assert_eq!(s.num_faces(), 1, "{st}");
        let kw = st.split(' ').next().unwrap();
        assert!(
            report.notes.iter().any(|n| n.contains(&format!("'{kw}'"))),
            "{st}: {:?}",
            report.notes
        );
    }
}

#[test]
fn obj_refuses_free_form_and_unknown_statements_naming_line_and_keyword() {
    let refused = [
        "cstype bspline",
        "deg 3",
        "bmat u 1 0 0 1",
        "step 1",
        "curv 0 1 1 2",
        "curv2 1 2",
        "surf 0 1 0 1 1 2 3 4",
        "parm u 0 1",
        "trim 0 1 1",
        "hole 0 1 1",
        "scrv 0 1 1",
        "sp 1 2",
        "end",
        "con 1 0 1 1 2 0 1 1",
        "call other.obj",
        "csh ls",
        "vx 1 2 3",
        "F 1 2 3",
    ];
    for st in refused {
        let text = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\n{st}\nf 1 2 3\n");
        let e = read(text.as_bytes(), Format::Obj).unwrap_err();
        let kw = st.split(' ').next().unwrap();
        let ReadErrorKind::UnsupportedStatement { keyword, .. } = e.kind else {
            panic!("{st}: {e}");
        };
        assert_eq!(keyword.as_bytes(), kw.as_bytes());
        assert_eq!(e.location, envelope_io::Location::Line(4), "{st}");
        assert!(
            e.to_string()
                .starts_with(&format!("<input>: line 4: unsupported statement '{kw}'")),
            "{e}"
        );
    }
}

#[test]
fn obj_with_a_bom_keeps_its_first_vertex() {
    // Before: the first `v` was read as the statement '\u{feff}v' and skipped, shifting
    // every index by one.
    let (s, report) = read(&with_bom(OBJ_TRI)[..], Format::Obj).unwrap();
    assert_eq!(s.num_vertices(), 4);
    assert_eq!(s.position(envelope_mesh::VertexId(0)), DVec3::ZERO);
    assert!(report.notes.is_empty(), "{:?}", report.notes);
}

#[test]
fn off_header_words_dimensions_and_a_missing_off_line() {
    let e = read(&b"4 4 6\n0 0 0\n"[..], Format::Off).unwrap_err();
    assert!(matches!(e.kind, ReadErrorKind::NotOffKeyword { .. }));
    assert_eq!(
        e.to_string(),
        "<input>: line 1: the first line must be the OFF keyword (OFF, COFF, NOFF, STOFF, ...), \
         found '4': the OFF line is missing"
    );
    assert!(matches!(
        kind("4OFF\n3 1 0\n", Format::Off),
        ReadErrorKind::Unsupported(_)
    ));
    assert!(matches!(
        kind("nOFF\n4\n3 1 0\n", Format::Off),
        ReadErrorKind::Unsupported(_)
    ));
    assert!(matches!(
        kind("OFFX\n3 1 0\n", Format::Off),
        ReadErrorKind::NotOffKeyword { .. }
    ));
    assert!(matches!(
        kind("OFF extra\n3 1 0\n", Format::Off),
        ReadErrorKind::UnsupportedStatement { .. }
    ));
    let tri = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let plain = soup(format!("OFF\n3 1 0\n{tri}").as_bytes(), Format::Off);
    for header in ["nOFF\n3\n3 1 0\n", "nOFF 3\n3 1 0\n", "nOFF 3 3 1 0\n"] {
        assert_eq!(
            soup(format!("{header}{tri}").as_bytes(), Format::Off),
            plain
        );
    }
}

#[test]
fn ply_refuses_ambiguous_layouts() {
    let head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
        property float z\n";
    let dup = format!(
        "{head}property float x\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    );
    assert!(matches!(
        kind(&dup, Format::Ply(PlyEncoding::Ascii)),
        ReadErrorKind::BadHeader(_)
    ));
    let both = format!(
        "{head}element face 1\nproperty list uchar int vertex_indices\n\
         property list uchar int vertex_index\nend_header\n"
    );
    assert!(matches!(
        kind(&both, Format::Ply(PlyEncoding::Ascii)),
        ReadErrorKind::BadHeader(_)
    ));
}

#[test]
fn obj_index_errors_quote_the_index_as_written() {
    let six = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 0 0\nv 2 1 0\n";
    let e = read(format!("{six}f 1 2 7\n").as_bytes(), Format::Obj).unwrap_err();
    assert_eq!(
        e.to_string(),
        "<input>: line 7: face 0: vertex index 7 names no vertex (6 defined so far; \
         allowed: 1 to 6, or -1 to -6 counting back)"
    );
    let e = read(format!("{six}f 1 2 -9\n").as_bytes(), Format::Obj).unwrap_err();
    assert!(
        e.to_string().contains("vertex index -9 names no vertex"),
        "{e}"
    );
    let e = read(&b"f 1 2 3\n"[..], Format::Obj).unwrap_err();
    assert!(e.to_string().contains("allowed: none"), "{e}");
}

/// An OBJ file of one polygon in the plane z = 0 (counter-clockwise seen from +z).
fn polygon_obj(points: &[DVec2]) -> String {
    let mut text = String::new();
    for p in points {
        text += &format!("v {:?} {:?} 0\n", p.x, p.y);
    }
    text += "f";
    for i in 1..=points.len() {
        text += &format!(" {i}");
    }
    text + "\n"
}

/// `n - 2` triangles, each counter-clockwise (the polygon's winding), no two overlapping.
fn assert_non_overlapping(s: &TriangleSoup, n: usize) {
    assert_eq!(s.num_faces(), n - 2);
    let flat: Vec<[DVec2; 3]> = s
        .faces
        .iter()
        .map(|f| f.map(|v| s.position(v).truncate()))
        .collect();
    for t in &flat {
        assert_eq!(orient2d(t[0], t[1], t[2]), Orientation::Positive, "{t:?}");
    }
    let boxes: Vec<(DVec2, DVec2)> = flat
        .iter()
        .map(|t| (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2])))
        .collect();
    for i in 0..flat.len() {
        for j in i + 1..flat.len() {
            let (a, b) = (boxes[i], boxes[j]);
            if a.1.x < b.0.x || b.1.x < a.0.x || a.1.y < b.0.y || b.1.y < a.0.y {
                continue;
            }
            assert!(!interiors_overlap(flat[i], flat[j]), "{i} {j}");
        }
    }
}

#[test]
fn a_u_shaped_octagon_is_not_folded() {
    let u = [
        (0., 0.),
        (3., 0.),
        (3., 3.),
        (2., 3.),
        (2., 1.),
        (1., 1.),
        (1., 3.),
        (0., 3.),
    ]
    .map(|(x, y)| DVec2::new(x, y));
    // Starting the polygon at every corner: a fan would fold from some of them.
    for r in 0..u.len() {
        let mut p = u.to_vec();
        p.rotate_left(r);
        let (s, report) = read(polygon_obj(&p).as_bytes(), Format::Obj).unwrap();
        assert_non_overlapping(&s, 8);
        assert_eq!(
            (report.polygons_triangulated, report.triangles_from_polygons),
            (1, 6)
        );
    }
}

#[test]
fn a_2000_corner_star_gives_no_intersecting_pair() {
    let n = 2000;
    let star: Vec<DVec2> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let r = if i % 2 == 0 { 10.0 } else { 4.0 };
            DVec2::new(r * a.cos(), r * a.sin())
        })
        .collect();
    let s = soup(polygon_obj(&star).as_bytes(), Format::Obj);
    assert_non_overlapping(&s, n);
    // And in space: triangles that share no corner do not meet (exact 3-D test).
    let tri = |f: &[envelope_mesh::VertexId; 3]| f.map(|v| s.position(v));
    for (i, f) in s.faces.iter().enumerate().step_by(7) {
        for g in &s.faces[i + 1..] {
            if f.iter().any(|v| g.contains(v)) {
                continue;
            }
            assert!(!triangles_intersect(tri(f), tri(g)));
        }
    }
}

#[test]
fn a_convex_100000_gon_triangulates() {
    let n = 100_000;
    let mut text = String::from("OFF\n");
    text += &format!("{n} 1 0\n");
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        text += &format!("{:?} {:?} 0\n", a.cos(), a.sin());
    }
    text += &n.to_string();
    for i in 0..n {
        text += &format!(" {i}");
    }
    text += "\n";
    let (s, report) = read(text.as_bytes(), Format::Off).unwrap();
    assert_eq!(s.num_faces(), n - 2);
    assert_eq!(report.triangles_from_polygons, (n - 2) as u64);
}

#[test]
fn a_bow_tie_is_refused_with_its_line() {
    let e = read(
        &b"v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\n# a bow-tie\nf 1 2 3 4\n"[..],
        Format::Obj,
    )
    .unwrap_err();
    assert_eq!(
        e.kind,
        ReadErrorKind::NotSimplePolygon {
            face: 0,
            corners: 4
        }
    );
    assert_eq!(e.location, envelope_io::Location::Line(6));
    assert!(e.to_string().contains("self-intersecting"), "{e}");
    // The same in OFF and PLY (a PLY face before its vertices).
    let off = "OFF\n4 1 0\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n4 0 1 2 3\n";
    let e = read(off.as_bytes(), Format::Off).unwrap_err();
    assert_eq!(e.location, envelope_io::Location::Line(7));
    let ply = "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n\
        element vertex 4\nproperty double x\nproperty double y\nproperty double z\nend_header\n\
        4 0 1 2 3\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n";
    let e = read(ply.as_bytes(), Format::Ply(PlyEncoding::Ascii)).unwrap_err();
    assert!(matches!(e.kind, ReadErrorKind::NotSimplePolygon { .. }));
    assert_eq!(e.location, envelope_io::Location::Line(10));
}

#[test]
fn a_non_planar_quad_gives_two_triangles_with_its_winding() {
    let (s, report) = read(
        &b"v 0 0 0\nv 1 0 0\nv 1 1 1\nv 0 1 0\nf 1 2 3 4\n"[..],
        Format::Obj,
    )
    .unwrap();
    assert_eq!(s.num_faces(), 2);
    assert_eq!(report.polygons_triangulated, 1);
    for f in &s.faces {
        let [a, b, c] = f.map(|v| s.position(v));
        assert!((b - a).cross(c - a).z > 0.0);
    }
}

#[test]
fn repeated_corners() {
    // Consecutive repeats (also last = first) are dropped and counted.
    let (s, report) = read(
        &b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 2 3 4 1\n"[..],
        Format::Obj,
    )
    .unwrap();
    assert_eq!(
        s,
        TriangleSoup::from_raw(
            &[[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]],
            &[[0, 1, 2], [0, 2, 3]]
        )
        .clone()
    );
    assert_eq!(report.polygon_corners_dropped, 2);
    // A quad down to a triangle.
    let (s, _) = read(&b"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 2 3\n"[..], Format::Obj).unwrap();
    assert_eq!(s.num_faces(), 1);
    // A vertex visited twice, not in a row: refused, naming the corners as written.
    let e = read(
        &b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 2 4\n"[..],
        Format::Obj,
    )
    .unwrap_err();
    assert_eq!(
        e.kind,
        ReadErrorKind::RepeatedCorner {
            face: 0,
            first: 2,
            second: 4
        }
    );
    // Fewer than three distinct corners.
    assert_eq!(
        kind("v 0 0 0\nv 1 0 0\nf 1 2 2 1\n", Format::Obj),
        ReadErrorKind::TooFewCorners {
            face: 0,
            corners: 2
        }
    );
}
