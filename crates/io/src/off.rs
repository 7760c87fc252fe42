//! Object File Format: an `OFF` header, a `vertices faces [edges]` counts line, one vertex per
//! line, then one face per line as `n i_1 ... i_n [colour]`. `#` starts a comment.
//!
//! * The `COFF`, `NOFF`, `CNOFF`, `STOFF` ... variants are read by keeping the first three
//!   values of each vertex line and ignoring the colour, normal and texture columns; `nOFF`
//!   is read when its dimension is 3. `4OFF` (homogeneous), `nOFF` of other dimensions,
//!   binary OFF and any other word on the OFF line are refused, and so is a file whose first
//!   word is not an OFF keyword (the error says what it found, e.g. the counts of a file
//!   without its `OFF` line). A UTF-8 byte order mark at the start is skipped.
//! * After a face's `n` indices up to four colour values may follow (ignored).
//! * Polygons with more than three corners are triangulated without overlaps, as in OBJ.
//! * Indices are 0-based; data after the announced faces is an error.

use std::io::{self, Read, Write};

use envelope_mesh::TriangleSoup;

use crate::build::{Faces, check_vertex_count, checked_position, finish, vertex_index};
use crate::error::{ReadError, ReadErrorKind, Word};
use crate::input::{Input, Lines, parse_f64, parse_i64, parse_u64};
use crate::{Format, ReadReport};

/// What an OFF-family keyword `[ST][C][N][4][n]OFF` announces.
enum Keyword {
    /// Vertices of three coordinates (the prefixes only add columns after them).
    Xyz,
    /// `nOFF`: the dimension comes before the counts.
    Dimension,
}

/// Checks an OFF-family keyword.
fn check_keyword(kw: &[u8]) -> Result<Keyword, ReadErrorKind> {
    let mut s = kw;
    for prefix in [&b"ST"[..], b"C", b"N"] {
        s = s.strip_prefix(prefix).unwrap_or(s);
    }
    match s {
        b"OFF" => Ok(Keyword::Xyz),
        b"nOFF" => Ok(Keyword::Dimension),
        b"4OFF" | b"4nOFF" => Err(ReadErrorKind::Unsupported(
            "4OFF: homogeneous coordinates (x y z w); only 3-D OFF is read",
        )),
        _ => Err(ReadErrorKind::NotOffKeyword {
            found: Word::new(kw),
        }),
    }
}

/// Numbers from the rest of the current line, or from the next non-blank line when it has none.
fn header_numbers<R: Read>(
    lines: &mut Lines<R>,
    rest: Vec<u64>,
    expected: &'static str,
) -> Result<Vec<u64>, ReadError> {
    if !rest.is_empty() {
        return Ok(rest);
    }
    if !lines.next_nonblank()? {
        return Err(lines.error(ReadErrorKind::Truncated { expected }));
    }
    lines
        .tokens()
        .map(|t| parse_u64(t).ok_or_else(|| lines.error(ReadErrorKind::MalformedNumber)))
        .collect()
}

