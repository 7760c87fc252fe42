//! Wavefront OBJ: `v x y z` and `f i j k ...` statements make the mesh; statements that cannot
//! change the triangle surface or the vertex numbering are skipped (and counted in the
//! report); any other statement refuses the file.
//!
//! * Face corners may be `i`, `i/t`, `i//n` or `i/t/n`. [`crate::read`] keeps only the vertex
//!   index `i` (and skips `vt` and `vn`); [`crate::read_with_attributes`] also reads the `vt`
//!   (`u [v [w]]`, keeping u and v) and `vn` tables and each corner's references, checked
//!   like vertex indices; a triangulated polygon's triangles keep their corners' references.
//!   An attribute some corners lack is dropped with a note naming the first such face.
//!   `fo` (the obsolete spelling of `f`) is read as `f`.
//! * Indices are 1-based; negative indices count back from the last vertex defined so far.
//!   Indices must name a vertex defined before the face (as every common writer does); an
//!   error quotes the index as written.
//! * Polygons with more than three corners are triangulated without overlaps
//!   ([`envelope_predicates::polygon`]): repeated consecutive corners are dropped, a polygon
//!   visiting a vertex twice or self-intersecting in every axis projection is refused.
//! * Skipped: texture and normal data (`vt`, `vn` unless read with attributes; `vp`), grouping and naming (`o`, `g`, `s`,
//!   `mg`), materials and maps (`mtllib`, `usemtl`, `maplib`, `usemap`), lines and points (`l`,
//!   `p`), and display attributes (`lod`, `bevel`, `c_interp`, `d_interp`, `shadow_obj`,
//!   `trace_obj`, `ctech`, `stech`). None defines a vertex or a face.
//! * Refused: free-form geometry (`cstype`, `deg`, `bmat`, `step`, `curv`, `curv2`, `surf`,
//!   `parm`, `trim`, `hole`, `scrv`, `sp`, `end`, `con`), and any unknown keyword (it might
//!   define geometry the reader would silently lose, or shift the vertex numbering).
//! * A UTF-8 byte order mark at the start is skipped. `#` starts a comment; a `\` at the end of
//!   a line joins the next line to it.
//! * Extra vertex values (`w`, or the common `r g b` colour extension) are ignored.
//! * The writer with attributes writes `vt` and `vn` tables as given and `f v/t/n` corners;
//!   OBJ has no colour statement, so colours are not written.

use std::collections::BTreeMap;
use std::io::{self, Read, Write};

use envelope_mesh::{Attributes, TriangleSoup, Wedges};

use crate::build::{Faces, check_vertex_count, checked_position, finish};
use crate::error::{ReadError, ReadErrorKind, Word};
use crate::input::{Input, Lines, parse_f64, parse_i64};
use crate::{Format, ReadReport};

/// Statements that define neither a vertex nor a face nor anything the surface depends on.
const SKIPPED: [&[u8]; 19] = [
    b"vt",
    b"vn",
    b"vp",
    b"o",
    b"g",
    b"s",
    b"mg",
    b"mtllib",
    b"usemtl",
    b"maplib",
    b"usemap",
    b"l",
    b"p",
    b"lod",
    b"bevel",
    b"c_interp",
    b"d_interp",
    b"shadow_obj",
    b"trace_obj",
];

/// Free-form render attributes: meaningful only for the free-form geometry refused below.
const SKIPPED_FREE_FORM_ATTRIBUTES: [&[u8]; 2] = [b"ctech", b"stech"];

/// Free-form geometry statements: curves and surfaces the reader cannot turn into triangles.
const FREE_FORM: [&[u8]; 14] = [
    b"cstype", b"deg", b"bmat", b"step", b"curv", b"curv2", b"surf", b"parm", b"trim", b"hole",
    b"scrv", b"sp", b"end", b"con",
];

