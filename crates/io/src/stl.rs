//! STL, ascii and binary, with vertex welding.
//!
//! * Encoding: a file is ascii when it starts with `solid` and its first 512 bytes are text
//!   mentioning `facet` or `endsolid`; otherwise it is binary (many binary files start their
//!   80-byte header with `solid` too). A binary file must then have exactly the size
//!   `84 + 50 * count` its header announces ([`Format::sniff`](crate::Format::sniff) uses the
//!   same formula to recognise binary STL without an extension).
//! * Values are `f32` (ascii numbers are parsed as `f32`), converted exactly to `f64`.
//! * Welding: corners with equal positions become one vertex (bitwise-equal `f32` triples,
//!   with `-0` read as `+0`), numbered in order of first appearance. Facet normals are ignored.
//! * A coordinate error names vertex `3 * facet + corner` (file order, before welding).
//! * Ascii files may hold several `solid ... endsolid` blocks, and start with a UTF-8 byte
//!   order mark (skipped). Any other keyword refuses the file.

use std::collections::HashMap;
use std::io::{Read, Write};

use envelope_mesh::{TriangleSoup, VertexId};
use glam::DVec3;

use crate::build::{checked_position, finish};
use crate::error::{Location, ReadError, ReadErrorKind, WriteError, WriteErrorKind};
use crate::input::{Input, Lines, Tokens, io_error, parse_f32, strip_bom};
use crate::{Format, ReadReport, StlEncoding};

/// The size a binary STL with this header must have (`head` holds at least 84 bytes).
pub(crate) fn binary_size(head: &[u8]) -> u64 {
    let n = u32::from_le_bytes([head[80], head[81], head[82], head[83]]);
    84 + 50 * u64::from(n)
}

pub(crate) fn looks_ascii(head: &[u8]) -> bool {
    let head = strip_bom(head);
    let printable = head
        .iter()
        .all(|&b| b.is_ascii_graphic() || b.is_ascii_whitespace());
    let lower = head.to_ascii_lowercase();
    let has = |w: &[u8]| lower.windows(w.len()).any(|x| x == w);
    printable && (has(b"facet") || has(b"endsolid"))
}

struct Welder {
    map: HashMap<[u32; 3], u32>,
    positions: Vec<DVec3>,
    faces: Vec<[VertexId; 3]>,
    welded: u64,
}

impl Welder {
    fn new(capacity: usize) -> Self {
        Self {
            map: HashMap::with_capacity(capacity / 2),
            positions: Vec::with_capacity(capacity / 2),
            faces: Vec::with_capacity(capacity),
            welded: 0,
        }
    }

    /// Adds one facet; `first_vertex` numbers its first corner in file order.
    fn facet(&mut self, corners: [[f32; 3]; 3], first_vertex: u64) -> Result<(), ReadErrorKind> {
        let mut face = [VertexId(0); 3];
        for (c, p) in corners.into_iter().enumerate() {
            // `x + 0.0` turns -0 into +0 and leaves everything else unchanged.
            let p = p.map(|x| x + 0.0);
            let key = p.map(f32::to_bits);
            let id = match self.map.get(&key) {
                Some(&id) => {
                    self.welded += 1;
                    id
                }
                None => {
                    let pos = checked_position(p.map(f64::from), first_vertex + c as u64)?;
                    let id = u32::try_from(self.positions.len())
                        .ok()
                        .filter(|&i| i < u32::MAX)
                        .ok_or(ReadErrorKind::TooMany("vertices"))?;
                    self.positions.push(pos);
                    self.map.insert(key, id);
                    id
                }
            };
            face[c] = VertexId(id);
        }
        self.faces.push(face);
        Ok(())
    }

    fn finish(
        self,
        encoding: StlEncoding,
        loc: Location,
    ) -> Result<(TriangleSoup, ReadReport), ReadError> {
        let mut report = ReadReport::new(Format::Stl(encoding));
        report.stl_corners_welded = self.welded;
        finish(self.positions, self.faces, report).map_err(|k| ReadError::new(loc, k))
    }
}

