//! Bilinear patches: the curved sides `β_e` of a fundamental prism (Cohen et al. 1996, section 3,
//! Fig. 2(b)), with an exact side function and an exact segment test.
//!
//! A patch with corners `p00, p10, p01, p11` is `B(u, s) = (1-u)((1-s) p00 + s p01) + u((1-s) p10
//! + s p11)`, `(u, s) ∈ [0, 1]²`. Its lines `s = 0` (`p00 p10`) and `s = 1` (`p01 p11`) are the
//! *directrices*; the lines `u = const` are the *rulings*.
//!
//! **Side function.** For a query `q` let
//! `α0 = orient3d(q, p01, p11, p00)`, `α1 = orient3d(q, p01, p11, p10)` (the plane through `q`
//! and the top directrix, evaluated at the two bottom corners) and
//! `β0 = orient3d(q, p00, p10, p01)`, `β1 = orient3d(q, p00, p10, p11)` (the plane through `q` and
//! the bottom directrix, at the two top corners). Then
//!
//! `F(q) = α0·β1 − α1·β0`
//!
//! is a quadratic polynomial in `q` that vanishes exactly on the hyperbolic paraboloid carrying
//! the patch: `q` lies on the ruling `u` iff the plane `(q, top line)` meets the bottom line at
//! `a(u)` *and* the plane `(q, bottom line)` meets the top line at `c(u)`, i.e. iff `(α0, α1)`
//! and `(β0, β1)` are both orthogonal to `(1-u, u)`. `F = P4·P2 − P3·P1` is the member of the
//! pencil of quadrics through the skew quadrilateral `p00 p10 p11 p01` (the `P` are its four
//! face planes) that contains the patch. At `p00`, `∇F = T·N` with
//! `T = orient3d(p00, p01, p11, p10)` (the twist: zero iff the patch is planar) and
//! `N = (p10 − p00)×(p01 − p00)` the patch normal, so **`side(q) = sign(F(q))·sign(T)`** is
//! positive on the side `N` points to. When `T = 0` the patch is planar and `side` is the plain
//! `orient3d(p00, p10, p01, q)` (same orientation). `F` is evaluated with a rigorous f64 error
//! bound and, when that cannot decide, exactly in rationals: the sign is exact.
//!
//! The zero set of `F` is the whole quadric, whose other parts can pass within a patch width of
//! the patch when it is nearly planar. So `F` is used only inside the hull tetrahedron `H` of the
//! four corners, where the quadric meets nothing but the patch (the bilinear weights of `B(u, s)`
//! are barycentric coordinates in `H`). Outside `H`, `side` is the side of the *outer split*
//! (the two corner triangles on the outer side of the patch): `min` of their two orientations,
//! a convex wedge that continues the patch across its four boundary edges.

use envelope_predicates::exact_num::Rational;
use envelope_predicates::{Filtered, Kernel, Orientation, Sign, generic};
use glam::DVec3;
use std::rc::Rc;

use crate::num::{ErrF64, Num, QSqrt, V, orient3d, rational_sign};

/// A bilinear patch `B(u, s)` given by its four corners (the side function is derived in the crate README).
///
/// ```
/// use envelope_prism::Patch;
/// use envelope_predicates::Sign;
/// use glam::DVec3;
/// // A twisted patch: the top edge is turned about the vertical axis.
/// let p = Patch::new(DVec3::new(0., 0., 0.), DVec3::new(1., 0., 0.),
///                    DVec3::new(0., 0., 1.), DVec3::new(1., 1., 1.));
/// assert!(!p.is_planar());
/// assert_eq!(p.side(p.point(0.5, 0.5)), Sign::Zero); // (0.5, 0.25, 0.5), exact
/// // The normal (p10 - p00) x (p01 - p00) = -y at p00; the surface is y = x z.
/// assert_eq!(p.side(DVec3::new(0.5, 0.0, 0.5)), Sign::Positive);
/// assert_eq!(p.side(DVec3::new(0.5, 0.5, 0.5)), Sign::Negative);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Patch {
    /// `[p00, p10, p01, p11]`.
    corners: [DVec3; 4],
}

