//! Which faces the L-infinity closing swallows, estimated on a voxel grid (issue 37).
//!
//! The alpha-hull of El-Sana and Varshney fills what an axis-aligned cube of side `2 alpha`
//! cannot reach: the morphological closing of the solid by that cube. A surface point stays
//! on the closed solid's boundary when some cube lying in empty space touches it; every other
//! point of the surface is inside the closing, in a tunnel, hole or pocket narrower than the
//! cube. We estimate this on voxels and use it only to *propose* regions:
//!
//! 1. **Solid.** Voxel centres inside the mesh, by the parity of the crossings of a ray along
//!    `+x` (exact orient2d on the projection to `yz`, with the top-left rule on edges so a
//!    shared edge counts once).
//! 2. **Reach.** The union of the cubes (of `2k + 1` voxels, `k = alpha / h` rounded) that
//!    lie in empty voxels: the free space eroded, then dilated, by the cube (separable
//!    running counts, linear in the grid).
//! 3. **Swallowed faces.** A face is swallowed unless the cube reaches it: at least two of
//!    four points of the face (the centroid and the points a third of the way from it to each
//!    corner), moved [`TOUCH_VOXELS`] voxels out along the face's normal, lie in reach voxels.
//!
//! Everything here is f64 and approximate (a voxel is `alpha / 4` wide, coarser when the grid
//! would pass [`MAX_VOXELS`]): a wrong answer only proposes a rim that the exact acceptance of
//! [`crate::reduce_genus`] refuses, or misses one. No guarantee rests on it.

use envelope_mesh::TriangleSoup;
use envelope_predicates::{Orientation, orient2d};
use glam::{DVec2, DVec3};

/// Largest grid, in voxels (one byte each).
pub(crate) const MAX_VOXELS: usize = 1 << 22;

/// Most (face, column) pairs the voxelization looks at, and most crossings it keeps: past
/// either (faces whose projections pile up, as hostile input can) there is no estimate.
const MAX_COLUMN_TESTS: usize = 1 << 28;
const MAX_CROSSINGS: usize = 1 << 23;

/// How far out of the face (in voxels) a point is looked up in the reach.
const TOUCH_VOXELS: f64 = 1.5;

/// Voxels per `alpha` when the grid allows it.
const VOXELS_PER_ALPHA: f64 = 4.0;

/// A voxel grid: `dims[0] * dims[1] * dims[2]` cells of side `h`, x fastest.
struct Grid {
    origin: DVec3,
    h: f64,
    dims: [usize; 3],
}

