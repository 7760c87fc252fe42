//! Typed read and write errors. A [`ReadError`] names the file, the place in it (a line for
//! text, a byte offset for binary data) and what was wrong ([`ReadErrorKind`], `Copy + Eq` so
//! tests and callers can match on it).

use std::fmt;
use std::io;
use std::path::PathBuf;

use envelope_mesh::CoordError;
use thiserror::Error;

/// Where in the input an error was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// No position applies (for example a missing file).
    None,
    /// 1-based line number in a text file or text header.
    Line(u64),
    /// 0-based byte offset in a binary file.
    Byte(u64),
}

/// One of the three coordinates of a position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// The first coordinate.
    X,
    /// The second coordinate.
    Y,
    /// The third coordinate.
    Z,
}

impl Axis {
    pub(crate) const ALL: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];
}

impl fmt::Display for Axis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Axis::X => "x",
            Axis::Y => "y",
            Axis::Z => "z",
        })
    }
}

/// What was wrong with the input.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum ReadErrorKind {
    /// The path does not exist.
    #[error("file not found")]
    NotFound,
    /// The path is a directory.
    #[error("is a directory, not a mesh file")]
    IsADirectory,
    /// Any other I/O failure.
    #[error("I/O error: {0}")]
    Io(io::ErrorKind),
    /// Neither the extension nor the content identifies a supported format.
    #[error("unrecognised file format (expected OBJ, OFF, PLY or STL)")]
    UnknownFormat,
    /// The header is malformed; the text says how.
    #[error("malformed header: {0}")]
    BadHeader(&'static str),
    /// A valid but unsupported variant of the format.
    #[error("unsupported: {0}")]
    Unsupported(&'static str),
    /// A token that should be a number is not one (or does not fit its declared type).
    #[error("malformed number")]
    MalformedNumber,
    /// A keyword or value other than the one the format requires here.
    #[error("unexpected content: expected {expected}")]
    Unexpected {
        /// What the format requires at this place.
        expected: &'static str,
    },
    /// The input ends before the data the header (or the syntax) announced.
    #[error("file ends early: expected {expected}")]
    Truncated {
        /// What was still expected.
        expected: &'static str,
    },
    /// More data follows what the header announced.
    #[error("data after the last element the header announced")]
    TrailingData,
    /// A line holds the wrong number of values.
    #[error("{found} values where {expected} were expected")]
    WrongValueCount {
        /// How many values the line should hold.
        expected: u64,
        /// How many it holds.
        found: u64,
    },
    /// A coordinate outside the range the exact predicates support.
    #[error("vertex {vertex}: {axis} coordinate rejected: {error}")]
    Coordinate {
        /// 0-based vertex number in file order (for STL: 3 * facet + corner, before welding).
        vertex: u64,
        /// Which coordinate.
        axis: Axis,
        /// Why it was rejected.
        error: CoordError,
    },
    /// A vertex index that names no vertex (0-based formats: OFF, PLY).
    #[error(
        "{what} {element}: vertex index {index} out of range ({vertices} vertices; allowed: {})",
        allowed_0_based(*.vertices)
    )]
    IndexOutOfRange {
        /// The kind of element holding the index ("face", "strip").
        what: &'static str,
        /// 0-based number of that element in the file.
        element: u64,
        /// The index as written.
        index: i64,
        /// The number of vertices the index had to be below.
        vertices: u64,
    },
    /// An OBJ face corner naming no vertex defined so far.
    #[error(
        "face {face}: vertex index {index} names no vertex ({vertices} defined so far; allowed: {})",
        allowed_obj(*.vertices)
    )]
    ObjIndexOutOfRange {
        /// 0-based number of the face (`f` statement) in the file.
        face: u64,
        /// The index as written (1-based, or negative counting back from the last vertex).
        index: i64,
        /// Vertices defined before the face.
        vertices: u64,
    },
    /// An OBJ face corner whose texture-coordinate or normal index names no `vt` or `vn`
    /// defined so far (read only with attributes).
    #[error(
        "face {face}: {what} index {index} names no {what} ({defined} defined so far; allowed: {})",
        allowed_obj_attribute(*.defined)
    )]
    ObjAttributeIndexOutOfRange {
        /// 0-based number of the face (`f` statement) in the file.
        face: u64,
        /// "texture coordinate" or "normal".
        what: &'static str,
        /// The index as written (1-based, or negative counting back from the last one).
        index: i64,
        /// Values of that kind defined before the face.
        defined: u64,
    },
    /// An attribute value (texture coordinate, normal, colour) that is NaN or infinite.
    #[error("{what} {element}: a value is not finite")]
    AttributeValue {
        /// "texture coordinate", "normal" or "vertex" (PLY per-vertex attributes).
        what: &'static str,
        /// Its 0-based number in file order.
        element: u64,
    },
    /// An OBJ face corner that is not `i`, `i/t`, `i//n` or `i/t/n` with integers fitting 64
    /// bits.
    #[error(
        "face {face}: corner '{corner}' is not a vertex reference (allowed: i, i/t, i//n or \
         i/t/n, each an integer, 1-based or negative)"
    )]
    ObjBadCorner {
        /// 0-based number of the face (`f` statement) in the file.
        face: u64,
        /// The corner as written.
        corner: Word,
    },
    /// A polygon with fewer than three distinct corners (after dropping consecutive repeats).
    #[error("face {face} has {corners} distinct corners, at least 3 are needed")]
    TooFewCorners {
        /// 0-based face number in the file.
        face: u64,
        /// Its number of corners.
        corners: u64,
    },
    /// A polygon that passes through one vertex twice (not at consecutive corners).
    #[error(
        "face {face}: corners {first} and {second} are the same vertex; a polygon may visit a \
         vertex only once (split it into simple polygons)"
    )]
    RepeatedCorner {
        /// 0-based face number in the file.
        face: u64,
        /// 1-based position of the first of the two corners in the face as written.
        first: u64,
        /// 1-based position of the second.
        second: u64,
    },
    /// A polygon that is not simple in any axis-aligned projection, so it cannot be
    /// triangulated without overlapping triangles.
    #[error(
        "face {face}: its {corners} corners form a self-intersecting polygon (not simple in any \
         axis-aligned projection); only simple polygons can be triangulated, split it"
    )]
    NotSimplePolygon {
        /// 0-based face number in the file.
        face: u64,
        /// Its number of distinct corners.
        corners: u64,
    },
    /// A statement that could change the surface or the vertex numbering, and that the reader
    /// does not support (it refuses the file rather than read a different mesh).
    #[error("unsupported statement '{keyword}': {why}")]
    UnsupportedStatement {
        /// The keyword as written.
        keyword: Word,
        /// Why it cannot be ignored, and what is allowed.
        why: &'static str,
    },
    /// The first word of an OFF file is not an OFF keyword.
    #[error(
        "the first line must be the OFF keyword (OFF, COFF, NOFF, STOFF, ...), found '{found}'{}",
        if found.is_number() { ": the OFF line is missing" } else { "" }
    )]
    NotOffKeyword {
        /// The first word of the file.
        found: Word,
    },
    /// The file holds no triangle.
    #[error("the mesh has no faces")]
    NoFaces,
    /// More vertices or triangles than 32-bit ids can name.
    #[error("too many {0} for 32-bit ids")]
    TooMany(&'static str),
}

