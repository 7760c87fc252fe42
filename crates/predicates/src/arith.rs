//! Generic polynomial evaluation: every non-orientation primitive is written once over [`Num`]
//! and evaluated either with a rigorous running error bound ([`ErrF64`], the filter) or exactly
//! ([`Dyadic`], the fallback; any [`ExactNum`]).
//!
//! Public for crates that write their own exact predicates on the same pattern (the prism
//! crate's bilinear-patch tests): evaluate the polynomial on [`ErrF64`], take
//! [`ErrF64::sign`], and when it is `None` evaluate it again on `Rational` and take
//! [`rational_sign`].

use glam::DVec3;

use crate::Sign;
pub use crate::exact_num::{Dyadic, Rational};

/// A ring in which the predicate polynomials are evaluated.
pub trait Num: Sized + Clone {
    /// An input double, exactly.
    fn lit(x: f64) -> Self;
    /// `self + o`.
    fn add(&self, o: &Self) -> Self;
    /// `self - o`.
    fn sub(&self, o: &Self) -> Self;
    /// `self * o`.
    fn mul(&self, o: &Self) -> Self;
}

/// Unit roundoff 2^-53.
const U: f64 = 1.0 / 9_007_199_254_740_992.0;
/// Inflation factor covering the rounding of the bound computation itself (at most 6 roundings).
const INFLATE: f64 = 1.0 + 8.0 * U;
/// Absolute slack per operation covering underflow (each underflowing rounding errs by <= 2^-1075).
const TINY: f64 = 1.0e-318;

/// An f64 approximation `v` of an exact real `x` with a rigorous bound `|v - x| <= e`.
#[derive(Clone, Copy, Debug)]
pub struct ErrF64 {
    v: f64,
    e: f64,
}

impl Num for ErrF64 {
    #[inline]
    fn lit(x: f64) -> Self {
        ErrF64 { v: x, e: 0.0 }
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        let v = self.v + o.v;
        // |fl(x~ + y~) - (x~ + y~)| <= U |fl(...)|; input errors add up.
        ErrF64 {
            v,
            e: (self.e + o.e + U * v.abs() + TINY) * INFLATE,
        }
    }
    #[inline]
    fn sub(&self, o: &Self) -> Self {
        let v = self.v - o.v;
        ErrF64 {
            v,
            e: (self.e + o.e + U * v.abs() + TINY) * INFLATE,
        }
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        let v = self.v * o.v;
        // |x~ y~ - x y| <= |x~| e_y + |y~| e_x + e_x e_y, plus the rounding of the product.
        let e = self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + U * v.abs() + TINY;
        ErrF64 { v, e: e * INFLATE }
    }
}

impl ErrF64 {
    /// The certified sign, or `None` when the filter cannot decide.
    #[inline]
    pub fn sign(self) -> Option<Sign> {
        if !(self.v.is_finite() && self.e.is_finite()) {
            None
        } else if self.v > self.e {
            Some(Sign::Positive)
        } else if -self.v > self.e {
            Some(Sign::Negative)
        } else if self.e == 0.0 {
            // Only reachable for an exact literal.
            Some(if self.v == 0.0 {
                Sign::Zero
            } else if self.v > 0.0 {
                Sign::Positive
            } else {
                Sign::Negative
            })
        } else {
            None
        }
    }
}

/// Converts a finite double to an exact rational.
///
/// # Panics
/// On NaN or an infinity: predicates are undefined there (inputs are validated at the boundary).
pub fn rational(x: f64) -> Rational {
    Rational::from_f64(x).unwrap_or_else(|| {
        panic!("envelope-predicates: non-finite coordinate {x:?}; validate inputs (envelope_mesh::check_coordinate)")
    })
}

impl Num for Dyadic {
    fn lit(x: f64) -> Self {
        Dyadic::from_f64(x)
    }
    fn add(&self, o: &Self) -> Self {
        Dyadic::add(self, o)
    }
    fn sub(&self, o: &Self) -> Self {
        Dyadic::sub(self, o)
    }
    fn mul(&self, o: &Self) -> Self {
        Dyadic::mul(self, o)
    }
}

