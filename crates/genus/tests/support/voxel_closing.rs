//! An independent estimate of what the L-infinity alpha-hull closes: voxelize the solid a
//! closed mesh bounds, close it with a cube of side `2 alpha` (dilate then erode, both with
//! the cube of radius `alpha`), and count the genus of the closed solid's boundary from the
//! Euler characteristic of the voxel complex.
//!
//! Test and bench code only; it shares nothing with `envelope-genus` (no predicate, no
//! adjacency, no prism): f64 ray parity along x, a separable max filter, and a cell count.
//! The voxel size limits it: tunnels within a voxel or two of `2 alpha` may go either way,
//! so tests use parts whose tunnels are clearly narrower or wider.

#![allow(dead_code)]

use envelope_mesh::TriangleSoup;
use glam::DVec3;

/// A solid on a regular grid: `dims` voxels of side `h` from `origin`.
pub struct Voxels {
    /// Voxel counts along x, y, z.
    pub dims: [usize; 3],
    /// Filled flags, x fastest.
    pub filled: Vec<bool>,
}

impl Voxels {
    fn index(&self, i: usize, j: usize, k: usize) -> usize {
        i + self.dims[0] * (j + self.dims[1] * k)
    }

    /// Filled, with everything outside the grid empty.
    fn at(&self, i: i64, j: i64, k: i64) -> bool {
        let d = self.dims;
        i >= 0
            && j >= 0
            && k >= 0
            && (i as usize) < d[0]
            && (j as usize) < d[1]
            && (k as usize) < d[2]
            && self.filled[self.index(i as usize, j as usize, k as usize)]
    }
}

/// The solid bounded by the closed mesh `soup`, sampled at voxel centres on a grid of side
/// `h` padded by `pad` empty voxels on every side. Inside is decided by the parity of
/// crossings of a ray along +x (rays are offset by an irrational fraction of `h` so they
/// miss the edges of meshes with round coordinates).
pub fn voxelize(soup: &TriangleSoup, h: f64, pad: usize) -> Voxels {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for p in &soup.positions {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let padf = pad as f64 * h;
    let origin = lo - DVec3::splat(padf);
    let dims: [usize; 3] =
        std::array::from_fn(|a| ((hi[a] - lo[a]) / h).ceil() as usize + 2 * pad + 1);
    let mut v = Voxels {
        dims,
        filled: vec![false; dims[0] * dims[1] * dims[2]],
    };
    // Sample y and z at centres shifted by irrational fractions.
    let (sy, sz) = (0.5 + 0.013_579_246_8, 0.5 - 0.021_436_587_9);
    let yc = |j: usize| origin.y + (j as f64 + sy) * h;
    let zc = |k: usize| origin.z + (k as f64 + sz) * h;
    // Bin the triangles by the columns their yz bounding boxes cover.
    let mut bins: Vec<Vec<usize>> = vec![Vec::new(); dims[1] * dims[2]];
    for (f, t) in soup.faces.iter().enumerate() {
        let p = t.map(|w| soup.positions[w.index()]);
        let (ylo, yhi) = (
            p[0].y.min(p[1].y).min(p[2].y),
            p[0].y.max(p[1].y).max(p[2].y),
        );
        let (zlo, zhi) = (
            p[0].z.min(p[1].z).min(p[2].z),
            p[0].z.max(p[1].z).max(p[2].z),
        );
        let j0 = (((ylo - origin.y) / h - sy).floor().max(0.0)) as usize;
        let j1 = (((yhi - origin.y) / h - sy).ceil().max(0.0) as usize).min(dims[1] - 1);
        let k0 = (((zlo - origin.z) / h - sz).floor().max(0.0)) as usize;
        let k1 = (((zhi - origin.z) / h - sz).ceil().max(0.0) as usize).min(dims[2] - 1);
        for k in k0..=k1 {
            for j in j0..=j1 {
                bins[j + dims[1] * k].push(f);
            }
        }
    }
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            let (y, z) = (yc(j), zc(k));
            let mut xs: Vec<f64> = Vec::new();
            for &f in &bins[j + dims[1] * k] {
                let p = soup.faces[f].map(|w| soup.positions[w.index()]);
                // Barycentric coordinates of (y, z) in the yz projection.
                let d =
                    (p[1].y - p[0].y) * (p[2].z - p[0].z) - (p[2].y - p[0].y) * (p[1].z - p[0].z);
                if d == 0.0 {
                    continue;
                }
                let b1 = ((y - p[0].y) * (p[2].z - p[0].z) - (p[2].y - p[0].y) * (z - p[0].z)) / d;
                let b2 = ((p[1].y - p[0].y) * (z - p[0].z) - (y - p[0].y) * (p[1].z - p[0].z)) / d;
                let b0 = 1.0 - b1 - b2;
                if b0 >= 0.0 && b1 >= 0.0 && b2 >= 0.0 {
                    xs.push(b0 * p[0].x + b1 * p[1].x + b2 * p[2].x);
                }
            }
            xs.sort_by(f64::total_cmp);
            for i in 0..dims[0] {
                let x = origin.x + (i as f64 + 0.5) * h;
                let crossings = xs.iter().filter(|&&c| c < x).count();
                if crossings % 2 == 1 {
                    let idx = v.index(i, j, k);
                    v.filled[idx] = true;
                }
            }
        }
    }
    v
}

