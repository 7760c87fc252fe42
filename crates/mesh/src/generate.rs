//! Deterministic test meshes with known topology.
//!
//! Every closed or bordered surface here is a consistently oriented 2-manifold with outward
//! (counter-clockwise seen from outside) faces and shared vertices. Positions are f64
//! constructions with no exactness claim. A few deliberately broken soups ([`bow_tie`],
//! [`three_triangles_on_edge`], [`moebius_strip`]) exercise the degeneracy finders.
//!
//! | generator | components | border loops | genus |
//! |---|---|---|---|
//! | [`tetrahedron`], [`icosphere`], [`uv_sphere`], [`box_mesh`], [`block_with_pocket`] | 1 | 0 | 0 |
//! | [`torus`], [`box_with_tunnel`] | 1 | 0 | 1 |
//! | [`plate_with_holes`]`(k)` | 1 | 0 | k |
//! | [`open_cylinder`] | 1 | 2 | 0 |
//! | [`demo_model`] (a cup) | 1 | 1 | 0 |
//! | [`disk_with_holes`]`(k)` | 1 | k + 1 | 0 |

use crate::{TriangleSoup, VertexId};
use glam::DVec3;
use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

fn soup(positions: Vec<DVec3>, faces: Vec<[u32; 3]>) -> TriangleSoup {
    TriangleSoup::new(
        positions,
        faces.into_iter().map(|f| f.map(VertexId)).collect(),
    )
}

/// Pushes quad `a b c d` (counter-clockwise) as triangles `a b c` and `a c d`.
fn quad(faces: &mut Vec<[u32; 3]>, [a, b, c, d]: [u32; 4]) {
    faces.push([a, b, c]);
    faces.push([a, c, d]);
}

/// The tetrahedron on the origin and the three unit points: V4 E6 F4, genus 0.
#[must_use]
pub fn tetrahedron() -> TriangleSoup {
    TriangleSoup::from_raw(
        &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
}

/// An icosahedron subdivided `subdivisions` times (each triangle into four), projected onto
/// the sphere of `radius` about the origin. Vertices 0..12 are the icosahedron's (valence 5);
/// `10 * 4^s + 2` vertices, `20 * 4^s` faces.
///
/// ```
/// let s = envelope_mesh::generate::icosphere(2, 1.0);
/// assert_eq!((s.num_vertices(), s.num_faces()), (162, 320));
/// ```
#[must_use]
pub fn icosphere(subdivisions: u32, radius: f64) -> TriangleSoup {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut pos: Vec<DVec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|&p| DVec3::from_array(p).normalize())
    .collect();
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mut midpoint = |a: u32, b: u32, pos: &mut Vec<DVec3>| -> u32 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                pos.push(((pos[a as usize] + pos[b as usize]) * 0.5).normalize());
                (pos.len() - 1) as u32
            })
        };
        let mut next = Vec::with_capacity(faces.len() * 4);
        for [a, b, c] in faces {
            let ab = midpoint(a, b, &mut pos);
            let bc = midpoint(b, c, &mut pos);
            let ca = midpoint(c, a, &mut pos);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = next;
    }
    soup(pos.into_iter().map(|p| p * radius).collect(), faces)
}

/// A latitude-longitude sphere: two poles, `n_rings - 1` rings of `n_around` vertices.
/// Needs `n_around >= 3`, `n_rings >= 2`.
#[must_use]
pub fn uv_sphere(n_around: u32, n_rings: u32, radius: f64) -> TriangleSoup {
    assert!(
        n_around >= 3 && n_rings >= 2,
        "uv_sphere needs n_around >= 3, n_rings >= 2"
    );
    let mut pos = vec![DVec3::Z * radius];
    for j in 1..n_rings {
        let th = PI * f64::from(j) / f64::from(n_rings);
        for i in 0..n_around {
            let u = TAU * f64::from(i) / f64::from(n_around);
            pos.push(DVec3::new(th.sin() * u.cos(), th.sin() * u.sin(), th.cos()) * radius);
        }
    }
    let bottom = pos.len() as u32;
    pos.push(-DVec3::Z * radius);
    let ring = |i: u32, j: u32| 1 + (j - 1) * n_around + i % n_around;
    let mut faces = Vec::new();
    for i in 0..n_around {
        faces.push([0, ring(i, 1), ring(i + 1, 1)]);
        for j in 1..n_rings - 1 {
            quad(
                &mut faces,
                [
                    ring(i, j + 1),
                    ring(i + 1, j + 1),
                    ring(i + 1, j),
                    ring(i, j),
                ],
            );
        }
        faces.push([bottom, ring(i + 1, n_rings - 1), ring(i, n_rings - 1)]);
    }
    soup(pos, faces)
}