impl Patch {
    /// The patch with corners `B(0,0) = p00`, `B(1,0) = p10`, `B(0,1) = p01`, `B(1,1) = p11`.
    #[must_use]
    pub fn new(p00: DVec3, p10: DVec3, p01: DVec3, p11: DVec3) -> Patch {
        Patch {
            corners: [p00, p10, p01, p11],
        }
    }

    /// `[p00, p10, p01, p11]`.
    #[must_use]
    pub fn corners(&self) -> [DVec3; 4] {
        self.corners
    }

    /// `B(u, s)`, a *construction* in f64 (rounded; exact when all the products and sums are,
    /// e.g. dyadic corners and parameters). Used for tests and sampling, never for decisions.
    #[must_use]
    pub fn point(&self, u: f64, s: f64) -> DVec3 {
        let [p00, p10, p01, p11] = self.corners;
        let a = p00 * (1.0 - s) + p01 * s;
        let c = p10 * (1.0 - s) + p11 * s;
        a * (1.0 - u) + c * u
    }

    /// The twist `orient3d(p00, p01, p11, p10)`: `Degenerate` iff the four corners are coplanar.
    #[must_use]
    pub fn twist(&self) -> Orientation {
        details::twist::<Filtered>(self)
    }

    /// True when the four corners are coplanar (exact): the patch is a planar quadrilateral.
    #[must_use]
    pub fn is_planar(&self) -> bool {
        self.twist().is_degenerate()
    }

    /// Exact side of `q`: `Zero` on the patch's surface (the quadric inside the corners' hull
    /// tetrahedron, the outer split's planes outside it; the plane if planar), `Positive` on the
    /// side the normal `(p10 − p00)×(p01 − p00)` points to.
    #[must_use]
    pub fn side(&self, q: DVec3) -> Sign {
        details::side_of_patch::<Filtered>(self, q)
    }

    /// True when the closed segment `pq` meets the closed patch (exact; `p == q` is a point test).
    ///
    /// ```
    /// use envelope_prism::Patch;
    /// use glam::DVec3;
    /// let p = Patch::new(DVec3::ZERO, DVec3::X, DVec3::Z, DVec3::new(1., 1., 1.));
    /// assert!(p.intersects_segment(DVec3::new(0.5, -1., 0.5), DVec3::new(0.5, 1., 0.5)));
    /// assert!(!p.intersects_segment(DVec3::new(2., -1., 0.5), DVec3::new(2., 1., 0.5)));
    /// ```
    #[must_use]
    pub fn intersects_segment(&self, p: DVec3, q: DVec3) -> bool {
        details::segment_patch::<Filtered>(self, p, q)
    }

    /// The two triangles of the planar split along the diagonal `p00 p11` (`main = true`) or
    /// `p10 p01`, both oriented like the patch normal.
    #[must_use]
    pub fn split(&self, main: bool) -> [[DVec3; 3]; 2] {
        let [p00, p10, p01, p11] = self.corners;
        if main {
            [[p00, p10, p11], [p00, p11, p01]]
        } else {
            [[p00, p10, p01], [p10, p11, p01]]
        }
    }
}

/// `F(q)` over `N` (see the module docs).
fn side_polynomial<N: Num>(c: &[V<N>; 4], q: &V<N>) -> N {
    let [p00, p10, p01, p11] = c;
    let a0 = orient3d(q, p01, p11, p00);
    let a1 = orient3d(q, p01, p11, p10);
    let b0 = orient3d(q, p00, p10, p01);
    let b1 = orient3d(q, p00, p10, p11);
    a0.mul(&b1).sub(&a1.mul(&b0))
}

/// Specialised and kernel-generic variants.
pub mod details {
    use super::*;

    /// [`Patch::twist`] on kernel `K`.
    #[must_use]
    pub fn twist<K: Kernel>(patch: &Patch) -> Orientation {
        let [p00, p10, p01, p11] = patch.corners;
        K::orient3d(p00, p01, p11, p10)
    }