pub(crate) fn read<R: Read>(mut input: Input<R>) -> Result<(TriangleSoup, ReadReport), ReadError> {
    let head = input
        .peek(512)
        .map_err(|e| io_error(&e, Location::Byte(0)))?;
    let text = strip_bom(head).trim_ascii_start();
    let solid = text.len() >= 5 && text[..5].eq_ignore_ascii_case(b"solid");
    if solid && looks_ascii(head) {
        read_ascii(input)
    } else {
        read_binary(input)
    }
}

fn read_binary<R: Read>(mut input: Input<R>) -> Result<(TriangleSoup, ReadReport), ReadError> {
    let at = |o: u64, k| ReadError::new(Location::Byte(o), k);
    let n = match input
        .take(84)
        .map_err(|e| io_error(&e, Location::Byte(0)))?
    {
        Some(h) => u32::from_le_bytes([h[80], h[81], h[82], h[83]]),
        None => {
            return Err(at(
                0,
                ReadErrorKind::Truncated {
                    expected: "84-byte binary STL header",
                },
            ));
        }
    };
    let need = 50 * u64::from(n);
    match input.remaining() {
        Some(r) if r < need => {
            return Err(at(
                84 + r - r % 50,
                ReadErrorKind::Truncated {
                    expected: "facet record",
                },
            ));
        }
        Some(r) if r > need => return Err(at(84 + need, ReadErrorKind::TrailingData)),
        _ => {}
    }
    let mut w = Welder::new(input.reservation(u64::from(n), 50));
    for f in 0..u64::from(n) {
        let offset = input.offset();
        let rec = match input
            .take(50)
            .map_err(|e| io_error(&e, Location::Byte(offset)))?
        {
            Some(r) => r,
            None => {
                return Err(at(
                    offset,
                    ReadErrorKind::Truncated {
                        expected: "facet record",
                    },
                ));
            }
        };
        let mut corners = [[0f32; 3]; 3];
        for (c, corner) in corners.iter_mut().enumerate() {
            for (k, x) in corner.iter_mut().enumerate() {
                let o = 12 + 12 * c + 4 * k;
                *x = f32::from_le_bytes([rec[o], rec[o + 1], rec[o + 2], rec[o + 3]]);
            }
        }
        w.facet(corners, 3 * f).map_err(|k| at(offset, k))?;
    }
    let end = input.offset();
    if !input
        .at_eof()
        .map_err(|e| io_error(&e, Location::Byte(end)))?
    {
        return Err(at(end, ReadErrorKind::TrailingData));
    }
    w.finish(StlEncoding::Binary, Location::Byte(end))
}

fn read_ascii<R: Read>(input: Input<R>) -> Result<(TriangleSoup, ReadReport), ReadError> {
    let mut t = Tokens::new(Lines::new(input, None));
    t.expect_keyword("solid")?;
    t.skip_rest_of_line();
    let mut w = Welder::new(0);
    let mut f = 0u64;
    loop {
        let Some(tok) = t.next()? else {
            return Err(t.error(ReadErrorKind::Truncated {
                expected: "endsolid",
            }));
        };
        if tok.eq_ignore_ascii_case(b"endsolid") {
            t.skip_rest_of_line();
            match t.next()? {
                None => break,
                Some(s) if s.eq_ignore_ascii_case(b"solid") => {
                    t.skip_rest_of_line();
                    continue;
                }
                Some(_) => return Err(t.error(ReadErrorKind::TrailingData)),
            }
        }
        if !tok.eq_ignore_ascii_case(b"facet") {
            return Err(t.error(ReadErrorKind::Unexpected {
                expected: "facet or endsolid",
            }));
        }
        t.expect_keyword("normal")?;
        for _ in 0..3 {
            t.number("normal component", parse_f32)?;
        }
        t.expect_keyword("outer")?;
        t.expect_keyword("loop")?;
        let mut corners = [[0f32; 3]; 3];
        for corner in &mut corners {
            t.expect_keyword("vertex")?;
            for x in corner.iter_mut() {
                *x = t.number("vertex coordinate", parse_f32)?;
            }
        }
        t.expect_keyword("endloop")?;
        t.expect_keyword("endfacet")?;
        w.facet(corners, 3 * f).map_err(|k| t.error(k))?;
        f += 1;
    }
    let loc = t.lines.location();
    w.finish(StlEncoding::Ascii, loc)
}

