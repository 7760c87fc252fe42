//! The numbers of the exact path, in pure Rust (no C library to build).
//!
//! * [`Dyadic`]: `m 2^e` with a big integer `m`. Every f64 is one, and sums, differences and
//!   products of dyadics are dyadic, so the kernels' polynomials in f64 inputs are evaluated
//!   exactly without a single division or gcd. This is the exact kernel's number.
//! * [`Rational`] and [`Integer`]: big rationals and integers (`dashu`, whose gcd is Lehmer's)
//!   for the exact tests that divide (the prism crate's patch roots, the certificate's
//!   distances). Their interface follows `rug`'s, which the crates used before: `Rational::new()`
//!   is zero, `cmp0()` is the sign, `Rational::from(&a * &b)` takes a product.
//!
//! With the feature `gmp` the crate also has a GMP kernel (`rug`), and a test checks that
//! both exact kernels give every sign the same.

use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Shl, Sub};

use dashu_base::Sign as BigSign;
use dashu_int::{IBig as BigInt, UBig};
use dashu_ratio::RBig as BigRational;

use crate::Sign;

/// `m 2^e`: an exact binary fraction.
#[derive(Clone, Debug)]
pub struct Dyadic {
    m: BigInt,
    e: i32,
}

impl Dyadic {
    /// The exact value of a finite double.
    ///
    /// # Panics
    /// On NaN or an infinity: predicates are undefined there (inputs are validated at the
    /// boundary).
    #[must_use]
    pub fn from_f64(x: f64) -> Dyadic {
        assert!(
            x.is_finite(),
            "envelope-predicates: non-finite coordinate {x:?}; validate inputs (envelope_mesh::check_coordinate)"
        );
        if x == 0.0 {
            return Dyadic {
                m: BigInt::ZERO,
                e: 0,
            };
        }
        let bits = x.to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i32;
        let frac = bits & ((1u64 << 52) - 1);
        // Subnormals have no hidden bit and the exponent of the smallest normal.
        let (mant, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1u64 << 52), exp - 1075)
        };
        let m = BigInt::from(mant);
        Dyadic {
            m: if x < 0.0 { -m } else { m },
            e,
        }
    }

    /// The sign.
    #[must_use]
    pub fn sign(&self) -> Sign {
        if self.m == BigInt::ZERO {
            Sign::Zero
        } else if self.m.sign() == BigSign::Negative {
            Sign::Negative
        } else {
            Sign::Positive
        }
    }

    /// The same value as a rational.
    #[must_use]
    pub fn to_rational(&self) -> Rational {
        Rational(if self.e >= 0 {
            BigRational::from(&self.m << self.e as usize)
        } else {
            BigRational::from_parts(self.m.clone(), UBig::ONE << (-self.e) as usize)
        })
    }

    /// Both mantissas on the smaller exponent.
    fn aligned(&self, o: &Dyadic) -> (BigInt, BigInt, i32) {
        match self.e.cmp(&o.e) {
            Ordering::Equal => (self.m.clone(), o.m.clone(), self.e),
            Ordering::Greater => (&self.m << (self.e - o.e) as usize, o.m.clone(), o.e),
            Ordering::Less => (self.m.clone(), &o.m << (o.e - self.e) as usize, self.e),
        }
    }
}

impl Dyadic {
    /// `self + o`, exactly.
    #[must_use]
    pub fn add(&self, o: &Self) -> Self {
        if o.m == BigInt::ZERO {
            return self.clone();
        }
        if self.m == BigInt::ZERO {
            return o.clone();
        }
        let (a, b, e) = self.aligned(o);
        Dyadic { m: a + b, e }
    }
    /// `self - o`, exactly.
    #[must_use]
    pub fn sub(&self, o: &Self) -> Self {
        if o.m == BigInt::ZERO {
            return self.clone();
        }
        let (a, b, e) = self.aligned(o);
        Dyadic { m: a - b, e }
    }
    /// `self * o`, exactly.
    #[must_use]
    pub fn mul(&self, o: &Self) -> Self {
        Dyadic {
            m: &self.m * &o.m,
            e: self.e + o.e,
        }
    }
}

/// An exact rational number (`rug::Rational`'s interface, on `dashu-ratio`).
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Rational(BigRational);

/// An exact integer (`rug::Integer`'s interface, on `dashu-int`).
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Integer(BigInt);

impl Rational {
    /// Zero.
    #[must_use]
    pub fn new() -> Rational {
        Rational(BigRational::ZERO)
    }

    /// The exact value of a finite double (`None` for NaN and infinities).
    #[must_use]
    pub fn from_f64(x: f64) -> Option<Rational> {
        x.is_finite().then(|| Dyadic::from_f64(x).to_rational())
    }

    /// The nearest double (an approximation, for display and constructions).
    #[must_use]
    pub fn to_f64(&self) -> f64 {
        self.0.to_f64().value()
    }

    /// The absolute value.
    #[must_use]
    pub fn abs(self) -> Rational {
        if self.cmp0() == Ordering::Less {
            -self
        } else {
            self
        }
    }

    /// Greater than zero.
    #[must_use]
    pub fn is_positive(&self) -> bool {
        self.cmp0() == Ordering::Greater
    }

    /// Less than zero.
    #[must_use]
    pub fn is_negative(&self) -> bool {
        self.cmp0() == Ordering::Less
    }

    /// The sign, as an ordering against zero.
    #[must_use]
    pub fn cmp0(&self) -> Ordering {
        if self.0.is_zero() {
            Ordering::Equal
        } else if self.0.sign() == BigSign::Negative {
            Ordering::Less
        } else {
            Ordering::Greater
        }
    }
}