/// Dilation by the cube of radius `r` voxels (a separable max filter; outside is empty).
fn dilate(v: &Voxels, r: usize) -> Voxels {
    let mut cur = v.filled.clone();
    let d = v.dims;
    for axis in 0..3 {
        let mut next = vec![false; cur.len()];
        for k in 0..d[2] {
            for j in 0..d[1] {
                for i in 0..d[0] {
                    let c = [i, j, k];
                    let lo = c[axis].saturating_sub(r);
                    let hi = (c[axis] + r).min(d[axis] - 1);
                    let any = (lo..=hi).any(|m| {
                        let mut q = c;
                        q[axis] = m;
                        cur[q[0] + d[0] * (q[1] + d[1] * q[2])]
                    });
                    next[i + d[0] * (j + d[1] * k)] = any;
                }
            }
        }
        cur = next;
    }
    Voxels {
        dims: d,
        filled: cur,
    }
}

/// Closing by the cube of radius `r` voxels: dilate, then erode (erosion is the complement
/// of the dilation of the complement; the grid must be padded by more than `r`).
pub fn close(v: &Voxels, r: usize) -> Voxels {
    let dil = dilate(v, r);
    let comp = Voxels {
        dims: dil.dims,
        filled: dil.filled.iter().map(|&b| !b).collect(),
    };
    let back = dilate(&comp, r);
    Voxels {
        dims: back.dims,
        filled: back.filled.iter().map(|&b| !b).collect(),
    }
}

/// Euler characteristic of the union of the closed filled voxels (vertices - edges + faces
/// - cubes of the cubical complex).
pub fn euler_solid(v: &Voxels) -> i64 {
    let d = v.dims;
    let mut chi = 0i64;
    // Lattice cells: a cell with "odd" coordinates along a set of axes spans those axes.
    // Cell (i, j, k, mask): touches the voxels around it in the axes not in the mask.
    for k in 0..=d[2] as i64 {
        for j in 0..=d[1] as i64 {
            for i in 0..=d[0] as i64 {
                for mask in 0..8u32 {
                    let span = [mask & 1 != 0, mask & 2 != 0, mask & 4 != 0];
                    if (0..3).any(|a| span[a] && [i, j, k][a] == d[a] as i64) {
                        continue;
                    }
                    // The voxels containing this cell: along spanned axes the voxel index
                    // is fixed, along the others it is c - 1 or c.
                    let mut present = false;
                    'around: for di in 0..2i64 {
                        for dj in 0..2i64 {
                            for dk in 0..2i64 {
                                let q = [
                                    if span[0] { i } else { i - di },
                                    if span[1] { j } else { j - dj },
                                    if span[2] { k } else { k - dk },
                                ];
                                if v.at(q[0], q[1], q[2]) {
                                    present = true;
                                    break 'around;
                                }
                            }
                        }
                    }
                    if present {
                        let dim = mask.count_ones();
                        chi += if dim % 2 == 0 { 1 } else { -1 };
                    }
                }
            }
        }
    }
    chi
}

/// Connected components of the filled voxels (26-connected: closed cubes sharing a corner
/// meet) and of the empty voxels (6-connected), the outside included.
fn components(v: &Voxels, filled: bool) -> usize {
    let d = v.dims;
    let mut seen = vec![false; v.filled.len()];
    let mut count = 0;
    let mut stack = Vec::new();
    for start in 0..v.filled.len() {
        if seen[start] || v.filled[start] != filled {
            continue;
        }
        count += 1;
        seen[start] = true;
        stack.push(start);
        while let Some(c) = stack.pop() {
            let (i, j, k) = (c % d[0], (c / d[0]) % d[1], c / (d[0] * d[1]));
            for dk in -1i64..=1 {
                for dj in -1i64..=1 {
                    for di in -1i64..=1 {
                        let steps = di.abs() + dj.abs() + dk.abs();
                        if steps == 0 || (!filled && steps > 1) {
                            continue;
                        }
                        let q = [i as i64 + di, j as i64 + dj, k as i64 + dk];
                        if (0..3).any(|a| q[a] < 0 || q[a] >= d[a] as i64) {
                            continue;
                        }
                        let n = q[0] as usize + d[0] * (q[1] as usize + d[1] * q[2] as usize);
                        if !seen[n] && v.filled[n] == filled {
                            seen[n] = true;
                            stack.push(n);
                        }
                    }
                }
            }
        }
    }
    count
}

/// The total genus of the boundary of the solid (summed over boundary components): with
/// `c` boundary components (solid components plus cavities) and `chi(boundary) = 2 chi`,
/// `genus = c - chi`.
pub fn genus(v: &Voxels) -> i64 {
    let boundary_components = components(v, true) as i64 + components(v, false) as i64 - 1;
    boundary_components - euler_solid(v)
}

/// The genus of the L-infinity closing of the solid bounded by `soup` with the cube of
/// side `2 alpha`, on voxels of side `h`: the cube is `2 r + 1` voxels wide with `r` the
/// nearest whole number to `(2 alpha / h - 1) / 2`.
pub fn closing_genus(soup: &TriangleSoup, alpha: f64, h: f64) -> i64 {
    let r = ((2.0 * alpha / h - 1.0) / 2.0).round().max(0.0) as usize;
    let v = voxelize(soup, h, r + 2);
    genus(&close(&v, r))
}

/// The genus of the voxelized solid itself (no closing): a check of the voxelization.
pub fn voxel_genus(soup: &TriangleSoup, h: f64) -> i64 {
    genus(&voxelize(soup, h, 1))
}
