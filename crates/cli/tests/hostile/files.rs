//! Mesh files for the hostile-input suite, made in code: valid files through
//! `envelope_io::write`, and hand-rolled writers for the hostile variants (lying headers,
//! odd numbers, polygons) that no real writer would produce.

use envelope_io::{Format, PlyEncoding, StlEncoding, write};
use envelope_mesh::{TriangleSoup, generate};
use glam::DVec3;

/// Every encoding a reader supports: (label, format, extension).
pub const ENCODINGS: [(&str, Format, &str); 7] = [
    ("obj", Format::Obj, "obj"),
    ("off", Format::Off, "off"),
    ("ply-ascii", Format::Ply(PlyEncoding::Ascii), "ply"),
    (
        "ply-le",
        Format::Ply(PlyEncoding::BinaryLittleEndian),
        "ply",
    ),
    ("ply-be", Format::Ply(PlyEncoding::BinaryBigEndian), "ply"),
    ("stl-ascii", Format::Stl(StlEncoding::Ascii), "stl"),
    ("stl-bin", Format::Stl(StlEncoding::Binary), "stl"),
];

/// The text encodings (a BOM or CRLF line ends make sense for them).
pub const TEXT_ENCODINGS: [(&str, Format, &str); 4] = [
    ("obj", Format::Obj, "obj"),
    ("off", Format::Off, "off"),
    ("ply-ascii", Format::Ply(PlyEncoding::Ascii), "ply"),
    ("stl-ascii", Format::Stl(StlEncoding::Ascii), "stl"),
];

/// Positions rounded to f32, so that an STL file holds the same mesh as the others.
fn f32_exact(mut s: TriangleSoup) -> TriangleSoup {
    for p in &mut s.positions {
        *p = p.as_vec3().as_dvec3();
    }
    s
}

/// The unit tetrahedron (4 faces).
pub fn tet() -> TriangleSoup {
    generate::tetrahedron()
}

/// A unit cube (12 faces).
pub fn cube() -> TriangleSoup {
    generate::box_mesh(DVec3::ONE, 1)
}

/// A unit icosphere: 80 faces at `s = 1`, 320 at `s = 2`.
pub fn ico(s: u32) -> TriangleSoup {
    f32_exact(generate::icosphere(s, 1.0))
}

/// The demo cup (4032 faces, a border loop).
pub fn cup() -> TriangleSoup {
    f32_exact(generate::demo_model())
}

/// A small torus (genus 1, 96 faces).
pub fn torus() -> TriangleSoup {
    f32_exact(generate::torus(2.0, 0.5, 12, 8))
}

/// `s` scaled by `k` and moved by `offset`.
pub fn scaled(s: &TriangleSoup, k: f64, offset: f64) -> TriangleSoup {
    let mut s = s.clone();
    for p in &mut s.positions {
        *p = *p * k + DVec3::splat(offset);
    }
    s
}

/// `s` in `format`.
pub fn encode(s: &TriangleSoup, format: Format) -> Vec<u8> {
    let mut bytes = Vec::new();
    write(&mut bytes, s, format).expect("write a generated mesh");
    bytes
}

/// The UTF-8 byte order mark.
pub const BOM: &[u8] = b"\xEF\xBB\xBF";

/// `bytes` with every `\n` turned into `\r\n`.
pub fn crlf(bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes.len() * 2);
    for &b in bytes {
        if b == b'\n' {
            out.push(b'\r');
        }
        out.push(b);
    }
    out
}

/// `bytes` with the first occurrence of `from` replaced by `to` (panics when absent: a
/// generator bug, not a product bug).
pub fn replace_once(bytes: &[u8], from: &str, to: &str) -> Vec<u8> {
    let from = from.as_bytes();
    let at = bytes
        .windows(from.len())
        .position(|w| w == from)
        .unwrap_or_else(|| panic!("{:?} not in the file", String::from_utf8_lossy(from)));
    let mut out = bytes[..at].to_vec();
    out.extend_from_slice(to.as_bytes());
    out.extend_from_slice(&bytes[at + from.len()..]);
    out
}

/// Vertex coordinates as written in a text file (any token, valid or not).
pub type Row = [String; 3];

/// Rows of a soup, formatted exactly.
pub fn rows(s: &TriangleSoup) -> Vec<Row> {
    s.positions
        .iter()
        .map(|p| [p.x, p.y, p.z].map(|c| format!("{c:?}")))
        .collect()
}

/// Rows from numbers.
pub fn rows_of(points: &[[f64; 3]]) -> Vec<Row> {
    points.iter().map(|p| p.map(|c| format!("{c:?}"))).collect()
}

