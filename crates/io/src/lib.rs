//! Readers and writers for OBJ, OFF, PLY and STL triangle meshes.
//!
//! Every reader produces a [`TriangleSoup`] and a [`ReadReport`] (and, through
//! [`read_with_attributes`], the per-corner [`Attributes`] OBJ and PLY hold: texture
//! coordinates, normals, colours; [`write_with_attributes`] writes them back, OFF and STL
//! drop them), and validates at the
//! boundary: each coordinate passes [`envelope_mesh::check_coordinate`], each index is in
//! range, and anything else wrong (truncation, wrong header counts, malformed numbers, no
//! faces, garbage) is a typed [`ReadError`] naming the file, the line or byte offset and the
//! problem. Readers never panic and never reserve more than the remaining input can hold, so
//! a header announcing 2^31 vertices in a 100-byte file fails fast instead of allocating.
//!
//! A reader never ignores anything that could change the geometry or the vertex numbering:
//! such a statement, header word or element refuses the file ([`ReadErrorKind::UnsupportedStatement`],
//! [`ReadErrorKind::NotOffKeyword`], [`ReadErrorKind::Unsupported`], ...); what is skipped
//! (texture data, groups, materials, unknown PLY elements whose layout the header gives) is
//! named in the report's notes. A UTF-8 byte order mark at the start of any text format is
//! skipped, also by [`Format::sniff`]. Errors name the element as written: the line or byte,
//! the index as it appears in the file (1-based or negative in OBJ), and what is allowed.
//!
//! Conversions (all listed in the report):
//! * polygons with more than three corners (OBJ, OFF, PLY) are triangulated without overlaps
//!   by [`envelope_predicates::polygon::triangulate_polygon`] (constrained Delaunay in an
//!   axis-aligned projection where the polygon is simple, decided exactly; also for
//!   non-planar polygons, whose triangles then form a height field over that plane), after
//!   dropping repeated consecutive corners; a polygon that visits a vertex twice or is not
//!   simple in any axis-aligned projection (a bow-tie) is refused. Triangles are kept as
//!   written (the input checker reports degenerate ones);
//! * PLY `tristrips` are expanded with alternating winding, `-1` restarting a strip, and strip
//!   triangles with a repeated corner dropped;
//! * STL corners are welded: bitwise-equal positions become one vertex, numbered in order of
//!   first appearance. STL stores `f32`; the conversion to `f64` is exact.
//!
//! Writers use Rust's shortest round-trip float formatting, so text output read back gives
//! the same `f64` values; binary PLY stores `double`. STL stores `f32`, so an STL round trip is
//! exact only for `f32`-representable coordinates, and loses unreferenced vertices and the
//! vertex order (vertices come back in order of first use).
//!
//! ```
//! use envelope_io::{read, write, Format, PlyEncoding};
//! use envelope_mesh::TriangleSoup;
//! let soup = TriangleSoup::from_raw(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.1, 0.0]], &[[0, 1, 2]]);
//! let mut bytes = Vec::new();
//! write(&mut bytes, &soup, Format::Ply(PlyEncoding::BinaryLittleEndian)).unwrap();
//! let (back, report) = read(&bytes[..], Format::Ply(PlyEncoding::Ascii)).unwrap();
//! assert_eq!(back, soup);
//! assert_eq!(report.format, Format::Ply(PlyEncoding::BinaryLittleEndian)); // the header decides
//! ```
#![forbid(unsafe_code)]

mod build;
mod error;
mod input;
mod obj;
mod off;
mod ply;
mod ply_write;
mod report;
mod stl;

use std::fmt;
use std::fs;
use std::io::{self, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use envelope_mesh::{Attributes, TriangleSoup, check_coordinate};

pub use error::{Axis, Location, ReadError, ReadErrorKind, Word, WriteError, WriteErrorKind};
pub use report::ReadReport;

use input::Input;

/// Encoding of a PLY file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PlyEncoding {
    /// `format ascii 1.0`.
    Ascii,
    /// `format binary_little_endian 1.0`.
    BinaryLittleEndian,
    /// `format binary_big_endian 1.0`.
    BinaryBigEndian,
}

