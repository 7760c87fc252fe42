//! The fundamental prism (Cohen et al. 1996, section 3, Fig. 3): top and bottom triangles and
//! three bilinear-patch sides; exact point, segment and triangle tests.

use envelope_predicates::exact_num::Rational;
use envelope_predicates::{Filtered, Kernel, Orientation, Sign, generic};
use glam::DVec3;

use crate::num::{ErrF64, Num, V, rational_sign};
use crate::patch::{self, Patch, boxes_overlap};

/// Where a point is relative to a closed solid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Location {
    /// In the interior.
    Inside,
    /// On the boundary.
    OnBoundary,
    /// Not in the closed solid.
    Outside,
}

/// Why a prism is not well-formed ([`Prism::check`]). Corner and side indices are `0..3`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, thiserror::Error)]
pub enum PrismError {
    /// A corner coordinate is NaN or infinite (`corner` 0..3 bottom, 3..6 top).
    #[error("prism corner {corner} is not finite")]
    NonFinite {
        /// `0..3` bottom `v_i-`, `3..6` top `v_i+`.
        corner: u8,
    },
    /// `v_i- == v_i+`: the vertical segment of vertex `vertex` has no length.
    #[error("the vertical segment of vertex {vertex} is degenerate")]
    DegenerateLeg {
        /// Local vertex index.
        vertex: u8,
    },
    /// `v_i+` is not strictly above the bottom triangle's plane (also reported when the bottom
    /// triangle is degenerate or clockwise seen from the top).
    #[error("top corner {vertex} is not strictly above the bottom plane")]
    TopNotAbove {
        /// Local vertex index.
        vertex: u8,
    },
    /// `v_i-` is not strictly below the top triangle's plane.
    #[error("bottom corner {vertex} is not strictly below the top plane")]
    BottomNotBelow {
        /// Local vertex index.
        vertex: u8,
    },
    /// The normal `B_u × B_s` of side `side` vanishes or turns over somewhere on `[0, 1]²`
    /// (the side folds).
    #[error("side {side} folds")]
    FoldedSide {
        /// Side `e` joins vertices `e` and `e + 1 (mod 3)`.
        side: u8,
    },
    /// The corners of the opposite vertical segment are not strictly on the inner side of side
    /// `side` (the side's quadric cuts the prism).
    #[error("the vertex opposite side {side} is not strictly on its inner side")]
    OppositeCornerOutside {
        /// Side `e` joins vertices `e` and `e + 1 (mod 3)`.
        side: u8,
    },
}

/// A fundamental prism, given by its six corners: `bottom[i] = v_i-`, `top[i] = v_i+`.
///
/// The solid is the intersection of five closed "half-spaces": above the bottom plane, below
/// the top plane, and on the inner side of each side's quadric ([`Patch::side`]). For a
/// well-formed prism ([`Prism::check`]) this is the region bounded by the two triangles and
/// the three bilinear patches.
///
/// Conventions: the bottom triangle `v0- v1- v2-` is counter-clockwise seen from the top
/// (the fundamental triangle is counter-clockwise seen from the side its normals point to);
/// side `e` is the patch through `v_e-, v_{e+1}-, v_{e+1}+, v_e+`.
///
/// ```
/// use envelope_prism::{Location, Prism};
/// use glam::DVec3;
/// let tri = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// let normals = [DVec3::Z, DVec3::new(0.6, 0.0, 0.8), DVec3::Z]; // vertex 1 leans outward
/// let prism = Prism::from_offsets(tri, normals, [0.5; 3], [0.5; 3]);
/// prism.check().unwrap();
/// assert_eq!(prism.classify(DVec3::new(0.2, 0.2, 0.0)), Location::Inside);
/// assert_eq!(prism.classify(tri[0]), Location::OnBoundary); // on the vertical edge of v0
/// assert_eq!(prism.classify(DVec3::new(0.2, 0.2, 0.6)), Location::Outside); // above the top
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prism {
    bottom: [DVec3; 3],
    top: [DVec3; 3],
}

impl Prism {
    /// The prism of a fundamental triangle with unit vertex normals `normals` and per-vertex
    /// offsets: `top[i] = v_i + eps_plus[i]·n_i`, `bottom[i] = v_i − eps_minus[i]·n_i`.
    ///
    /// These six points are **constructions**: each coordinate is one fused multiply-add,
    /// rounded once to f64. Every later decision is exact *on these rounded corners*.
    #[must_use]
    pub fn from_offsets(
        triangle: [DVec3; 3],
        normals: [DVec3; 3],
        eps_plus: [f64; 3],
        eps_minus: [f64; 3],
    ) -> Prism {
        let off = |v: DVec3, n: DVec3, e: f64| {
            DVec3::new(
                n.x.mul_add(e, v.x),
                n.y.mul_add(e, v.y),
                n.z.mul_add(e, v.z),
            )
        };
        Prism {
            bottom: std::array::from_fn(|i| off(triangle[i], normals[i], -eps_minus[i])),
            top: std::array::from_fn(|i| off(triangle[i], normals[i], eps_plus[i])),
        }
    }