/// A torus about the z axis: tube centre radius `major`, tube radius `minor`, `nu` segments
/// around the axis and `nv` around the tube (both >= 3). Genus 1.
#[must_use]
pub fn torus(major: f64, minor: f64, nu: u32, nv: u32) -> TriangleSoup {
    assert!(nu >= 3 && nv >= 3, "torus needs nu, nv >= 3");
    let mut pos = Vec::new();
    for i in 0..nu {
        let u = TAU * f64::from(i) / f64::from(nu);
        for j in 0..nv {
            let v = TAU * f64::from(j) / f64::from(nv);
            let r = major + minor * v.cos();
            pos.push(DVec3::new(r * u.cos(), r * u.sin(), minor * v.sin()));
        }
    }
    let id = |i: u32, j: u32| (i % nu) * nv + j % nv;
    let mut faces = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            quad(
                &mut faces,
                [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
            );
        }
    }
    soup(pos, faces)
}

/// The side of a cylinder about the z axis from `z = 0` to `z = height`, `n_around >= 3`
/// segments around and `n_up >= 1` rows; normals point away from the axis. Two border loops.
#[must_use]
pub fn open_cylinder(radius: f64, height: f64, n_around: u32, n_up: u32) -> TriangleSoup {
    assert!(
        n_around >= 3 && n_up >= 1,
        "open_cylinder needs n_around >= 3, n_up >= 1"
    );
    let mut pos = Vec::new();
    for j in 0..=n_up {
        for i in 0..n_around {
            let u = TAU * f64::from(i) / f64::from(n_around);
            let z = height * f64::from(j) / f64::from(n_up);
            pos.push(DVec3::new(radius * u.cos(), radius * u.sin(), z));
        }
    }
    let id = |i: u32, j: u32| j * n_around + i % n_around;
    let mut faces = Vec::new();
    for j in 0..n_up {
        for i in 0..n_around {
            quad(
                &mut faces,
                [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
            );
        }
    }
    soup(pos, faces)
}

/// The built-in model of `envelope demo`: a cup with a flat bottom, a bulging, fluted wall
/// (curvature in both directions), a sharp crease where wall and bottom meet, and an open
/// rim (one border loop). Outward-oriented (the bottom faces down); 64 segments around,
/// 24 wall rows, 8 bottom rings: 2,049 vertices, 4,032 faces, genus 0.
///
/// ```
/// let cup = envelope_mesh::generate::demo_model();
/// let t = envelope_mesh::analyze(&cup);
/// assert_eq!((cup.num_faces(), t.genus, t.num_border_loops()), (4032, Some(0), 1));
/// ```
#[must_use]
pub fn demo_model() -> TriangleSoup {
    const AROUND: u32 = 64;
    const ROWS: u32 = 24;
    const RINGS: u32 = 8;
    const HEIGHT: f64 = 1.2;
    let radius = |u: f64, z: f64| {
        let t = z / HEIGHT;
        (0.5 + 0.12 * (PI * t).sin() + 0.1 * t) * (1.0 + 0.03 * (6.0 * u).cos())
    };
    let mut pos = Vec::new();
    // Wall rows 0..=ROWS (row 0 is the bottom's outer ring), then bottom rings RINGS-1..1,
    // then the bottom centre.
    for j in 0..=ROWS {
        let z = HEIGHT * f64::from(j) / f64::from(ROWS);
        for i in 0..AROUND {
            let u = TAU * f64::from(i) / f64::from(AROUND);
            let r = radius(u, z);
            pos.push(DVec3::new(r * u.cos(), r * u.sin(), z));
        }
    }
    for k in (1..RINGS).rev() {
        for i in 0..AROUND {
            let u = TAU * f64::from(i) / f64::from(AROUND);
            let r = radius(u, 0.0) * f64::from(k) / f64::from(RINGS);
            pos.push(DVec3::new(r * u.cos(), r * u.sin(), 0.0));
        }
    }
    let centre = pos.len() as u32;
    pos.push(DVec3::ZERO);
    let wall = |i: u32, j: u32| j * AROUND + i % AROUND;
    // Bottom ring k (RINGS is the wall's row 0).
    let ring = |i: u32, k: u32| {
        if k == RINGS {
            wall(i, 0)
        } else {
            (ROWS + 1) * AROUND + (RINGS - 1 - k) * AROUND + i % AROUND
        }
    };
    let mut faces = Vec::new();
    for j in 0..ROWS {
        for i in 0..AROUND {
            quad(
                &mut faces,
                [
                    wall(i, j),
                    wall(i + 1, j),
                    wall(i + 1, j + 1),
                    wall(i, j + 1),
                ],
            );
        }
    }
    // Seen from below (outside): counter-clockwise is inner i, inner i+1, outer i+1, outer i.
    for k in 2..=RINGS {
        for i in 0..AROUND {
            quad(
                &mut faces,
                [
                    ring(i, k - 1),
                    ring(i + 1, k - 1),
                    ring(i + 1, k),
                    ring(i, k),
                ],
            );
        }
    }
    for i in 0..AROUND {
        faces.push([centre, ring(i + 1, 1), ring(i, 1)]);
    }
    soup(pos, faces)
}

/// The boundary of the union of the unit cells `(i, j, k)` (`i < nx`, ...) with
/// `filled(i, j, k)`, scaled by `cell` per axis, with the lattice origin at the origin. Each
/// exposed cell face becomes two triangles; lattice points are shared.
///
/// The output is a closed, outward-oriented 2-manifold **unless** two filled cells meet only
/// along an edge or at a corner (with the cells sharing their faces empty): then that edge or
/// vertex is non-manifold. The convenience shapes below never do that.
///
/// ```
/// use envelope_mesh::{analyze, generate};
/// use glam::DVec3;
/// // Two cubes meeting at one edge: a non-manifold edge with four faces.
/// let s = generate::voxel_surface(2, 2, 1, |i, j, _| i == j, DVec3::ONE);
/// assert!(!analyze(&s).manifold);
/// ```
#[must_use]
pub fn voxel_surface(
    nx: u32,
    ny: u32,
    nz: u32,
    filled: impl Fn(u32, u32, u32) -> bool,
    cell: DVec3,
) -> TriangleSoup {
    let n = [nx, ny, nz];
    let grid: Vec<bool> = (0..nz)
        .flat_map(|k| (0..ny).flat_map(move |j| (0..nx).map(move |i| (i, j, k))))
        .map(|(i, j, k)| filled(i, j, k))
        .collect();
    let is_filled = |c: [i64; 3]| -> bool {
        (0..3).all(|a| c[a] >= 0 && c[a] < i64::from(n[a]))
            && grid[(c[0] + i64::from(nx) * (c[1] + i64::from(ny) * c[2])) as usize]
    };
    let (lx, ly) = (u64::from(nx) + 1, u64::from(ny) + 1);
    let mut ids: HashMap<u64, u32> = HashMap::new();
    let mut pos = Vec::new();
    let mut vertex = |p: [i64; 3]| -> u32 {
        let key = p[0] as u64 + lx * (p[1] as u64 + ly * p[2] as u64);
        *ids.entry(key).or_insert_with(|| {
            pos.push(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) * cell);
            (pos.len() - 1) as u32
        })
    };
    let mut faces = Vec::new();
    for k in 0..i64::from(nz) {
        for j in 0..i64::from(ny) {
            for i in 0..i64::from(nx) {
                let c = [i, j, k];
                if !is_filled(c) {
                    continue;
                }
                for a in 0..3 {
                    let (u, w) = ((a + 1) % 3, (a + 2) % 3);
                    for up in [false, true] {
                        let mut nb = c;
                        nb[a] += if up { 1 } else { -1 };
                        if is_filled(nb) {
                            continue;
                        }
                        let mut p0 = c;
                        p0[a] += i64::from(up);
                        let mut p1 = p0;
                        p1[u] += 1;
                        let mut p2 = p1;
                        p2[w] += 1;
                        let mut p3 = p0;
                        p3[w] += 1;
                        let q = [p0, p1, p2, p3].map(&mut vertex);
                        // e_u x e_w = e_a: counter-clockwise seen from +a.
                        if up {
                            quad(&mut faces, q);
                        } else {
                            quad(&mut faces, [q[0], q[3], q[2], q[1]]);
                        }
                    }
                }
            }
        }
    }
    soup(pos, faces)
}

