//! Vertex normals within 90 degrees of every adjacent face normal (Cohen et al. 3).
//!
//! The paper asks for "a single vertex normal as a combination of the normals of the
//! surrounding triangles" lying within 90 degrees of each of them, without saying which
//! combination. Choices made here:
//!
//! 1. First try the angle-weighted average of the unit face normals (Thürmer-Wüthrich), the
//!    usual smooth choice.
//! 2. When it fails the exact test (sharp vertices: spikes, saddles with folded fans), take the
//!    *maximin* direction, the unit `n` maximising `min_i n . f_i` over the unit face normals
//!    `f_i`. It is `p / |p|` for `p` the point of the convex hull of the `f_i` closest to the
//!    origin (the hard-margin SVM dual), found with Gilbert's algorithm.
//! 3. Validity is decided *exactly* on the constructed f64 direction: for every adjacent face
//!    `abc` with the vertex `v`, `orient3d(a, b, c, v + s n) = Positive` where `s` is the mean
//!    incident edge length (so the test point is not swamped by rounding). A vertex where both
//!    candidates fail (its face normals do not fit in an open hemisphere, or only by a margin
//!    below rounding) is reported in [`VertexNormals::invalid`]; no invalid normal is ever
//!    returned as valid.
//!
//! Normals are f64 constructions, unit length up to rounding. Unreferenced vertices get
//! `DVec3::ZERO` (no face constrains them).
use envelope_mesh::{TriangleSoup, VertexFaces, VertexId};
use envelope_predicates::{Orientation, orient3d};
use glam::DVec3;
use rayon::prelude::*;

/// Vertex normals and the vertices that have none.
#[derive(Clone, Debug)]
pub struct VertexNormals {
    /// One unit normal per vertex (zero for unreferenced and invalid vertices).
    pub normals: Vec<DVec3>,
    /// Vertices with no direction strictly within 90 degrees of all adjacent faces (exact).
    pub invalid: Vec<VertexId>,
}

/// True when `n` is strictly within 90 degrees of the oriented normal of every face of `fan`
/// around vertex `v` (exact on the constructed point `p_v + s n`).
pub(crate) fn normal_is_valid(soup: &TriangleSoup, fan: &[u32], v: usize, n: DVec3) -> bool {
    let p = soup.positions[v];
    let s = fan_scale(soup, fan, v);
    let q = p + n * s;
    if q == p {
        return false;
    }
    fan.iter().all(|&f| {
        let [a, b, c] = soup.faces[f as usize].map(|i| soup.positions[i.0 as usize]);
        orient3d(a, b, c, q) == Orientation::Positive
    })
}

fn fan_scale(soup: &TriangleSoup, fan: &[u32], v: usize) -> f64 {
    let p = soup.positions[v];
    let mut sum = 0.0;
    let mut k = 0.0;
    for &f in fan {
        for i in soup.faces[f as usize] {
            let d = soup.positions[i.0 as usize].distance(p);
            if d > 0.0 {
                sum += d;
                k += 1.0;
            }
        }
    }
    if k > 0.0 { sum / k } else { 1.0 }
}

