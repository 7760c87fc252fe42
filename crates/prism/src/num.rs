//! Exact arithmetic for the patch predicates: one polynomial, evaluated either with a rigorous
//! running error bound ([`ErrF64`], the filter) or exactly ([`rug::Rational`], the fallback),
//! both from `envelope_predicates::arith`, plus the quadratic extension `Q(√D)` ([`QSqrt`])
//! used to place the roots of a quadratic.

use envelope_predicates::Sign;
use envelope_predicates::exact_num::Rational;

pub(crate) use envelope_predicates::arith::{ErrF64, Num, V, rational_sign};

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
        let a2 = &self.a * &self.a;
        let b2d = (&self.b * &self.b) * &*self.d;
        sa * rational_sign(&(a2 - b2d))
    }
}

impl Num for QSqrt {
    fn lit(_x: f64) -> Self {
        unreachable!("QSqrt literals are made with QSqrt::new (they need the shared radicand)")
    }
    fn add(&self, o: &Self) -> Self {
        QSqrt::new(&self.a + &o.a, &self.b + &o.b, self.d.clone())
    }
    fn sub(&self, o: &Self) -> Self {
        QSqrt::new(&self.a - &o.a, &self.b - &o.b, self.d.clone())
    }
    fn mul(&self, o: &Self) -> Self {
        let a = (&self.a * &o.a) + (&self.b * &o.b) * &*self.d;
        let b = (&self.a * &o.b) + (&self.b * &o.a);
        QSqrt::new(a, b, self.d.clone())
    }
}
