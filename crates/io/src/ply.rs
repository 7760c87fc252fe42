//! Stanford PLY in all three encodings (`ascii`, `binary_little_endian`,
//! `binary_big_endian`).
//!
//! * Elements and properties may come in any order and with any scalar type (`char uchar
//!   short ushort int uint float double` and the `int8 ... float64` aliases); lists may use
//!   any integer count type and any item type. Unknown elements and properties are skipped
//!   (and named in the report): the header defines their layout, and only the `vertex`,
//!   `face` and `tristrips` elements can define the mesh. An element declaring a property
//!   twice, or a face element with both `vertex_indices` and `vertex_index`, is refused (the
//!   reader would have to guess which one holds the data). `comment` and `obj_info` lines are
//!   ignored; any other header keyword is refused. A UTF-8 byte order mark before `ply` is
//!   skipped.
//! * Vertices come from the `vertex` element's `x`, `y`, `z` properties; faces from the
//!   `face` element's `vertex_indices` (or `vertex_index`) list, polygons triangulated
//!   without overlaps as in OBJ; strips from the `tristrips` element's `vertex_indices` list, where `-1`
//!   restarts a strip, windings alternate, and triangles with a repeated corner are dropped.
//! * With attributes ([`crate::read_with_attributes`]): the vertex properties `u v` (or `s t`,
//!   `texture_u texture_v`, `texture_s texture_t`), `nx ny nz` and `red green blue [alpha]`,
//!   each used only when all its components are scalars; integer colours are divided by their
//!   type's maximum (`uchar` by 255, exactly rounded), float colours kept as written, alpha 1
//!   when absent; and the scalar `quality` (any type, kept as written: an error map's bounds).
//!   A corner's value is its vertex's. Face-level `texcoord` lists are not read.
//! * Every value is read as declared: a `float` coordinate written in ascii is rounded to
//!   `f32`, exactly as its binary encoding would be.
//! * Before any data is read, the header's counts are checked against the remaining file size
//!   (when known), so a header announcing billions of elements in a small file fails at once.
//! * Data after the last announced element is an error.

use std::io::Read;

use envelope_mesh::{Attributes, TriangleSoup, VertexId, Wedges};

use crate::build::{Faces, check_vertex_count, checked_position, finish, vertex_index};
use crate::error::{Location, ReadError, ReadErrorKind};
use crate::input::{Input, Lines, Tokens, io_error, parse_f32, parse_f64, parse_i64, parse_u64};
use crate::{Format, PlyEncoding, ReadReport};

pub(crate) use crate::ply_write::{write, write_with_attributes};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn from_name(name: &[u8]) -> Option<Self> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_int(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
struct Property {
    name: Vec<u8>,
    kind: Kind,
}

#[derive(Debug)]
struct Element {
    name: Vec<u8>,
    count: u64,
    props: Vec<Property>,
}

impl Element {
    fn find(&self, names: &[&[u8]]) -> Option<usize> {
        self.props
            .iter()
            .position(|p| names.contains(&p.name.as_slice()))
    }

    /// Smallest possible encoded size of one item.
    fn min_bytes(&self, encoding: PlyEncoding) -> u64 {
        self.props
            .iter()
            .map(|p| match (encoding, p.kind) {
                (PlyEncoding::Ascii, _) => 1,
                (_, Kind::Scalar(s)) | (_, Kind::List { count: s, .. }) => s.size() as u64,
            })
            .sum()
    }
}

struct Header {
    encoding: PlyEncoding,
    elements: Vec<Element>,
}

fn bad(lines: &Lines<impl Read>, what: &'static str) -> ReadError {
    lines.error(ReadErrorKind::BadHeader(what))
}

fn read_header<R: Read>(lines: &mut Lines<R>) -> Result<Header, ReadError> {
    if !lines.next()? || lines.line.trim_ascii() != b"ply" {
        return Err(bad(lines, "the first line must be 'ply'"));
    }
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        if !lines.next()? {
            return Err(lines.error(ReadErrorKind::Truncated {
                expected: "end_header",
            }));
        }
        let t: Vec<&[u8]> = lines.tokens().collect();
        match t.as_slice() {
            [] | [b"comment", ..] | [b"obj_info", ..] => {}
            [b"format", enc, version] => {
                encoding = Some(match *enc {
                    b"ascii" => PlyEncoding::Ascii,
                    b"binary_little_endian" => PlyEncoding::BinaryLittleEndian,
                    b"binary_big_endian" => PlyEncoding::BinaryBigEndian,
                    _ => return Err(lines.error(ReadErrorKind::Unsupported("PLY encoding"))),
                });
                if !version.starts_with(b"1") {
                    return Err(lines.error(ReadErrorKind::Unsupported("PLY version")));
                }
            }
            [b"element", name, count] => {
                let count =
                    parse_u64(count).ok_or_else(|| lines.error(ReadErrorKind::MalformedNumber))?;
                elements.push(Element {
                    name: name.to_vec(),
                    count,
                    props: Vec::new(),
                });
            }
            [b"property", b"list", count, item, name] => {
                let (Some(count), Some(item)) = (Scalar::from_name(count), Scalar::from_name(item))
                else {
                    return Err(bad(lines, "unknown property type"));
                };
                if !count.is_int() {
                    return Err(bad(lines, "list count type must be an integer"));
                }
                let kind = Kind::List { count, item };
                let e = elements
                    .last_mut()
                    .ok_or_else(|| bad(lines, "property before element"))?;
                e.props.push(Property {
                    name: name.to_vec(),
                    kind,
                });
            }
            [b"property", ty, name] => {
                let ty =
                    Scalar::from_name(ty).ok_or_else(|| bad(lines, "unknown property type"))?;
                let e = elements
                    .last_mut()
                    .ok_or_else(|| bad(lines, "property before element"))?;
                e.props.push(Property {
                    name: name.to_vec(),
                    kind: Kind::Scalar(ty),
                });
            }
            [b"end_header"] => break,
            [b"format", ..] | [b"element", ..] | [b"property", ..] => {
                return Err(bad(lines, "malformed format, element or property line"));
            }
            _ => return Err(bad(lines, "unknown header keyword")),
        }
    }
    let encoding = encoding.ok_or_else(|| bad(lines, "no format line"))?;
    Ok(Header { encoding, elements })
}