    /// The prism with the given corners (`bottom[i] = v_i-`, `top[i] = v_i+`), taken as they are.
    #[must_use]
    pub fn from_corners(bottom: [DVec3; 3], top: [DVec3; 3]) -> Prism {
        Prism { bottom, top }
    }

    /// `[v0-, v1-, v2-]`.
    #[must_use]
    pub fn bottom(&self) -> [DVec3; 3] {
        self.bottom
    }

    /// `[v0+, v1+, v2+]`.
    #[must_use]
    pub fn top(&self) -> [DVec3; 3] {
        self.top
    }

    /// The six corners, bottom then top (the corner numbering of [`PrismError::NonFinite`],
    /// [`details::tetrahedra_corners`] and [`crate::PolyhedralPrism`]).
    #[must_use]
    pub fn corners(&self) -> [DVec3; 6] {
        let (b, t) = (self.bottom, self.top);
        [b[0], b[1], b[2], t[0], t[1], t[2]]
    }

    /// Side `e` (`0..3`) as a patch whose normal points into the prism: corners
    /// `p00 = v_{e+1}-`, `p10 = v_e-`, `p01 = v_{e+1}+`, `p11 = v_e+`, so
    /// [`Patch::side`] is `Positive` on the inner side.
    ///
    /// # Panics
    /// If `e >= 3`.
    #[must_use]
    pub fn side(&self, e: usize) -> Patch {
        let (i, j) = (e, (e + 1) % 3);
        Patch::new(self.bottom[j], self.bottom[i], self.top[j], self.top[i])
    }

    /// Checks that the prism is well-formed (exact), in this order:
    /// finite corners; non-degenerate vertical segments `v_i- v_i+`; every top corner strictly
    /// above the bottom plane and every bottom corner strictly below the top plane (so both
    /// triangles are non-degenerate and consistently oriented); no side folds (`B_u × B_s`
    /// has a positive component along a fixed direction at the four corners, hence, being
    /// bilinear, on all of `[0, 1]²`); the opposite vertical segment's endpoints strictly on
    /// the inner side of each side.
    ///
    /// These conditions are necessary for the five-half-space description to be the bounded
    /// region; they do not prove that a strongly twisted side's quadric cannot re-enter the
    /// prism far from the patch (see the crate README).
    ///
    /// # Errors
    /// The first violated condition.
    pub fn check(&self) -> Result<(), PrismError> {
        let c = self.corners();
        if let Some(k) = c.iter().position(|p| !p.is_finite()) {
            return Err(PrismError::NonFinite { corner: k as u8 });
        }
        for k in 0..3 {
            if self.bottom[k] == self.top[k] {
                return Err(PrismError::DegenerateLeg { vertex: k as u8 });
            }
        }
        let [b0, b1, b2] = self.bottom;
        let [t0, t1, t2] = self.top;
        for k in 0..3 {
            if Filtered::orient3d(b0, b1, b2, self.top[k]) != Orientation::Positive {
                return Err(PrismError::TopNotAbove { vertex: k as u8 });
            }
        }
        for k in 0..3 {
            if Filtered::orient3d(t0, t1, t2, self.bottom[k]) != Orientation::Negative {
                return Err(PrismError::BottomNotBelow { vertex: k as u8 });
            }
        }
        for e in 0..3 {
            if side_folds(&self.side(e)) {
                return Err(PrismError::FoldedSide { side: e as u8 });
            }
        }
        for e in 0..3 {
            let k = (e + 2) % 3;
            let s = self.side(e);
            if s.side(self.bottom[k]) != Sign::Positive || s.side(self.top[k]) != Sign::Positive {
                return Err(PrismError::OppositeCornerOutside { side: e as u8 });
            }
        }
        Ok(())
    }

    /// Panics with the [`PrismError`] and a pasteable reproduction when [`Prism::check`] fails.
    #[track_caller]
    pub fn sanity_check(&self) {
        if let Err(e) = self.check() {
            panic!("ill-formed prism: {e}\n{}", self.repro());
        }
    }

