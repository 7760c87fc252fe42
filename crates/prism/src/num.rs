//! Exact arithmetic for the patch predicates: one polynomial, evaluated either with a rigorous
//! running error bound ([`ErrF64`], the filter) or exactly ([`rug::Rational`], the fallback),
//! plus the quadratic extension `Q(√D)` ([`QSqrt`]) used to place the roots of a quadratic.

use envelope_predicates::Sign;
use glam::DVec3;
use rug::Rational;

/// A ring in which the predicate polynomials are evaluated.
pub(crate) trait Num: Sized + Clone {
    fn lit(x: f64) -> Self;
    fn add(&self, o: &Self) -> Self;
    fn sub(&self, o: &Self) -> Self;
    fn mul(&self, o: &Self) -> Self;
}

/// Unit roundoff 2^-53.
const U: f64 = 1.0 / 9_007_199_254_740_992.0;
/// Inflation factor covering the rounding of the bound computation itself.
const INFLATE: f64 = 1.0 + 8.0 * U;
/// Absolute slack per operation covering underflow (each underflowing rounding errs by <= 2^-1075).
const TINY: f64 = 1.0e-318;

/// An f64 approximation `v` of an exact real `x` with a rigorous bound `|v - x| <= e`
/// (same scheme as `envelope-predicates`' filter).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ErrF64 {
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
        let e = self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + U * v.abs() + TINY;
        ErrF64 { v, e: e * INFLATE }
    }
}

impl ErrF64 {
    /// The certified sign, or `None` when the filter cannot decide.
    #[inline]
    pub(crate) fn sign(self) -> Option<Sign> {
        if !(self.v.is_finite() && self.e.is_finite()) {
            None
        } else if self.v > self.e {
            Some(Sign::Positive)
        } else if -self.v > self.e {
            Some(Sign::Negative)
        } else if self.e == 0.0 && self.v == 0.0 {
            Some(Sign::Zero)
        } else {
            None
        }
    }
}

/// Converts a finite double to an exact rational.
///
/// # Panics
/// On NaN or an infinity (inputs are validated at the boundary).
pub(crate) fn rational(x: f64) -> Rational {
    Rational::from_f64(x).unwrap_or_else(|| {
        panic!("envelope-prism: non-finite coordinate {x:?}; validate inputs first")
    })
}

impl Num for Rational {
    fn lit(x: f64) -> Self {
        rational(x)
    }
    fn add(&self, o: &Self) -> Self {
        Rational::from(self + o)
    }
    fn sub(&self, o: &Self) -> Self {
        Rational::from(self - o)
    }
    fn mul(&self, o: &Self) -> Self {
        Rational::from(self * o)
    }
}

/// Exact sign of a rational.
pub(crate) fn rational_sign(r: &Rational) -> Sign {
    Sign::from_ordering(r.cmp0())
}

/// A 3-vector over `N`.
#[derive(Clone, Debug)]
pub(crate) struct V<N>(pub N, pub N, pub N);

impl<N: Num> V<N> {
    pub(crate) fn pt(p: DVec3) -> Self {
        V(N::lit(p.x), N::lit(p.y), N::lit(p.z))
    }
    pub(crate) fn sub(&self, o: &Self) -> Self {
        V(self.0.sub(&o.0), self.1.sub(&o.1), self.2.sub(&o.2))
    }
    pub(crate) fn dot(&self, o: &Self) -> N {
        self.0
            .mul(&o.0)
            .add(&self.1.mul(&o.1))
            .add(&self.2.mul(&o.2))
    }
    pub(crate) fn cross(&self, o: &Self) -> Self {
        V(
            self.1.mul(&o.2).sub(&self.2.mul(&o.1)),
            self.2.mul(&o.0).sub(&self.0.mul(&o.2)),
            self.0.mul(&o.1).sub(&self.1.mul(&o.0)),
        )
    }
}

/// `((b-a)×(c-a))·(d-a)` over `N`.
pub(crate) fn orient3d<N: Num>(a: &V<N>, b: &V<N>, c: &V<N>, d: &V<N>) -> N {
    b.sub(a).cross(&c.sub(a)).dot(&d.sub(a))
}

/// `a + b·√d` for rationals `a, b` and a fixed rational `d >= 0` (shared by all operands).
#[derive(Clone, Debug)]
pub(crate) struct QSqrt {
    pub a: Rational,
    pub b: Rational,
    d: std::rc::Rc<Rational>,
}

impl QSqrt {
    /// The field element `a + b√d`.
    pub(crate) fn new(a: Rational, b: Rational, d: std::rc::Rc<Rational>) -> Self {
        QSqrt { a, b, d }
    }

    /// The exact sign of `a + b√d`.
    pub(crate) fn sign(&self) -> Sign {
        let sa = rational_sign(&self.a);
        let sb = if self.d.cmp0().is_eq() {
            Sign::Zero
        } else {
            rational_sign(&self.b)
        };
        if sb == Sign::Zero {
            return sa;
        }
        if sa == Sign::Zero || sa == sb {
            return sb;
        }
        // Opposite signs: |a| vs |b|√d, i.e. the sign of a² - b²d, carried by a.
        let a2 = Rational::from(&self.a * &self.a);
        let b2d = Rational::from(&self.b * &self.b) * &*self.d;
        sa * rational_sign(&(a2 - b2d))
    }
}

impl Num for QSqrt {
    fn lit(_x: f64) -> Self {
        unreachable!("QSqrt literals are made with QSqrt::new (they need the shared radicand)")
    }
    fn add(&self, o: &Self) -> Self {
        QSqrt::new(
            Rational::from(&self.a + &o.a),
            Rational::from(&self.b + &o.b),
            self.d.clone(),
        )
    }
    fn sub(&self, o: &Self) -> Self {
        QSqrt::new(
            Rational::from(&self.a - &o.a),
            Rational::from(&self.b - &o.b),
            self.d.clone(),
        )
    }
    fn mul(&self, o: &Self) -> Self {
        let a = Rational::from(&self.a * &o.a) + Rational::from(&self.b * &o.b) * &*self.d;
        let b = Rational::from(&self.a * &o.b) + Rational::from(&self.b * &o.a);
        QSqrt::new(a, b, self.d.clone())
    }
}