/// Unit normal of a face (zero when degenerate).
pub(crate) fn face_normal(t: [DVec3; 3]) -> DVec3 {
    (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero()
}

/// The maximin direction of unit vectors `fs`: the normalised closest point to the origin of
/// their convex hull (Gilbert's algorithm). `None` when the hull (nearly) contains the origin.
pub(crate) fn maximin_direction(fs: &[DVec3]) -> Option<DVec3> {
    let mut x = *fs.first()?;
    for _ in 0..1000 {
        // Support point in direction -x.
        let (w, dw) = fs
            .iter()
            .map(|&f| (f, f.dot(x)))
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        let xx = x.dot(x);
        if xx - dw <= 1e-15 * xx.max(1e-300) {
            break;
        }
        // Closest point to the origin on segment [x, w].
        let d = w - x;
        let t = (-x.dot(d) / d.dot(d)).clamp(0.0, 1.0);
        x += d * t;
        if x.length_squared() < 1e-28 {
            return None;
        }
    }
    x.try_normalize()
}

/// Computes the normal of every vertex (section 3); see the module docs for the choices.
///
/// ```
/// use envelope_mesh::generate;
/// let cube = generate::box_mesh(glam::DVec3::ONE, 1);
/// let n = envelope_offset::vertex_normals(&cube);
/// assert!(n.invalid.is_empty());
/// ```
#[must_use]
pub fn vertex_normals(soup: &TriangleSoup) -> VertexNormals {
    let vf = VertexFaces::new(soup.num_vertices(), &soup.faces);
    vertex_normals_with(soup, &vf)
}

pub(crate) fn vertex_normals_with(soup: &TriangleSoup, vf: &VertexFaces) -> VertexNormals {
    let results: Vec<Option<DVec3>> = (0..soup.num_vertices())
        .into_par_iter()
        .map(|v| {
            let fan = vf.of(v);
            if fan.is_empty() {
                return Some(DVec3::ZERO);
            }
            let p = soup.positions[v];
            let mut fs = Vec::with_capacity(fan.len());
            let mut avg = DVec3::ZERO;
            for &f in fan {
                let t = soup.triangle(envelope_mesh::FaceId(f));
                let fnrm = face_normal(t);
                // Angle at v.
                let i = soup.faces[f as usize]
                    .iter()
                    .position(|x| x.0 as usize == v)?;
                let (a, b) = (t[(i + 1) % 3] - p, t[(i + 2) % 3] - p);
                let angle = a.angle_between(b);
                avg += fnrm * if angle.is_finite() { angle } else { 0.0 };
                fs.push(fnrm);
            }
            if let Some(n) = avg.try_normalize()
                && normal_is_valid(soup, fan, v, n)
            {
                return Some(n);
            }
            let n = maximin_direction(&fs)?;
            normal_is_valid(soup, fan, v, n).then_some(n)
        })
        .collect();
    let mut invalid = Vec::new();
    let normals = results
        .into_iter()
        .enumerate()
        .map(|(v, r)| {
            r.unwrap_or_else(|| {
                invalid.push(VertexId(v as u32));
                DVec3::ZERO
            })
        })
        .collect();
    VertexNormals { normals, invalid }
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::generate;

    #[test]
    fn cube_corner_normal_is_the_diagonal() {
        let cube = generate::box_mesh(DVec3::ONE, 1);
        let n = vertex_normals(&cube);
        assert!(n.invalid.is_empty());
        let c = cube.bounding_box().unwrap();
        let centre = (c.0 + c.1) * 0.5;
        for (v, &p) in cube.positions.iter().enumerate() {
            let expected = (p - centre).normalize();
            assert!(
                n.normals[v].dot(expected) > 0.9999,
                "vertex {v}: {:?}",
                n.normals[v]
            );
        }
    }

    /// A thin spike: the apex fan spans almost a hemisphere's worth of normals; the average
    /// of the base vertices can fail but the maximin direction must not.
    #[test]
    fn spike_apex_and_sharp_base() {
        // Apex far above a small triangle base, closed with the base face.
        let pos = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 0.1, 0.0],
            [0.5, 0.03, 50.0],
        ];
        let faces = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
        let soup = TriangleSoup::from_raw(&pos, &faces);
        let n = vertex_normals(&soup);
        assert!(n.invalid.is_empty(), "{:?}", n.invalid);
        assert!(n.normals[3].z > 0.99);
        // Every normal is exactly valid.
        let vf = VertexFaces::new(4, &soup.faces);
        for v in 0..4 {
            assert!(normal_is_valid(&soup, vf.of(v), v, n.normals[v]));
        }
    }

    #[test]
    fn maximin_beats_average_on_a_lopsided_fan() {
        // Many faces on one side, one on the other: the average leans too far.
        let mut fs = vec![DVec3::new(1.0, 0.0, 0.1).normalize(); 20];
        fs.push(DVec3::new(-1.0, 0.0, 0.1).normalize());
        let avg = fs.iter().sum::<DVec3>().normalize();
        assert!(fs.iter().any(|f| f.dot(avg) <= 0.0));
        let n = maximin_direction(&fs).unwrap();
        assert!(fs.iter().all(|f| f.dot(n) > 0.09));
        assert!(n.z > 0.99);
    }

    #[test]
    fn no_direction_for_opposite_faces() {
        let fs = [DVec3::Z, -DVec3::Z];
        assert_eq!(maximin_direction(&fs), None);
    }
}
