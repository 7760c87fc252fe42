//! Attributes read and written: OBJ and PLY round trips bit-exact per corner, malformed
//! corner references refused with their line and index, triangulated polygons keeping their
//! corners' references, PLY colour types.

use envelope_io::{
    Format, PlyEncoding, ReadErrorKind, read, read_path_with_attributes, read_with_attributes,
    write_path_with_attributes, write_with_attributes,
};
use envelope_mesh::{Attributes, TriangleSoup, Wedges};

/// A 3x3-vertex grid (8 triangles) with a texture seam down the middle column (the faces left
/// and right of it give its vertices different u), a normal per corner and colours.
fn seamed_grid() -> (TriangleSoup, Attributes) {
    let mut positions = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            positions.push([f64::from(i) * 0.5, f64::from(j) * 0.25, 0.1]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..2u32 {
        for i in 0..2u32 {
            let v = j * 3 + i;
            faces.push([v, v + 1, v + 4]);
            faces.push([v, v + 4, v + 3]);
        }
    }
    let soup = TriangleSoup::from_raw(&positions, &faces);
    let mut uv = Wedges::default();
    let mut normals = Wedges::default();
    let mut colors = Wedges::default();
    for (f, face) in faces.iter().enumerate() {
        let right = f >= 2 && (f / 2) % 2 == 1;
        let mut c = [0; 3];
        let mut n = [0; 3];
        let mut k3 = [0; 3];
        for (k, &v) in face.iter().enumerate() {
            let p = positions[v as usize];
            // The right chart is shifted in u: a seam at x = 0.5.
            let u = if right { p[0] + 0.375 } else { p[0] * 0.7 };
            uv.values.push([u, p[1] / 3.0]);
            c[k] = (uv.values.len() - 1) as u32;
            normals
                .values
                .push([0.0, if right { 0.1 } else { -0.1 }, 1.0]);
            n[k] = (normals.values.len() - 1) as u32;
            colors.values.push([
                f64::from(v) / 255.0,
                1.0,
                0.0,
                if right { 1.0 } else { 128.0 / 255.0 },
            ]);
            k3[k] = (colors.values.len() - 1) as u32;
        }
        uv.corners.push(c);
        normals.corners.push(n);
        colors.corners.push(k3);
    }
    let attributes = Attributes {
        texcoords: Some(uv),
        normals: Some(normals),
        colors: Some(colors),
        quality: None,
    };
    (soup, attributes)
}

/// Per face and corner: the position and each attribute value, as bits.
fn corner_bits(soup: &TriangleSoup, a: &Attributes) -> Vec<Vec<u64>> {
    let mut out = Vec::new();
    for (f, face) in soup.faces.iter().enumerate() {
        for (k, v) in face.iter().enumerate() {
            let mut bits: Vec<u64> = soup.positions[v.index()]
                .to_array()
                .iter()
                .map(|x| x.to_bits())
                .collect();
            if let Some(t) = &a.texcoords {
                bits.extend(t.value(f, k).map(f64::to_bits));
            }
            if let Some(n) = &a.normals {
                bits.extend(n.value(f, k).map(f64::to_bits));
            }
            if let Some(c) = &a.colors {
                bits.extend(c.value(f, k).map(f64::to_bits));
            }
            out.push(bits);
        }
    }
    out
}

#[test]
fn obj_round_trip_is_exact() {
    let (soup, mut attributes) = seamed_grid();
    attributes.colors = None;
    let mut bytes = Vec::new();
    write_with_attributes(&mut bytes, &soup, &attributes, Format::Obj).unwrap();
    let (back, again, report) = read_with_attributes(&bytes[..], Format::Obj).unwrap();
    assert_eq!(back, soup);
    assert_eq!(again, attributes);
    assert!(!report.notes.iter().any(|n| n.contains("'vt'")), "{report}");
    // Without attributes the same file reads as positions, the tables skipped.
    let (plain, report) = read(&bytes[..], Format::Obj).unwrap();
    assert_eq!(plain, soup);
    assert!(report.notes.iter().any(|n| n.contains("'vt'")));
}

#[test]
fn ply_round_trip_is_exact_per_corner_in_every_encoding() {
    let (soup, attributes) = seamed_grid();
    for enc in [
        PlyEncoding::Ascii,
        PlyEncoding::BinaryLittleEndian,
        PlyEncoding::BinaryBigEndian,
    ] {
        let mut bytes = Vec::new();
        write_with_attributes(&mut bytes, &soup, &attributes, Format::Ply(enc)).unwrap();
        let (back, again, report) = read_with_attributes(&bytes[..], Format::Ply(enc)).unwrap();
        assert!(report.notes.is_empty(), "{report}");
        assert_eq!(back.num_faces(), soup.num_faces());
        assert_eq!(corner_bits(&back, &again), corner_bits(&soup, &attributes));
        // The seam splits its 3 vertices (and each corner has its own normal and colour
        // here, so every face-distinct combination is a vertex of its own).
        assert!(back.num_vertices() > soup.num_vertices());
        // Colours k/255 are written as uchar.
        let text = String::from_utf8_lossy(&bytes);
        assert!(text.contains("property uchar red"));
    }
}

#[test]
fn ply_without_seams_keeps_numbering_and_float_colours_stay_double() {
    let soup = TriangleSoup::from_raw(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [5.0, 5.0, 5.0],
        ],
        &[[0, 1, 2]],
    );
    let colors = Wedges {
        values: vec![
            [0.1, 0.2, 0.3, 1.0],
            [1.0, 1.0, 1.0, 1.0],
            [0.0, 0.0, 0.0, 1.0],
        ],
        corners: vec![[0, 1, 2]],
    };
    let attributes = Attributes {
        colors: Some(colors),
        ..Attributes::default()
    };
    let mut bytes = Vec::new();
    let format = Format::Ply(PlyEncoding::Ascii);
    write_with_attributes(&mut bytes, &soup, &attributes, format).unwrap();
    let text = String::from_utf8(bytes.clone()).unwrap();
    assert!(text.contains("property double red"), "{text}");
    // The unused vertex keeps its place, with zero values.
    assert!(text.contains("5.0 5.0 5.0 0.0 0.0 0.0 1.0\n"), "{text}");
    let (back, again, _) = read_with_attributes(&bytes[..], format).unwrap();
    assert_eq!(back, soup);
    assert_eq!(corner_bits(&back, &again), corner_bits(&soup, &attributes));
}