/// An axis-aligned box of extents `size` centred at the origin, each side split into
/// `subdivisions`² squares (sharp edges and corners). Genus 0.
#[must_use]
pub fn box_mesh(size: DVec3, subdivisions: u32) -> TriangleSoup {
    let n = subdivisions.max(1);
    let mut s = voxel_surface(n, n, n, |_, _, _| true, size / f64::from(n));
    for p in &mut s.positions {
        *p -= size * 0.5;
    }
    s
}

/// A `(2k + 1) x 3 x 1` block of unit cubes with `k` square through-holes in a row: genus `k`
/// (`k = 2` is a double torus).
#[must_use]
pub fn plate_with_holes(k: u32) -> TriangleSoup {
    voxel_surface(
        2 * k + 1,
        3,
        1,
        |i, j, _| !(i % 2 == 1 && j == 1),
        DVec3::ONE,
    )
}

/// A block of `8 x 8 x 8` unit cubes with a fin of `7 x 8` cubes one layer high on one
/// side, squeezed to `thickness` from one cube out of the block on (it tapers over the
/// first cube): a thin part on a thick body. Closed, genus 0.
///
/// ```
/// let fin = envelope_mesh::generate::block_with_fin(0.04);
/// let t = envelope_mesh::analyze(&fin);
/// assert_eq!((t.genus, t.num_border_loops(), t.manifold), (Some(0), 0, true));
/// ```
#[must_use]
pub fn block_with_fin(thickness: f64) -> TriangleSoup {
    let mut s = voxel_surface(16, 8, 8, |i, _, k| i < 8 || k == 4, DVec3::ONE);
    for p in &mut s.positions {
        if p.x > 8.5 {
            p.z = 4.5 + (p.z - 4.5) * thickness;
        }
    }
    s
}