/// Encoding of an STL file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StlEncoding {
    /// `solid ... endsolid` text.
    Ascii,
    /// 80-byte header, `u32` count, 50-byte records.
    Binary,
}

/// A mesh file format. For reading only the family matters (the PLY header and the STL
/// content decide the encoding); for writing the encoding is used as given.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Wavefront OBJ (`v` and `f` statements).
    Obj,
    /// Object File Format (`OFF`, also `COFF`, `NOFF`, `STOFF` headers when reading).
    Off,
    /// Stanford polygon format.
    Ply(PlyEncoding),
    /// Stereolithography triangles.
    Stl(StlEncoding),
}

impl Format {
    /// The format a file extension names (ASCII case-insensitive, without the dot), with the
    /// binary encoding for PLY and STL.
    ///
    /// ```
    /// use envelope_io::{Format, StlEncoding};
    /// assert_eq!(Format::from_extension("STL"), Some(Format::Stl(StlEncoding::Binary)));
    /// assert_eq!(Format::from_extension("txt"), None);
    /// ```
    #[must_use]
    pub fn from_extension(ext: &str) -> Option<Self> {
        let ext = ext.to_ascii_lowercase();
        match ext.as_str() {
            "obj" => Some(Format::Obj),
            "off" => Some(Format::Off),
            "ply" => Some(Format::Ply(PlyEncoding::BinaryLittleEndian)),
            "stl" => Some(Format::Stl(StlEncoding::Binary)),
            _ => None,
        }
    }

    /// The format a path's extension names, see [`Format::from_extension`].
    #[must_use]
    pub fn from_path(path: &Path) -> Option<Self> {
        Self::from_extension(path.extension()?.to_str()?)
    }

    /// Guesses the format from the first bytes of a file (a few hundred suffice) and, when
    /// known, its total length (needed to recognise binary STL by its size).
    ///
    /// ```
    /// use envelope_io::{Format, PlyEncoding};
    /// assert_eq!(Format::sniff(b"ply\nformat ascii 1.0\n", None), Some(Format::Ply(PlyEncoding::Ascii)));
    /// assert_eq!(Format::sniff(b"# cube\nv 0 0 0\n", None), Some(Format::Obj));
    /// ```
    #[must_use]
    pub fn sniff(head: &[u8], len: Option<u64>) -> Option<Self> {
        let full = head;
        let head = input::strip_bom(head);
        if head.starts_with(b"ply\n") || head.starts_with(b"ply\r\n") {
            let enc = if contains(head, b"binary_little_endian") {
                PlyEncoding::BinaryLittleEndian
            } else if contains(head, b"binary_big_endian") {
                PlyEncoding::BinaryBigEndian
            } else {
                PlyEncoding::Ascii
            };
            return Some(Format::Ply(enc));
        }
        // A text STL whose length happens to fit the binary formula stays text.
        if full.len() >= 84
            && len.is_some_and(|l| l == stl::binary_size(full))
            && !stl::looks_ascii(full)
        {
            return Some(Format::Stl(StlEncoding::Binary));
        }
        let text = head.trim_ascii_start();
        if text.len() >= 5 && text[..5].eq_ignore_ascii_case(b"solid") {
            return Some(Format::Stl(StlEncoding::Ascii));
        }
        // The first non-comment token decides between OFF and OBJ.
        let mut first = None;
        for line in head.split(|&b| b == b'\n') {
            let line = line.split(|&b| b == b'#').next().unwrap_or_default();
            if let Some(t) = input::tokens(line).next() {
                first = Some(t);
                break;
            }
        }
        let first = first?;
        if first.ends_with(b"OFF") {
            return Some(Format::Off);
        }
        const OBJ_KEYWORDS: [&[u8]; 12] = [
            b"v", b"vt", b"vn", b"vp", b"f", b"o", b"g", b"s", b"l", b"p", b"mtllib", b"usemtl",
        ];
        if OBJ_KEYWORDS.contains(&first) {
            return Some(Format::Obj);
        }
        None
    }