fn allowed_0_based(vertices: u64) -> String {
    match vertices {
        0 => "none, no vertex is defined".to_owned(),
        n => format!("0 to {}", n - 1),
    }
}

fn allowed_obj(vertices: u64) -> String {
    match vertices {
        0 => "none, no vertex is defined before this face".to_owned(),
        n => format!("1 to {n}, or -1 to -{n} counting back"),
    }
}

fn allowed_obj_attribute(defined: u64) -> String {
    match defined {
        0 => "none, none is defined before this face".to_owned(),
        n => format!("1 to {n}, or -1 to -{n} counting back"),
    }
}

/// A word from the input (a keyword), kept by value so that [`ReadErrorKind`] stays `Copy`:
/// up to 24 bytes, longer words are cut (and shown with `...`).
///
/// ```
/// use envelope_io::{read, Format, ReadErrorKind};
/// let err = read(&b"v 0 0 0\ncurv 0 1 1\n"[..], Format::Obj).unwrap_err();
/// let ReadErrorKind::UnsupportedStatement { keyword, .. } = err.kind else { panic!() };
/// assert_eq!(keyword.to_string(), "curv");
/// ```
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Word {
    bytes: [u8; Word::CAP],
    len: u8,
    cut: bool,
}

impl Word {
    const CAP: usize = 48;

    pub(crate) fn new(word: &[u8]) -> Self {
        let len = word.len().min(Self::CAP);
        let mut bytes = [0; Self::CAP];
        bytes[..len].copy_from_slice(&word[..len]);
        Self {
            bytes,
            len: len as u8,
            cut: word.len() > Self::CAP,
        }
    }