/// A `3 x 3 x 3` block of unit cubes with the central column removed: genus 1.
#[must_use]
pub fn box_with_tunnel() -> TriangleSoup {
    voxel_surface(3, 3, 3, |i, j, _| !(i == 1 && j == 1), DVec3::ONE)
}

/// A `3 x 3 x 2` block of unit cubes with a blind pocket (the top centre cube removed):
/// genus 0, with concave edges.
#[must_use]
pub fn block_with_pocket() -> TriangleSoup {
    voxel_surface(3, 3, 2, |i, j, k| !(i == 1 && j == 1 && k == 1), DVec3::ONE)
}

/// A flat `(2k + 1) x 3` grid of unit squares in the plane `z = 0` (normal `+z`) with `k`
/// square holes in a row: genus 0, `k + 1` border loops.
#[must_use]
pub fn disk_with_holes(k: u32) -> TriangleSoup {
    let (nx, ny) = (2 * k + 1, 3u32);
    let mut ids = vec![u32::MAX; ((nx + 1) * (ny + 1)) as usize];
    let mut pos = Vec::new();
    let mut vertex = |i: u32, j: u32| -> u32 {
        let slot = &mut ids[(j * (nx + 1) + i) as usize];
        if *slot == u32::MAX {
            *slot = pos.len() as u32;
            pos.push(DVec3::new(f64::from(i), f64::from(j), 0.0));
        }
        *slot
    };
    let mut faces = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            if i % 2 == 1 && j == 1 {
                continue;
            }
            let q = [
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i + 1, j + 1),
                vertex(i, j + 1),
            ];
            quad(&mut faces, q);
        }
    }
    soup(pos, faces)
}

/// A Möbius strip of `n >= 5` quads (two triangles each): one border loop, Euler
/// characteristic 0, non-orientable, so necessarily inconsistently oriented as a soup.
#[must_use]
pub fn moebius_strip(n: u32) -> TriangleSoup {
    assert!(n >= 5, "moebius_strip needs n >= 5");
    let mut pos = Vec::new();
    for i in 0..n {
        let u = TAU * f64::from(i) / f64::from(n);
        let radial = DVec3::new(u.cos(), u.sin(), 0.0);
        let across = radial * (u / 2.0).cos() + DVec3::Z * (u / 2.0).sin();
        pos.push(radial * 2.0 + across * 0.5);
        pos.push(radial * 2.0 - across * 0.5);
    }
    // Vertex 2i is the "top" at step i, 2i + 1 the "bottom"; after a full turn they swap.
    let top = |i: u32| if i == n { 1 } else { 2 * i };
    let bottom = |i: u32| if i == n { 0 } else { 2 * i + 1 };
    let mut faces = Vec::new();
    for i in 0..n {
        quad(&mut faces, [top(i), bottom(i), bottom(i + 1), top(i + 1)]);
    }
    soup(pos, faces)
}