#[test]
fn ply_reads_every_spelling_and_colour_type() {
    let header = |props: &str, row: &str| {
        format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\n{props}element face 1\nproperty list uchar int vertex_indices\n\
             end_header\n0 0 0 {row}\n1 0 0 {row}\n0 1 0 {row}\n3 0 1 2\n"
        )
    };
    for names in [
        ["u", "v"],
        ["s", "t"],
        ["texture_u", "texture_v"],
        ["texture_s", "texture_t"],
    ] {
        let text = header(
            &format!("property float {}\nproperty float {}\n", names[0], names[1]),
            "0.5 0.25",
        );
        let (_, a, report) =
            read_with_attributes(text.as_bytes(), Format::Ply(PlyEncoding::Ascii)).unwrap();
        assert_eq!(a.texcoords.unwrap().value(0, 2), [0.5, 0.25], "{names:?}");
        assert!(report.notes.is_empty(), "{report}");
    }
    let text = header(
        "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty ushort alpha\n\
         property double nx\nproperty double ny\nproperty double nz\n",
        "255 51 0 65535 0 0 -1",
    );
    let (_, a, _) = read_with_attributes(text.as_bytes(), Format::Ply(PlyEncoding::Ascii)).unwrap();
    assert_eq!(a.colors.unwrap().value(0, 0), [1.0, 51.0 / 255.0, 0.0, 1.0]);
    assert_eq!(a.normals.unwrap().value(0, 1), [0.0, 0.0, -1.0]);
    // Without attributes they are ignored properties, named.
    let (_, report) = read(text.as_bytes(), Format::Ply(PlyEncoding::Ascii)).unwrap();
    assert!(report.notes.iter().any(|n| n.contains("red")), "{report}");
    // A colour that is not finite is refused, naming the vertex.
    let text = header(
        "property float red\nproperty float green\nproperty float blue\n",
        "nan 0 0",
    );
    let err = read_with_attributes(text.as_bytes(), Format::Ply(PlyEncoding::Ascii)).unwrap_err();
    assert_eq!(
        err.kind,
        ReadErrorKind::AttributeValue {
            what: "vertex",
            element: 0
        }
    );
}

fn obj_err(text: &str) -> String {
    read_with_attributes(text.as_bytes(), Format::Obj)
        .unwrap_err()
        .to_string()
}