    /// The present attributes this format cannot write (`"texture coordinates"`,
    /// `"normals"`, `"colours"`, `"quality"`), for a note when they are dropped.
    ///
    /// ```
    /// use envelope_io::Format;
    /// use envelope_mesh::{Attributes, Wedges};
    /// let colours = Wedges { values: vec![[1.0, 0.0, 0.0, 1.0]], corners: vec![[0, 0, 0]] };
    /// let a = Attributes { colors: Some(colours), ..Attributes::default() };
    /// assert_eq!(Format::Obj.dropped_attributes(&a), ["colours"]);
    /// assert!(Format::from_extension("ply").unwrap().dropped_attributes(&a).is_empty());
    /// ```
    #[must_use]
    pub fn dropped_attributes(self, attributes: &Attributes) -> Vec<&'static str> {
        let (tex, normals, colors) = match self {
            Format::Obj => (true, true, false),
            Format::Ply(_) => (true, true, true),
            Format::Off | Format::Stl(_) => (false, false, false),
        };
        let mut out = Vec::new();
        if attributes.texcoords.is_some() && !tex {
            out.push("texture coordinates");
        }
        if attributes.normals.is_some() && !normals {
            out.push("normals");
        }
        if attributes.colors.is_some() && !colors {
            out.push("colours");
        }
        // Only PLY has a per-vertex scalar property that viewers know.
        if attributes.quality.is_some() && !matches!(self, Format::Ply(_)) {
            out.push("quality");
        }
        out
    }

    /// The usual file extension.
    #[must_use]
    pub fn extension(self) -> &'static str {
        match self {
            Format::Obj => "obj",
            Format::Off => "off",
            Format::Ply(_) => "ply",
            Format::Stl(_) => "stl",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Format::Obj => "OBJ",
            Format::Off => "OFF",
            Format::Ply(PlyEncoding::Ascii) => "PLY (ascii)",
            Format::Ply(PlyEncoding::BinaryLittleEndian) => "PLY (binary little-endian)",
            Format::Ply(PlyEncoding::BinaryBigEndian) => "PLY (binary big-endian)",
            Format::Stl(StlEncoding::Ascii) => "STL (ascii)",
            Format::Stl(StlEncoding::Binary) => "STL (binary)",
        })
    }
}

fn contains(hay: &[u8], needle: &[u8]) -> bool {
    hay.windows(needle.len()).any(|w| w == needle)
}

/// Reads a mesh in the given format family from any reader (buffering is done here; a
/// `BufReader` is not needed). Without a known input size, reservations from header counts
/// are capped and the arrays grow as real data arrives.
///
/// ```
/// use envelope_io::{read, Format};
/// let off = b"OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
/// let (soup, report) = read(&off[..], Format::Off).unwrap();
/// assert_eq!((soup.num_vertices(), soup.num_faces()), (4, 2));
/// assert_eq!(report.polygons_triangulated, 1);
/// ```
///
/// # Errors
/// A [`ReadError`] (with `path: None`) for anything wrong with the input.
pub fn read<R: Read>(reader: R, format: Format) -> Result<(TriangleSoup, ReadReport), ReadError> {
    read_input(Input::new(reader, None), format)
}

fn read_input<R: Read>(
    input: Input<R>,
    format: Format,
) -> Result<(TriangleSoup, ReadReport), ReadError> {
    match format {
        Format::Obj => obj::read(input),
        Format::Off => off::read(input),
        Format::Ply(_) => ply::read(input),
        Format::Stl(_) => stl::read(input),
    }
}