/// The vertex element's attribute properties (indices into its properties), each found only
/// when all its components are scalars.
#[derive(Clone, Copy, Debug, Default)]
struct VertexAttributes {
    uv: Option<[usize; 2]>,
    normal: Option<[usize; 3]>,
    rgb: Option<[usize; 3]>,
    alpha: Option<usize>,
    quality: Option<usize>,
}

/// The texture coordinate spellings, in the order they are looked for.
const UV_NAMES: [[&[u8]; 2]; 4] = [
    [b"u", b"v"],
    [b"s", b"t"],
    [b"texture_u", b"texture_v"],
    [b"texture_s", b"texture_t"],
];

impl VertexAttributes {
    fn find(e: &Element) -> Self {
        let scalars = |names: &[&[u8]]| -> Option<Vec<usize>> {
            names
                .iter()
                .map(|n| {
                    e.find(&[n])
                        .filter(|&i| matches!(e.props[i].kind, Kind::Scalar(_)))
                })
                .collect()
        };
        VertexAttributes {
            uv: UV_NAMES
                .iter()
                .find_map(|names| scalars(names))
                .map(|i| [i[0], i[1]]),
            normal: scalars(&[b"nx", b"ny", b"nz"]).map(|i| [i[0], i[1], i[2]]),
            rgb: scalars(&[b"red", b"green", b"blue"]).map(|i| [i[0], i[1], i[2]]),
            alpha: scalars(&[b"alpha"]).map(|i| i[0]),
            quality: scalars(&[b"quality"]).map(|i| i[0]),
        }
    }

    /// The property indices read.
    fn used(&self) -> Vec<usize> {
        let mut out: Vec<usize> = self.uv.iter().flatten().copied().collect();
        out.extend(self.normal.iter().flatten());
        if let Some(rgb) = self.rgb {
            out.extend(rgb);
            out.extend(self.alpha);
        }
        out.extend(self.quality);
        out
    }
}

/// What the reader does with an element, decided from the header.
enum Role {
    Vertex {
        xyz: [usize; 3],
        attributes: VertexAttributes,
    },
    Faces {
        list: usize,
    },
    Strips {
        list: usize,
    },
    Skip,
}

fn roles<R: Read>(lines: &Lines<R>, h: &Header) -> Result<Vec<Role>, ReadError> {
    let mut seen_vertex = false;
    let mut out = Vec::new();
    for e in &h.elements {
        // Two properties of one name: which one a reader uses is a guess, the data could differ.
        for (i, p) in e.props.iter().enumerate() {
            if e.props[..i].iter().any(|q| q.name == p.name) {
                return Err(bad(lines, "an element declares the same property twice"));
            }
        }
        let index_list = |e: &Element, names: &[&[u8]]| -> Result<Option<usize>, ReadError> {
            if names.iter().filter(|n| e.find(&[n]).is_some()).count() > 1 {
                return Err(bad(
                    lines,
                    "the face element has both vertex_indices and vertex_index lists",
                ));
            }
            match e.find(names) {
                None => Ok(None),
                Some(i) => match e.props[i].kind {
                    Kind::List { item, .. } if item.is_int() => Ok(Some(i)),
                    _ => Err(bad(lines, "vertex index lists must have integer items")),
                },
            }
        };
        out.push(match e.name.as_slice() {
            b"vertex" => {
                if seen_vertex {
                    return Err(bad(lines, "more than one vertex element"));
                }
                seen_vertex = true;
                let mut xyz = [0; 3];
                for (k, name) in [&b"x"[..], b"y", b"z"].into_iter().enumerate() {
                    match e.find(&[name]) {
                        Some(i) if matches!(e.props[i].kind, Kind::Scalar(_)) => xyz[k] = i,
                        _ => return Err(bad(lines, "the vertex element needs scalar x, y, z")),
                    }
                }
                Role::Vertex {
                    xyz,
                    attributes: VertexAttributes::find(e),
                }
            }
            b"face" => match index_list(e, &[b"vertex_indices", b"vertex_index"])? {
                Some(list) => Role::Faces { list },
                None => return Err(bad(lines, "the face element has no vertex_indices list")),
            },
            b"tristrips" => match index_list(e, &[b"vertex_indices"])? {
                Some(list) => Role::Strips { list },
                None => {
                    return Err(bad(
                        lines,
                        "the tristrips element has no vertex_indices list",
                    ));
                }
            },
            _ => Role::Skip,
        });
    }
    if !seen_vertex {
        return Err(bad(lines, "no vertex element"));
    }
    Ok(out)
}

