//! The polyhedral prism of section 8.1: each bilinear side replaced by two triangles, and the
//! prism cut into three tetrahedra.

use envelope_predicates::{Containment, Filtered, Kernel, Sign, generic};
use glam::DVec3;

use crate::patch::boxes_overlap;
use crate::{Location, Prism};

/// Which diagonal splits each bilinear side into two triangles.
///
/// A side patch lies in the tetrahedron of its four corners, between the two ways of
/// splitting it: one pair of triangles lies on the prism's inner side of the patch, the other
/// on the outer side (they coincide for a planar side).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Split {
    /// The pair on the inner side: the polyhedral prism is **contained in** the bilinear one
    /// (conservative for "is this inside the envelope?"). Chosen per prism, so two prisms
    /// sharing a side split it differently (each inward).
    Inner,
    /// The pair on the outer side: the polyhedral prism **contains** the bilinear one
    /// (conservative for "could this touch the prism?").
    Outer,
    /// By global vertex ids of the fundamental triangle: side `(i, j)` is split along the
    /// diagonal from the bottom corner of the smaller id to the top corner of the larger. Two
    /// prisms sharing an edge agree, and the three diagonals never form a cycle, so the prism
    /// is the union of the three tetrahedra of [`Prism::tetrahedra`].
    Ids([u32; 3]),
}

/// A prism whose sides are split into triangles: 6 corners (bottom `0..3`, top `3..6`) and
/// 8 faces oriented outward (counter-clockwise seen from outside).
///
/// ```
/// use envelope_prism::{Location, PolyhedralPrism, Prism, Split};
/// use glam::DVec3;
/// let p = Prism::from_offsets([DVec3::ZERO, DVec3::X, DVec3::Y], [DVec3::Z; 3], [1.0; 3], [1.0; 3]);
/// let poly = PolyhedralPrism::new(&p, Split::Ids([0, 1, 2]));
/// assert_eq!(poly.classify(DVec3::new(0.25, 0.25, 0.0)), Location::Inside);
/// assert_eq!(poly.classify(DVec3::new(0.5, 0.5, 0.0)), Location::OnBoundary);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolyhedralPrism {
    corners: [DVec3; 6],
    faces: [[u32; 3]; 8],
}

impl PolyhedralPrism {
    /// Splits the sides of `prism` as `split` says.
    #[must_use]
    pub fn new(prism: &Prism, split: Split) -> PolyhedralPrism {
        let mut faces = [[0u32; 3]; 8];
        faces[0] = [0, 2, 1];
        faces[1] = [3, 4, 5];
        for e in 0..3 {
            let (i, j) = (e as u32, ((e + 1) % 3) as u32);
            // The side patch has p00 = j-, p10 = i-, p01 = j+, p11 = i+ and an inward normal.
            let main = match split {
                Split::Inner => prism.side(e).twist().sign() != Sign::Negative,
                Split::Outer => prism.side(e).twist().sign() == Sign::Negative,
                // main diagonal p00 p11 = j- i+: from the bottom of j to the top of i.
                Split::Ids(ids) => (ids[j as usize], j) < (ids[i as usize], i),
            };
            let (p00, p10, p01, p11) = (j, i, j + 3, i + 3);
            // Patch::split, reversed to face outward.
            let tris = if main {
                [[p00, p11, p10], [p00, p01, p11]]
            } else {
                [[p00, p01, p10], [p10, p01, p11]]
            };
            faces[2 + 2 * e] = tris[0];
            faces[3 + 2 * e] = tris[1];
        }
        PolyhedralPrism {
            corners: prism.corners(),
            faces,
        }
    }

    /// The six corners, bottom then top.
    #[must_use]
    pub fn corners(&self) -> [DVec3; 6] {
        self.corners
    }

    /// The eight faces as corner indices, outward: bottom, top, then two per side.
    #[must_use]
    pub fn faces(&self) -> [[u32; 3]; 8] {
        self.faces
    }

    /// The eight faces as triangles.
    #[must_use]
    pub fn triangles(&self) -> [[DVec3; 3]; 8] {
        self.faces.map(|f| f.map(|k| self.corners[k as usize]))
    }

    /// Exact location of `q` (ray parity on the closed surface; the solid need not be convex).
    #[must_use]
    pub fn classify(&self, q: DVec3) -> Location {
        details::classify_polyhedral::<Filtered>(self, q)
    }

    /// True when the closed triangle `t` meets the closed polyhedral prism (exact).
    #[must_use]
    pub fn intersects_triangle(&self, t: [DVec3; 3]) -> bool {
        details::intersects_triangle_polyhedral::<Filtered>(self, t)
    }
}

/// Kernel-generic variants.
pub mod details {
    use super::*;

    /// [`PolyhedralPrism::classify`] on kernel `K`.
    #[must_use]
    pub fn classify_polyhedral<K: Kernel>(p: &PolyhedralPrism, q: DVec3) -> Location {
        match generic::point_in_surface::<K>(q, &p.corners, &p.faces) {
            Containment::Inside => Location::Inside,
            Containment::On => Location::OnBoundary,
            Containment::Outside => Location::Outside,
        }
    }

    /// [`PolyhedralPrism::intersects_triangle`] on kernel `K`: a vertex of `t` in the solid,
    /// or `t` meets a face.
    #[must_use]
    pub fn intersects_triangle_polyhedral<K: Kernel>(p: &PolyhedralPrism, t: [DVec3; 3]) -> bool {
        boxes_overlap(&p.corners, &t)
            && (t
                .iter()
                .any(|&v| classify_polyhedral::<K>(p, v) != Location::Outside)
                || p.triangles()
                    .iter()
                    .any(|f| generic::triangles_intersect::<K>(t, *f)))
    }
}
