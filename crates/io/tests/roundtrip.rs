//! Write-then-read round trips for every format and encoding, and file-level behaviour
//! (paths, sniffing, atomic writes, huge header counts).

use std::time::{Duration, Instant};

use envelope_io::{
    Format, PlyEncoding, ReadErrorKind, StlEncoding, WriteErrorKind, read, read_path, write,
    write_path,
};
use envelope_mesh::{TriangleSoup, VertexId, check_coordinate};
use glam::DVec3;
use proptest::prelude::*;

const EXACT: [Format; 5] = [
    Format::Obj,
    Format::Off,
    Format::Ply(PlyEncoding::Ascii),
    Format::Ply(PlyEncoding::BinaryLittleEndian),
    Format::Ply(PlyEncoding::BinaryBigEndian),
];
const STL: [Format; 2] = [
    Format::Stl(StlEncoding::Ascii),
    Format::Stl(StlEncoding::Binary),
];

fn coordinate() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        Just(0.0),
        Just(-0.0),
        (-20i32..20).prop_map(f64::from),
        -1e3..1e3f64,
        any::<f64>().prop_filter("in range", |&x| check_coordinate(x).is_ok()),
    ]
}

fn coordinate_f32() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        (-20i32..20).prop_map(f64::from),
        (-1e3..1e3f32).prop_map(f64::from),
        any::<f32>()
            .prop_map(f64::from)
            .prop_filter("in range", |&x| check_coordinate(x).is_ok()),
    ]
}

fn soup(coord: impl Strategy<Value = f64> + Clone) -> impl Strategy<Value = TriangleSoup> {
    (1usize..24).prop_flat_map(move |n| {
        let positions = prop::collection::vec([coord.clone(), coord.clone(), coord.clone()], n);
        let faces = prop::collection::vec([0..n as u32, 0..n as u32, 0..n as u32], 1..40);
        (positions, faces).prop_map(|(p, f)| TriangleSoup::from_raw(&p, &f))
    })
}

fn roundtrip(soup: &TriangleSoup, format: Format) -> TriangleSoup {
    let mut bytes = Vec::new();
    write(&mut bytes, soup, format).unwrap();
    let (back, report) = read(&bytes[..], format).unwrap();
    assert_eq!(report.format, format);
    back
}

/// Bit-exact comparison (`==` on f64 would equate -0 and +0).
fn bits(s: &TriangleSoup) -> (Vec<[u64; 3]>, &[[VertexId; 3]]) {
    (
        s.positions
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect(),
        &s.faces,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn exact_formats_round_trip(s in soup(coordinate())) {
        for format in EXACT {
            let back = roundtrip(&s, format);
            prop_assert_eq!(bits(&back), bits(&s), "{}", format);
        }
    }

    /// STL keeps f32 and welds: compare triangle by triangle, and check that the vertices
    /// are exactly the distinct positions used, in order of first use.
    #[test]
    fn stl_round_trips_triangles(s in soup(coordinate_f32())) {
        for format in STL {
            let back = roundtrip(&s, format);
            prop_assert_eq!(back.faces.len(), s.faces.len());
            for f in s.face_ids() {
                prop_assert_eq!(back.triangle(f), s.triangle(f), "{}", format);
            }
            let mut used: Vec<DVec3> = Vec::new();
            for p in s.faces.iter().flatten().map(|&v| s.position(v)) {
                if !used.contains(&p) {
                    used.push(p);
                }
            }
            prop_assert_eq!(&back.positions, &used);
        }
    }

    /// Truncating any file anywhere gives an error or a (smaller) valid soup, never a panic.
    #[test]
    fn truncations_never_panic(s in soup(coordinate()), cut in any::<prop::sample::Index>()) {
        for format in EXACT.into_iter().chain(STL) {
            let mut bytes = Vec::new();
            write(&mut bytes, &s, format).unwrap();
            let n = cut.index(bytes.len());
            if let Ok((t, _)) = read(&bytes[..n], format) {
                prop_assert!(t.indices_in_range());
            }
        }
    }
}

fn tetrahedron() -> TriangleSoup {
    TriangleSoup::from_raw(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        &[[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]],
    )
}

#[test]
fn paths_extensions_and_sniffing() {
    let dir = tempfile::tempdir().unwrap();
    let t = tetrahedron();
    for format in EXACT.into_iter().chain(STL) {
        let path = dir
            .path()
            .join(format!("mesh.{}", format.extension().to_uppercase()));
        write_path(&path, &t, format).unwrap();
        let (back, report) = read_path(&path).unwrap();
        assert_eq!(back, t, "{format}");
        assert_eq!(report.format, format);
        // Without the extension the content decides.
        let bare = dir.path().join("mesh");
        std::fs::rename(&path, &bare).unwrap();
        let (back, report) = read_path(&bare).unwrap();
        assert_eq!((back, report.format), (t.clone(), format));
    }
    // Only the written files remain: no temporary files left behind.
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, ["mesh"]);
}

