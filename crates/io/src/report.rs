//! [`ReadReport`]: what a reader did to the file's content on the way to a triangle soup.

use std::fmt;

use crate::Format;

/// What a reader found and changed: the exact format, and every conversion the user may need
/// to know about (polygons triangulated, strips expanded, STL corners welded, data ignored).
///
/// ```
/// use envelope_io::{read, Format};
/// let obj = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
/// let (soup, report) = read(&obj[..], Format::Obj).unwrap();
/// assert_eq!(soup.num_faces(), 2);
/// assert_eq!((report.polygons_triangulated, report.triangles_from_polygons), (1, 2));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct ReadReport {
    /// The format and encoding actually read.
    pub format: Format,
    /// Vertices in the soup.
    pub vertices: u64,
    /// Triangles in the soup.
    pub triangles: u64,
    /// Faces with more than three corners, triangulated without overlaps (see
    /// `envelope_predicates::polygon`).
    pub polygons_triangulated: u64,
    /// Triangles those polygons produced.
    pub triangles_from_polygons: u64,
    /// Repeated consecutive corners (`f 1 2 2 3 4`, or a last corner equal to the first)
    /// dropped from those polygons before triangulating.
    pub polygon_corners_dropped: u64,
    /// Triangle strips expanded (PLY `tristrips`; each run between `-1` restarts counts).
    pub strips_expanded: u64,
    /// Strip triangles with a repeated corner (the usual strip-joining trick), dropped.
    pub strip_triangles_dropped: u64,
    /// STL facet corners that reused an earlier, bitwise-equal vertex.
    pub stl_corners_welded: u64,
    /// Anything else worth knowing (ignored statements, elements or columns), one per line.
    pub notes: Vec<String>,
}

impl ReadReport {
    pub(crate) fn new(format: Format) -> Self {
        Self {
            format,
            vertices: 0,
            triangles: 0,
            polygons_triangulated: 0,
            triangles_from_polygons: 0,
            polygon_corners_dropped: 0,
            strips_expanded: 0,
            strip_triangles_dropped: 0,
            stl_corners_welded: 0,
            notes: Vec::new(),
        }
    }

    pub(crate) fn note(&mut self, note: impl Into<String>) {
        self.notes.push(note.into());
    }
}

impl fmt::Display for ReadReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: {} vertices, {} triangles",
            self.format, self.vertices, self.triangles
        )?;
        if self.polygons_triangulated > 0 {
            write!(
                f,
                "\n{} polygons triangulated into {} triangles",
                self.polygons_triangulated, self.triangles_from_polygons
            )?;
        }
        if self.polygon_corners_dropped > 0 {
            write!(
                f,
                "\n{} repeated consecutive polygon corners dropped",
                self.polygon_corners_dropped
            )?;
        }
        if self.strips_expanded > 0 {
            write!(
                f,
                "\n{} triangle strips expanded, {} degenerate strip triangles dropped",
                self.strips_expanded, self.strip_triangles_dropped
            )?;
        }
        if self.stl_corners_welded > 0 {
            write!(
                f,
                "\n{} STL corners welded to bitwise-equal vertices",
                self.stl_corners_welded
            )?;
        }
        for n in &self.notes {
            write!(f, "\n{n}")?;
        }
        Ok(())
    }
}