/// Faces of a soup as 0-based index lists.
pub fn polys(s: &TriangleSoup) -> Vec<Vec<i64>> {
    s.faces
        .iter()
        .map(|f| f.iter().map(|v| i64::from(v.0)).collect())
        .collect()
}

/// An OBJ file: `v` rows, then `f` lines of 1-based indices (written as given, so 0 and
/// negative indices pass through).
pub fn obj(rows: &[Row], faces: &[Vec<i64>]) -> Vec<u8> {
    let mut s = String::new();
    for r in rows {
        s += &format!("v {} {} {}\n", r[0], r[1], r[2]);
    }
    for f in faces {
        let idx: Vec<String> = f.iter().map(ToString::to_string).collect();
        s += &format!("f {}\n", idx.join(" "));
    }
    s.into_bytes()
}

/// 0-based polygons as 1-based OBJ indices.
pub fn one_based(faces: &[Vec<i64>]) -> Vec<Vec<i64>> {
    faces
        .iter()
        .map(|f| f.iter().map(|i| i + 1).collect())
        .collect()
}

/// An OFF file with the given header counts (which may lie).
pub fn off_counts(rows: &[Row], faces: &[Vec<i64>], nv: u64, nf: u64) -> Vec<u8> {
    let mut s = format!("OFF\n{nv} {nf} 0\n");
    for r in rows {
        s += &format!("{} {} {}\n", r[0], r[1], r[2]);
    }
    for f in faces {
        let idx: Vec<String> = f.iter().map(ToString::to_string).collect();
        s += &format!("{} {}\n", f.len(), idx.join(" "));
    }
    s.into_bytes()
}

/// An OFF file with true counts.
pub fn off(rows: &[Row], faces: &[Vec<i64>]) -> Vec<u8> {
    off_counts(rows, faces, rows.len() as u64, faces.len() as u64)
}

/// An ASCII PLY file with the given element counts.
pub fn ply_ascii_counts(rows: &[Row], faces: &[Vec<i64>], nv: u64, nf: u64) -> Vec<u8> {
    let mut s = format!(
        "ply\nformat ascii 1.0\nelement vertex {nv}\nproperty double x\nproperty double y\n\
         property double z\nelement face {nf}\nproperty list uchar int vertex_indices\nend_header\n"
    );
    for r in rows {
        s += &format!("{} {} {}\n", r[0], r[1], r[2]);
    }
    for f in faces {
        let idx: Vec<String> = f.iter().map(ToString::to_string).collect();
        s += &format!("{} {}\n", f.len(), idx.join(" "));
    }
    s.into_bytes()
}

/// An ASCII PLY file with true counts.
pub fn ply_ascii(rows: &[Row], faces: &[Vec<i64>]) -> Vec<u8> {
    ply_ascii_counts(rows, faces, rows.len() as u64, faces.len() as u64)
}