/// Where element values come from: binary records or ascii tokens.
trait Source {
    /// Marks the start of an element item (the place errors point at).
    fn begin_item(&mut self);
    fn error(&self, kind: ReadErrorKind) -> ReadError;
    /// Where the current item is (the place errors point at).
    fn location(&self) -> Location;
    fn float(&mut self, t: Scalar, what: &'static str) -> Result<f64, ReadError>;
    fn int(&mut self, t: Scalar, what: &'static str) -> Result<i64, ReadError>;
    fn skip(&mut self, t: Scalar, n: u64, what: &'static str) -> Result<(), ReadError>;
    fn at_end(&mut self) -> Result<bool, ReadError>;

    fn list_len(&mut self, t: Scalar, what: &'static str) -> Result<u64, ReadError> {
        let n = self.int(t, what)?;
        u64::try_from(n).map_err(|_| {
            self.error(ReadErrorKind::Unexpected {
                expected: "a non-negative list length",
            })
        })
    }

    fn skip_property(&mut self, kind: Kind, what: &'static str) -> Result<(), ReadError> {
        match kind {
            Kind::Scalar(t) => self.skip(t, 1, what),
            Kind::List { count, item } => {
                let n = self.list_len(count, what)?;
                self.skip(item, n, what)
            }
        }
    }
}

struct Binary<'a, R, const BE: bool> {
    input: &'a mut Input<R>,
    item_start: u64,
}

impl<R: Read, const BE: bool> Binary<'_, R, BE> {
    #[inline]
    fn bytes(&mut self, n: usize, what: &'static str) -> Result<&[u8], ReadError> {
        let loc = Location::Byte(self.item_start);
        match self.input.take(n) {
            Ok(Some(b)) => Ok(b),
            Ok(None) => Err(ReadError::new(
                loc,
                ReadErrorKind::Truncated { expected: what },
            )),
            Err(e) => Err(io_error(&e, loc)),
        }
    }
}

macro_rules! word {
    ($b:expr, $n:literal, $be:expr) => {{
        let mut a = [0u8; $n];
        a.copy_from_slice(&$b[..$n]);
        if $be {
            a.reverse()
        }
        a
    }};
}

impl<R: Read, const BE: bool> Source for Binary<'_, R, BE> {
    #[inline]
    fn begin_item(&mut self) {
        self.item_start = self.input.offset();
    }

    fn error(&self, kind: ReadErrorKind) -> ReadError {
        ReadError::new(self.location(), kind)
    }

    fn location(&self) -> Location {
        Location::Byte(self.item_start)
    }

    #[inline]
    fn float(&mut self, t: Scalar, what: &'static str) -> Result<f64, ReadError> {
        if t.is_int() {
            return self.int(t, what).map(|i| i as f64);
        }
        let b = self.bytes(t.size(), what)?;
        Ok(if t == Scalar::F32 {
            f64::from(f32::from_le_bytes(word!(b, 4, BE)))
        } else {
            f64::from_le_bytes(word!(b, 8, BE))
        })
    }

    #[inline]
    fn int(&mut self, t: Scalar, what: &'static str) -> Result<i64, ReadError> {
        let b = self.bytes(t.size(), what)?;
        Ok(match t {
            Scalar::I8 => i64::from(b[0] as i8),
            Scalar::U8 => i64::from(b[0]),
            Scalar::I16 => i64::from(i16::from_le_bytes(word!(b, 2, BE))),
            Scalar::U16 => i64::from(u16::from_le_bytes(word!(b, 2, BE))),
            Scalar::I32 => i64::from(i32::from_le_bytes(word!(b, 4, BE))),
            Scalar::U32 => i64::from(u32::from_le_bytes(word!(b, 4, BE))),
            // Header checks keep floats out of integer places; truncation is never reached.
            Scalar::F32 => f32::from_le_bytes(word!(b, 4, BE)) as i64,
            Scalar::F64 => f64::from_le_bytes(word!(b, 8, BE)) as i64,
        })
    }

    fn skip(&mut self, t: Scalar, n: u64, what: &'static str) -> Result<(), ReadError> {
        let loc = Location::Byte(self.item_start);
        let total = n.checked_mul(t.size() as u64);
        match total.map(|b| self.input.skip(b)) {
            Some(Ok(true)) => Ok(()),
            None | Some(Ok(false)) => Err(ReadError::new(
                loc,
                ReadErrorKind::Truncated { expected: what },
            )),
            Some(Err(e)) => Err(io_error(&e, loc)),
        }
    }