    /// The sign of `F(q)` (the unoriented quadric polynomial of the module docs), through the
    /// f64 filter with an exact-rational fallback.
    #[must_use]
    pub fn quadric_sign_filtered(patch: &Patch, q: DVec3) -> Sign {
        let c = patch.corners.map(V::<ErrF64>::pt);
        match side_polynomial(&c, &V::pt(q)).sign() {
            Some(s) => s,
            None => quadric_sign_exact(patch, q),
        }
    }

    /// The sign of `F(q)`, always in exact rationals.
    #[must_use]
    pub fn quadric_sign_exact(patch: &Patch, q: DVec3) -> Sign {
        let c = patch.corners.map(V::<Rational>::pt);
        rational_sign(&side_polynomial(&c, &V::pt(q)))
    }

    /// [`Patch::side`] with the orientation tests on kernel `K` (the quadric sign always goes
    /// through the filter and, if needed, rationals).
    #[must_use]
    pub fn side_of_patch<K: Kernel>(patch: &Patch, q: DVec3) -> Sign {
        let t = twist::<K>(patch).sign();
        if t == Sign::Zero {
            return planar_side::<K>(patch, q);
        }
        if point_in_tetrahedron::<K>(q, patch.corners) {
            // In the hull the quadric meets only the patch: the bilinear weights of B(u, s)
            // are its barycentric coordinates, all >= 0 iff (u, s) ∈ [0, 1]².
            return quadric_sign_filtered(patch, q) * t;
        }
        // Outside the hull: the two planes of the outer split (the inner split for the
        // opposite orientation), continuing the patch across its four boundary edges.
        let outer = patch.split(t == Sign::Negative);
        let s0 = K::orient3d(outer[0][0], outer[0][1], outer[0][2], q).sign();
        let s1 = K::orient3d(outer[1][0], outer[1][1], outer[1][2], q).sign();
        s0.min(s1)
    }

    /// The side of `q` for a planar patch: `orient3d(p00, p10, p01, q)`, or through the corner
    /// `p11` when `p00, p10, p01` are collinear; `Zero` for a patch without area.
    fn planar_side<K: Kernel>(patch: &Patch, q: DVec3) -> Sign {
        let [p00, p10, p01, p11] = patch.corners;
        if !generic::collinear::<K>(p00, p10, p01) {
            K::orient3d(p00, p10, p01, q).sign()
        } else if !generic::collinear::<K>(p11, p01, p10) {
            K::orient3d(p11, p01, p10, q).sign()
        } else {
            Sign::Zero
        }
    }

    /// [`Patch::intersects_segment`] with the orientation tests on kernel `K`.
    ///
    /// Planar patches: the two triangles of either split (equal to the quadrilateral when it is
    /// convex). Curved patches: box and tetrahedral-hull rejection, then the exact method: a
    /// point of the patch lies on a ruling `u ∈ [0, 1]`; the line `p + t·d` is coplanar with the
    /// ruling `a(u) c(u)` iff `φ(u) = det[d, a(u) − p, c(u) − a(u)] = 0`, a quadratic in `u`.
    /// Each root (in `Q(√D)`, no rounding) is kept when `u ∈ [0, 1]` and the two coplanar lines
    /// meet at `t ∈ [0, 1]` on the segment and `s ∈ [0, 1]` on the ruling (or overlap, if
    /// parallel). If `φ ≡ 0` the other family of rulings is used.
    #[must_use]
    pub fn segment_patch<K: Kernel>(patch: &Patch, p: DVec3, q: DVec3) -> bool {
        let c = patch.corners;
        if !boxes_overlap(&c, &[p, q]) {
            return false;
        }
        if twist::<K>(patch).is_degenerate() {
            return patch
                .split(true)
                .iter()
                .chain(patch.split(false).iter())
                .any(|t| generic::segment_triangle::<K>(p, q, *t).intersects());
        }
        if !segment_meets_tetrahedron::<K>(p, q, c) {
            return false;
        }
        segment_patch_exact(patch, p, q)
    }