impl From<i32> for Rational {
    fn from(x: i32) -> Self {
        Rational(BigRational::from(BigInt::from(x)))
    }
}

impl From<u32> for Rational {
    fn from(x: u32) -> Self {
        Rational(BigRational::from(BigInt::from(x)))
    }
}

impl From<(i32, i32)> for Rational {
    fn from((n, d): (i32, i32)) -> Self {
        Rational(BigRational::from_parts_signed(
            BigInt::from(n),
            BigInt::from(d),
        ))
    }
}

impl From<Integer> for Rational {
    fn from(x: Integer) -> Self {
        Rational(BigRational::from(x.0))
    }
}

macro_rules! integer_from {
    ($($t:ty),*) => {$(
        impl From<$t> for Integer {
            fn from(x: $t) -> Self {
                Integer(BigInt::from(x))
            }
        }
    )*};
}
integer_from!(i32, u32, i64, u64, usize);

impl Shl<u32> for Integer {
    type Output = Integer;
    fn shl(self, k: u32) -> Integer {
        Integer(self.0 << k as usize)
    }
}

/// The four owned/borrowed combinations of a binary operator between two rationals.
macro_rules! binary {
    ($tr:ident, $f:ident) => {
        impl $tr<&Rational> for &Rational {
            type Output = Rational;
            fn $f(self, o: &Rational) -> Rational {
                Rational((&self.0).$f(&o.0))
            }
        }
        impl $tr<Rational> for &Rational {
            type Output = Rational;
            fn $f(self, o: Rational) -> Rational {
                Rational((&self.0).$f(o.0))
            }
        }
        impl $tr<&Rational> for Rational {
            type Output = Rational;
            fn $f(self, o: &Rational) -> Rational {
                Rational(self.0.$f(&o.0))
            }
        }
        impl $tr<Rational> for Rational {
            type Output = Rational;
            fn $f(self, o: Rational) -> Rational {
                Rational(self.0.$f(o.0))
            }
        }
    };
}
binary!(Add, add);
binary!(Sub, sub);
binary!(Mul, mul);
binary!(Div, div);

/// A rational times or over a small integer or an [`Integer`].
macro_rules! scalar {
    ($tr:ident, $f:ident, $t:ty, $conv:expr) => {
        impl $tr<$t> for &Rational {
            type Output = Rational;
            fn $f(self, o: $t) -> Rational {
                Rational((&self.0).$f(BigRational::from($conv(o))))
            }
        }
        impl $tr<$t> for Rational {
            type Output = Rational;
            fn $f(self, o: $t) -> Rational {
                Rational(self.0.$f(BigRational::from($conv(o))))
            }
        }
    };
}
scalar!(Mul, mul, u32, BigInt::from);
scalar!(Div, div, u32, BigInt::from);
scalar!(Mul, mul, Integer, |i: Integer| i.0);
scalar!(Mul, mul, &Integer, |i: &Integer| i.0.clone());

impl<'a> std::iter::Sum<&'a Rational> for Rational {
    fn sum<I: Iterator<Item = &'a Rational>>(iter: I) -> Rational {
        iter.fold(Rational::new(), |acc, x| acc + x)
    }
}

impl PartialEq<i32> for Rational {
    fn eq(&self, o: &i32) -> bool {
        self.0.is_int() && *self.0.numerator() == BigInt::from(*o)
    }
}

impl PartialOrd<i32> for Rational {
    fn partial_cmp(&self, o: &i32) -> Option<Ordering> {
        Some(if *o == 0 {
            self.cmp0()
        } else {
            self.0.cmp(&BigRational::from(BigInt::from(*o)))
        })
    }
}

impl Neg for Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        Rational(-self.0)
    }
}

impl Neg for &Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        Rational(-&self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dyadics_are_exact() {
        for x in [
            0.0,
            -0.0,
            1.0,
            -3.5,
            0.1,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            -1e300,
        ] {
            let d = Dyadic::from_f64(x);
            assert_eq!(d.to_rational().to_f64(), x, "{x}");
        }
        let (a, b) = (Dyadic::from_f64(0.1), Dyadic::from_f64(0.2));
        // 0.1 + 0.2 - 0.3 in f64 inputs is exactly 2^-54 + 2^-56... not zero: its sign is exact.
        let s = a.add(&b).sub(&Dyadic::from_f64(0.3));
        assert_eq!(s.sign(), Sign::Positive);
        assert_eq!(
            s.to_rational(),
            Rational::from_f64(0.1).unwrap() + Rational::from_f64(0.2).unwrap()
                - Rational::from_f64(0.3).unwrap()
        );
        let p = Dyadic::from_f64(1e-300).mul(&Dyadic::from_f64(1e-300));
        assert_eq!(p.sign(), Sign::Positive);
        assert_eq!(
            Dyadic::from_f64(2.0).sub(&Dyadic::from_f64(2.0)).sign(),
            Sign::Zero
        );
    }

    #[test]
    fn rationals_follow_rugs_interface() {
        let half = Rational::from((1, 2));
        assert_eq!((&half * &half), Rational::from((1, 4)));
        assert_eq!((&half * 4u32).cmp0(), Ordering::Greater);
        assert_eq!((-&half).cmp0(), Ordering::Less);
        assert_eq!(Rational::new().cmp0(), Ordering::Equal);
        let eighth = Rational::from(Integer::from(1)) / Rational::from(Integer::from(1) << 3);
        assert_eq!(eighth.to_f64(), 0.125);
        assert_eq!((&eighth * Integer::from(8)).to_f64(), 1.0);
        assert_eq!(Rational::from_f64(f64::NAN), None);
    }
}