pub(crate) fn read<R: Read>(input: Input<R>) -> Result<(TriangleSoup, ReadReport), ReadError> {
    let mut lines = Lines::new(input, Some(b'#'));
    let mut report = ReadReport::new(Format::Off);
    if !lines.next_nonblank()? {
        return Err(lines.error(ReadErrorKind::Truncated {
            expected: "OFF header",
        }));
    }
    let keyword;
    let mut rest: Vec<u64> = Vec::new();
    {
        let mut t = lines.tokens();
        let kw = t.next().unwrap_or_default();
        keyword = check_keyword(kw).map_err(|k| lines.error(k))?;
        let words: Vec<&[u8]> = t.collect();
        if words
            .first()
            .is_some_and(|t| t.eq_ignore_ascii_case(b"BINARY"))
        {
            return Err(lines.error(ReadErrorKind::Unsupported("binary OFF")));
        }
        for w in words {
            let n = parse_u64(w).ok_or_else(|| {
                lines.error(ReadErrorKind::UnsupportedStatement {
                    keyword: Word::new(w),
                    why: "unknown word on the OFF line; allowed after the keyword: BINARY \
                          (refused) or the counts",
                })
            })?;
            rest.push(n);
        }
    }
    if let Keyword::Dimension = keyword {
        let mut dim = header_numbers(&mut lines, rest, "nOFF dimension")?;
        if dim.first() != Some(&3) {
            return Err(lines.error(ReadErrorKind::Unsupported(
                "nOFF with a dimension other than 3; only 3-D vertices are read",
            )));
        }
        dim.remove(0);
        rest = dim;
    }
    let toks = header_numbers(&mut lines, rest, "counts line")?;
    let (nv, nf) = match toks[..] {
        [v, f] | [v, f, _] => (v, f),
        _ => {
            return Err(lines.error(ReadErrorKind::BadHeader(
                "the counts line must be: vertices faces [edges]",
            )));
        }
    };
    check_vertex_count(nv).map_err(|k| lines.error(k))?;
    if nf == 0 {
        return Err(lines.error(ReadErrorKind::NoFaces));
    }
    let mut positions = Vec::with_capacity(lines.input.reservation(nv, 6));
    let mut faces = Faces::new();
    faces.reserve(lines.input.reservation(nf, 8));
    let mut extra_vertex_columns = 0u64;
    for v in 0..nv {
        if !lines.next_nonblank()? {
            return Err(lines.error(ReadErrorKind::Truncated {
                expected: "vertex line",
            }));
        }
        let err = |k| lines.error(k);
        let mut p = [0.0; 3];
        let mut t = lines.tokens();
        for (i, c) in p.iter_mut().enumerate() {
            let tok = t.next().ok_or_else(|| {
                err(ReadErrorKind::WrongValueCount {
                    expected: 3,
                    found: i as u64,
                })
            })?;
            *c = parse_f64(tok).ok_or_else(|| err(ReadErrorKind::MalformedNumber))?;
        }
        if t.next().is_some() {
            extra_vertex_columns += 1;
        }
        positions.push(checked_position(p, v).map_err(err)?);
    }
    let mut poly = Vec::new();
    let mut coloured = 0u64;
    for f in 0..nf {
        if !lines.next_nonblank()? {
            return Err(lines.error(ReadErrorKind::Truncated {
                expected: "face line",
            }));
        }
        let err = |k| lines.error(k);
        let mut t = lines.tokens();
        let n = parse_u64(t.next().unwrap_or_default())
            .ok_or_else(|| err(ReadErrorKind::MalformedNumber))?;
        poly.clear();
        let skip = usize::try_from(n).unwrap_or(usize::MAX).saturating_add(1);
        for tok in t.by_ref().take(skip - 1) {
            let i = parse_i64(tok).ok_or_else(|| err(ReadErrorKind::MalformedNumber))?;
            poly.push(vertex_index(i, nv, "face", f).map_err(err)?);
        }
        if (poly.len() as u64) < n {
            return Err(err(ReadErrorKind::WrongValueCount {
                expected: n.saturating_add(1),
                found: poly.len() as u64 + 1,
            }));
        }
        // At most four colour values (a colour-map index, RGB or RGBA) may follow.
        let mut extra = 0u64;
        for tok in t {
            parse_f64(tok).ok_or_else(|| err(ReadErrorKind::MalformedNumber))?;
            extra += 1;
        }
        if extra > 4 {
            return Err(err(ReadErrorKind::WrongValueCount {
                expected: n.saturating_add(1),
                found: n + 1 + extra,
            }));
        }
        if extra > 0 {
            coloured += 1;
        }
        let at = lines.location();
        faces.push_polygon(&poly, f, at, &mut report).map_err(err)?;
    }
    if lines.next_nonblank()? {
        return Err(lines.error(ReadErrorKind::TrailingData));
    }
    if extra_vertex_columns > 0 {
        report.note(format!(
            "{extra_vertex_columns} vertex lines had columns after x y z (colour/normal/texture, ignored)"
        ));
    }
    if coloured > 0 {
        report.note(format!("{coloured} faces had colour values (ignored)"));
    }
    let faces = faces.resolve(&positions)?;
    let loc = lines.location();
    finish(positions, faces, report).map_err(|k| ReadError::new(loc, k))
}

