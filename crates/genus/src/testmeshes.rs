//! CAD-like test parts with known answers (plates with square through-holes of several
//! widths, blocks with blind pockets, square-section tori, flat disks with holes, a
//! coarsely triangulated plate with a long slot). They live
//! here rather than in `envelope_mesh::generate` because only the genus tests need them.
//! Every part is a closed (or, for the disks, bordered) outward-oriented 2-manifold with
//! integer coordinates times `cell`.

use envelope_mesh::{TriangleSoup, VertexId, generate};
use glam::DVec3;

/// Layout of square holes of `widths` (in cells) in a row along x, separated and framed by
/// one-cell bars: `(nx, ny, is_hole(i, j))`.
fn hole_layout(widths: &[u32]) -> (u32, u32, Vec<(u32, u32, u32)>) {
    let ny = widths.iter().copied().max().unwrap_or(0) + 2;
    let mut x = 1;
    let mut holes = Vec::new();
    for &w in widths {
        holes.push((x, 1, w));
        x += w + 1;
    }
    (x.max(1), ny.max(1), holes)
}

fn in_hole(holes: &[(u32, u32, u32)], i: u32, j: u32) -> bool {
    holes
        .iter()
        .any(|&(x, y, w)| i >= x && i < x + w && j >= y && j < y + w)
}

/// A plate `thickness` cells thick with square through-holes of the given widths (in cells of
/// side `cell`): genus `widths.len()`.
///
/// ```
/// use envelope_genus::testmeshes::plate_with_square_holes;
/// use envelope_mesh::analyze;
/// assert_eq!(analyze(&plate_with_square_holes(&[1, 2, 3], 1, 1.0)).genus, Some(3));
/// ```
#[must_use]
pub fn plate_with_square_holes(widths: &[u32], thickness: u32, cell: f64) -> TriangleSoup {
    let (nx, ny, holes) = hole_layout(widths);
    generate::voxel_surface(
        nx,
        ny,
        thickness.max(1),
        |i, j, _| !in_hole(&holes, i, j),
        DVec3::splat(cell),
    )
}

/// A `(w + 2) x (w + 2) x (depth + 1)` block of cells with a `w x w` pocket `depth` cells deep
/// opening at the top: genus 0.
///
/// ```
/// use envelope_genus::testmeshes::block_with_square_pocket;
/// use envelope_mesh::analyze;
/// let t = analyze(&block_with_square_pocket(2, 1, 1.0));
/// assert_eq!((t.genus, t.num_border_loops()), (Some(0), 0));
/// ```
#[must_use]
pub fn block_with_square_pocket(w: u32, depth: u32, cell: f64) -> TriangleSoup {
    generate::voxel_surface(
        w + 2,
        w + 2,
        depth + 1,
        |i, j, k| !(i >= 1 && i <= w && j >= 1 && j <= w && k >= 1),
        DVec3::splat(cell),
    )
}

/// A flat grid of unit squares (times `cell`) in `z = 0` with square holes of the given
/// widths: genus 0, `widths.len() + 1` border loops.
///
/// ```
/// use envelope_genus::testmeshes::disk_with_square_holes;
/// use envelope_mesh::analyze;
/// assert_eq!(analyze(&disk_with_square_holes(&[1, 3], 1.0)).num_border_loops(), 3);
/// ```
#[must_use]
pub fn disk_with_square_holes(widths: &[u32], cell: f64) -> TriangleSoup {
    let (nx, ny, holes) = hole_layout(widths);
    let mut ids = vec![u32::MAX; ((nx + 1) * (ny + 1)) as usize];
    let mut positions = Vec::new();
    let mut vertex = |i: u32, j: u32| -> VertexId {
        let slot = &mut ids[(j * (nx + 1) + i) as usize];
        if *slot == u32::MAX {
            *slot = positions.len() as u32;
            positions.push(DVec3::new(f64::from(i), f64::from(j), 0.0) * cell);
        }
        VertexId(*slot)
    };
    let mut faces = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            if in_hole(&holes, i, j) {
                continue;
            }
            let q = [
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i + 1, j + 1),
                vertex(i, j + 1),
            ];
            faces.push([q[0], q[1], q[2]]);
            faces.push([q[0], q[2], q[3]]);
        }
    }
    TriangleSoup::new(positions, faces)
}