#[test]
fn malformed_obj_corner_references_are_refused_with_line_and_index() {
    let head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvn 0 0 1\n";
    assert_eq!(
        obj_err(&format!("{head}f 1/1 2/3 3/2\n")),
        "<input>: line 7: face 0: texture coordinate index 3 names no texture coordinate \
         (2 defined so far; allowed: 1 to 2, or -1 to -2 counting back)"
    );
    assert_eq!(
        obj_err(&format!("{head}f 1//1 2//-2 3//1\n")),
        "<input>: line 7: face 0: normal index -2 names no normal (1 defined so far; allowed: \
         1 to 1, or -1 to -1 counting back)"
    );
    assert!(obj_err(&format!("{head}f 1/0 2/1 3/1\n")).contains("texture coordinate index 0"));
    // A reference to a value defined after the face.
    assert!(
        obj_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\nvn 0 0 1\n").contains(
            "line 4: face 0: normal index 1 names no normal (0 defined so far; allowed: none"
        )
    );
    assert!(
        obj_err(&format!("{head}vt 0 inf\n"))
            .contains("line 7: texture coordinate 2: a value is not finite")
    );
    assert!(obj_err(&format!("{head}vn 0 1\n")).contains("2 values where 3 were expected"));
    // Negative references count back.
    let (_, a, _) = read_with_attributes(
        format!("{head}f 1/-2/-1 2/-1/1 3/1/1\n").as_bytes(),
        Format::Obj,
    )
    .unwrap();
    assert_eq!(a.texcoords.unwrap().corners, vec![[0, 1, 0]]);
}

#[test]
fn obj_mixed_corners_drop_the_attribute_with_a_note() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvn 0 0 1\n\
                f 1/1/1 2/1/1 4/1/1\nf 1//1 4//1 3//1\n";
    let (soup, a, report) = read_with_attributes(text.as_bytes(), Format::Obj).unwrap();
    assert_eq!(soup.num_faces(), 2);
    assert!(a.texcoords.is_none());
    assert_eq!(a.normals.unwrap().corners, vec![[0, 0, 0], [0, 0, 0]]);
    assert!(
        report
            .notes
            .iter()
            .any(|n| n.starts_with("texture coordinates dropped: face 1")),
        "{report}"
    );
}

#[test]
fn obj_polygons_keep_their_corners_references() {
    // A concave pentagon (its triangulation is not a fan from corner 1), corner i has vt i
    // whose u is the vertex's x: every triangle corner must find its own.
    let xs = [(0.0, 0.0), (4.0, 0.0), (4.0, 3.0), (2.0, 1.0), (0.0, 3.0)];
    let mut text = String::new();
    for (x, y) in xs {
        text += &format!("v {x} {y} 0\n");
    }
    for (x, y) in xs {
        text += &format!("vt {x} {y}\n");
    }
    // The face starts at vertex 3, so references and vertices are rotated against each other.
    text += "f 3/3 4/4 5/5 1/1 2/2\n";
    let (soup, a, report) = read_with_attributes(text.as_bytes(), Format::Obj).unwrap();
    assert_eq!(report.polygons_triangulated, 1);
    assert_eq!(soup.num_faces(), 3);
    let uv = a.texcoords.unwrap();
    for (f, face) in soup.faces.iter().enumerate() {
        for (k, v) in face.iter().enumerate() {
            let p = soup.positions[v.index()];
            assert_eq!(uv.value(f, k), [p.x, p.y]);
        }
    }
    // Repeated consecutive corners are dropped with their references.
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 9 9\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
                f 1/2 1/1 2/3 3/4 4/5\n";
    let (soup, a, _) = read_with_attributes(text.as_bytes(), Format::Obj).unwrap();
    let uv = a.texcoords.unwrap();
    for (f, face) in soup.faces.iter().enumerate() {
        for (k, v) in face.iter().enumerate() {
            let p = soup.positions[v.index()];
            assert_eq!(uv.value(f, k), [p.x, p.y]);
        }
    }
}