    fn at_end(&mut self) -> Result<bool, ReadError> {
        let loc = self.input.byte_location();
        self.input.at_eof().map_err(|e| io_error(&e, loc))
    }
}

struct Ascii<R> {
    tokens: Tokens<R>,
}

impl<R: Read> Source for Ascii<R> {
    fn begin_item(&mut self) {}

    fn error(&self, kind: ReadErrorKind) -> ReadError {
        self.tokens.error(kind)
    }

    fn location(&self) -> Location {
        self.tokens.lines.location()
    }

    fn float(&mut self, t: Scalar, what: &'static str) -> Result<f64, ReadError> {
        match t {
            Scalar::F32 => self.tokens.number(what, parse_f32).map(f64::from),
            Scalar::F64 => self.tokens.number(what, parse_f64),
            _ => self.int(t, what).map(|i| i as f64),
        }
    }

    fn int(&mut self, _t: Scalar, what: &'static str) -> Result<i64, ReadError> {
        self.tokens.number(what, parse_i64)
    }

    fn skip(&mut self, _t: Scalar, n: u64, what: &'static str) -> Result<(), ReadError> {
        for _ in 0..n {
            self.tokens.number(what, parse_f64)?;
        }
        Ok(())
    }

    fn at_end(&mut self) -> Result<bool, ReadError> {
        Ok(self.tokens.next()?.is_none())
    }
}

pub(crate) fn read<R: Read>(input: Input<R>) -> Result<(TriangleSoup, ReadReport), ReadError> {
    read_impl(input, false).map(|(soup, _, report)| (soup, report))
}

pub(crate) fn read_with_attributes<R: Read>(
    input: Input<R>,
) -> Result<(TriangleSoup, Attributes, ReadReport), ReadError> {
    read_impl(input, true)
}

fn read_impl<R: Read>(
    input: Input<R>,
    with_attributes: bool,
) -> Result<(TriangleSoup, Attributes, ReadReport), ReadError> {
    let mut lines = Lines::new(input, None);
    let header = read_header(&mut lines)?;
    let roles = roles(&lines, &header)?;
    let encoding = header.encoding;
    let mut report = ReadReport::new(Format::Ply(encoding));
    let body_location = match encoding {
        PlyEncoding::Ascii => lines.location(),
        _ => lines.input.byte_location(),
    };
    let min_total = header.elements.iter().fold(0u64, |acc, e| {
        acc.saturating_add(e.count.saturating_mul(e.min_bytes(encoding)))
    });
    if lines.input.remaining().is_some_and(|r| r < min_total) {
        return Err(ReadError::new(
            body_location,
            ReadErrorKind::Truncated {
                expected: "the element data the header announces",
            },
        ));
    }
    let nv = header
        .elements
        .iter()
        .find(|e| e.name == b"vertex")
        .map_or(0, |e| e.count);
    check_vertex_count(nv).map_err(|k| ReadError::new(body_location, k))?;
    let mut out = Output {
        positions: Vec::new(),
        faces: Faces::new(),
        poly: Vec::new(),
        nv,
        report: &mut report,
        with_attributes,
        texcoords: Vec::new(),
        normals: Vec::new(),
        colors: Vec::new(),
        quality: Vec::new(),
    };
    for (e, role) in header.elements.iter().zip(&roles) {
        let min = e.min_bytes(encoding);
        match role {
            Role::Vertex { .. } => {
                out.positions = Vec::with_capacity(lines.input.reservation(e.count, min));
            }
            Role::Faces { .. } => {
                out.faces.reserve(lines.input.reservation(e.count, min));
            }
            _ => {}
        }
    }
    let end_loc = match encoding {
        PlyEncoding::Ascii => {
            let mut src = Ascii {
                tokens: Tokens::new(lines),
            };
            read_elements(&mut src, &header, &roles, &mut out)?;
            src.tokens.lines.location()
        }
        PlyEncoding::BinaryLittleEndian => {
            let mut input = lines.input;
            let mut src = Binary::<R, false> {
                input: &mut input,
                item_start: 0,
            };
            read_elements(&mut src, &header, &roles, &mut out)?;
            input.byte_location()
        }
        PlyEncoding::BinaryBigEndian => {
            let mut input = lines.input;
            let mut src = Binary::<R, true> {
                input: &mut input,
                item_start: 0,
            };
            read_elements(&mut src, &header, &roles, &mut out)?;
            input.byte_location()
        }
    };
    let faces = out.faces.resolve(&out.positions)?;
    let positions = out.positions;
    let found = roles
        .iter()
        .find_map(|r| match r {
            Role::Vertex { attributes, .. } if with_attributes => Some(*attributes),
            _ => None,
        })
        .unwrap_or_default();
    let attributes = Attributes {
        texcoords: found.uv.map(|_| per_vertex(out.texcoords, &faces)),
        normals: found.normal.map(|_| per_vertex(out.normals, &faces)),
        colors: found.rgb.map(|_| per_vertex(out.colors, &faces)),
        quality: found.quality.map(|_| per_vertex(out.quality, &faces)),
    };
    for (e, role) in header.elements.iter().zip(&roles) {
        let name = String::from_utf8_lossy(&e.name);
        let mut vertex_used = Vec::new();
        let used: &[usize] = match role {
            Role::Vertex { xyz, attributes } => {
                vertex_used.extend(xyz);
                if with_attributes {
                    vertex_used.extend(attributes.used());
                }
                &vertex_used
            }
            Role::Faces { list } | Role::Strips { list } => std::slice::from_ref(list),
            Role::Skip => {
                report.note(format!("skipped element '{name}' ({} items)", e.count));
                continue;
            }
        };
        let ignored: Vec<_> = (0..e.props.len())
            .filter(|i| !used.contains(i))
            .map(|i| String::from_utf8_lossy(&e.props[i].name).into_owned())
            .collect();
        if !ignored.is_empty() {
            report.note(format!(
                "ignored '{name}' properties: {}",
                ignored.join(", ")
            ));
        }
    }
    let (soup, report) =
        finish(positions, faces, report).map_err(|k| ReadError::new(end_loc, k))?;
    Ok((soup, attributes, report))
}