    /// The exact method of [`segment_patch`] without the rejection tests, all in rationals.
    #[must_use]
    pub fn segment_patch_exact(patch: &Patch, p: DVec3, q: DVec3) -> bool {
        let pr = V::<Rational>::pt(p);
        if p == q {
            // A point: lines through p in the axis directions, with t ∈ [0, 0].
            for d in [DVec3::X, DVec3::Y, DVec3::Z] {
                if let Some(hit) = line_hits(patch, &pr, &V::pt(d), &Rational::new()) {
                    return hit;
                }
            }
            unreachable!("no axis line is coplanar with every ruling of both families")
        }
        let d = V::<Rational>::pt(q).sub(&pr);
        match line_hits(patch, &pr, &d, &Rational::from(1)) {
            Some(hit) => hit,
            // Only a planar patch has a line coplanar with all rulings of both families.
            None => patch
                .split(true)
                .iter()
                .any(|t| generic::segment_triangle::<Filtered>(p, q, *t).intersects()),
        }
    }
}

/// Closed axis-aligned boxes of two point sets overlap (exact: comparisons of doubles).
pub(crate) fn boxes_overlap(a: &[DVec3], b: &[DVec3]) -> bool {
    let bounds = |s: &[DVec3]| {
        s.iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            })
    };
    let (alo, ahi) = bounds(a);
    let (blo, bhi) = bounds(b);
    alo.cmple(bhi).all() && blo.cmple(ahi).all()
}

/// The closed segment meets the closed tetrahedron `t` (non-degenerate), exact.
fn segment_meets_tetrahedron<K: Kernel>(p: DVec3, q: DVec3, t: [DVec3; 4]) -> bool {
    point_in_tetrahedron::<K>(p, t)
        || point_in_tetrahedron::<K>(q, t)
        || [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]
            .iter()
            .any(|f| generic::segment_triangle::<K>(p, q, f.map(|i| t[i])).intersects())
}

/// `p` in the closed non-degenerate tetrahedron `t`.
pub(crate) fn point_in_tetrahedron<K: Kernel>(p: DVec3, t: [DVec3; 4]) -> bool {
    let o = K::orient3d(t[0], t[1], t[2], t[3]).sign();
    let faces = [(0, 1, 2, 3), (1, 0, 3, 2), (2, 3, 0, 1), (3, 2, 1, 0)];
    // Each face (a, b, c) with opposite vertex d: p on d's side or on the face.
    faces.iter().all(|&(a, b, c, d)| {
        let side = K::orient3d(t[a], t[b], t[c], p).sign();
        let want = K::orient3d(t[a], t[b], t[c], t[d]).sign();
        debug_assert!(want == o || want == o.reverse());
        side == Sign::Zero || side == want
    })
}

/// The determinant `d · (w × e)`.
fn det<N: Num>(d: &V<N>, w: &V<N>, e: &V<N>) -> N {
    d.dot(&w.cross(e))
}

/// Does the closed segment `p + t·d`, `t ∈ [0, tmax]`, meet the patch? `None` when the line is
/// coplanar with every ruling of both families.
fn line_hits(patch: &Patch, p: &V<Rational>, d: &V<Rational>, tmax: &Rational) -> Option<bool> {
    let [p00, p10, p01, p11] = patch.corners.map(V::<Rational>::pt);
    // (A0, A1, C0, C1): the ruling at x joins A(x) = A0 + x(A1 - A0) to C(x) = C0 + x(C1 - C0).
    let families = [
        (&p00, &p10, &p01, &p11), // rulings u = const, from the bottom line to the top line
        (&p00, &p01, &p10, &p11), // rulings s = const, from the left leg to the right leg
    ];
    for (a0, a1, c0, c1) in families {
        let w0 = a0.sub(p);
        let w1 = a1.sub(a0);
        let e0 = c0.sub(a0);
        let e1 = c1.sub(c0).sub(&w1);
        let f0 = det(d, &w0, &e0);
        let f1 = det(d, &w0, &e1).add(&det(d, &w1, &e0));
        let f2 = det(d, &w1, &e1);
        let roots = match quadratic_roots(&f0, &f1, &f2) {
            Some(r) => r,
            None => continue,
        };
        let hit = roots.iter().any(|x| {
            let lift = |v: &V<Rational>| {
                V(
                    QSqrt::new(v.0.clone(), Rational::new(), x.1.clone()),
                    QSqrt::new(v.1.clone(), Rational::new(), x.1.clone()),
                    QSqrt::new(v.2.clone(), Rational::new(), x.1.clone()),
                )
            };
            let xs = &x.0;
            let scale = |v: &V<Rational>| {
                let l = lift(v);
                V(xs.mul(&l.0), xs.mul(&l.1), xs.mul(&l.2))
            };
            let one = QSqrt::new(Rational::from(1), Rational::new(), x.1.clone());
            let tm = QSqrt::new(tmax.clone(), Rational::new(), x.1.clone());
            if xs.sign() == Sign::Negative || one.sub(xs).sign() == Sign::Negative {
                return false;
            }
            let dq = lift(d);
            let w = add(&lift(&w0), &scale(&w1));
            let e = add(&lift(&e0), &scale(&e1));
            ruling_meets_segment(&dq, &w, &e, &tm, &one)
        });
        return Some(hit);
    }
    None
}