/// [`read`], with the per-corner attributes the format holds: OBJ `vt` and `vn` tables and
/// `f i/t/n` corners; PLY vertex properties `u v` (or `s t`, `texture_u texture_v`,
/// `texture_s texture_t`), `nx ny nz` and `red green blue [alpha]` (integer colours divided
/// by their type's maximum, `uchar` by 255; floats as written). OFF and STL give none.
/// The soup is exactly the one [`read`] gives: attributes never change the positions, the
/// faces or the numbering (so a PLY vertex split at a seam stays split; `envelope repair`
/// welds it).
///
/// An OBJ attribute some corners have and others lack is dropped, with a note naming the
/// first face without it (the positions are whole; refusing would refuse common files whose
/// untextured parts omit `vt`). Corner indices are checked like vertex indices: 1-based or
/// negative, naming a `vt`/`vn` defined before the face; an error names the line and the
/// index as written.
///
/// ```
/// use envelope_io::{read_with_attributes, Format};
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
/// let (soup, attributes, _report) = read_with_attributes(&obj[..], Format::Obj).unwrap();
/// assert_eq!(soup.num_faces(), 1);
/// assert_eq!(attributes.texcoords.unwrap().value(0, 1), [1.0, 0.0]);
/// let bad = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n";
/// let err = read_with_attributes(&bad[..], Format::Obj).unwrap_err();
/// assert!(err.to_string().contains("line 5: face 0: texture coordinate index 2"), "{err}");
/// ```
///
/// # Errors
/// As [`read`]; also a corner index naming no value, or a value that is not finite.
pub fn read_with_attributes<R: Read>(
    reader: R,
    format: Format,
) -> Result<(TriangleSoup, Attributes, ReadReport), ReadError> {
    read_input_with_attributes(Input::new(reader, None), format)
}

fn read_input_with_attributes<R: Read>(
    input: Input<R>,
    format: Format,
) -> Result<(TriangleSoup, Attributes, ReadReport), ReadError> {
    let without = |(soup, report)| (soup, Attributes::default(), report);
    match format {
        Format::Obj => obj::read_with_attributes(input),
        Format::Off => off::read(input).map(without),
        Format::Ply(_) => ply::read_with_attributes(input),
        Format::Stl(_) => stl::read(input).map(without),
    }
}

/// [`read_path`] with attributes ([`read_with_attributes`]).
///
/// # Errors
/// As [`read_path`] and [`read_with_attributes`].
pub fn read_path_with_attributes(
    path: impl AsRef<Path>,
) -> Result<(TriangleSoup, Attributes, ReadReport), ReadError> {
    let path = path.as_ref();
    let fail = |kind: ReadErrorKind| ReadError::new(Location::None, kind).with_path(path);
    let meta = fs::metadata(path).map_err(|e| fail(e.kind().into()))?;
    if meta.is_dir() {
        return Err(fail(ReadErrorKind::IsADirectory));
    }
    let file = fs::File::open(path).map_err(|e| fail(e.kind().into()))?;
    let mut input = Input::new(file, Some(meta.len()));
    let format = format_of(&mut input, path, Some(meta.len()))?;
    read_input_with_attributes(input, format).map_err(|e| e.with_path(path))
}

/// Reads a mesh file, choosing the format from the extension (case-insensitive) or, when the
/// extension is missing or unknown, from the content ([`Format::sniff`]).
///
/// ```
/// # let dir = tempfile::tempdir().unwrap();
/// # let path = dir.path().join("tri.obj");
/// # std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
/// let (soup, _report) = envelope_io::read_path(&path).unwrap();
/// assert_eq!(soup.num_faces(), 1);
/// let err = envelope_io::read_path(dir.path()).unwrap_err();
/// assert_eq!(err.kind, envelope_io::ReadErrorKind::IsADirectory);
/// ```
///
/// # Errors
/// A [`ReadError`] naming `path` for a missing file, a directory, an unknown format or
/// anything wrong with the content.
pub fn read_path(path: impl AsRef<Path>) -> Result<(TriangleSoup, ReadReport), ReadError> {
    let path = path.as_ref();
    let fail = |kind: ReadErrorKind| ReadError::new(Location::None, kind).with_path(path);
    let meta = fs::metadata(path).map_err(|e| fail(e.kind().into()))?;
    if meta.is_dir() {
        return Err(fail(ReadErrorKind::IsADirectory));
    }
    let file = fs::File::open(path).map_err(|e| fail(e.kind().into()))?;
    read_named(Input::new(file, Some(meta.len())), path, Some(meta.len()))
}