/// One value per vertex: a corner's value index is its vertex.
fn per_vertex<const N: usize>(values: Vec<[f64; N]>, faces: &[[VertexId; 3]]) -> Wedges<N> {
    Wedges {
        values,
        corners: faces.iter().map(|f| f.map(|v| v.0)).collect(),
    }
}

struct Output<'a> {
    positions: Vec<glam::DVec3>,
    faces: Faces,
    poly: Vec<u32>,
    nv: u64,
    report: &'a mut ReadReport,
    /// Whether to read the vertex attributes into the four tables below (one per vertex).
    with_attributes: bool,
    texcoords: Vec<[f64; 2]>,
    normals: Vec<[f64; 3]>,
    colors: Vec<[f64; 4]>,
    quality: Vec<[f64; 1]>,
}

fn read_elements<S: Source>(
    src: &mut S,
    header: &Header,
    roles: &[Role],
    out: &mut Output<'_>,
) -> Result<(), ReadError> {
    for (e, role) in header.elements.iter().zip(roles) {
        match *role {
            Role::Vertex { xyz, attributes } => {
                let attributes = if out.with_attributes {
                    attributes
                } else {
                    VertexAttributes::default()
                };
                read_vertices(src, e, xyz, attributes, out)?;
            }
            Role::Faces { list } => read_faces(src, e, list, false, out)?,
            Role::Strips { list } => read_faces(src, e, list, true, out)?,
            // An element without properties occupies no bytes, whatever its count.
            Role::Skip if e.props.is_empty() => {}
            Role::Skip => {
                for _ in 0..e.count {
                    src.begin_item();
                    for p in &e.props {
                        src.skip_property(p.kind, "element data")?;
                    }
                }
            }
        }
    }
    if !src.at_end()? {
        return Err(src.error(ReadErrorKind::TrailingData));
    }
    Ok(())
}

/// Where a vertex property's value goes.
#[derive(Clone, Copy)]
enum Target {
    Position(usize),
    Texcoord(usize),
    Normal(usize),
    Color(usize),
    Quality,
    Skip,
}

/// What an integer colour component is divided by (its type's largest value: `uchar` 255,
/// so 255 is 1 exactly); float components are kept as written.
fn color_scale(t: Scalar) -> f64 {
    match t {
        Scalar::I8 => f64::from(i8::MAX),
        Scalar::U8 => f64::from(u8::MAX),
        Scalar::I16 => f64::from(i16::MAX),
        Scalar::U16 => f64::from(u16::MAX),
        Scalar::I32 => f64::from(i32::MAX),
        Scalar::U32 => f64::from(u32::MAX),
        Scalar::F32 | Scalar::F64 => 1.0,
    }
}