#[test]
fn path_errors_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.ply");
    let e = read_path(&missing).unwrap_err();
    assert_eq!(e.kind, ReadErrorKind::NotFound);
    assert!(e.to_string().contains("missing.ply: file not found"), "{e}");
    assert_eq!(
        read_path(dir.path()).unwrap_err().kind,
        ReadErrorKind::IsADirectory
    );
    let unknown = dir.path().join("noise.bin");
    std::fs::write(&unknown, [0x13u8, 0x37, 0x00, 0xff, 0x42]).unwrap();
    assert_eq!(
        read_path(&unknown).unwrap_err().kind,
        ReadErrorKind::UnknownFormat
    );
    let off = dir.path().join("bad.off");
    std::fs::write(&off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").unwrap();
    let e = read_path(&off).unwrap_err();
    assert!(
        e.to_string().ends_with(
            "bad.off: line 6: face 0: vertex index 3 out of range (3 vertices; allowed: 0 to 2)"
        ),
        "{e}"
    );
}

#[test]
fn failed_write_keeps_the_old_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("keep.obj");
    std::fs::write(&path, "old").unwrap();
    let broken = TriangleSoup::from_raw(&[[0.0; 3]], &[[0, 0, 1]]);
    let e = write_path(&path, &broken, Format::Obj).unwrap_err();
    assert!(matches!(
        e.kind,
        WriteErrorKind::IndexOutOfRange {
            face: 0,
            index: 1,
            ..
        }
    ));
    let nan = TriangleSoup::from_raw(&[[0.0, f64::NAN, 0.0]], &[[0, 0, 0]]);
    assert!(matches!(
        write_path(&path, &nan, Format::Obj).unwrap_err().kind,
        WriteErrorKind::Coordinate { .. }
    ));
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
    // A target inside a missing directory fails cleanly.
    let e = write_path(
        dir.path().join("no/such/dir.obj"),
        &tetrahedron(),
        Format::Obj,
    )
    .unwrap_err();
    assert!(matches!(e.kind, WriteErrorKind::Io(_)), "{e}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn huge_header_counts_on_tiny_files_fail_fast() {
    let dir = tempfile::tempdir().unwrap();
    let files: [(&str, Vec<u8>); 4] = [
        (
            "huge.ply",
            b"ply\nformat binary_little_endian 1.0\nelement vertex 2147483648\nproperty float x\n\
              property float y\nproperty float z\nelement face 2147483648\n\
              property list uchar int vertex_indices\nend_header\n\0\0\0\0"
                .to_vec(),
        ),
        (
            "huge_ascii.ply",
            b"ply\nformat ascii 1.0\nelement vertex 2147483648\nproperty float x\n\
              property float y\nproperty float z\nend_header\n0 0 0\n"
                .to_vec(),
        ),
        (
            "huge.off",
            b"OFF\n2147483648 2147483648 0\n0 0 0\n".to_vec(),
        ),
        ("huge.stl", {
            let mut b = vec![0u8; 80];
            b.extend(u32::MAX.to_le_bytes());
            b.extend([0u8; 50]);
            b
        }),
    ];
    for (name, bytes) in files {
        let path = dir.path().join(name);
        std::fs::write(&path, &bytes).unwrap();
        let start = Instant::now();
        let e = read_path(&path).unwrap_err();
        assert!(
            matches!(e.kind, ReadErrorKind::Truncated { .. }),
            "{name}: {e}"
        );
        // The same bytes from a plain reader (size unknown): capped reservations.
        let format = Format::from_path(&path).unwrap();
        assert!(matches!(
            read(&bytes[..], format).unwrap_err().kind,
            ReadErrorKind::Truncated { .. }
        ));
        assert!(
            start.elapsed() < Duration::from_secs(2),
            "{name} took {:?}",
            start.elapsed()
        );
    }
}