/// A closed genus-0 surface of 9 vertices with a *folded* vertex: the faces around vertex 4
/// have normals that fit in no open hemisphere, so no vertex normal is within 90 degrees of
/// all of them (section 3's assumption fails; `envelope-offset` pins such a vertex). The fan
/// of vertex 4 is the one of vertex 1143 of `hand.off` (Debian's `libcgal-demo`), closed by
/// a cone to vertex 8 and oriented outwards; manifold and free of self-intersections.
#[must_use]
pub fn folded_vertex() -> TriangleSoup {
    TriangleSoup::from_raw(
        &[
            [0.252281, -0.0528258, 0.176936],
            [0.272219, 0.0103774, 0.195095],
            [0.249193, -0.0712395, 0.244956],
            [0.232666, -0.0507647, 0.173094],
            [0.246718, -0.0295268, 0.179409],
            [0.218797, 0.0265626, 0.184945],
            [0.252236, -0.0139216, 0.207271],
            [0.248447, -0.0303258, 0.181752],
            [
                0.2573058511216858,
                -0.04046152464596106,
                0.18351760999999997,
            ],
        ],
        &[
            [0, 3, 4],
            [4, 2, 6],
            [5, 1, 4],
            [0, 4, 1],
            [4, 7, 5],
            [6, 7, 4],
            [3, 2, 4],
            [2, 8, 6],
            [6, 8, 7],
            [0, 8, 3],
            [3, 8, 2],
            [5, 8, 1],
            [1, 8, 0],
            [7, 8, 5],
        ],
    )
}

/// Two triangles sharing only vertex 0: a non-manifold vertex, two components.
#[must_use]
pub fn bow_tie() -> TriangleSoup {
    TriangleSoup::from_raw(
        &[
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [-1.0, -1.0, 0.0],
        ],
        &[[0, 1, 2], [0, 3, 4]],
    )
}

/// Three triangles on edge `0-1` (faces 0 and 2 both run it `0 -> 1`): a non-manifold edge.
#[must_use]
pub fn three_triangles_on_edge() -> TriangleSoup {
    TriangleSoup::from_raw(
        &[
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [0.5, -1.0, 0.0],
            [0.5, 0.0, 1.0],
        ],
        &[[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{FaceId, analyze};

    fn signed_volume(s: &TriangleSoup) -> f64 {
        s.face_ids()
            .map(|f| {
                let [a, b, c] = s.triangle(f);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    #[test]
    fn closed_generators_face_outward() {
        let cases = [
            (tetrahedron(), 1.0 / 6.0),
            (icosphere(0, 1.0), 2.536_150_710_120_062),
            (box_mesh(DVec3::new(1.0, 2.0, 3.0), 2), 6.0),
            (block_with_pocket(), 17.0),
            (box_with_tunnel(), 24.0),
            (plate_with_holes(2), 13.0),
            (torus(2.0, 0.5, 64, 32), 2.0 * PI * PI * 2.0 * 0.25),
            (uv_sphere(64, 32, 1.0), 4.0 / 3.0 * PI),
            (folded_vertex(), 1.063_589e-5),
        ];
        for (i, (s, v)) in cases.iter().enumerate() {
            let got = signed_volume(s);
            assert!(
                (got - v).abs() < 0.02 * v,
                "case {i}: volume {got}, expected about {v}"
            );
        }
    }

    #[test]
    fn open_generators_face_the_right_way() {
        // The disk faces +z.
        let d = disk_with_holes(2);
        for f in d.face_ids() {
            let [a, b, c] = d.triangle(f);
            assert!((b - a).cross(c - a).z > 0.0);
        }
        // The cylinder faces away from its axis.
        let c = open_cylinder(1.0, 1.0, 8, 2);
        for f in c.face_ids() {
            let [a, b, p] = c.triangle(f);
            let centre = (a + b + p) / 3.0;
            assert!((b - a).cross(p - a).dot(centre.with_z(0.0)) > 0.0);
        }
    }

    #[test]
    fn generators_are_deterministic_and_sized() {
        assert_eq!(icosphere(1, 2.0), icosphere(1, 2.0));
        let s = icosphere(3, 1.0);
        assert_eq!((s.num_vertices(), s.num_faces()), (642, 1280));
        let b = box_mesh(DVec3::ONE, 3);
        assert_eq!(b.num_faces(), 6 * 9 * 2);
        assert_eq!(b.num_vertices(), 6 * 9 + 2);
        let t = analyze(&moebius_strip(5));
        assert_eq!(t.components[0].first_face, FaceId(0));
    }
}