/// Reads a mesh file's bytes, already in memory (for callers that also hash them), as
/// [`read_path`] reads the file: the format from `path`'s extension or the content, and
/// errors naming `path`.
///
/// ```
/// let bytes = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n";
/// let err = envelope_io::read_bytes(bytes, "tri.obj".as_ref()).unwrap_err();
/// assert!(err.to_string().starts_with("tri.obj: line 4"), "{err}");
/// ```
///
/// # Errors
/// As [`read_path`], for the content.
pub fn read_bytes(bytes: &[u8], path: &Path) -> Result<(TriangleSoup, ReadReport), ReadError> {
    let len = Some(bytes.len() as u64);
    read_named(Input::new(bytes, len), path, len)
}

/// [`read_bytes`] with the per-corner attributes, as [`read_with_attributes`].
///
/// # Errors
/// As [`read_bytes`].
pub fn read_bytes_with_attributes(
    bytes: &[u8],
    path: &Path,
) -> Result<(TriangleSoup, Attributes, ReadReport), ReadError> {
    let len = Some(bytes.len() as u64);
    let mut input = Input::new(bytes, len);
    let format = format_of(&mut input, path, len)?;
    read_input_with_attributes(input, format).map_err(|e| e.with_path(path))
}

/// The format from `path` or the content, then the reader; errors name `path`.
fn read_named<R: Read>(
    mut input: Input<R>,
    path: &Path,
    len: Option<u64>,
) -> Result<(TriangleSoup, ReadReport), ReadError> {
    let format = format_of(&mut input, path, len)?;
    read_input(input, format).map_err(|e| e.with_path(path))
}

/// The format `path` names, or else the one the content shows.
fn format_of<R: Read>(
    input: &mut Input<R>,
    path: &Path,
    len: Option<u64>,
) -> Result<Format, ReadError> {
    let fail = |kind: ReadErrorKind| ReadError::new(Location::None, kind).with_path(path);
    Ok(match Format::from_path(path) {
        Some(f) => f,
        None => {
            let head = input.peek(512).map_err(|e| fail(e.kind().into()))?;
            Format::sniff(head, len).ok_or_else(|| fail(ReadErrorKind::UnknownFormat))?
        }
    })
}

/// Checks what the readers would check, so that whatever is written can be read back.
fn validate(soup: &TriangleSoup) -> Result<(), WriteErrorKind> {
    for (v, p) in soup.positions.iter().enumerate() {
        for (axis, x) in Axis::ALL.into_iter().zip(p.to_array()) {
            if let Err(error) = check_coordinate(x) {
                return Err(WriteErrorKind::Coordinate {
                    vertex: v as u64,
                    axis,
                    error,
                });
            }
        }
    }
    let n = soup.positions.len();
    for (f, face) in soup.faces.iter().enumerate() {
        if let Some(v) = face.iter().find(|v| v.index() >= n) {
            return Err(WriteErrorKind::IndexOutOfRange {
                face: f as u64,
                index: v.0,
                vertices: n as u64,
            });
        }
    }
    Ok(())
}

/// Writes `soup` in `format` (buffered internally). Coordinates that
/// [`envelope_mesh::check_coordinate`] rejects and out-of-range indices are refused before
/// anything is written. An empty soup is written as such, but readers reject it.
///
/// ```
/// use envelope_io::{write, Format};
/// use envelope_mesh::TriangleSoup;
/// let soup = TriangleSoup::from_raw(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.5, 0.0]], &[[0, 1, 2]]);
/// let mut out = Vec::new();
/// write(&mut out, &soup, Format::Obj).unwrap();
/// assert!(String::from_utf8(out).unwrap().ends_with("v 0.0 0.5 0.0\nf 1 2 3\n"));
/// ```
///
/// # Errors
/// [`WriteErrorKind::Io`] when the writer fails, the other kinds for an invalid soup.
pub fn write<W: Write>(writer: W, soup: &TriangleSoup, format: Format) -> Result<(), WriteError> {
    validate(soup)?;
    let mut w = BufWriter::with_capacity(1 << 16, writer);
    match format {
        Format::Obj => obj::write(&mut w, soup)?,
        Format::Off => off::write(&mut w, soup)?,
        Format::Ply(enc) => ply::write(&mut w, soup, enc)?,
        Format::Stl(enc) => stl::write(&mut w, soup, enc)?,
    }
    w.flush()?;
    Ok(())
}

