//! Helpers every reader uses to build a [`TriangleSoup`] and its [`ReadReport`]: the
//! coordinate check, polygon triangulation, and the final "has faces, fits in 32-bit ids" check.

use std::ops::Range;

use envelope_mesh::{TriangleSoup, VertexId, check_coordinate};
use envelope_predicates::polygon::triangulate_polygon;
use glam::DVec3;

use crate::error::{Axis, Location, ReadError, ReadErrorKind};
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

/// Per triangle, the number of each corner among all corners as written.
pub(crate) type CornerOrigins = Vec<[u64; 3]>;

/// The faces of a file as they are read. Triangles are kept as written; polygons are checked
/// for repeated corners at once and triangulated ([`triangulate_polygon`]) when all positions
/// are known (a PLY file may list its faces before its vertices), their triangles keeping the
/// polygon's place in face order.
pub(crate) struct Faces {
    triangles: Vec<[VertexId; 3]>,
    pending: Vec<Pending>,
    /// Corners of the pending polygons, one after another.
    corners: Vec<u32>,
    /// (vertex, 1-based corner position as written) of the polygon being added.
    kept: Vec<(u32, u64)>,
    /// With [`Faces::track_corners`]: per triangle, the number of each corner among all
    /// corners as written (so a reader can find the corner's attribute indices).
    origins: Option<Vec<[u64; 3]>>,
    /// Corners as written so far (counted only while tracking).
    written: u64,
    /// With tracking: the written number of each pending polygon corner, beside `corners`.
    corner_origins: Vec<u64>,
}

/// A polygon whose triangles are still to be computed.
struct Pending {
    face: u64,
    at: Location,
    /// Its first triangle in `Faces::triangles` (placeholders until resolved).
    first: usize,
    /// Its corners in `Faces::corners`.
    corners: Range<usize>,
}

impl Faces {
    pub(crate) fn new() -> Self {
        Self {
            triangles: Vec::new(),
            pending: Vec::new(),
            corners: Vec::new(),
            kept: Vec::new(),
            origins: None,
            written: 0,
            corner_origins: Vec::new(),
        }
    }

    /// Records, per triangle, which written corners it was made of (see
    /// [`Faces::resolve_with_origins`]); only for [`Faces::push_polygon`], not strips.
    pub(crate) fn track_corners(&mut self) {
        self.origins = Some(Vec::new());
    }

    pub(crate) fn reserve(&mut self, n: usize) {
        self.triangles.reserve(n);
    }

    /// Appends polygon `poly` (already range-checked) of face number `face`, read at `at`.
    pub(crate) fn push_polygon(
        &mut self,
        poly: &[u32],
        face: u64,
        at: Location,
        report: &mut ReadReport,
    ) -> Result<(), ReadErrorKind> {
        let base = self.written;
        if self.origins.is_some() {
            self.written += poly.len() as u64;
        }
        match poly.len() {
            n if n < 3 => {
                return Err(ReadErrorKind::TooFewCorners {
                    face,
                    corners: n as u64,
                });
            }
            // Triangles are kept as written; the input checker reports degenerate ones.
            3 => {
                self.triangles
                    .push([VertexId(poly[0]), VertexId(poly[1]), VertexId(poly[2])]);
                if let Some(o) = &mut self.origins {
                    o.push([base, base + 1, base + 2]);
                }
                return Ok(());
            }
            _ => {}
        }
        self.kept.clear();
        for (k, &v) in poly.iter().enumerate() {
            if self.kept.last().map(|l| l.0) != Some(v) {
                self.kept.push((v, k as u64 + 1));
            }
        }
        while self.kept.len() > 1 && self.kept.last().map(|l| l.0) == Some(self.kept[0].0) {
            self.kept.pop();
        }
        let m = self.kept.len();
        report.polygon_corners_dropped += (poly.len() - m) as u64;
        // A vertex met twice (sorting keeps the cost n log n).
        let mut sorted = self.kept.clone();
        sorted.sort_unstable();
        if let Some(w) = sorted.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(ReadErrorKind::RepeatedCorner {
                face,
                first: w[0].1,
                second: w[1].1,
            });
        }
        if m < 3 {
            return Err(ReadErrorKind::TooFewCorners {
                face,
                corners: m as u64,
            });
        }
        report.polygons_triangulated += 1;
        report.triangles_from_polygons += (m - 2) as u64;
        if m == 3 {
            let [a, b, c] = [0, 1, 2].map(|i| VertexId(self.kept[i].0));
            self.triangles.push([a, b, c]);
            if let Some(o) = &mut self.origins {
                o.push([0, 1, 2].map(|i| base + self.kept[i].1 - 1));
            }
            return Ok(());
        }
        let start = self.corners.len();
        self.corners.extend(self.kept.iter().map(|&(v, _)| v));
        if let Some(o) = &mut self.origins {
            self.corner_origins
                .extend(self.kept.iter().map(|&(_, k)| base + k - 1));
            o.resize(o.len() + m - 2, [u64::MAX; 3]);
        }
        self.pending.push(Pending {
            face,
            at,
            first: self.triangles.len(),
            corners: start..self.corners.len(),
        });
        self.triangles
            .resize(self.triangles.len() + m - 2, [VertexId(u32::MAX); 3]);
        Ok(())
    }

    /// Appends the triangles of one strip (already range-checked; no restart markers):
    /// triangle `k` is `(s[k], s[k+1], s[k+2])` for even `k` and `(s[k+1], s[k], s[k+2])` for
    /// odd `k`, so all share the first triangle's orientation. Triangles with a repeated
    /// corner are dropped.
    pub(crate) fn push_strip(&mut self, s: &[u32], report: &mut ReadReport) {
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
                self.triangles.push([VertexId(a), VertexId(b), VertexId(c)]);
            }
        }
    }

    /// The triangles, polygons triangulated on `positions` (which every index is below).
    pub(crate) fn resolve(self, positions: &[DVec3]) -> Result<Vec<[VertexId; 3]>, ReadError> {
        Ok(self.resolve_with_origins(positions)?.0)
    }

    /// [`Faces::resolve`], and with [`Faces::track_corners`] the written corner number of
    /// each triangle corner.
    pub(crate) fn resolve_with_origins(
        mut self,
        positions: &[DVec3],
    ) -> Result<(Vec<[VertexId; 3]>, Option<CornerOrigins>), ReadError> {
        let mut corners = Vec::new();
        for p in &self.pending {
            let ids = &self.corners[p.corners.clone()];
            corners.clear();
            corners.extend(ids.iter().map(|&v| positions[v as usize]));
            let not_simple = || {
                ReadError::new(
                    p.at,
                    ReadErrorKind::NotSimplePolygon {
                        face: p.face,
                        corners: ids.len() as u64,
                    },
                )
            };
            let triangles = triangulate_polygon(&corners).map_err(|_| not_simple())?;
            if triangles.len() != ids.len() - 2 {
                return Err(not_simple());
            }
            if let Some(o) = &mut self.origins {
                let written = &self.corner_origins[p.corners.clone()];
                for (slot, t) in o[p.first..].iter_mut().zip(&triangles) {
                    *slot = t.map(|i| written[i as usize]);
                }
            }
            for (slot, t) in self.triangles[p.first..].iter_mut().zip(triangles) {
                *slot = t.map(|i| VertexId(ids[i as usize]));
            }
        }
        Ok((self.triangles, self.origins))
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