/// A binary PLY file (`double` coordinates, `uint` list counts and `int` indices), with
/// the given element counts and list counts taken from `list_count` when given.
pub fn ply_binary(
    big_endian: bool,
    points: &[[f64; 3]],
    faces: &[Vec<i64>],
    counts: (u64, u64),
    list_count: Option<u32>,
) -> Vec<u8> {
    let enc = if big_endian {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut out = format!(
        "ply\nformat {enc} 1.0\nelement vertex {}\nproperty double x\nproperty double y\n\
         property double z\nelement face {}\nproperty list uint int vertex_indices\nend_header\n",
        counts.0, counts.1
    )
    .into_bytes();
    let f64b = |x: f64| {
        if big_endian {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    let u32b = |x: u32| {
        if big_endian {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    for p in points {
        for &c in p {
            out.extend_from_slice(&f64b(c));
        }
    }
    for f in faces {
        out.extend_from_slice(&u32b(list_count.unwrap_or(f.len() as u32)));
        for &i in f {
            out.extend_from_slice(&u32b(i as i32 as u32));
        }
    }
    out
}

/// An ASCII STL file of triangles (coordinates as written).
pub fn stl_ascii(tris: &[[Row; 3]]) -> Vec<u8> {
    let mut s = String::from("solid hostile\n");
    for t in tris {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for r in t {
            s += &format!("      vertex {} {} {}\n", r[0], r[1], r[2]);
        }
        s += "    endloop\n  endfacet\n";
    }
    s += "endsolid hostile\n";
    s.into_bytes()
}

/// A binary STL file of f32 triangles with the given facet count in its header.
pub fn stl_binary(tris: &[[[f32; 3]; 3]], count: u32) -> Vec<u8> {
    let mut out = vec![b' '; 80];
    out[..7].copy_from_slice(b"hostile");
    out.extend_from_slice(&count.to_le_bytes());
    for t in tris {
        out.extend_from_slice(&[0u8; 12]);
        for p in t {
            for c in p {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        out.extend_from_slice(&[0u8; 2]);
    }
    out
}

/// The triangles of a soup as STL corners.
pub fn stl_tris(s: &TriangleSoup) -> Vec<[[f32; 3]; 3]> {
    s.faces
        .iter()
        .map(|f| f.map(|v| s.positions[v.index()].to_array().map(|c| c as f32)))
        .collect()
}

/// The triangles of a soup as ASCII STL rows.
pub fn stl_rows(s: &TriangleSoup) -> Vec<[Row; 3]> {
    let r = rows(s);
    s.faces
        .iter()
        .map(|f| f.map(|v| r[v.index()].clone()))
        .collect()
}

/// An L-shaped prism with its two caps as single non-convex hexagons, each listed from a
/// corner whose fan leaves the polygon: a fan triangulation overlaps itself, a proper one
/// is a closed manifold. Returns (points, 0-based polygons).
pub fn l_prism() -> (Vec<[f64; 3]>, Vec<Vec<i64>>) {
    let ring = [
        [2.0, 0.0],
        [2.0, 1.0],
        [1.0, 1.0],
        [1.0, 2.0],
        [0.0, 2.0],
        [0.0, 0.0],
    ];
    let mut pts = Vec::new();
    for z in [0.0, 1.0] {
        for [x, y] in ring {
            pts.push([x, y, z]);
        }
    }
    let mut faces = vec![vec![0, 5, 4, 3, 2, 1], vec![6, 7, 8, 9, 10, 11]];
    for i in 0..6 {
        let j = (i + 1) % 6;
        faces.push(vec![i, j, j + 6, i + 6]);
    }
    (pts, faces)
}

/// A unit cube with quads for faces. Returns (points, 0-based polygons).
pub fn quad_cube() -> (Vec<[f64; 3]>, Vec<Vec<i64>>) {
    let mut pts = Vec::new();
    for z in [0.0, 1.0] {
        for y in [0.0, 1.0] {
            for x in [0.0, 1.0] {
                pts.push([x, y, z]);
            }
        }
    }
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    (pts, faces.iter().map(|f| f.to_vec()).collect())
}

/// A flat regular pentagon's corners and the pentagram through them (a self-intersecting
/// polygon), 0-based.
pub fn pentagram() -> (Vec<[f64; 3]>, Vec<Vec<i64>>) {
    let pts = (0..5)
        .map(|k| {
            let a = f64::from(k) * std::f64::consts::TAU / 5.0;
            [a.cos(), a.sin(), 0.0]
        })
        .collect();
    (pts, vec![vec![0, 2, 4, 1, 3]])
}

/// A convex flat `n`-gon (a disk with one polygon), 0-based.
pub fn big_polygon(n: u32) -> (Vec<[f64; 3]>, Vec<Vec<i64>>) {
    let pts = (0..n)
        .map(|k| {
            let a = f64::from(k) * std::f64::consts::TAU / f64::from(n);
            [a.cos(), a.sin(), 0.0]
        })
        .collect();
    (pts, vec![(0..i64::from(n)).collect()])
}

/// An octahedron subdivided twice onto the unit sphere (66 vertices, 128 faces; midpoints
/// normalised, rounded to 6 decimals). Returns (points, 0-based triangles).
pub fn octasphere() -> (Vec<[f64; 3]>, Vec<Vec<i64>>) {
    let mut v: Vec<[f64; 3]> = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let mut f: Vec<[usize; 3]> = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    for _ in 0..2 {
        let mut cache = std::collections::HashMap::new();
        let mut mid = |v: &mut Vec<[f64; 3]>, a: usize, b: usize| {
            *cache.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let p = [0, 1, 2].map(|i| (v[a][i] + v[b][i]) / 2.0);
                let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                v.push(p.map(|x| format!("{:.6}", x / n).parse::<f64>().unwrap()));
                v.len() - 1
            })
        };
        let mut next = Vec::new();
        for [a, b, c] in f {
            let (ab, bc, ca) = (mid(&mut v, a, b), mid(&mut v, b, c), mid(&mut v, c, a));
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    let faces = f.iter().map(|t| t.map(|i| i as i64).to_vec()).collect();
    (v, faces)
}
