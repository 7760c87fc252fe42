//! [`FaceGrid`]: the dynamic spatial index of the current approximation's triangles (the
//! paper's octree of section 5.1, here a hashed uniform grid).
//!
//! Each live triangle is stored in every cell its exact bounding box overlaps. Cell
//! coordinates are `floor((x - origin) / cell)` in f64; that map is monotone in `x` (rounded
//! subtraction and division by a positive number are monotone), so two closed boxes that
//! overlap in exact arithmetic always share a cell: no candidate pair is missed, whatever the
//! rounding. A query visits each stored triangle once, in the first cell of the overlap of
//! the two cell ranges (no visited-set needed, so queries take `&self`).
//!
//! The cell starts at twice the mean box extent of the faces. Triangles grow as the surface is
//! simplified: [`FaceGrid::rebalance`] rebuilds the grid when the mean extent exceeds one
//! cell, with a cell of twice the mean extent again, so a typical triangle lies in one to
//! eight cells; rebuilds at least double the cell, so their total cost is amortised. Keys
//! are the three cell coordinates (clamped to 21 bits, still monotone) packed in a `u64`.

use envelope_mesh::{FaceId, HalfEdgeMesh, VertexId};
use envelope_predicates::bvh::Aabb;
use glam::DVec3;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Rebuild when the mean box extent of the live faces exceeds this many cells ...
const REBUILD_AT: f64 = 1.0;
/// ... with this many mean extents per cell.
const NEW_CELL: f64 = 2.0;

/// A cell key: three 21-bit coordinates packed in a `u64`.
type Cell = u64;
type CellRange = ([i32; 3], [i32; 3]);

/// Cell coordinates are clamped to `-LIMIT..LIMIT` (clamping is monotone, so still sound).
const LIMIT: i32 = 1 << 20;

fn key(x: i32, y: i32, z: i32) -> Cell {
    let f = |c: i32| u64::from((c + LIMIT) as u32) & 0x1f_ffff;
    f(x) | (f(y) << 21) | (f(z) << 42)
}

/// A multiply-rotate hasher for cell keys (`std`'s SipHash is several times slower here).
#[derive(Default)]
struct CellHasher(u64);

impl Hasher for CellHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u64(&mut self, i: u64) {
        let h = (self.0.rotate_left(5) ^ i).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
        self.0 = h ^ (h >> 29);
    }
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
}

/// The live triangles of an approximation, by [`FaceId`], in a hashed uniform grid.
#[derive(Clone, Debug)]
pub struct FaceGrid {
    origin: DVec3,
    cell: f64,
    cells: HashMap<Cell, Vec<FaceId>, BuildHasherDefault<CellHasher>>,
    /// Per face id: its corners' ids (`INVALID` when not stored) and its exact box.
    tris: Vec<[VertexId; 3]>,
    boxes: Vec<Aabb>,
    /// Per face id: the lowest cell of its box (where a query that starts below it meets it
    /// first).
    lows: Vec<[i32; 3]>,
    live: usize,
    extent_sum: f64,
}

fn max_extent(b: &Aabb) -> f64 {
    (b.max - b.min).max_element()
}

impl FaceGrid {
    /// An index of every face of `mesh`, with the cell size the mean box extent of its faces.
    #[must_use]
    pub fn from_mesh(mesh: &HalfEdgeMesh) -> Self {
        let mut faces: Vec<(FaceId, [VertexId; 3], Aabb)> = Vec::with_capacity(mesh.num_faces());
        faces.extend(mesh.faces().map(|f| {
            let t = mesh.face_vertices(f);
            (f, t, Aabb::from_triangle(t.map(|v| mesh.position(v))))
        }));
        let mean = faces.iter().map(|x| max_extent(&x.2)).sum::<f64>() / faces.len().max(1) as f64;
        let origin = faces.iter().fold(Aabb::EMPTY, |acc, x| acc.union(&x.2)).min;
        let origin = if origin.is_finite() {
            origin
        } else {
            DVec3::ZERO
        };
        let mut g = Self {
            origin,
            cell: if mean > 0.0 && mean.is_finite() {
                NEW_CELL * mean
            } else {
                1.0
            },
            ..Self::empty()
        };
        // Every face's slot at once (not grown face by face).
        let slots = faces.iter().map(|x| x.0.index() + 1).max().unwrap_or(0);
        g.tris.resize(slots, [VertexId::INVALID; 3]);
        g.boxes.resize(slots, Aabb::EMPTY);
        g.lows.resize(slots, [0; 3]);
        for (f, t, b) in faces {
            g.insert_with_box(f, t, b);
        }
        g
    }