impl Grid {
    fn len(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    fn index(&self, i: usize, j: usize, k: usize) -> usize {
        i + self.dims[0] * (j + self.dims[1] * k)
    }

    /// The voxel holding `p` (clamped to the grid).
    fn cell(&self, p: DVec3) -> [usize; 3] {
        let q = (p - self.origin) / self.h;
        let c = |x: f64, n: usize| (x.floor().max(0.0) as usize).min(n - 1);
        [
            c(q.x, self.dims[0]),
            c(q.y, self.dims[1]),
            c(q.z, self.dims[2]),
        ]
    }

    fn centre(&self, i: usize, j: usize, k: usize) -> DVec3 {
        self.origin + DVec3::new(i as f64 + 0.5, j as f64 + 0.5, k as f64 + 0.5) * self.h
    }
}

/// For every face of `soup` (closed, consistently oriented; `outward` when its faces face
/// out, as the sign of its signed volume says), whether the L-infinity closing by the cube of
/// side `2 alpha` swallows it (see the module docs). `None` when the grid
/// would be degenerate (no extent, or a cube narrower than one voxel at [`MAX_VOXELS`]) or
/// the voxelization too costly (see [`MAX_COLUMN_TESTS`]).
pub(crate) fn swallowed_faces(soup: &TriangleSoup, alpha: f64, outward: bool) -> Option<Vec<bool>> {
    let (lo, hi) = bounds(soup)?;
    // The cube must pass all around the part: a margin of 2 alpha and two voxels.
    let mut h = alpha / VOXELS_PER_ALPHA;
    if !h.is_normal() {
        return None; // a tiny alpha: voxels of its size would not be numbers apart
    }
    // Voxels per axis, saturating (a part huge against alpha asks for more than exist).
    let dims_for = |h: f64| {
        let ext = (hi - lo) + DVec3::splat(4.0 * alpha + 4.0 * h);
        [ext.x, ext.y, ext.z].map(|e| {
            let n = (e / h).ceil();
            if n.is_finite() && n < MAX_VOXELS as f64 {
                n as usize + 1
            } else {
                usize::MAX
            }
        })
    };
    let mut dims = dims_for(h);
    let total = |d: [usize; 3]| d[0].saturating_mul(d[1]).saturating_mul(d[2]);
    // Each round grows h by at least 5 %, by the cube root of the excess when it is known.
    while total(dims) > MAX_VOXELS {
        h *= ((total(dims) as f64) / MAX_VOXELS as f64).cbrt().max(1.05);
        if !h.is_finite() {
            return None;
        }
        dims = dims_for(h);
    }
    let k = (alpha / h).round() as usize;
    if k == 0 {
        return None;
    }
    let origin = lo - DVec3::splat(2.0 * alpha + 2.0 * h);
    let grid = Grid { origin, h, dims };
    let solid = voxelize(soup, &grid)?;
    // Cube centres: voxels whose cube holds no solid voxel; reach: the union of those cubes.
    let mut centres = dilate(&grid, solid, k);
    for c in &mut centres {
        *c = !*c;
    }
    let reach = dilate(&grid, centres, k);
    let outward = if outward { 1.0 } else { -1.0 };
    let swallowed = soup
        .face_ids()
        .map(|f| {
            let t = soup.triangle(f);
            let c = (t[0] + t[1] + t[2]) / 3.0;
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero() * outward;
            let samples = [
                c,
                (2.0 * c + t[0]) / 3.0,
                (2.0 * c + t[1]) / 3.0,
                (2.0 * c + t[2]) / 3.0,
            ];
            let touched = samples
                .iter()
                .filter(|&&p| {
                    let [i, j, l] = grid.cell(p + n * (TOUCH_VOXELS * h));
                    reach[grid.index(i, j, l)]
                })
                .count();
            touched < 2
        })
        .collect();
    Some(swallowed)
}

/// The bounding box of the referenced vertices.
fn bounds(soup: &TriangleSoup) -> Option<(DVec3, DVec3)> {
    let mut it = soup.face_ids().flat_map(|f| soup.triangle(f));
    let first = it.next()?;
    let (lo, hi) = it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)));
    ((hi - lo).max_element() > 0.0).then_some((lo, hi))
}

/// Whether the projected edge `a -> b` of a counter-clockwise triangle owns the points on it
/// (top-left rule: an edge shared by two triangles is owned by exactly one of them).
fn owns_edge(a: DVec2, b: DVec2) -> bool {
    let d = b - a;
    d.y < 0.0 || (d.y == 0.0 && d.x > 0.0)
}