/// Reads the next logical line (joining `\` continuations); false at the end.
fn next_statement<R: Read>(lines: &mut Lines<R>) -> Result<bool, ReadError> {
    if !lines.next()? {
        return Ok(false);
    }
    while lines.line.trim_ascii_end().ends_with(b"\\") {
        let mut acc = std::mem::take(&mut lines.line);
        let keep = acc.trim_ascii_end().len() - 1;
        acc.truncate(keep);
        acc.push(b' ');
        let more = lines.next()?;
        if more {
            acc.extend_from_slice(&lines.line);
        }
        lines.line = acc;
        if !more {
            break;
        }
    }
    Ok(true)
}

pub(crate) fn read<R: Read>(input: Input<R>) -> Result<(TriangleSoup, ReadReport), ReadError> {
    read_impl(input, false).map(|(soup, _, report)| (soup, report))
}

pub(crate) fn read_with_attributes<R: Read>(
    input: Input<R>,
) -> Result<(TriangleSoup, Attributes, ReadReport), ReadError> {
    read_impl(input, true)
}

/// No texture-coordinate or normal reference at a corner.
const NONE: u32 = u32::MAX;

/// The `vt` and `vn` tables and each written face corner's references into them.
#[derive(Default)]
struct CornerRefs {
    texcoords: Vec<[f64; 2]>,
    normals: Vec<[f64; 3]>,
    /// Per corner as written, in file order: 0-based (texture coordinate, normal), or `NONE`.
    corners: Vec<[u32; 2]>,
    /// Per kind, the first face with a corner lacking it, and whether any corner has it.
    first_without: [Option<u64>; 2],
    any_with: [bool; 2],
}

/// Parses up to `N` finite numbers; those after the first `needed` may be missing (then 0).
fn attribute_values<const N: usize>(
    toks: &mut dyn Iterator<Item = &[u8]>,
    needed: usize,
    what: &'static str,
    element: u64,
) -> Result<[f64; N], ReadErrorKind> {
    let mut out = [0.0; N];
    for (i, x) in out.iter_mut().enumerate() {
        match toks.next() {
            Some(t) => *x = parse_f64(t).ok_or(ReadErrorKind::MalformedNumber)?,
            None if i < needed => {
                return Err(ReadErrorKind::WrongValueCount {
                    expected: N as u64,
                    found: i as u64,
                });
            }
            None => break,
        }
        if !x.is_finite() {
            return Err(ReadErrorKind::AttributeValue { what, element });
        }
    }
    Ok(out)
}

/// A 1-based or negative OBJ index into a table of `n` entries defined so far, 0-based.
fn resolve_index(raw: i64, n: i64) -> Option<u32> {
    let index = match raw {
        r if r > 0 => r - 1,
        r if r < 0 => n.saturating_add(r),
        _ => -1,
    };
    (index >= 0 && index < n).then_some(index as u32)
}

