//! Helpers every reader uses to build a [`TriangleSoup`] and its [`ReadReport`]: the
//! coordinate check, fan triangulation, and the final "has faces, fits in 32-bit ids" check.

use envelope_mesh::{TriangleSoup, VertexId, check_coordinate};
use glam::DVec3;

use crate::error::{Axis, ReadErrorKind};
use crate::report::ReadReport;

/// Checks the three coordinates of vertex number `vertex`.
#[inline]
pub(crate) fn checked_position(p: [f64; 3], vertex: u64) -> Result<DVec3, ReadErrorKind> {
    for (axis, &x) in Axis::ALL.iter().zip(&p) {
        if let Err(error) = check_coordinate(x) {
            return Err(ReadErrorKind::Coordinate {
                vertex,
                axis: *axis,
                error,
            });
        }
    }
    Ok(DVec3::from_array(p))
}

/// Appends polygon `poly` (already range-checked), fan-triangulated from its first corner.
pub(crate) fn push_polygon(
    faces: &mut Vec<[VertexId; 3]>,
    poly: &[u32],
    face: u64,
    report: &mut ReadReport,
) -> Result<(), ReadErrorKind> {
    match poly.len() {
        n if n < 3 => {
            return Err(ReadErrorKind::TooFewCorners {
                face,
                corners: n as u64,
            });
        }
        3 => faces.push([VertexId(poly[0]), VertexId(poly[1]), VertexId(poly[2])]),
        n => {
            for i in 1..n - 1 {
                faces.push([VertexId(poly[0]), VertexId(poly[i]), VertexId(poly[i + 1])]);
            }
            report.polygons_triangulated += 1;
            report.triangles_from_polygons += (n - 2) as u64;
        }
    }
    Ok(())
}

/// Appends the triangles of one strip (already range-checked; no restart markers): triangle
/// `k` is `(s[k], s[k+1], s[k+2])` for even `k` and `(s[k+1], s[k], s[k+2])` for odd `k`, so
/// all share the first triangle's orientation. Triangles with a repeated corner are dropped.
pub(crate) fn push_strip(faces: &mut Vec<[VertexId; 3]>, s: &[u32], report: &mut ReadReport) {
    if s.is_empty() {
        return;
    }
    report.strips_expanded += 1;
    for k in 0..s.len().saturating_sub(2) {
        let (a, b, c) = if k % 2 == 0 {
            (s[k], s[k + 1], s[k + 2])
        } else {
            (s[k + 1], s[k], s[k + 2])
        };
        if a == b || b == c || a == c {
            report.strip_triangles_dropped += 1;
        } else {
            faces.push([VertexId(a), VertexId(b), VertexId(c)]);
        }
    }
}

/// Converts a file index to a vertex id when it is in `0..vertices`.
#[inline]
pub(crate) fn vertex_index(
    index: i64,
    vertices: u64,
    what: &'static str,
    element: u64,
) -> Result<u32, ReadErrorKind> {
    if index >= 0 && (index as u64) < vertices {
        Ok(index as u32)
    } else {
        Err(ReadErrorKind::IndexOutOfRange {
            what,
            element,
            index,
            vertices,
        })
    }
}

/// Rejects vertex counts that do not fit vertex ids (`u32::MAX` is the invalid id).
pub(crate) fn check_vertex_count(n: u64) -> Result<(), ReadErrorKind> {
    if n >= u64::from(u32::MAX) {
        Err(ReadErrorKind::TooMany("vertices"))
    } else {
        Ok(())
    }
}

/// Final checks shared by all readers.
pub(crate) fn finish(
    positions: Vec<DVec3>,
    faces: Vec<[VertexId; 3]>,
    mut report: ReadReport,
) -> Result<(TriangleSoup, ReadReport), ReadErrorKind> {
    if faces.is_empty() {
        return Err(ReadErrorKind::NoFaces);
    }
    if faces.len() >= u32::MAX as usize {
        return Err(ReadErrorKind::TooMany("faces"));
    }
    report.vertices = positions.len() as u64;
    report.triangles = faces.len() as u64;
    Ok((TriangleSoup::new(positions, faces), report))
}