#[test]
fn paths_are_written_atomically_and_off_stl_drop_attributes() {
    let dir = tempfile::tempdir().unwrap();
    let (soup, attributes) = seamed_grid();
    let obj = dir.path().join("grid.obj");
    write_path_with_attributes(&obj, &soup, &attributes, Format::Obj).unwrap();
    let (back, again, _) = read_path_with_attributes(&obj).unwrap();
    assert_eq!(back, soup);
    assert_eq!(again.texcoords, attributes.texcoords);
    assert!(again.colors.is_none());
    assert_eq!(Format::Obj.dropped_attributes(&attributes), ["colours"]);
    let off = dir.path().join("grid.off");
    write_path_with_attributes(&off, &soup, &attributes, Format::Off).unwrap();
    assert!(read_path_with_attributes(&off).unwrap().1.is_empty());
    assert_eq!(Format::Off.dropped_attributes(&attributes).len(), 3);
    // Attributes that do not fit are refused before anything is written.
    let mut bad = attributes.clone();
    bad.normals.as_mut().unwrap().corners.pop();
    let err = write_path_with_attributes(dir.path().join("bad.ply"), &soup, &bad, Format::Obj)
        .unwrap_err();
    assert!(err.to_string().contains("attributes do not fit"), "{err}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

mod round_trips {
    use super::*;
    use proptest::prelude::*;

    fn finite() -> impl Strategy<Value = f64> {
        any::<f64>().prop_filter("finite", |x| x.is_finite())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Any finite values at any corners come back bit-exact from OBJ and PLY.
        #[test]
        fn any_values_round_trip(
            uv in proptest::collection::vec([finite(), finite()], 6),
            normals in proptest::collection::vec([finite(), finite(), finite()], 6),
            colours in proptest::collection::vec([0u8..=255, 0u8..=255, 0u8..=255, 0u8..=255], 6),
        ) {
            let soup = TriangleSoup::from_raw(
                &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
                &[[0, 1, 2], [0, 2, 3]],
            );
            let corners = vec![[0, 1, 2], [3, 4, 5]];
            let attributes = Attributes {
                texcoords: Some(Wedges { values: uv, corners: corners.clone() }),
                normals: Some(Wedges { values: normals, corners: corners.clone() }),
                colors: Some(Wedges {
                    values: colours.iter().map(|c| c.map(|k| f64::from(k) / 255.0)).collect(),
                    corners,
                }),
                quality: None,
            };
            for format in [Format::Obj, Format::Ply(PlyEncoding::Ascii), Format::Ply(PlyEncoding::BinaryBigEndian)] {
                let mut bytes = Vec::new();
                write_with_attributes(&mut bytes, &soup, &attributes, format).unwrap();
                let (back, again, _) = read_with_attributes(&bytes[..], format).unwrap();
                let mut expected = attributes.clone();
                if format == Format::Obj {
                    expected.colors = None;
                }
                prop_assert_eq!(corner_bits(&back, &again), corner_bits(&soup, &expected));
            }
        }
    }
}

/// PLY `quality` round-trips through every encoding, beside colours, with the header comments
/// written; other formats report it dropped.
#[test]
fn quality_round_trips_through_ply_with_comments() {
    let (soup, mut attributes) = seamed_grid();
    let corners: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
    // Values that are floats exactly: written as `float`, read back bit for bit.
    let values: Vec<[f64; 1]> = (0..soup.num_vertices())
        .map(|v| [f64::from(0.1f32 * v as f32)])
        .collect();
    attributes.quality = Some(Wedges { values, corners });
    let comments = [
        "quality: a test value".to_string(),
        "two\nlines".to_string(),
    ];
    for enc in [
        PlyEncoding::Ascii,
        PlyEncoding::BinaryLittleEndian,
        PlyEncoding::BinaryBigEndian,
    ] {
        let mut bytes = Vec::new();
        envelope_io::write_with_comments(
            &mut bytes,
            &soup,
            &attributes,
            Format::Ply(enc),
            &comments,
        )
        .unwrap();
        let text = String::from_utf8_lossy(&bytes);
        let header = &text[..text.find("end_header").unwrap()];
        assert!(
            header.contains("comment quality: a test value\n"),
            "{header}"
        );
        assert!(header.contains("comment two lines\n"), "{header}");
        assert!(header.contains("property float quality\n"), "{header}");
        let (back, again, _) = read_with_attributes(&bytes[..], Format::Ply(enc)).unwrap();
        assert_eq!(
            back.positions.len(),
            soup.positions.len() + 3,
            "seam copies"
        );
        let q = again.quality.as_ref().expect("quality read back");
        let orig = attributes.quality.as_ref().unwrap();
        for f in 0..soup.num_faces() {
            for k in 0..3 {
                assert_eq!(
                    q.value(f, k),
                    orig.value(f, k),
                    "{enc:?} face {f} corner {k}"
                );
                assert_eq!(
                    again.colors.as_ref().unwrap().value(f, k),
                    attributes.colors.as_ref().unwrap().value(f, k)
                );
            }
        }
    }
    let only = Attributes {
        quality: attributes.quality.clone(),
        ..Attributes::default()
    };
    for format in [
        Format::Obj,
        Format::Off,
        Format::from_extension("stl").unwrap(),
    ] {
        assert_eq!(format.dropped_attributes(&only), ["quality"]);
    }
    assert!(
        Format::Ply(PlyEncoding::Ascii)
            .dropped_attributes(&only)
            .is_empty()
    );
}

/// `quality` of any scalar type is read as written.
#[test]
fn ply_quality_of_any_type() {
    for (ty, value, expect) in [
        ("uchar", "200", 200.0),
        ("double", "0.1", 0.1),
        ("int", "-3", -3.0),
    ] {
        let ply = format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\nproperty {ty} quality\nelement face 1\n\
             property list uchar int vertex_indices\nend_header\n\
             0 0 0 {value}\n1 0 0 {value}\n0 1 0 {value}\n3 0 1 2\n"
        );
        let (_, a, _) =
            read_with_attributes(ply.as_bytes(), Format::Ply(PlyEncoding::Ascii)).unwrap();
        assert_eq!(a.quality.unwrap().value(0, 2), [expect], "{ty}");
    }
}