fn read_vertices<S: Source>(
    src: &mut S,
    e: &Element,
    xyz: [usize; 3],
    attributes: VertexAttributes,
    out: &mut Output<'_>,
) -> Result<(), ReadError> {
    const WHAT: &str = "vertex data";
    let mut targets = vec![Target::Skip; e.props.len()];
    for (k, &i) in xyz.iter().enumerate() {
        targets[i] = Target::Position(k);
    }
    for (k, &i) in attributes.uv.iter().flatten().enumerate() {
        targets[i] = Target::Texcoord(k);
    }
    for (k, &i) in attributes.normal.iter().flatten().enumerate() {
        targets[i] = Target::Normal(k);
    }
    if let Some(rgb) = attributes.rgb {
        for (k, &i) in rgb.iter().chain(&attributes.alpha).enumerate() {
            targets[i] = Target::Color(k);
        }
    }
    if let Some(i) = attributes.quality {
        targets[i] = Target::Quality;
    }
    for v in 0..e.count {
        src.begin_item();
        let mut p = [0.0; 3];
        let (mut uv, mut normal, mut color) = ([0.0; 2], [0.0; 3], [0.0, 0.0, 0.0, 1.0]);
        let mut quality = [0.0];
        for (prop, &target) in e.props.iter().zip(&targets) {
            match (prop.kind, target) {
                (Kind::Scalar(t), Target::Position(k)) => p[k] = src.float(t, WHAT)?,
                (Kind::Scalar(t), Target::Texcoord(k)) => uv[k] = src.float(t, WHAT)?,
                (Kind::Scalar(t), Target::Normal(k)) => normal[k] = src.float(t, WHAT)?,
                (Kind::Scalar(t), Target::Color(k)) => {
                    color[k] = src.float(t, WHAT)? / color_scale(t);
                }
                (Kind::Scalar(t), Target::Quality) => quality[0] = src.float(t, WHAT)?,
                (kind, _) => src.skip_property(kind, WHAT)?,
            }
        }
        out.positions
            .push(checked_position(p, v).map_err(|k| src.error(k))?);
        let finite = uv
            .iter()
            .chain(&normal)
            .chain(&color)
            .chain(&quality)
            .all(|x| x.is_finite());
        if !finite {
            return Err(src.error(ReadErrorKind::AttributeValue {
                what: "vertex",
                element: v,
            }));
        }
        if attributes.uv.is_some() {
            out.texcoords.push(uv);
        }
        if attributes.normal.is_some() {
            out.normals.push(normal);
        }
        if attributes.rgb.is_some() {
            out.colors.push(color);
        }
        if attributes.quality.is_some() {
            out.quality.push(quality);
        }
    }
    Ok(())
}