fn add<N: Num>(a: &V<N>, b: &V<N>) -> V<N> {
    V(a.0.add(&b.0), a.1.add(&b.1), a.2.add(&b.2))
}

/// Segment `p + t·d`, `t ∈ [0, tmax]` and ruling `A + s·e`, `s ∈ [0, 1]`, coplanar, with
/// `w = A − p`: do they meet?
fn ruling_meets_segment(
    d: &V<QSqrt>,
    w: &V<QSqrt>,
    e: &V<QSqrt>,
    tmax: &QSqrt,
    one: &QSqrt,
) -> bool {
    let n = d.cross(e);
    let den = n.dot(&n);
    let nonneg = |x: &QSqrt| x.sign() != Sign::Negative;
    if den.sign() == Sign::Zero {
        // Parallel (or a degenerate ruling): they meet only if the ruling lies on the line.
        let c = w.cross(d);
        if [&c.0, &c.1, &c.2].iter().any(|x| x.sign() != Sign::Zero) {
            return false;
        }
        let dd = d.dot(d);
        let ka = w.dot(d); // t of A, times d·d
        let kc = add(w, e).dot(d); // t of C, times d·d
        let lim = tmax.mul(&dd);
        let below = ka.sign() == Sign::Negative && kc.sign() == Sign::Negative;
        let above = ka.sub(&lim).sign() == Sign::Positive && kc.sub(&lim).sign() == Sign::Positive;
        return !below && !above;
    }
    let tnum = w.cross(e).dot(&n);
    let snum = w.cross(d).dot(&n);
    nonneg(&tnum)
        && nonneg(&tmax.mul(&den).sub(&tnum))
        && nonneg(&snum)
        && nonneg(&one.mul(&den).sub(&snum))
}

/// Real roots of `f2 x² + f1 x + f0` as `a + b√D` (with their shared `D`); `None` if the
/// polynomial is identically zero.
fn quadratic_roots(
    f0: &Rational,
    f1: &Rational,
    f2: &Rational,
) -> Option<Vec<(QSqrt, Rc<Rational>)>> {
    let zero = Rc::new(Rational::new());
    let rat = |a: Rational| (QSqrt::new(a, Rational::new(), zero.clone()), zero.clone());
    if f2.cmp0().is_eq() {
        if f1.cmp0().is_eq() {
            return if f0.cmp0().is_eq() {
                None
            } else {
                Some(vec![])
            };
        }
        return Some(vec![rat((-f0) / f1)]);
    }
    let disc = (f1 * f1) - (f2 * f0) * 4u32;
    match disc.cmp0() {
        std::cmp::Ordering::Less => Some(vec![]),
        std::cmp::Ordering::Equal => Some(vec![rat((-f1) / (f2 * 2u32))]),
        std::cmp::Ordering::Greater => {
            let d = Rc::new(disc);
            let two_a = f2 * 2u32;
            let a = (-f1) / &two_a;
            let b = Rational::from(1) / &two_a;
            Some(vec![
                (QSqrt::new(a.clone(), b.clone(), d.clone()), d.clone()),
                (QSqrt::new(a, -b, d.clone()), d),
            ])
        }
    }
}