    /// The bytes kept.
    #[must_use]
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes[..usize::from(self.len)]
    }

    /// Whether the word reads as a (signed, decimal) number.
    #[must_use]
    pub fn is_number(&self) -> bool {
        std::str::from_utf8(self.as_bytes()).is_ok_and(|s| s.parse::<f64>().is_ok())
    }
}

impl fmt::Display for Word {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}",
            String::from_utf8_lossy(self.as_bytes()).escape_debug()
        )?;
        if self.cut {
            f.write_str("...")?;
        }
        Ok(())
    }
}

impl fmt::Debug for Word {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Word(\"{self}\")")
    }
}

impl From<io::ErrorKind> for ReadErrorKind {
    fn from(kind: io::ErrorKind) -> Self {
        match kind {
            io::ErrorKind::NotFound => ReadErrorKind::NotFound,
            io::ErrorKind::IsADirectory => ReadErrorKind::IsADirectory,
            io::ErrorKind::UnexpectedEof => ReadErrorKind::Truncated {
                expected: "more data",
            },
            other => ReadErrorKind::Io(other),
        }
    }
}

/// A failed read: which file, where in it, and what was wrong.
///
/// ```
/// use envelope_io::{read, Format, ReadErrorKind};
/// let err = read(&b"OFF\n3 1 0\n0 0 0\n1 0 0\n"[..], Format::Off).unwrap_err();
/// assert!(matches!(err.kind, ReadErrorKind::Truncated { .. }));
/// assert_eq!(err.to_string(), "<input>: line 4: file ends early: expected vertex line");
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadError {
    /// The file, when reading from a path.
    pub path: Option<PathBuf>,
    /// Where in the input.
    pub location: Location,
    /// What was wrong.
    pub kind: ReadErrorKind,
}

impl ReadError {
    pub(crate) fn new(location: Location, kind: ReadErrorKind) -> Self {
        Self {
            path: None,
            location,
            kind,
        }
    }

    pub(crate) fn with_path(mut self, path: &std::path::Path) -> Self {
        self.path = Some(path.to_path_buf());
        self
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.path {
            Some(p) => write!(f, "{}", p.display())?,
            None => f.write_str("<input>")?,
        }
        match self.location {
            Location::None => {}
            Location::Line(n) => write!(f, ": line {n}")?,
            Location::Byte(n) => write!(f, ": byte {n}")?,
        }
        write!(f, ": {}", self.kind)
    }
}

impl std::error::Error for ReadError {}

/// What made a write fail.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum WriteErrorKind {
    /// The underlying writer failed.
    #[error("I/O error: {0}")]
    Io(#[from] io::Error),
    /// A face names a vertex the soup does not have.
    #[error("face {face}: vertex index {index} out of range ({vertices} vertices)")]
    IndexOutOfRange {
        /// 0-based face number.
        face: u64,
        /// The offending index.
        index: u32,
        /// Number of vertices in the soup.
        vertices: u64,
    },
    /// A coordinate the readers would reject.
    #[error("vertex {vertex}: {axis} coordinate rejected: {error}")]
    Coordinate {
        /// 0-based vertex number.
        vertex: u64,
        /// Which coordinate.
        axis: Axis,
        /// Why it was rejected.
        error: CoordError,
    },
    /// More faces than binary STL's 32-bit count can hold.
    #[error("too many faces for the format")]
    TooManyFaces,
    /// Attributes without one corner triple per face, an index out of range, or a value that
    /// is not finite.
    #[error("the attributes do not fit the mesh ({faces} faces)")]
    InvalidAttributes {
        /// Faces in the soup.
        faces: u64,
    },
}

/// A failed write, naming the target file when there is one.
#[derive(Debug)]
pub struct WriteError {
    /// The target file, when writing to a path.
    pub path: Option<PathBuf>,
    /// What went wrong.
    pub kind: WriteErrorKind,
}

impl WriteError {
    pub(crate) fn with_path(mut self, path: &std::path::Path) -> Self {
        self.path = Some(path.to_path_buf());
        self
    }
}

impl From<WriteErrorKind> for WriteError {
    fn from(kind: WriteErrorKind) -> Self {
        Self { path: None, kind }
    }
}

impl From<io::Error> for WriteError {
    fn from(e: io::Error) -> Self {
        Self {
            path: None,
            kind: WriteErrorKind::Io(e),
        }
    }
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.path {
            Some(p) => write!(f, "{}: {}", p.display(), self.kind),
            None => write!(f, "{}", self.kind),
        }
    }
}

impl std::error::Error for WriteError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            WriteErrorKind::Io(e) => Some(e),
            _ => None,
        }
    }
}