fn read_impl<R: Read>(
    input: Input<R>,
    with_attributes: bool,
) -> Result<(TriangleSoup, Attributes, ReadReport), ReadError> {
    let mut lines = Lines::new(input, Some(b'#'));
    let mut report = ReadReport::new(Format::Obj);
    let mut positions = Vec::new();
    let mut faces = Faces::new();
    let mut refs = CornerRefs::default();
    if with_attributes {
        faces.track_corners();
    }
    let mut poly: Vec<u32> = Vec::new();
    let mut face_no = 0u64;
    let mut ignored: BTreeMap<String, u64> = BTreeMap::new();
    let mut extra_vertex_values = 0u64;
    while next_statement(&mut lines)? {
        let loc = lines.location();
        let err = |kind| ReadError::new(loc, kind);
        let mut toks = lines.tokens();
        let Some(keyword) = toks.next() else { continue };
        match keyword {
            b"v" => {
                let mut p = [0.0; 3];
                for (i, c) in p.iter_mut().enumerate() {
                    let t = toks.next().ok_or_else(|| {
                        err(ReadErrorKind::WrongValueCount {
                            expected: 3,
                            found: i as u64,
                        })
                    })?;
                    *c = parse_f64(t).ok_or_else(|| err(ReadErrorKind::MalformedNumber))?;
                }
                if toks.next().is_some() {
                    extra_vertex_values += 1;
                }
                let n = positions.len() as u64;
                check_vertex_count(n + 1).map_err(err)?;
                positions.push(checked_position(p, n).map_err(err)?);
            }
            // `vt u [v [w]]`: v defaults to 0 as the format says; w is not kept.
            b"vt" if with_attributes => {
                let n = refs.texcoords.len() as u64;
                check_vertex_count(n + 1)
                    .map_err(|_| err(ReadErrorKind::TooMany("texture coordinates")))?;
                let uv = attribute_values::<2>(&mut toks, 1, "texture coordinate", n);
                refs.texcoords.push(uv.map_err(err)?);
            }
            b"vn" if with_attributes => {
                let n = refs.normals.len() as u64;
                check_vertex_count(n + 1).map_err(|_| err(ReadErrorKind::TooMany("normals")))?;
                let normal = attribute_values::<3>(&mut toks, 3, "normal", n);
                refs.normals.push(normal.map_err(err)?);
            }
            b"f" | b"fo" => {
                poly.clear();
                let n = positions.len() as i64;
                for t in toks {
                    let bad = || {
                        err(ReadErrorKind::ObjBadCorner {
                            face: face_no,
                            corner: Word::new(t),
                        })
                    };
                    // `i`, `i/t`, `i//n`, `i/t/n`: a corner that is none of these is refused,
                    // not guessed.
                    let mut parts = t.split(|&b| b == b'/');
                    let idx = parts.next().unwrap_or_default();
                    let rest: Vec<&[u8]> = parts.collect();
                    let reference = |x: &[u8]| x.is_empty() || parse_i64(x).is_some();
                    let well_formed = rest.len() <= 2 && rest.iter().all(|x| reference(x));
                    let raw = parse_i64(idx).filter(|_| well_formed).ok_or_else(bad)?;
                    let index = resolve_index(raw, n).ok_or_else(|| {
                        err(ReadErrorKind::ObjIndexOutOfRange {
                            face: face_no,
                            index: raw,
                            vertices: n as u64,
                        })
                    })?;
                    poly.push(index);
                    if with_attributes {
                        let tables = [
                            ("texture coordinate", refs.texcoords.len()),
                            ("normal", refs.normals.len()),
                        ];
                        let mut corner = [NONE; 2];
                        for (k, (what, count)) in tables.into_iter().enumerate() {
                            match rest.get(k).and_then(|x| parse_i64(x)) {
                                Some(raw) => {
                                    corner[k] =
                                        resolve_index(raw, count as i64).ok_or_else(|| {
                                            err(ReadErrorKind::ObjAttributeIndexOutOfRange {
                                                face: face_no,
                                                what,
                                                index: raw,
                                                defined: count as u64,
                                            })
                                        })?;
                                    refs.any_with[k] = true;
                                }
                                None => {
                                    refs.first_without[k].get_or_insert(face_no);
                                }
                            }
                        }
                        refs.corners.push(corner);
                    }
                }
                faces
                    .push_polygon(&poly, face_no, loc, &mut report)
                    .map_err(err)?;
                face_no += 1;
            }
            k if SKIPPED.contains(&k) || SKIPPED_FREE_FORM_ATTRIBUTES.contains(&k) => {
                *ignored
                    .entry(String::from_utf8_lossy(k).into_owned())
                    .or_default() += 1;
            }
            k if FREE_FORM.contains(&k) => {
                return Err(err(ReadErrorKind::UnsupportedStatement {
                    keyword: Word::new(k),
                    why: "free-form curves and surfaces are not supported; \
                          only v and f statements make the mesh",
                }));
            }
            k => {
                return Err(err(ReadErrorKind::UnsupportedStatement {
                    keyword: Word::new(k),
                    why: "unknown OBJ statement (it might define geometry or vertices); \
                          allowed: v, f, and the attribute and grouping statements \
                          vt vn vp o g s mg mtllib usemtl maplib usemap l p lod bevel \
                          c_interp d_interp shadow_obj trace_obj ctech stech",
                }));
            }
        }
    }
    if extra_vertex_values > 0 {
        report.note(format!(
            "{extra_vertex_values} vertices had values after x y z (ignored)"
        ));
    }
    for (k, n) in ignored {
        report.note(format!("skipped {n} '{k}' statements"));
    }
    let (faces, origins) = faces.resolve_with_origins(&positions)?;
    let loc = lines.location();
    let (soup, mut report) =
        finish(positions, faces, report).map_err(|k| ReadError::new(loc, k))?;
    let attributes = match origins {
        Some(origins) => attributes(refs, &origins, &mut report),
        None => Attributes::default(),
    };
    Ok((soup, attributes, report))
}