/// The facet normal of the f32-rounded corners (an inexact f64 construction; zero when
/// degenerate). Readers ignore it.
fn normal(t: [[f32; 3]; 3]) -> [f32; 3] {
    let [a, b, c] = t.map(|p| DVec3::from_array(p.map(f64::from)));
    let n = (b - a).cross(c - a).normalize_or_zero();
    n.to_array().map(|x| x as f32)
}

pub(crate) fn write<W: Write>(
    w: &mut W,
    soup: &TriangleSoup,
    encoding: StlEncoding,
) -> Result<(), WriteError> {
    let tri = |f: &[VertexId; 3]| f.map(|v| soup.positions[v.index()].to_array().map(|x| x as f32));
    match encoding {
        StlEncoding::Ascii => {
            writeln!(w, "solid envelope")?;
            for f in &soup.faces {
                let t = tri(f);
                let n = normal(t);
                writeln!(
                    w,
                    "  facet normal {:?} {:?} {:?}\n    outer loop",
                    n[0], n[1], n[2]
                )?;
                for p in t {
                    writeln!(w, "      vertex {:?} {:?} {:?}", p[0], p[1], p[2])?;
                }
                writeln!(w, "    endloop\n  endfacet")?;
            }
            writeln!(w, "endsolid envelope")?;
        }
        StlEncoding::Binary => {
            let n = u32::try_from(soup.faces.len()).map_err(|_| WriteErrorKind::TooManyFaces)?;
            let mut header = [0u8; 84];
            let title = b"binary STL written by envelope-io";
            header[..title.len()].copy_from_slice(title);
            header[80..].copy_from_slice(&n.to_le_bytes());
            w.write_all(&header)?;
            let mut rec = [0u8; 50];
            for f in &soup.faces {
                let t = tri(f);
                for (k, v) in std::iter::once(normal(t)).chain(t).enumerate() {
                    for (j, x) in v.into_iter().enumerate() {
                        let o = 12 * k + 4 * j;
                        rec[o..o + 4].copy_from_slice(&x.to_le_bytes());
                    }
                }
                w.write_all(&rec)?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Axis, read};
    use envelope_mesh::CoordError;

    fn stl(bytes: &[u8]) -> Result<(TriangleSoup, ReadReport), ReadError> {
        read(bytes, Format::Stl(StlEncoding::Binary))
    }

    fn kind(bytes: &[u8]) -> ReadErrorKind {
        stl(bytes).unwrap_err().kind
    }

    /// A binary file with `header` (padded to 80 bytes), `count` and the facets' corners.
    fn binary(header: &[u8], count: u32, facets: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut out = header.to_vec();
        out.resize(80, b' ');
        out.extend(count.to_le_bytes());
        for f in facets {
            out.extend([0u8; 12]);
            out.extend(f.iter().flatten().flat_map(|x| x.to_le_bytes()));
            out.extend([0u8; 2]);
        }
        out
    }

    const TWO: [[[f32; 3]; 3]; 2] = [
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, -0.0]],
    ];

    fn expected() -> TriangleSoup {
        TriangleSoup::from_raw(
            &[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [1.0, 1.0, 0.0],
            ],
            &[[0, 1, 2], [1, 3, 2]],
        )
    }

    #[test]
    fn ascii_welds_and_allows_several_solids() {
        let text = "solid two\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n\
            vertex 0 1 0\n  endloop\n endfacet\nendsolid two\nSOLID more\nFACET NORMAL 0 0 1e-3\n\
            OUTER LOOP\nVERTEX 1 0 0\nVERTEX 1 1 0\nVERTEX 0 1 -0\nENDLOOP\nENDFACET\nENDSOLID\n";
        let (soup, report) = stl(text.as_bytes()).unwrap();
        assert_eq!(soup, expected());
        assert_eq!(soup.positions[2].z.to_bits(), 0, "-0 is welded to +0");
        assert_eq!(report.stl_corners_welded, 2);
        assert_eq!(report.format, Format::Stl(StlEncoding::Ascii));
    }

    #[test]
    fn binary_with_solid_header() {
        for header in [&b"solid but binary"[..], b"exported"] {
            let (soup, report) = stl(&binary(header, 2, &TWO)).unwrap();
            assert_eq!(soup, expected());
            assert_eq!(report.format, Format::Stl(StlEncoding::Binary));
        }
    }

    #[test]
    fn binary_bad_inputs() {
        let mut bad = TWO;
        bad[1][2][0] = f32::INFINITY;
        assert_eq!(
            kind(&binary(b"x", 2, &bad)),
            ReadErrorKind::Coordinate {
                vertex: 5,
                axis: Axis::X,
                error: CoordError::Infinite
            }
        );
        bad[1][2][0] = 1e-38;
        assert_eq!(
            kind(&binary(b"x", 2, &bad)),
            ReadErrorKind::Coordinate {
                vertex: 5,
                axis: Axis::X,
                error: CoordError::TooSmall
            }
        );
        let e = stl(&binary(b"x", 3, &TWO)).unwrap_err();
        assert_eq!(
            e.kind,
            ReadErrorKind::Truncated {
                expected: "facet record"
            }
        );
        assert_eq!(
            e.to_string(),
            "<input>: byte 184: file ends early: expected facet record"
        );
        assert_eq!(kind(&binary(b"x", 1, &TWO)), ReadErrorKind::TrailingData);
        assert_eq!(kind(&binary(b"x", 0, &[])), ReadErrorKind::NoFaces);
        assert!(matches!(kind(b"short"), ReadErrorKind::Truncated { .. }));
        assert!(matches!(kind(&[0xde; 83]), ReadErrorKind::Truncated { .. }));
        // A huge announced count in a tiny input fails fast.
        assert!(matches!(
            kind(&binary(b"x", u32::MAX, &TWO)),
            ReadErrorKind::Truncated { .. }
        ));
    }

    #[test]
    fn ascii_bad_inputs() {
        let facet = |v: &str| {
            format!(
                "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n{v}\n\
                 endloop\nendfacet\nendsolid s\n"
            )
        };
        assert_eq!(
            kind(facet("vertex 0 nan 0").as_bytes()),
            ReadErrorKind::Coordinate {
                vertex: 2,
                axis: Axis::Y,
                error: CoordError::NaN
            }
        );
        assert_eq!(
            kind(facet("vertex 0 1 0.0.0").as_bytes()),
            ReadErrorKind::MalformedNumber
        );
        assert_eq!(
            kind(facet("vertex 0 1").as_bytes()),
            ReadErrorKind::MalformedNumber
        );
        assert_eq!(
            kind(facet("vertx 0 1 0").as_bytes()),
            ReadErrorKind::Unexpected { expected: "vertex" }
        );
        assert_eq!(
            kind(facet("vertex 0 1 0\nvertex 0 1 0").as_bytes()),
            ReadErrorKind::Unexpected {
                expected: "endloop"
            }
        );
        let ok = facet("vertex 0 1 0");
        assert_eq!(
            kind(ok.replace("endsolid s\n", "").as_bytes()),
            ReadErrorKind::Truncated {
                expected: "endsolid"
            }
        );
        assert!(matches!(
            kind(&ok.as_bytes()[..ok.len() - 30]),
            ReadErrorKind::Truncated { .. }
        ));
        assert_eq!(
            kind(format!("{ok}junk\n").as_bytes()),
            ReadErrorKind::TrailingData
        );
        assert_eq!(
            kind(b"solid empty\nendsolid empty\n"),
            ReadErrorKind::NoFaces
        );
        let e = stl(facet("vertex 0 1 x").as_bytes()).unwrap_err();
        assert_eq!(e.to_string(), "<input>: line 6: malformed number");
    }
}