    /// An index with no face (unit cells).
    #[must_use]
    pub fn empty() -> Self {
        Self {
            origin: DVec3::ZERO,
            cell: 1.0,
            cells: HashMap::default(),
            tris: Vec::new(),
            boxes: Vec::new(),
            lows: Vec::new(),
            live: 0,
            extent_sum: 0.0,
        }
    }

    /// Cell size in use.
    #[must_use]
    pub fn cell_size(&self) -> f64 {
        self.cell
    }

    /// Number of stored triangles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.live
    }

    /// True when no triangle is stored.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.live == 0
    }

    fn coord(&self, x: f64, o: f64) -> i32 {
        // Saturating float-to-int cast and clamp: both monotone.
        (((x - o) / self.cell).floor() as i32).clamp(-LIMIT, LIMIT - 1)
    }

    fn range(&self, b: &Aabb) -> CellRange {
        (
            [0, 1, 2].map(|k| self.coord(b.min[k], self.origin[k])),
            [0, 1, 2].map(|k| self.coord(b.max[k], self.origin[k])),
        )
    }

    /// Stores face `f` with corners `tri` at positions `corners`.
    ///
    /// # Panics
    /// If `f` is already stored.
    pub fn insert(&mut self, f: FaceId, tri: [VertexId; 3], corners: [DVec3; 3]) {
        self.insert_with_box(f, tri, Aabb::from_triangle(corners));
    }

    fn insert_with_box(&mut self, f: FaceId, tri: [VertexId; 3], b: Aabb) {
        let i = f.index();
        if self.tris.len() <= i {
            self.tris.resize(i + 1, [VertexId::INVALID; 3]);
            self.boxes.resize(i + 1, Aabb::EMPTY);
            self.lows.resize(i + 1, [0; 3]);
        }
        assert!(!self.tris[i][0].is_valid(), "face {f} stored twice");
        self.tris[i] = tri;
        self.boxes[i] = b;
        self.live += 1;
        self.extent_sum += max_extent(&b);
        let (lo, hi) = self.range(&b);
        self.lows[i] = lo;
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    self.cells.entry(key(x, y, z)).or_default().push(f);
                }
            }
        }
    }

    /// Removes face `f` (no-op when not stored).
    pub fn remove(&mut self, f: FaceId) {
        let i = f.index();
        if i >= self.tris.len() || !self.tris[i][0].is_valid() {
            return;
        }
        let b = self.boxes[i];
        let (lo, hi) = self.range(&b);
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    let key = key(x, y, z);
                    if let Some(list) = self.cells.get_mut(&key) {
                        if let Some(k) = list.iter().position(|&g| g == f) {
                            list.swap_remove(k);
                        }
                        if list.is_empty() {
                            self.cells.remove(&key);
                        }
                    }
                }
            }
        }
        self.tris[i] = [VertexId::INVALID; 3];
        self.live -= 1;
        self.extent_sum -= max_extent(&b);
    }

    /// The box stored for face `f` (meaningful while `f` is stored).
    pub(crate) fn bounds(&self, f: FaceId) -> Aabb {
        self.boxes[f.index()]
    }

    /// The corners of stored face `f`, if stored.
    #[must_use]
    pub fn get(&self, f: FaceId) -> Option<[VertexId; 3]> {
        self.tris
            .get(f.index())
            .copied()
            .filter(|t| t[0].is_valid())
    }

    /// Calls `visit(face, corners)` once for every stored face whose box overlaps `query`
    /// (possibly a few more whose boxes only share a cell); stops when `visit` returns true
    /// and returns true then.
    pub fn any_overlapping(
        &self,
        query: &Aabb,
        mut visit: impl FnMut(FaceId, [VertexId; 3]) -> bool,
    ) -> bool {
        let (qlo, qhi) = self.range(query);
        // A query wider than the occupied cells (a tolerance reach at a huge epsilon) scans
        // the stored faces instead: the work stays bounded by the mesh, each face visited
        // once.
        let span: f64 = (0..3)
            .map(|k| f64::from(qhi[k]) - f64::from(qlo[k]) + 1.0)
            .product();
        if span > self.cells.len() as f64 {
            return self.tris.iter().enumerate().any(|(i, &t)| {
                t[0].is_valid() && self.boxes[i].overlaps(query) && visit(FaceId::from_index(i), t)
            });
        }
        for x in qlo[0]..=qhi[0] {
            for y in qlo[1]..=qhi[1] {
                for z in qlo[2]..=qhi[2] {
                    let Some(list) = self.cells.get(&key(x, y, z)) else {
                        continue;
                    };
                    for &f in list {
                        let b = &self.boxes[f.index()];
                        if !b.overlaps(query) {
                            continue;
                        }
                        // Visit only in the first cell of the overlap of both ranges.
                        let lo = self.lows[f.index()];
                        if [x, y, z] != [lo[0].max(qlo[0]), lo[1].max(qlo[1]), lo[2].max(qlo[2])] {
                            continue;
                        }
                        if visit(f, self.tris[f.index()]) {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }

    /// Rebuilds with a larger cell when the mean box extent exceeds one cell. Returns true
    /// when it rebuilt.
    pub fn rebalance(&mut self) -> bool {
        if self.live == 0 {
            return false;
        }
        let mean = self.extent_sum / self.live as f64;
        if mean <= REBUILD_AT * self.cell {
            return false;
        }
        let stored: Vec<(FaceId, [VertexId; 3], Aabb)> = (0..self.tris.len())
            .filter(|&i| self.tris[i][0].is_valid())
            .map(|i| (FaceId::from_index(i), self.tris[i], self.boxes[i]))
            .collect();
        self.cell = (NEW_CELL * mean).max(2.0 * self.cell);
        self.cells.clear();
        self.tris
            .iter_mut()
            .for_each(|t| *t = [VertexId::INVALID; 3]);
        self.live = 0;
        self.extent_sum = 0.0;
        for (f, t, b) in stored {
            self.insert_with_box(f, t, b);
        }
        true
    }

    /// Checks that the grid stores exactly the faces of `mesh`, with their corners, each in
    /// every cell its box overlaps.
    pub fn sanity_check(&self, mesh: &HalfEdgeMesh) -> Result<(), String> {
        let mut n = 0;
        for f in mesh.faces() {
            n += 1;
            if self.get(f) != Some(mesh.face_vertices(f)) {
                return Err(format!(
                    "face {f} missing from the grid or with other corners"
                ));
            }
            let (lo, hi) = self.range(&self.boxes[f.index()]);
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        if !self
                            .cells
                            .get(&key(x, y, z))
                            .is_some_and(|l| l.contains(&f))
                        {
                            return Err(format!("face {f} missing from cell {x},{y},{z}"));
                        }
                    }
                }
            }
        }
        if n != self.live {
            return Err(format!("grid stores {} faces, mesh has {n}", self.live));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::generate;

    /// Queries agree with brute force over box overlap, before and after edits and rebuilds.
    #[test]
    fn queries_match_brute_force() {
        let mut m = HalfEdgeMesh::from_soup(&generate::icosphere(3, 1.0)).unwrap();
        let mut g = FaceGrid::from_mesh(&m);
        g.sanity_check(&m).unwrap();
        let check = |g: &FaceGrid, m: &HalfEdgeMesh| {
            for f in m.faces().step_by(7) {
                let t = m.face_vertices(f).map(|v| m.position(v));
                let q = Aabb::from_triangle([t[0] * 1.3, t[1] * 0.8, t[2]]);
                let mut got = Vec::new();
                g.any_overlapping(&q, |h, _| {
                    got.push(h);
                    false
                });
                got.sort();
                let n = got.len();
                got.dedup();
                assert_eq!(n, got.len(), "a face visited twice");
                let want: Vec<FaceId> = m
                    .faces()
                    .filter(|&h| {
                        let b = Aabb::from_triangle(m.face_vertices(h).map(|v| m.position(v)));
                        b.overlaps(&q)
                    })
                    .collect();
                assert_eq!(got, want);
            }
            // A query far wider than the mesh (the scan, not the cells): every face once.
            let mut all = Vec::new();
            g.any_overlapping(&Aabb::from_points(&[DVec3::ZERO]).inflated(1e20), |h, _| {
                all.push(h);
                false
            });
            all.sort();
            assert_eq!(all, m.faces().collect::<Vec<_>>());
        };
        check(&g, &m);
        // Remove a few fans; grow the boxes by hand through a rebuild.
        for v in [VertexId(0), VertexId(40), VertexId(200)] {
            let fan: Vec<FaceId> = m.vertex_faces(v).collect();
            for &f in &fan {
                g.remove(f);
            }
            m.remove_vertex_fan(v).unwrap();
        }
        g.sanity_check(&m).unwrap();
        check(&g, &m);
        g.cell *= 0.25;
        assert!(g.rebalance());
        g.sanity_check(&m).unwrap();
        check(&g, &m);
    }
}