/// The wedges of the corner references; an attribute some corners lack is dropped, with a
/// note naming the first face without it (the file is still read: the positions are whole).
fn attributes(refs: CornerRefs, origins: &[[u64; 3]], report: &mut ReadReport) -> Attributes {
    let corners = |k: usize| -> Vec<[u32; 3]> {
        origins
            .iter()
            .map(|o| o.map(|c| refs.corners[c as usize][k]))
            .collect()
    };
    let mut present = [false; 2];
    for (k, name) in ["texture coordinates", "normals"].into_iter().enumerate() {
        match (refs.any_with[k], refs.first_without[k]) {
            (true, None) => present[k] = true,
            (true, Some(face)) => report.note(format!(
                "{name} dropped: face {face} has a corner without one while other corners have \
                 them"
            )),
            (false, _) => {}
        }
    }
    Attributes {
        texcoords: present[0].then(|| Wedges {
            corners: corners(0),
            values: refs.texcoords,
        }),
        normals: present[1].then(|| Wedges {
            corners: corners(1),
            values: refs.normals,
        }),
        colors: None,
        quality: None,
    }
}

pub(crate) fn write<W: Write>(w: &mut W, soup: &TriangleSoup) -> io::Result<()> {
    writeln!(
        w,
        "# {} vertices, {} triangles",
        soup.num_vertices(),
        soup.num_faces()
    )?;
    for p in &soup.positions {
        writeln!(w, "v {:?} {:?} {:?}", p.x, p.y, p.z)?;
    }
    for f in &soup.faces {
        writeln!(
            w,
            "f {} {} {}",
            f[0].0 as u64 + 1,
            f[1].0 as u64 + 1,
            f[2].0 as u64 + 1
        )?;
    }
    Ok(())
}