pub(crate) fn write<W: Write>(w: &mut W, soup: &TriangleSoup) -> io::Result<()> {
    writeln!(w, "OFF\n{} {} 0", soup.num_vertices(), soup.num_faces())?;
    for p in &soup.positions {
        writeln!(w, "{:?} {:?} {:?}", p.x, p.y, p.z)?;
    }
    for f in &soup.faces {
        writeln!(w, "3 {} {} {}", f[0].0, f[1].0, f[2].0)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Axis, Location, read};
    use envelope_mesh::CoordError;

    fn off(s: &str) -> Result<(TriangleSoup, ReadReport), ReadError> {
        read(s.as_bytes(), Format::Off)
    }

    fn kind(s: &str) -> ReadErrorKind {
        off(s).unwrap_err().kind
    }

    #[test]
    fn quad_and_triangle_with_comments_and_colours() {
        let (soup, report) = off(concat!(
            "OFF # header\n",
            "# comment\n",
            "\n",
            "5 2 0\n",
            "0 0 0\n1 0 0\n1 1 0\n0 1 0\n",
            "0 0 1 # apex\n",
            "4 0 1 2 3 255 0 0\n",
            "3 0 1 4\n",
        ))
        .unwrap();
        assert_eq!(soup.num_vertices(), 5);
        assert_eq!(soup.faces.len(), 3);
        assert_eq!(
            soup,
            TriangleSoup::from_raw(
                &[
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 1.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0]
                ],
                &[[0, 1, 2], [0, 2, 3], [0, 1, 4]]
            )
        );
        assert_eq!(report.polygons_triangulated, 1);
        assert!(report.notes.iter().any(|n| n.contains("colour")));
    }

    #[test]
    fn variants() {
        let noff = "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
        assert_eq!(off(noff).unwrap().0.num_faces(), 1);
        let coff = "COFF 3 1\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n";
        assert_eq!(off(coff).unwrap().0.num_faces(), 1);
        assert!(matches!(
            kind("4OFF\n1 1 0\n"),
            ReadErrorKind::Unsupported(_)
        ));
        assert!(matches!(
            kind("nOFF\n4\n1 1 0\n"),
            ReadErrorKind::Unsupported(_)
        ));
        assert!(matches!(
            kind("OFF BINARY\n"),
            ReadErrorKind::Unsupported(_)
        ));
        assert_eq!(
            kind("PLY\n"),
            ReadErrorKind::NotOffKeyword {
                found: Word::new(b"PLY")
            }
        );
    }

    #[test]
    fn bad_inputs() {
        let tri = |v: &str, f: &str| format!("OFF\n3 1 0\n0 0 0\n{v}\n0 1 0\n{f}\n");
        assert_eq!(
            kind(&tri("1 0 -inf", "3 0 1 2")),
            ReadErrorKind::Coordinate {
                vertex: 1,
                axis: Axis::Z,
                error: CoordError::Infinite
            }
        );
        assert_eq!(
            kind(&tri("1e-200 0 0", "3 0 1 2")),
            ReadErrorKind::Coordinate {
                vertex: 1,
                axis: Axis::X,
                error: CoordError::TooSmall
            }
        );
        assert_eq!(
            kind(&tri("1 0", "3 0 1 2")),
            ReadErrorKind::WrongValueCount {
                expected: 3,
                found: 2
            }
        );
        assert_eq!(
            kind(&tri("1 0 z", "3 0 1 2")),
            ReadErrorKind::MalformedNumber
        );
        assert_eq!(
            kind(&tri("1 0 0", "3 0 1 3")),
            ReadErrorKind::IndexOutOfRange {
                what: "face",
                element: 0,
                index: 3,
                vertices: 3
            }
        );
        assert_eq!(
            kind(&tri("1 0 0", "3 0 -1 2")),
            ReadErrorKind::IndexOutOfRange {
                what: "face",
                element: 0,
                index: -1,
                vertices: 3
            }
        );
        assert_eq!(
            kind(&tri("1 0 0", "3 0 1")),
            ReadErrorKind::WrongValueCount {
                expected: 4,
                found: 3
            }
        );
        assert_eq!(
            kind(&tri("1 0 0", "2 0 1")),
            ReadErrorKind::TooFewCorners {
                face: 0,
                corners: 2
            }
        );
        assert_eq!(
            kind(&tri("1 0 0", "3 0 1 2 1 1 1 1 1")),
            ReadErrorKind::WrongValueCount {
                expected: 4,
                found: 9
            }
        );
        assert_eq!(
            kind(&tri("1 0 0", "3 0 1 2 red")),
            ReadErrorKind::MalformedNumber
        );
        assert_eq!(
            kind(&tri("1 0 0", "3 0 1 2.5")),
            ReadErrorKind::MalformedNumber
        );
        // Too many items: data after the announced faces.
        assert_eq!(
            kind(&tri("1 0 0", "3 0 1 2\n3 0 1 2")),
            ReadErrorKind::TrailingData
        );
        // Too few items.
        assert_eq!(
            kind("OFF\n3 1 0\n0 0 0\n1 0 0\n"),
            ReadErrorKind::Truncated {
                expected: "vertex line"
            }
        );
        assert_eq!(
            kind("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            ReadErrorKind::Truncated {
                expected: "face line"
            }
        );
        assert_eq!(
            kind("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"),
            ReadErrorKind::NoFaces
        );
        assert!(matches!(kind("OFF\n3\n"), ReadErrorKind::BadHeader(_)));
        assert_eq!(kind("OFF\n3 x 0\n"), ReadErrorKind::MalformedNumber);
        assert_eq!(
            kind(""),
            ReadErrorKind::Truncated {
                expected: "OFF header"
            }
        );
        assert_eq!(
            kind("OFF\n"),
            ReadErrorKind::Truncated {
                expected: "counts line"
            }
        );
        assert_eq!(
            kind("OFF\n5000000000 1 0\n"),
            ReadErrorKind::TooMany("vertices")
        );
        assert!(matches!(
            read(&[0x4f, 0x46, 0x46, 0xff, 0xfe][..], Format::Off)
                .unwrap_err()
                .kind,
            ReadErrorKind::NotOffKeyword { .. }
        ));
    }

    #[test]
    fn error_names_the_line() {
        let e = off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n").unwrap_err();
        assert_eq!(e.location, Location::Line(6));
        assert!(
            e.to_string()
                .starts_with("<input>: line 6: face 0: vertex index 7"),
            "{e}"
        );
    }
}