fn read_faces<S: Source>(
    src: &mut S,
    e: &Element,
    list: usize,
    strips: bool,
    out: &mut Output<'_>,
) -> Result<(), ReadError> {
    let what = if strips { "strip data" } else { "face data" };
    let noun = if strips { "strip" } else { "face" };
    for f in 0..e.count {
        src.begin_item();
        for (i, prop) in e.props.iter().enumerate() {
            match prop.kind {
                Kind::List { count, item } if i == list => {
                    let n = src.list_len(count, what)?;
                    out.poly.clear();
                    for _ in 0..n {
                        let index = src.int(item, what)?;
                        if strips && index == -1 {
                            out.faces.push_strip(&out.poly, out.report);
                            out.poly.clear();
                            continue;
                        }
                        let v = vertex_index(index, out.nv, noun, f).map_err(|k| src.error(k))?;
                        out.poly.push(v);
                    }
                    if strips {
                        out.faces.push_strip(&out.poly, out.report);
                    } else {
                        let at = src.location();
                        out.faces
                            .push_polygon(&out.poly, f, at, out.report)
                            .map_err(|k| src.error(k))?;
                    }
                }
                kind => src.skip_property(kind, what)?,
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

    fn ply(bytes: &[u8]) -> Result<(TriangleSoup, ReadReport), ReadError> {
        read(bytes, Format::Ply(PlyEncoding::Ascii))
    }

    fn kind(bytes: &[u8]) -> ReadErrorKind {
        ply(bytes).unwrap_err().kind
    }

    /// A binary file: `ply`, the format line for `be`, then `header` and `data`.
    fn binary(be: bool, header: &str, data: &[u8]) -> Vec<u8> {
        let enc = if be {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        let mut out = format!("ply\nformat {enc} 1.0\n{header}end_header\n").into_bytes();
        out.extend_from_slice(data);
        out
    }

    const ASCII_TRI: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
        property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n\
        end_header\n";

    #[test]
    fn ascii_any_order_unknown_elements_polygons_and_comments() {
        let file = "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info nothing\r\n\
            element material 1\r\nproperty list uchar float coeffs\r\nproperty uchar id\r\n\
            element face 2\r\nproperty uchar flags\r\nproperty list uchar uint vertex_index\r\n\
            element vertex 4\r\nproperty double nx\r\nproperty float z\r\nproperty double y\r\n\
            property double x\r\nend_header\r\n\
            2 0.5 0.25 7\r\n0 3 0 1 2\r\n1 4 0 1 2 3\r\n\
            9 0 0 0\n9 0 0 1\n9 0 1 1\n9 0 1 0\n";
        let (soup, report) = ply(file.as_bytes()).unwrap();
        assert_eq!(
            soup,
            TriangleSoup::from_raw(
                &[
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 1.0, 0.0],
                    [0.0, 1.0, 0.0]
                ],
                &[[0, 1, 2], [0, 1, 2], [0, 2, 3]]
            )
        );
        assert_eq!(
            (report.polygons_triangulated, report.triangles_from_polygons),
            (1, 2)
        );
        assert!(
            report
                .notes
                .iter()
                .any(|n| n.contains("skipped element 'material'"))
        );
        assert!(
            report
                .notes
                .iter()
                .any(|n| n.contains("'vertex' properties: nx"))
        );
        assert!(
            report
                .notes
                .iter()
                .any(|n| n.contains("'face' properties: flags"))
        );
    }

    #[test]
    fn ascii_float_values_are_rounded_to_f32() {
        let file = format!("{ASCII_TRI}0.1 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        let (soup, _) = ply(file.as_bytes()).unwrap();
        assert_eq!(soup.positions[0].x, f64::from(0.1f32));
    }

    #[test]
    fn tristrips_restart_alternate_and_drop_degenerates() {
        let file = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n\
            property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n\
            0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 2 0\n1 2 0\n\
            10 0 1 2 3 3 4 -1 3 4 5\n";
        let (soup, report) = ply(file.as_bytes()).unwrap();
        // Strip 0 1 2 3 3 4: (0 1 2) (2 1 3) (2 3 3)x (3 3 4)x; strip 3 4 5: (3 4 5).
        assert_eq!(
            soup.faces,
            TriangleSoup::from_raw(&[], &[[0, 1, 2], [2, 1, 3], [3, 4, 5]]).faces
        );
        assert_eq!(
            (report.strips_expanded, report.strip_triangles_dropped),
            (2, 2)
        );
    }

    #[test]
    fn binary_both_endiannesses_and_mixed_types() {
        let header = "element vertex 3\nproperty uchar red\nproperty double x\nproperty short y\n\
            property float z\nelement junk 2\nproperty list uint short values\n\
            element face 1\nproperty list ushort uint vertex_indices\nproperty int flags\n";
        for be in [false, true] {
            let mut data = Vec::new();
            for (x, y, z) in [(0.5f64, 0i16, 0.0f32), (1.0, 0, 0.0), (0.0, -3, 2.5)] {
                data.push(255);
                let (xb, yb, zb) = if be {
                    (
                        x.to_be_bytes().to_vec(),
                        y.to_be_bytes().to_vec(),
                        z.to_be_bytes().to_vec(),
                    )
                } else {
                    (
                        x.to_le_bytes().to_vec(),
                        y.to_le_bytes().to_vec(),
                        z.to_le_bytes().to_vec(),
                    )
                };
                data.extend(xb.iter().chain(&yb).chain(&zb));
            }
            let word = |v: u32| if be { v.to_be_bytes() } else { v.to_le_bytes() };
            for n in [1u32, 0] {
                data.extend(word(n));
                data.extend(vec![7u8; 2 * n as usize]);
            }
            data.extend(if be {
                3u16.to_be_bytes()
            } else {
                3u16.to_le_bytes()
            });
            for i in [2u32, 1, 0] {
                data.extend(word(i));
            }
            data.extend(word(99));
            let (soup, report) = ply(&binary(be, header, &data)).unwrap();
            assert_eq!(
                soup,
                TriangleSoup::from_raw(
                    &[[0.5, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, -3.0, 2.5]],
                    &[[2, 1, 0]]
                )
            );
            let enc = if be {
                PlyEncoding::BinaryBigEndian
            } else {
                PlyEncoding::BinaryLittleEndian
            };
            assert_eq!(report.format, Format::Ply(enc));
        }
    }

    fn le_tri(coords: [[f32; 3]; 3], face: [i32; 3], trailing: &[u8]) -> Vec<u8> {
        let header = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
            element face 1\nproperty list uchar int vertex_indices\n";
        let mut data: Vec<u8> = coords
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        data.push(3);
        data.extend(face.iter().flat_map(|i| i.to_le_bytes()));
        data.extend_from_slice(trailing);
        binary(false, header, &data)
    }

    #[test]
    fn binary_bad_inputs() {
        let ok = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert!(ply(&le_tri(ok, [0, 1, 2], &[])).is_ok());
        let mut nan = ok;
        nan[2][1] = f32::NAN;
        assert_eq!(
            kind(&le_tri(nan, [0, 1, 2], &[])),
            ReadErrorKind::Coordinate {
                vertex: 2,
                axis: Axis::Y,
                error: CoordError::NaN
            }
        );
        assert_eq!(
            kind(&le_tri(ok, [0, 3, 2], &[])),
            ReadErrorKind::IndexOutOfRange {
                what: "face",
                element: 0,
                index: 3,
                vertices: 3
            }
        );
        assert_eq!(
            kind(&le_tri(ok, [0, -1, 2], &[])),
            ReadErrorKind::IndexOutOfRange {
                what: "face",
                element: 0,
                index: -1,
                vertices: 3
            }
        );
        assert_eq!(
            kind(&le_tri(ok, [0, 1, 2], &[0])),
            ReadErrorKind::TrailingData
        );
        let full = le_tri(ok, [0, 1, 2], &[]);
        let e = ply(&full[..full.len() - 1]).unwrap_err();
        assert_eq!(
            e.kind,
            ReadErrorKind::Truncated {
                expected: "face data"
            }
        );
        assert!(e.to_string().contains("byte "), "{e}");
        let cut = &full[..full.len() - 20];
        assert!(matches!(kind(cut), ReadErrorKind::Truncated { .. }));
        // A negative list length.
        let header = "element vertex 0\nproperty float x\nproperty float y\nproperty float z\n\
            element face 1\nproperty list char int vertex_indices\n";
        assert!(matches!(
            kind(&binary(false, header, &[0xff])),
            ReadErrorKind::Unexpected { .. }
        ));
        // Binary garbage after a valid header.
        let garbage: Vec<u8> = (0..200u32).map(|i| (i * 7919 % 251) as u8).collect();
        assert!(ply(&binary(false, header, &garbage)).is_err());
    }

    #[test]
    fn ascii_bad_inputs() {
        let f = |body: &str| format!("{ASCII_TRI}{body}").into_bytes();
        assert_eq!(
            kind(&f("0 0 0\n1 0 0\n0 1 1e39\n3 0 1 2\n")),
            ReadErrorKind::Coordinate {
                vertex: 2,
                axis: Axis::Z,
                error: CoordError::Infinite
            }
        );
        assert_eq!(
            kind(&f("0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n")),
            ReadErrorKind::MalformedNumber
        );
        assert_eq!(
            kind(&f("0 0 0\n1 0 0\n0 1 0\n3 0 1 2.0\n")),
            ReadErrorKind::MalformedNumber
        );
        assert_eq!(
            kind(&f("0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n")),
            ReadErrorKind::IndexOutOfRange {
                what: "face",
                element: 0,
                index: 5,
                vertices: 3
            }
        );
        assert_eq!(
            kind(&f("0 0 0\n1 0 0\n0 1 0\n2 0 1\n")),
            ReadErrorKind::TooFewCorners {
                face: 0,
                corners: 2
            }
        );
        assert_eq!(
            kind(&f("0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n")),
            ReadErrorKind::TrailingData
        );
        assert_eq!(
            kind(&f("0 0 0\n1 0 0\n0 1 0\n3 0 1")),
            ReadErrorKind::Truncated {
                expected: "face data"
            }
        );
        let e = ply(&f("0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("<input>: line 13: face 0: vertex index 7"),
            "{e}"
        );
        let no_faces = ASCII_TRI.replace("element face 1", "element face 0");
        assert_eq!(
            kind(format!("{no_faces}0 0 0\n1 0 0\n0 1 0\n").as_bytes()),
            ReadErrorKind::NoFaces
        );
    }

    #[test]
    fn bad_headers() {
        let bad = |h: &str| kind(h.as_bytes());
        assert!(matches!(bad("plx\n"), ReadErrorKind::BadHeader(_)));
        assert!(matches!(
            bad("ply\nelement vertex 1\nproperty float x\n"),
            ReadErrorKind::Truncated { .. }
        ));
        assert!(matches!(
            bad("ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
            ReadErrorKind::BadHeader(_)
        ));
        assert!(matches!(
            bad("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n"),
            ReadErrorKind::BadHeader(_)
        ));
        assert!(matches!(
            bad("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n"),
            ReadErrorKind::BadHeader(_)
        ));
        assert!(matches!(
            bad(
                "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            ),
            ReadErrorKind::BadHeader(_)
        ));
        assert!(matches!(
            bad("ply\nformat binary_middle_endian 1.0\nend_header\n"),
            ReadErrorKind::Unsupported(_)
        ));
        assert!(matches!(
            bad("ply\nformat ascii 2.0\nend_header\n"),
            ReadErrorKind::Unsupported(_)
        ));
        assert_eq!(
            bad("ply\nformat ascii 1.0\nelement vertex many\n"),
            ReadErrorKind::MalformedNumber
        );
        assert!(matches!(
            bad("ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\n"),
            ReadErrorKind::BadHeader(_)
        ));
        assert!(matches!(
            bad(
                "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar float vertex_indices\nend_header\n"
            ),
            ReadErrorKind::BadHeader(_)
        ));
        assert!(matches!(
            bad("ply\nformat ascii 1.0\nwhatever\n"),
            ReadErrorKind::BadHeader(_)
        ));
    }

    #[test]
    fn empty_element_with_huge_count_is_skipped_at_once() {
        let header = format!("{ASCII_TRI}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").replace(
            "end_header",
            "element nothing 18446744073709551615\nend_header",
        );
        let start = std::time::Instant::now();
        assert_eq!(ply(header.as_bytes()).unwrap().0.num_faces(), 1);
        assert!(start.elapsed().as_secs() < 2);
    }

    #[test]
    fn huge_counts_do_not_allocate() {
        let header = "element vertex 4294967294\nproperty float x\nproperty float y\nproperty float z\n\
            element face 2147483648\nproperty list uchar int vertex_indices\n";
        // Unknown size (plain reader): reservations are capped, the data runs out.
        let e = ply(&binary(false, header, &[0; 64])).unwrap_err();
        assert!(matches!(e.kind, ReadErrorKind::Truncated { .. }));
        let header =
            "element vertex 4294967295\nproperty float x\nproperty float y\nproperty float z\n";
        assert_eq!(
            kind(&binary(false, header, &[0; 64])),
            ReadErrorKind::TooMany("vertices")
        );
    }
}