/// Voxel centres inside the closed mesh, by ray parity along `+x`; `None` past
/// [`MAX_COLUMN_TESTS`] or [`MAX_CROSSINGS`].
fn voxelize(soup: &TriangleSoup, grid: &Grid) -> Option<Vec<bool>> {
    let [nx, ny, nz] = grid.dims;
    let mut tests = 0usize;
    // (column, x) of every crossing of a column's ray with a face.
    let mut crossings: Vec<(usize, f64)> = Vec::new();
    for f in soup.face_ids() {
        let t = soup.triangle(f);
        let mut p = t.map(|v| DVec2::new(v.y, v.z));
        let mut x = t.map(|v| v.x);
        match orient2d(p[0], p[1], p[2]) {
            Orientation::Degenerate => continue,
            Orientation::Negative => {
                p.swap(1, 2);
                x.swap(1, 2);
            }
            Orientation::Positive => {}
        }
        let (lo, hi) = (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]));
        let first = |v: f64, o: f64| (((v - o) / grid.h - 0.5).ceil().max(0.0)) as usize;
        let (j0, k0) = (first(lo.x, grid.origin.y), first(lo.y, grid.origin.z));
        for kk in k0..nz {
            let c = grid.centre(0, 0, kk);
            if c.z > hi.y {
                break;
            }
            for j in j0..ny {
                let c = grid.centre(0, j, kk);
                if c.y > hi.x {
                    break;
                }
                tests += 1;
                if tests > MAX_COLUMN_TESTS || crossings.len() >= MAX_CROSSINGS {
                    return None;
                }
                let q = DVec2::new(c.y, c.z);
                let inside = (0..3).all(|e| {
                    let (a, b) = (p[e], p[(e + 1) % 3]);
                    match orient2d(a, b, q) {
                        Orientation::Positive => true,
                        Orientation::Degenerate => owns_edge(a, b),
                        Orientation::Negative => false,
                    }
                });
                if inside {
                    // Barycentric weights (f64: the crossing's x only places a voxel).
                    let area = (p[1] - p[0]).perp_dot(p[2] - p[0]);
                    let w1 = (q - p[0]).perp_dot(p[2] - p[0]) / -area;
                    let w2 = (p[1] - p[0]).perp_dot(q - p[0]) / area;
                    let xx = x[0] + w1 * (x[1] - x[0]) + w2 * (x[2] - x[0]);
                    crossings.push((j + ny * kk, xx));
                }
            }
        }
    }
    crossings.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut solid = vec![false; grid.len()];
    for run in crossings.chunk_by(|a, b| a.0 == b.0) {
        let col = run[0].0;
        let (j, kk) = (col % ny, col / ny);
        for pair in run.chunks_exact(2) {
            let (a, b) = (pair[0].1, pair[1].1);
            let first = (((a - grid.origin.x) / grid.h - 0.5).ceil().max(0.0)) as usize;
            for i in first..nx {
                if grid.centre(i, 0, 0).x > b {
                    break;
                }
                solid[grid.index(i, j, kk)] = true;
            }
        }
    }
    Some(solid)
}

/// `cells` dilated by the cube of `2k + 1` voxels: separable, one running count per line.
fn dilate(grid: &Grid, mut cells: Vec<bool>, k: usize) -> Vec<bool> {
    let dims = grid.dims;
    let strides = [1, dims[0], dims[0] * dims[1]];
    let mut line: Vec<bool> = Vec::new();
    for axis in 0..3 {
        let n = dims[axis];
        let stride = strides[axis];
        let (o1, o2) = ((axis + 1) % 3, (axis + 2) % 3);
        for a in 0..dims[o1] {
            for b in 0..dims[o2] {
                let base = a * strides[o1] + b * strides[o2];
                line.clear();
                line.extend((0..n).map(|i| cells[base + i * stride]));
                // count of set cells in the window [i - k, i + k]
                let mut count = line[..k.min(n)].iter().filter(|&&s| s).count();
                for i in 0..n {
                    if i + k < n && line[i + k] {
                        count += 1;
                    }
                    if i > k && line[i - k - 1] {
                        count -= 1;
                    }
                    cells[base + i * stride] = count > 0;
                }
            }
        }
    }
    cells
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tessellation::signed_volume;
    use envelope_mesh::generate;

    #[test]
    fn a_narrow_tunnel_is_swallowed_and_a_wide_one_is_not() {
        let part = generate::box_with_tunnel();
        let faces = part.num_faces();
        let outward = signed_volume(&part) >= 0.0;
        let narrow = swallowed_faces(&part, 0.75, outward).unwrap();
        let wide = swallowed_faces(&part, 0.1, outward).unwrap();
        let n_narrow = narrow.iter().filter(|&&s| s).count();
        let n_wide = wide.iter().filter(|&&s| s).count();
        assert!(n_narrow > 0 && n_narrow < faces, "{n_narrow} of {faces}");
        assert_eq!(n_wide, 0);
    }
}