/// A torus of square cross-section (side `2 minor`, axis-aligned in the `(r, z)` half-plane)
/// around the z axis, `nu >= 3` segments around: flat top and bottom annuli, an inner and an
/// outer wall, sharp 90-degree rims. The central hole has radius `major - minor` (at the
/// polygon's vertices). Genus 1.
///
/// ```
/// use envelope_genus::testmeshes::square_torus;
/// use envelope_mesh::analyze;
/// assert_eq!(analyze(&square_torus(1.0, 0.3, 16)).genus, Some(1));
/// ```
#[must_use]
pub fn square_torus(major: f64, minor: f64, nu: u32) -> TriangleSoup {
    let nu = nu.max(3);
    // Cross-section corners, counter-clockwise in the (r, z) plane.
    let section = [
        (major - minor, -minor),
        (major + minor, -minor),
        (major + minor, minor),
        (major - minor, minor),
    ];
    let mut positions = Vec::new();
    for i in 0..nu {
        let t = std::f64::consts::TAU * f64::from(i) / f64::from(nu);
        for &(r, z) in &section {
            positions.push(DVec3::new(r * t.cos(), r * t.sin(), z));
        }
    }
    let id = |i: u32, k: u32| VertexId((i % nu) * 4 + k % 4);
    let mut faces = Vec::new();
    for i in 0..nu {
        for k in 0..4 {
            let (a, b, c, d) = (id(i, k), id(i, k + 1), id(i + 1, k + 1), id(i + 1, k));
            faces.push([a, d, c]);
            faces.push([a, c, b]);
        }
    }
    TriangleSoup::new(positions, faces)
}

/// A plate `thickness` thick with one rectangular through-slot `length x width` (along x),
/// framed by a border of 1, triangulated coarsely: each face of the plate is two or eight
/// triangles, so the slot's rims run along single edges `length` long. Genus 1, 32 faces.
///
/// ```
/// use envelope_genus::testmeshes::plate_with_slot;
/// use envelope_mesh::analyze;
/// let plate = plate_with_slot(8.0, 1.0, 1.0);
/// assert_eq!((analyze(&plate).genus, plate.num_faces()), (Some(1), 32));
/// ```
#[must_use]
pub fn plate_with_slot(length: f64, width: f64, thickness: f64) -> TriangleSoup {
    let (lx, ly) = (length + 2.0, width + 2.0);
    // Outer corners then slot corners, each counter-clockwise seen from +z; bottom then top.
    let outline = [(0.0, 0.0), (lx, 0.0), (lx, ly), (0.0, ly)];
    let slot = [
        (1.0, 1.0),
        (1.0 + length, 1.0),
        (1.0 + length, 1.0 + width),
        (1.0, 1.0 + width),
    ];
    let mut positions = Vec::new();
    for z in [0.0, thickness] {
        for &(x, y) in outline.iter().chain(&slot) {
            positions.push(DVec3::new(x, y, z));
        }
    }
    // Outer corner i, slot corner i, at the bottom (top = false) or the top.
    let o = |i: u32, top: bool| VertexId(i % 4 + if top { 8 } else { 0 });
    let s = |i: u32, top: bool| VertexId(4 + i % 4 + if top { 8 } else { 0 });
    let mut faces = Vec::new();
    for i in 0..4 {
        // The frame between the outline and the slot: one slot edge per triangle at most.
        faces.push([o(i, true), o(i + 1, true), s(i + 1, true)]);
        faces.push([o(i, true), s(i + 1, true), s(i, true)]);
        faces.push([o(i, false), s(i + 1, false), o(i + 1, false)]);
        faces.push([o(i, false), s(i, false), s(i + 1, false)]);
        // Outer walls face out, slot walls face into the slot.
        faces.push([o(i, false), o(i + 1, false), o(i + 1, true)]);
        faces.push([o(i, false), o(i + 1, true), o(i, true)]);
        faces.push([s(i, false), s(i + 1, true), s(i + 1, false)]);
        faces.push([s(i, false), s(i, true), s(i + 1, true)]);
    }
    TriangleSoup::new(positions, faces)
}