    /// The prism as pasteable Rust.
    #[must_use]
    pub fn repro(&self) -> String {
        let p = |v: DVec3| format!("DVec3::new({:?}, {:?}, {:?})", v.x, v.y, v.z);
        format!(
            "Prism::from_corners([{}, {}, {}], [{}, {}, {}])",
            p(self.bottom[0]),
            p(self.bottom[1]),
            p(self.bottom[2]),
            p(self.top[0]),
            p(self.top[1]),
            p(self.top[2])
        )
    }

    /// Exact location of `q` in the closed prism.
    #[must_use]
    pub fn classify(&self, q: DVec3) -> Location {
        details::classify::<Filtered>(self, q)
    }

    /// `q` in the closed prism (`Inside` or `OnBoundary`).
    #[must_use]
    pub fn contains(&self, q: DVec3) -> bool {
        self.classify(q) != Location::Outside
    }

    /// True when the closed segment `pq` meets the closed prism (exact).
    ///
    /// ```
    /// use envelope_prism::Prism;
    /// use glam::DVec3;
    /// let p = Prism::from_offsets([DVec3::ZERO, DVec3::X, DVec3::Y], [DVec3::Z; 3], [1.0; 3], [1.0; 3]);
    /// assert!(p.intersects_segment(DVec3::new(-1., 0.2, 0.), DVec3::new(1., 0.2, 0.)));
    /// assert!(!p.intersects_segment(DVec3::new(-1., 0.2, 2.), DVec3::new(1., 0.2, 2.)));
    /// ```
    #[must_use]
    pub fn intersects_segment(&self, p: DVec3, q: DVec3) -> bool {
        details::intersects_segment::<Filtered>(self, p, q)
    }

    /// True when the closed triangle `t` meets the closed prism (exact).
    ///
    /// ```
    /// use envelope_prism::Prism;
    /// use glam::DVec3;
    /// let p = Prism::from_offsets([DVec3::ZERO, DVec3::X, DVec3::Y], [DVec3::Z; 3], [1.0; 3], [1.0; 3]);
    /// // A large triangle slicing through the prism with no vertex inside it.
    /// let t = [DVec3::new(-5., -5., 0.5), DVec3::new(5., -5., 0.5), DVec3::new(0., 5., 0.5)];
    /// assert!(p.intersects_triangle(t));
    /// assert!(!p.intersects_triangle(t.map(|v| v + DVec3::new(0., 0., 1.0))));
    /// ```
    #[must_use]
    pub fn intersects_triangle(&self, t: [DVec3; 3]) -> bool {
        details::intersects_triangle::<Filtered>(self, t)
    }

    /// The three tetrahedra of the polyhedral prism split by [`crate::Split::Ids`]`(ids)`
    /// (`ids`: the global ids of the fundamental triangle's vertices, distinct), each
    /// positively oriented for a straight prism. Neighbouring prisms that share an edge (same
    /// ids, same corners) split the shared side along the same diagonal: the one from the
    /// bottom corner of the smaller id to the top corner of the larger.
    ///
    /// ```
    /// use envelope_prism::Prism;
    /// use glam::DVec3;
    /// let p = Prism::from_offsets([DVec3::ZERO, DVec3::X, DVec3::Y], [DVec3::Z; 3], [1.0; 3], [1.0; 3]);
    /// let vol: f64 = p.tetrahedra([7, 3, 5]).iter()
    ///     .map(|t| (t[1] - t[0]).cross(t[2] - t[0]).dot(t[3] - t[0]) / 6.0).sum();
    /// assert_eq!(vol, 1.0); // base area 1/2, height 2
    /// ```
    #[must_use]
    pub fn tetrahedra(&self, ids: [u32; 3]) -> [[DVec3; 4]; 3] {
        let c = self.corners();
        details::tetrahedra_corners(ids).map(|t| t.map(|k| c[k]))
    }
}

/// True when the normal `N(u, s) = B_u × B_s` of the patch is not strictly positive along the
/// certificate direction `v = N(1/2, 1/2)` (an f64 construction) at one of the four corners.
/// `N·v` is bilinear in `(u, s)`, so positivity at the corners gives positivity everywhere.
fn side_folds(patch: &Patch) -> bool {
    let [p00, p10, p01, p11] = patch.corners();
    let v = ((p10 - p00) + (p11 - p01)).cross((p01 - p00) + (p11 - p10));
    if !v.is_finite() || v == DVec3::ZERO {
        return true;
    }
    // (B_u, B_s) at the corners (0,0), (1,0), (0,1), (1,1).
    let pairs = [
        ((p10, p00), (p01, p00)),
        ((p10, p00), (p11, p10)),
        ((p11, p01), (p01, p00)),
        ((p11, p01), (p11, p10)),
    ];
    pairs.iter().any(|&((a, b), (c, d))| {
        let s = normal_dot::<ErrF64>(a, b, c, d, v)
            .sign()
            .unwrap_or_else(|| rational_sign(&normal_dot::<Rational>(a, b, c, d, v)));
        s != Sign::Positive
    })
}