/// [`write()`], with the attributes the format holds: OBJ writes `vt`/`vn` tables and `f
/// v/t/n` corners (no colours: OBJ has no colour statement); PLY writes per-vertex `u v`,
/// `nx ny nz` and `red green blue alpha` columns, a vertex split into one per distinct
/// combination of values its corners have (a seam's copies are then separate vertices of the
/// file); OFF and STL write positions only ([`Format::dropped_attributes`] says what is lost).
///
/// ```
/// use envelope_io::{read_with_attributes, write_with_attributes, Format};
/// use envelope_mesh::{Attributes, TriangleSoup, Wedges};
/// let soup = TriangleSoup::from_raw(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
/// let normals = Wedges { values: vec![[0.0, 0.0, 1.0]], corners: vec![[0, 0, 0]] };
/// let attributes = Attributes { normals: Some(normals), ..Attributes::default() };
/// let mut out = Vec::new();
/// write_with_attributes(&mut out, &soup, &attributes, Format::Obj).unwrap();
/// assert!(String::from_utf8(out.clone()).unwrap().ends_with("vn 0.0 0.0 1.0\nf 1//1 2//1 3//1\n"));
/// let (back, again, _) = read_with_attributes(&out[..], Format::Obj).unwrap();
/// assert_eq!((back, again), (soup, attributes));
/// ```
///
/// # Errors
/// As [`write()`]; [`WriteErrorKind::InvalidAttributes`] when the attributes do not fit the
/// soup ([`Attributes::is_valid_for`]).
pub fn write_with_attributes<W: Write>(
    writer: W,
    soup: &TriangleSoup,
    attributes: &Attributes,
    format: Format,
) -> Result<(), WriteError> {
    write_with_comments(writer, soup, attributes, format, &[])
}

/// [`write_with_attributes`], with `comments` as PLY header `comment` lines after the
/// writer's own (a line break inside one becomes a space); other formats ignore them.
///
/// ```
/// use envelope_io::{read_with_attributes, write_with_comments, Format, PlyEncoding};
/// use envelope_mesh::{Attributes, TriangleSoup, Wedges};
/// let soup = TriangleSoup::from_raw(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
/// let quality = Wedges { values: vec![[0.25], [0.5], [1.0]], corners: vec![[0, 1, 2]] };
/// let attributes = Attributes { quality: Some(quality), ..Attributes::default() };
/// let mut out = Vec::new();
/// let comments = ["quality: a test".to_string()];
/// write_with_comments(&mut out, &soup, &attributes, Format::Ply(PlyEncoding::Ascii), &comments).unwrap();
/// let text = String::from_utf8(out.clone()).unwrap();
/// assert!(text.contains("comment quality: a test\n") && text.contains("property float quality\n"));
/// let (back, again, _) = read_with_attributes(&out[..], Format::Ply(PlyEncoding::Ascii)).unwrap();
/// assert_eq!((back, again), (soup, attributes));
/// ```
///
/// # Errors
/// As [`write_with_attributes`].
pub fn write_with_comments<W: Write>(
    writer: W,
    soup: &TriangleSoup,
    attributes: &Attributes,
    format: Format,
    comments: &[String],
) -> Result<(), WriteError> {
    validate(soup)?;
    validate_attributes(soup, attributes)?;
    let mut w = BufWriter::with_capacity(1 << 16, writer);
    match format {
        Format::Obj => obj::write_with_attributes(&mut w, soup, attributes)?,
        Format::Off => off::write(&mut w, soup)?,
        Format::Ply(enc) => ply::write_with_attributes(&mut w, soup, attributes, enc, comments)?,
        Format::Stl(enc) => stl::write(&mut w, soup, enc)?,
    }
    w.flush()?;
    Ok(())
}