/// Writes the soup with `vt` and `vn` tables and `f v/t/n` corners (colours have no OBJ
/// statement and are not written).
pub(crate) fn write_with_attributes<W: Write>(
    w: &mut W,
    soup: &TriangleSoup,
    attributes: &Attributes,
) -> io::Result<()> {
    let (tex, normals) = (&attributes.texcoords, &attributes.normals);
    if tex.is_none() && normals.is_none() {
        return write(w, soup);
    }
    writeln!(
        w,
        "# {} vertices, {} triangles",
        soup.num_vertices(),
        soup.num_faces()
    )?;
    for p in &soup.positions {
        writeln!(w, "v {:?} {:?} {:?}", p.x, p.y, p.z)?;
    }
    for t in tex.iter().flat_map(|t| &t.values) {
        writeln!(w, "vt {:?} {:?}", t[0], t[1])?;
    }
    for n in normals.iter().flat_map(|n| &n.values) {
        writeln!(w, "vn {:?} {:?} {:?}", n[0], n[1], n[2])?;
    }
    for (f, face) in soup.faces.iter().enumerate() {
        w.write_all(b"f")?;
        for (k, v) in face.iter().enumerate() {
            write!(w, " {}", v.0 as u64 + 1)?;
            match (tex, normals) {
                (Some(t), Some(n)) => write!(
                    w,
                    "/{}/{}",
                    t.corners[f][k] as u64 + 1,
                    n.corners[f][k] as u64 + 1
                )?,
                (Some(t), None) => write!(w, "/{}", t.corners[f][k] as u64 + 1)?,
                (None, Some(n)) => write!(w, "//{}", n.corners[f][k] as u64 + 1)?,
                (None, None) => {}
            }
        }
        w.write_all(b"\n")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Axis, Location, read};
    use envelope_mesh::CoordError;

    fn obj(s: &str) -> Result<(TriangleSoup, ReadReport), ReadError> {
        read(s.as_bytes(), Format::Obj)
    }

    fn kind(s: &str) -> ReadErrorKind {
        obj(s).unwrap_err().kind
    }

    #[test]
    fn quad_with_slashes_negatives_continuations_and_comments() {
        let (soup, report) = obj(concat!(
            "# a quad\n",
            "mtllib x.mtl\n",
            "v 0 0 0\nv 1 0 0 # comment\nv 1 1 0 1.0\n",
            "v 0 \\\n 1 0\n",
            "vt 0 0\nvn 0 0 1\n",
            "f 1/1/1 2//1 -2/1 -1\n",
        ))
        .unwrap();
        assert_eq!(
            soup,
            TriangleSoup::from_raw(
                &[
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 1.0, 0.0],
                    [0.0, 1.0, 0.0]
                ],
                &[[0, 1, 2], [0, 2, 3]]
            )
        );
        assert_eq!(report.polygons_triangulated, 1);
        assert_eq!(report.triangles_from_polygons, 2);
        assert!(report.notes.iter().any(|n| n.contains("'vt'")));
        assert!(report.notes.iter().any(|n| n.contains("after x y z")));
    }

    #[test]
    fn crlf_lines() {
        let (soup, _) = obj("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n").unwrap();
        assert_eq!(soup.num_faces(), 1);
    }

    #[test]
    fn bad_inputs() {
        assert_eq!(
            kind("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"),
            ReadErrorKind::Coordinate {
                vertex: 1,
                axis: Axis::Y,
                error: CoordError::NaN
            }
        );
        assert_eq!(
            kind("v 0 0 1e300\n"),
            ReadErrorKind::Coordinate {
                vertex: 0,
                axis: Axis::Z,
                error: CoordError::TooLarge
            }
        );
        assert_eq!(
            kind("v 0 0\n"),
            ReadErrorKind::WrongValueCount {
                expected: 3,
                found: 2
            }
        );
        assert_eq!(kind("v 0 0 x\n"), ReadErrorKind::MalformedNumber);
        assert_eq!(
            kind("v 0 0 0\nf 1 2 3\n"),
            ReadErrorKind::ObjIndexOutOfRange {
                face: 0,
                index: 2,
                vertices: 1
            }
        );
        assert_eq!(
            kind("v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 3\nf 0 1 2\n"),
            ReadErrorKind::ObjIndexOutOfRange {
                face: 1,
                index: 0,
                vertices: 3
            }
        );
        assert_eq!(
            kind("v 0 0 0\nv 0 0 0\nv 0 0 0\nf -4 1 2\n"),
            ReadErrorKind::ObjIndexOutOfRange {
                face: 0,
                index: -4,
                vertices: 3
            }
        );
        assert_eq!(
            kind("v 0 0 0\nv 0 0 0\nf 1 2\n"),
            ReadErrorKind::TooFewCorners {
                face: 0,
                corners: 2
            }
        );
        assert!(matches!(
            kind("v 0 0 0\nf x/1 1 1\n"),
            ReadErrorKind::ObjBadCorner { face: 0, corner } if corner.to_string() == "x/1"
        ));
        assert!(matches!(
            kind("v 0 0 0\nf 1/a/2 1 1\n"),
            ReadErrorKind::ObjBadCorner { face: 0, .. }
        ));
        assert!(matches!(
            kind("v 0 0 0\nf 1/1/1/1 1 1\n"),
            ReadErrorKind::ObjBadCorner { face: 0, .. }
        ));
        assert_eq!(kind("v 0 0 0\nv 1 1 1\n"), ReadErrorKind::NoFaces);
        assert_eq!(kind(""), ReadErrorKind::NoFaces);
        // Garbage is an unknown statement, not an empty mesh.
        assert!(matches!(
            read(&[0xff, 0x00, 0x13, 0x80][..], Format::Obj)
                .unwrap_err()
                .kind,
            ReadErrorKind::UnsupportedStatement { .. }
        ));
    }

    #[test]
    fn error_names_the_line() {
        let e = obj("v 0 0 0\n\nv 1 inf 0\n").unwrap_err();
        assert_eq!(e.location, Location::Line(3));
        assert_eq!(
            e.to_string(),
            "<input>: line 3: vertex 1: y coordinate rejected: coordinate is infinite"
        );
    }
}