/// `((a − b) × (c − d)) · v`.
fn normal_dot<N: Num>(a: DVec3, b: DVec3, c: DVec3, d: DVec3, v: DVec3) -> N {
    let bu = V::<N>::pt(a).sub(&V::pt(b));
    let bs = V::<N>::pt(c).sub(&V::pt(d));
    bu.cross(&bs).dot(&V::pt(v))
}

/// Kernel-generic variants and index-level helpers.
pub mod details {
    use super::*;

    /// [`Prism::classify`] with the orientation tests on kernel `K`.
    #[must_use]
    pub fn classify<K: Kernel>(prism: &Prism, q: DVec3) -> Location {
        let [b0, b1, b2] = prism.bottom;
        let [t0, t1, t2] = prism.top;
        let mut signs = [
            K::orient3d(b0, b1, b2, q).sign(), // above the bottom
            K::orient3d(t0, t2, t1, q).sign(), // below the top
            Sign::Zero,
            Sign::Zero,
            Sign::Zero,
        ];
        if signs[..2].contains(&Sign::Negative) {
            return Location::Outside;
        }
        for e in 0..3 {
            signs[2 + e] = patch::details::side_of_patch::<K>(&prism.side(e), q);
            if signs[2 + e] == Sign::Negative {
                return Location::Outside;
            }
        }
        if signs.contains(&Sign::Zero) {
            Location::OnBoundary
        } else {
            Location::Inside
        }
    }

    /// [`Prism::intersects_segment`] on kernel `K`.
    #[must_use]
    pub fn intersects_segment<K: Kernel>(prism: &Prism, p: DVec3, q: DVec3) -> bool {
        if !boxes_overlap(&prism.corners(), &[p, q]) {
            return false;
        }
        classify::<K>(prism, p) != Location::Outside
            || classify::<K>(prism, q) != Location::Outside
            || generic::segment_triangle::<K>(p, q, prism.bottom).intersects()
            || generic::segment_triangle::<K>(p, q, prism.top).intersects()
            || (0..3).any(|e| patch::details::segment_patch::<K>(&prism.side(e), p, q))
    }

    /// [`Prism::intersects_triangle`] on kernel `K`. The closed triangle `t` meets the closed
    /// prism iff (1) a vertex of `t` is in the prism, or (2) `t` meets the top or bottom
    /// triangle, or (3) a vertical edge `v_i- v_i+` meets `t`, or (4) an edge of `t` meets a
    /// side patch. Complete because otherwise `t ∩ ∂prism` would contain a closed curve inside
    /// one face: impossible on a planar face, and on a patch because plane sections of a
    /// hyperbolic paraboloid are hyperbolas, parabolas or line pairs, never ellipses.
    #[must_use]
    pub fn intersects_triangle<K: Kernel>(prism: &Prism, t: [DVec3; 3]) -> bool {
        if !boxes_overlap(&prism.corners(), &t) {
            return false;
        }
        t.iter()
            .any(|&v| classify::<K>(prism, v) != Location::Outside)
            || generic::triangles_intersect::<K>(t, prism.bottom)
            || generic::triangles_intersect::<K>(t, prism.top)
            || (0..3).any(|k| {
                generic::segment_triangle::<K>(prism.bottom[k], prism.top[k], t).intersects()
            })
            || (0..3).any(|e| {
                let s = prism.side(e);
                (0..3).any(|k| patch::details::segment_patch::<K>(&s, t[k], t[(k + 1) % 3]))
            })
    }

    /// The tetrahedra of [`Prism::tetrahedra`] as corner indices (`0..3` bottom, `3..6` top).
    /// With the local vertices relabelled `a, b, c` by increasing id, they are
    /// `(a-, b-, c-, c+)`, `(a-, b-, c+, b+)`, `(a-, a+, b+, c+)` (the first two swapped when
    /// the relabelling reverses the orientation). Ties between ids are broken by local index.
    #[must_use]
    pub fn tetrahedra_corners(ids: [u32; 3]) -> [[usize; 4]; 3] {
        let mut o = [0usize, 1, 2];
        o.sort_by_key(|&k| (ids[k], k));
        let [a, b, c] = o;
        let odd = matches!(o, [0, 2, 1] | [2, 1, 0] | [1, 0, 2]);
        let mut tets = [
            [a, b, c, c + 3],
            [a, b, c + 3, b + 3],
            [a, a + 3, b + 3, c + 3],
        ];
        if odd {
            for t in &mut tets {
                t.swap(0, 1);
            }
        }
        tets
    }
}