fn validate_attributes(soup: &TriangleSoup, attributes: &Attributes) -> Result<(), WriteErrorKind> {
    if attributes.is_valid_for(soup.num_faces()) {
        Ok(())
    } else {
        Err(WriteErrorKind::InvalidAttributes {
            faces: soup.num_faces() as u64,
        })
    }
}

/// [`write_path`] with attributes ([`write_with_attributes`]), atomically.
///
/// # Errors
/// As [`write_path`] and [`write_with_attributes`].
pub fn write_path_with_attributes(
    path: impl AsRef<Path>,
    soup: &TriangleSoup,
    attributes: &Attributes,
    format: Format,
) -> Result<(), WriteError> {
    write_path_with_comments(path, soup, attributes, format, &[])
}

/// [`write_path_with_attributes`] with PLY header comments ([`write_with_comments`]),
/// atomically.
///
/// # Errors
/// As [`write_path_with_attributes`].
pub fn write_path_with_comments(
    path: impl AsRef<Path>,
    soup: &TriangleSoup,
    attributes: &Attributes,
    format: Format,
    comments: &[String],
) -> Result<(), WriteError> {
    let path = path.as_ref();
    validate(soup)
        .and_then(|()| validate_attributes(soup, attributes))
        .map_err(|k| WriteError::from(k).with_path(path))?;
    atomically(path, |file| {
        write_with_comments(file, soup, attributes, format, comments)
    })
}

static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// Writes `soup` to `path` atomically: into a temporary file in the same directory, synced,
/// then renamed over `path`. An existing file at `path` is never left half-written, and the
/// temporary file is removed on error.
///
/// ```
/// use envelope_io::{read_path, write_path, Format, StlEncoding};
/// use envelope_mesh::TriangleSoup;
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("tri.stl");
/// let soup = TriangleSoup::from_raw(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.5, 0.0]], &[[0, 1, 2]]);
/// write_path(&path, &soup, Format::Stl(StlEncoding::Binary)).unwrap();
/// assert_eq!(read_path(&path).unwrap().0, soup);
/// ```
///
/// # Errors
/// A [`WriteError`] naming `path`.
pub fn write_path(
    path: impl AsRef<Path>,
    soup: &TriangleSoup,
    format: Format,
) -> Result<(), WriteError> {
    let path = path.as_ref();
    validate(soup).map_err(|k| WriteError::from(k).with_path(path))?;
    atomically(path, |file| write(file, soup, format))
}

/// Runs `write` on a temporary file beside `path`, synced and renamed over `path` on success,
/// removed on failure.
fn atomically(
    path: &Path,
    write: impl FnOnce(&fs::File) -> Result<(), WriteError>,
) -> Result<(), WriteError> {
    let (tmp, file) = create_temp(path).map_err(|e| WriteError::from(e).with_path(path))?;
    let result = write(&file)
        .and_then(|()| file.sync_all().map_err(WriteError::from))
        .and_then(|()| fs::rename(&tmp, path).map_err(WriteError::from));
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result.map_err(|e| e.with_path(path))
}

fn create_temp(path: &Path) -> io::Result<(PathBuf, fs::File)> {
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "path has no file name"))?;
    let dir = path.parent().unwrap_or(Path::new(""));
    loop {
        let n = TEMP_COUNTER.fetch_add(1, Ordering::Relaxed);
        let mut tmp_name = std::ffi::OsString::from(".");
        tmp_name.push(name);
        tmp_name.push(format!(".{}.{n}.tmp", std::process::id()));
        let tmp = dir.join(tmp_name);
        match fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
        {
            Ok(f) => return Ok((tmp, f)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && n < u64::MAX => {}
            Err(e) => return Err(e),
        }
    }
}