impl Num for Rational {
    fn lit(x: f64) -> Self {
        rational(x)
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
}

/// A number whose sign is exact: what the exact path evaluates a polynomial on.
pub trait ExactNum: Num {
    /// The exact sign.
    fn exact_sign(&self) -> Sign;
}

impl ExactNum for Dyadic {
    fn exact_sign(&self) -> Sign {
        self.sign()
    }
}

impl ExactNum for Rational {
    fn exact_sign(&self) -> Sign {
        rational_sign(self)
    }
}

/// Exact sign of a rational.
pub fn rational_sign(r: &Rational) -> Sign {
    Sign::from_ordering(r.cmp0())
}

#[cfg(feature = "gmp")]
impl Num for rug::Rational {
    fn lit(x: f64) -> Self {
        rug::Rational::from_f64(x).unwrap_or_else(|| {
            panic!("envelope-predicates: non-finite coordinate {x:?}; validate inputs (envelope_mesh::check_coordinate)")
        })
    }
    fn add(&self, o: &Self) -> Self {
        rug::Rational::from(self + o)
    }
    fn sub(&self, o: &Self) -> Self {
        rug::Rational::from(self - o)
    }
    fn mul(&self, o: &Self) -> Self {
        rug::Rational::from(self * o)
    }
}

#[cfg(feature = "gmp")]
impl ExactNum for rug::Rational {
    fn exact_sign(&self) -> Sign {
        Sign::from_ordering(self.cmp0())
    }
}

/// A 3-vector over `N`.
#[derive(Clone, Debug)]
pub struct V<N>(pub N, pub N, pub N);

impl<N: Num> V<N> {
    /// An input point, exactly.
    pub fn pt(p: DVec3) -> Self {
        V(N::lit(p.x), N::lit(p.y), N::lit(p.z))
    }
    /// `b - a` for input points (the subtraction is the first rounded operation).
    pub fn diff(b: DVec3, a: DVec3) -> Self {
        let (b, a) = (V::<N>::pt(b), V::<N>::pt(a));
        V(b.0.sub(&a.0), b.1.sub(&a.1), b.2.sub(&a.2))
    }
    /// `self - o`.
    pub fn sub(&self, o: &Self) -> Self {
        V(self.0.sub(&o.0), self.1.sub(&o.1), self.2.sub(&o.2))
    }
    /// Dot product.
    pub fn dot(&self, o: &Self) -> N {
        self.0
            .mul(&o.0)
            .add(&self.1.mul(&o.1))
            .add(&self.2.mul(&o.2))
    }
    /// Cross product.
    pub fn cross(&self, o: &Self) -> Self {
        V(
            self.1.mul(&o.2).sub(&self.2.mul(&o.1)),
            self.2.mul(&o.0).sub(&self.0.mul(&o.2)),
            self.0.mul(&o.1).sub(&self.1.mul(&o.0)),
        )
    }
}

// ---- the primitive polynomials ----

/// `((b-a)×(c-a))·(d-a)`.
pub(crate) fn orient3d<N: Num>(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> N {
    V::<N>::diff(b, a).cross(&V::diff(c, a)).dot(&V::diff(d, a))
}

/// `(b-a)×(c-a)` in the plane.
pub(crate) fn orient2d<N: Num>(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> N {
    let (ax, ay) = (N::lit(a[0]), N::lit(a[1]));
    let (ux, uy) = (N::lit(b[0]).sub(&ax), N::lit(b[1]).sub(&ay));
    let (vx, vy) = (N::lit(c[0]).sub(&ax), N::lit(c[1]).sub(&ay));
    ux.mul(&vy).sub(&uy.mul(&vx))
}

/// Shewchuk's insphere determinant, negated: rows `(p - e, |p - e|^2)` for `p = a, b, c, d`, times -1.
pub(crate) fn insphere<N: Num>(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> N {
    let rows = [a, b, c, d].map(|p| {
        let v = V::<N>::diff(p, e);
        let w = v.dot(&v);
        [v.0, v.1, v.2, w]
    });
    let m = |i: usize, j: usize| {
        rows[i][0]
            .mul(&rows[j][1])
            .sub(&rows[j][0].mul(&rows[i][1]))
    };
    let n = |k: usize, l: usize| {
        rows[k][2]
            .mul(&rows[l][3])
            .sub(&rows[l][2].mul(&rows[k][3]))
    };
    let det = m(0, 1)
        .mul(&n(2, 3))
        .sub(&m(0, 2).mul(&n(1, 3)))
        .add(&m(0, 3).mul(&n(1, 2)))
        .add(&m(1, 2).mul(&n(0, 3)))
        .sub(&m(1, 3).mul(&n(0, 2)))
        .add(&m(2, 3).mul(&n(0, 1)));
    N::lit(0.0).sub(&det)
}

/// `(b-a)·(d-c)`.
pub(crate) fn dot<N: Num>(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> N {
    V::<N>::diff(b, a).dot(&V::diff(d, c))
}

/// `|p-q|^2 - eps2`.
pub(crate) fn sq_dist<N: Num>(p: DVec3, q: DVec3, eps2: f64) -> N {
    let v = V::<N>::diff(p, q);
    v.dot(&v).sub(&N::lit(eps2))
}

/// `|(p-a)×(b-a)|^2 - eps2 |b-a|^2` (`|b-a|^2` times the squared distance from `p` to line `ab`, minus eps2).
pub(crate) fn point_line<N: Num>(p: DVec3, a: DVec3, b: DVec3, eps2: f64) -> N {
    let u = V::<N>::diff(b, a);
    let x = V::<N>::diff(p, a).cross(&u);
    x.dot(&x).sub(&N::lit(eps2).mul(&u.dot(&u)))
}

/// `(n·(p-a))^2 - eps2 |n|^2` with `n = (b-a)×(c-a)`.
pub(crate) fn point_plane<N: Num>(p: DVec3, a: DVec3, b: DVec3, c: DVec3, eps2: f64) -> N {
    let n = V::<N>::diff(b, a).cross(&V::diff(c, a));
    let s = n.dot(&V::diff(p, a));
    s.mul(&s).sub(&N::lit(eps2).mul(&n.dot(&n)))
}

/// `((d1×d2)·(p0-q0))^2 - eps2 |d1×d2|^2` with `d1 = p1-p0`, `d2 = q1-q0`.
pub(crate) fn line_line<N: Num>(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3, eps2: f64) -> N {
    let n = V::<N>::diff(p1, p0).cross(&V::diff(q1, q0));
    let s = n.dot(&V::diff(p0, q0));
    s.mul(&s).sub(&N::lit(eps2).mul(&n.dot(&n)))
}

/// `(u·u)(v·w) - (u·v)(u·w)` with `u = b-a, v = c-a, w = p-a`: equals `(n×u)·w` for the normal
/// `n = u×v`, i.e. positive when `p` is on `c`'s side of the line `ab` after orthogonal
/// projection onto the plane `abc`.
pub(crate) fn edge_side<N: Num>(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> N {
    let (u, v, w) = (V::<N>::diff(b, a), V::<N>::diff(c, a), V::<N>::diff(p, a));
    u.dot(&u).mul(&v.dot(&w)).sub(&u.dot(&v).mul(&u.dot(&w)))
}

/// For segments `p0 + s d1`, `q0 + t d2` (`r = p0 - q0`): with `a = d1·d1, b = d1·d2,
/// c = d2·d2, d = d1·r, e = d2·r, den = ac - b²`, the closest points of the two lines have
/// `s = (be - cd)/den`, `t = (ae - bd)/den`. Returns `[be-cd, den-(be-cd), ae-bd, den-(ae-bd)]`;
/// all four are positive exactly when the closest points are interior to both segments.
pub(crate) fn closest_params<N: Num>(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> [N; 4] {
    let (d1, d2, r) = (
        V::<N>::diff(p1, p0),
        V::<N>::diff(q1, q0),
        V::<N>::diff(p0, q0),
    );
    let (a, b, c, d, e) = (
        d1.dot(&d1),
        d1.dot(&d2),
        d2.dot(&d2),
        d1.dot(&r),
        d2.dot(&r),
    );
    let den = a.mul(&c).sub(&b.mul(&b));
    let s = b.mul(&e).sub(&c.mul(&d));
    let t = a.mul(&e).sub(&b.mul(&d));
    let ds = den.sub(&s);
    let dt = den.sub(&t);
    [s, ds, t, dt]
}
