//! Kernels: the primitive exact signs every derived predicate is built from.
//!
//! * [`Filtered`]: Shewchuk's adaptive predicates (crate `robust`) for the orientation and
//!   insphere tests, a floating-point filter with a rigorous running error bound for the other
//!   primitives, and [`Exact`] as the fallback (always when a coordinate is outside
//!   [`in_exact_range`](crate::in_exact_range)).
//! * [`Exact`]: every f64 converted exactly to a binary fraction with a big-integer mantissa
//!   ([`Dyadic`](crate::exact_num::Dyadic), pure Rust); slow, the reference. With the feature
//!   `gmp`, `ExactGmp` answers the same on GMP rationals, for the cross-check of the two.
//! * [`Checked<A, B>`]: runs both and panics with a pasteable reproduction on disagreement.
//!
//! All kernels answer the same exact question: the sign of a polynomial in the f64 inputs,
//! evaluated in infinite precision. NaN or infinite inputs make every kernel panic with a clear
//! message (inputs are validated at the boundary, see `envelope_mesh::check_coordinate`); no
//! kernel ever returns a sign for them.

use std::marker::PhantomData;

use glam::{DVec2, DVec3};

use crate::arith::{self, ErrF64, ExactNum};
use crate::exact_num::Dyadic;
use crate::range::{all_in_range, in_exact_range};
use crate::{Orientation, Sign};

/// The primitive signs. Every method is an exact decision on its f64 arguments.
///
/// Kernels are zero-sized types used through static methods: `K::orient3d(a, b, c, d)`.
pub trait Kernel {
    /// Orientation of `a, b, c` in the plane: [`Orientation::Positive`] when counter-clockwise,
    /// the sign of `(b-a)×(c-a)`.
    fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> Orientation;
    /// Orientation of `d` relative to the oriented plane `abc`: the sign of
    /// `((b-a)×(c-a))·(d-a)`, positive when `d` is on the side the right-hand normal of `abc`
    /// points to (CGAL's convention; the opposite of Shewchuk's).
    fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Orientation;
    /// Side of `e` relative to the oriented sphere through `a, b, c, d`: [`Sign::Positive`] when
    /// `e` is inside the sphere and `orient3d(a, b, c, d)` is `Positive` (CGAL's
    /// `side_of_oriented_sphere`); the sign flips with the orientation of `abcd`; `Zero` when
    /// the five points are cospherical (or `abcd` is coplanar and `e` on that plane's circle/line).
    fn insphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> Sign;
    /// The sign of the dot product `(b-a)·(d-c)`.
    fn dot(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign;
    /// The sign of `|p-q|^2 - eps2`.
    fn cmp_sq_dist(p: DVec3, q: DVec3, eps2: f64) -> Sign;
    /// The sign of `dist(p, line ab)^2 - eps2`, computed as `|(p-a)×(b-a)|^2 - eps2 |b-a|^2`
    /// (so `Zero` when `a == b`).
    fn cmp_sq_dist_point_line(p: DVec3, a: DVec3, b: DVec3, eps2: f64) -> Sign;
    /// The sign of `dist(p, plane abc)^2 - eps2`, computed as `(n·(p-a))^2 - eps2 |n|^2`
    /// with `n = (b-a)×(c-a)` (so `Zero` when `a, b, c` are collinear).
    fn cmp_sq_dist_point_plane(p: DVec3, a: DVec3, b: DVec3, c: DVec3, eps2: f64) -> Sign;
    /// The sign of `dist(line p0p1, line q0q1)^2 - eps2`, computed as
    /// `(n·(p0-q0))^2 - eps2 |n|^2` with `n = (p1-p0)×(q1-q0)` (so `Zero` for parallel lines).
    fn cmp_sq_dist_line_line(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3, eps2: f64) -> Sign;
    /// Side of `p`'s orthogonal projection onto the plane `abc` relative to the line `ab`:
    /// the sign of `(n×(b-a))·(p-a)` with `n = (b-a)×(c-a)`; `Positive` on `c`'s side.
    fn edge_side(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> Sign;
    /// True when the lines through segments `p0p1` and `q0q1` are not parallel and their
    /// closest points are interior to both segments (parameters strictly in `(0, 1)`).
    fn closest_points_interior(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> bool;
}

/// Exact sign from a filtered evaluation, falling back to rationals.
macro_rules! filtered {
    ($f:ident ( $($arg:expr),* )) => {{
        match arith::$f::<ErrF64>($($arg),*).sign() {
            Some(s) => s,
            None => arith::$f::<Dyadic>($($arg),*).exact_sign(),
        }
    }};
}

macro_rules! exact {
    ($n:ty, $f:ident ( $($arg:expr),* )) => {
        arith::$f::<$n>($($arg),*).exact_sign()
    };
}

fn robust3(p: DVec3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

fn closest_interior_from(signs: [Sign; 4]) -> bool {
    signs.iter().all(|&s| s == Sign::Positive)
}

/// The default kernel: adaptive floating point with exact fallback.
///
/// ```
/// use envelope_predicates::{Filtered, Kernel, Orientation};
/// use glam::DVec3;
/// let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
/// assert_eq!(Filtered::orient3d(a, b, c, DVec3::Z), Orientation::Positive);
/// assert_eq!(Filtered::orient3d(a, b, c, -DVec3::Z), Orientation::Negative);
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Filtered;

/// The reference kernel: every f64 converted exactly, polynomials evaluated exactly.
///
/// ```
/// use envelope_predicates::{Exact, Kernel, Sign};
/// use glam::DVec3;
/// // 0.1 + 0.2 != 0.3 in doubles, and the exact kernel sees the doubles exactly.
/// let d = Exact::cmp_sq_dist(DVec3::new(0.1 + 0.2, 0.0, 0.0), DVec3::ZERO, 0.09);
/// assert_eq!(d, Sign::Positive);
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Exact;

/// The exact kernel on the number type `$n`.
macro_rules! exact_kernel {
    ($kernel:ty, $n:ty) => {
        impl Kernel for $kernel {
            fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> Orientation {
                Orientation::from_sign(exact!(
                    $n,
                    orient2d(a.to_array(), b.to_array(), c.to_array())
                ))
            }
            fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Orientation {
                Orientation::from_sign(exact!($n, orient3d(a, b, c, d)))
            }
            fn insphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> Sign {
                exact!($n, insphere(a, b, c, d, e))
            }
            fn dot(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
                exact!($n, dot(a, b, c, d))
            }
            fn cmp_sq_dist(p: DVec3, q: DVec3, eps2: f64) -> Sign {
                exact!($n, sq_dist(p, q, eps2))
            }
            fn cmp_sq_dist_point_line(p: DVec3, a: DVec3, b: DVec3, eps2: f64) -> Sign {
                exact!($n, point_line(p, a, b, eps2))
            }
            fn cmp_sq_dist_point_plane(p: DVec3, a: DVec3, b: DVec3, c: DVec3, eps2: f64) -> Sign {
                exact!($n, point_plane(p, a, b, c, eps2))
            }
            fn cmp_sq_dist_line_line(
                p0: DVec3,
                p1: DVec3,
                q0: DVec3,
                q1: DVec3,
                eps2: f64,
            ) -> Sign {
                exact!($n, line_line(p0, p1, q0, q1, eps2))
            }
            fn edge_side(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> Sign {
                exact!($n, edge_side(a, b, c, p))
            }
            fn closest_points_interior(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> bool {
                closest_interior_from(
                    arith::closest_params::<$n>(p0, p1, q0, q1).map(|r| r.exact_sign()),
                )
            }
        }
    };
}

exact_kernel!(Exact, Dyadic);

/// [`Exact`] on GMP rationals (`rug`): the same signs, for the cross-check of the two exact
/// kernels (feature `gmp`).
#[cfg(feature = "gmp")]
#[derive(Clone, Copy, Debug, Default)]
pub struct ExactGmp;

#[cfg(feature = "gmp")]
exact_kernel!(ExactGmp, rug::Rational);

impl Kernel for Filtered {
    #[inline]
    fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> Orientation {
        let in_range = [a, b, c]
            .iter()
            .all(|p| in_exact_range(p.x) && in_exact_range(p.y));
        if !in_range {
            return Exact::orient2d(a, b, c);
        }
        InRange::orient2d(a, b, c)
    }
    #[inline]
    fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Orientation {
        if !all_in_range(&[a, b, c, d]) {
            return Exact::orient3d(a, b, c, d);
        }
        InRange::orient3d(a, b, c, d)
    }
    fn insphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> Sign {
        if !all_in_range(&[a, b, c, d, e]) {
            return Exact::insphere(a, b, c, d, e);
        }
        let r = robust::insphere(robust3(a), robust3(b), robust3(c), robust3(d), robust3(e));
        float_sign(r).reverse()
    }
    #[inline]
    fn dot(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
        filtered!(dot(a, b, c, d))
    }
    #[inline]
    fn cmp_sq_dist(p: DVec3, q: DVec3, eps2: f64) -> Sign {
        filtered!(sq_dist(p, q, eps2))
    }
    fn cmp_sq_dist_point_line(p: DVec3, a: DVec3, b: DVec3, eps2: f64) -> Sign {
        filtered!(point_line(p, a, b, eps2))
    }
    fn cmp_sq_dist_point_plane(p: DVec3, a: DVec3, b: DVec3, c: DVec3, eps2: f64) -> Sign {
        filtered!(point_plane(p, a, b, c, eps2))
    }
    fn cmp_sq_dist_line_line(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3, eps2: f64) -> Sign {
        filtered!(line_line(p0, p1, q0, q1, eps2))
    }
    fn edge_side(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> Sign {
        filtered!(edge_side(a, b, c, p))
    }
    fn closest_points_interior(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> bool {
        let f = arith::closest_params::<ErrF64>(p0, p1, q0, q1).map(ErrF64::sign);
        if f.iter()
            .any(|s| *s == Some(Sign::Negative) || *s == Some(Sign::Zero))
        {
            return false;
        }
        if f.iter().all(|s| *s == Some(Sign::Positive)) {
            return true;
        }
        Exact::closest_points_interior(p0, p1, q0, q1)
    }
}

/// [`Filtered`] on points already known to be [`in_exact_range`] (every coordinate): the
/// orientation tests go to the adaptive predicates without asking the range again, the other
/// primitives are [`Filtered`]'s. For the crate's derived predicates, which check the range of
/// all their points once (projections of in-range points stay in range, and nothing else is
/// constructed) instead of at every orientation test. Outside the range the answer could be
/// wrong (an expansion may underflow): never use it without the check (debug builds assert it).
pub(crate) struct InRange;

impl Kernel for InRange {
    #[inline]
    fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> Orientation {
        debug_assert!(
            [a, b, c]
                .iter()
                .all(|p| in_exact_range(p.x) && in_exact_range(p.y))
        );
        let r = robust::orient2d(
            robust::Coord { x: a.x, y: a.y },
            robust::Coord { x: b.x, y: b.y },
            robust::Coord { x: c.x, y: c.y },
        );
        Orientation::from_sign(float_sign(r))
    }
    #[inline]
    fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Orientation {
        debug_assert!(all_in_range(&[a, b, c, d]));
        // Shewchuk's orient3d is positive when d is *below* abc: negate.
        let r = robust::orient3d(robust3(a), robust3(b), robust3(c), robust3(d));
        Orientation::from_sign(float_sign(r).reverse())
    }
    fn insphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> Sign {
        Filtered::insphere(a, b, c, d, e)
    }
    #[inline]
    fn dot(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
        Filtered::dot(a, b, c, d)
    }
    fn cmp_sq_dist(p: DVec3, q: DVec3, eps2: f64) -> Sign {
        Filtered::cmp_sq_dist(p, q, eps2)
    }
    fn cmp_sq_dist_point_line(p: DVec3, a: DVec3, b: DVec3, eps2: f64) -> Sign {
        Filtered::cmp_sq_dist_point_line(p, a, b, eps2)
    }
    fn cmp_sq_dist_point_plane(p: DVec3, a: DVec3, b: DVec3, c: DVec3, eps2: f64) -> Sign {
        Filtered::cmp_sq_dist_point_plane(p, a, b, c, eps2)
    }
    fn cmp_sq_dist_line_line(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3, eps2: f64) -> Sign {
        Filtered::cmp_sq_dist_line_line(p0, p1, q0, q1, eps2)
    }
    fn edge_side(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> Sign {
        Filtered::edge_side(a, b, c, p)
    }
    fn closest_points_interior(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> bool {
        Filtered::closest_points_interior(p0, p1, q0, q1)
    }
}

/// Sign of an adaptive-predicate result (exact when the inputs are in range). NaN cannot come
/// out of in-range inputs; it is treated as a bug.
fn float_sign(r: f64) -> Sign {
    if r > 0.0 {
        Sign::Positive
    } else if r < 0.0 {
        Sign::Negative
    } else {
        assert!(
            r == 0.0,
            "adaptive predicate returned NaN on in-range input"
        );
        Sign::Zero
    }
}

/// Runs kernels `A` and `B` and panics with a pasteable Rust reproduction when they disagree.
///
/// ```
/// use envelope_predicates::{Checked, Exact, Filtered, Kernel, Orientation};
/// use glam::DVec3;
/// type K = Checked<Filtered, Exact>;
/// let o = K::orient3d(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.3, 0.3, 1e-300));
/// assert_eq!(o, Orientation::Positive);
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct Checked<A, B>(PhantomData<(A, B)>);

/// Formats arguments as Rust source that reproduces the call.
fn repro(call: &str, points: &[DVec3], scalars: &[f64]) -> String {
    let mut args: Vec<String> = points
        .iter()
        .map(|p| format!("DVec3::new({:?}, {:?}, {:?})", p.x, p.y, p.z))
        .collect();
    args.extend(scalars.iter().map(|s| format!("{s:?}")));
    format!("{call}({})", args.join(", "))
}

macro_rules! check {
    ($name:literal, $a:expr, $b:expr, $pts:expr, $sc:expr) => {{
        let (ra, rb) = ($a, $b);
        if ra != rb {
            panic!(
                "kernel disagreement in {}: {} says {:?}, {} says {:?}\nreproduce with:\n    {};",
                $name,
                std::any::type_name::<A>(),
                ra,
                std::any::type_name::<B>(),
                rb,
                repro(concat!("Checked::<Filtered, Exact>::", $name), $pts, $sc)
            );
        }
        ra
    }};
}

impl<A: Kernel, B: Kernel> Kernel for Checked<A, B> {
    fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> Orientation {
        let ra = A::orient2d(a, b, c);
        let rb = B::orient2d(a, b, c);
        if ra != rb {
            let args: Vec<String> = [a, b, c]
                .iter()
                .map(|p| format!("DVec2::new({:?}, {:?})", p.x, p.y))
                .collect();
            panic!(
                "kernel disagreement in orient2d: {ra:?} vs {rb:?}\nreproduce with:\n    \
                 Checked::<Filtered, Exact>::orient2d({});",
                args.join(", ")
            );
        }
        ra
    }
    fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Orientation {
        check!(
            "orient3d",
            A::orient3d(a, b, c, d),
            B::orient3d(a, b, c, d),
            &[a, b, c, d],
            &[]
        )
    }
    fn insphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> Sign {
        check!(
            "insphere",
            A::insphere(a, b, c, d, e),
            B::insphere(a, b, c, d, e),
            &[a, b, c, d, e],
            &[]
        )
    }
    fn dot(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
        check!(
            "dot",
            A::dot(a, b, c, d),
            B::dot(a, b, c, d),
            &[a, b, c, d],
            &[]
        )
    }
    fn cmp_sq_dist(p: DVec3, q: DVec3, eps2: f64) -> Sign {
        check!(
            "cmp_sq_dist",
            A::cmp_sq_dist(p, q, eps2),
            B::cmp_sq_dist(p, q, eps2),
            &[p, q],
            &[eps2]
        )
    }
    fn cmp_sq_dist_point_line(p: DVec3, a: DVec3, b: DVec3, eps2: f64) -> Sign {
        check!(
            "cmp_sq_dist_point_line",
            A::cmp_sq_dist_point_line(p, a, b, eps2),
            B::cmp_sq_dist_point_line(p, a, b, eps2),
            &[p, a, b],
            &[eps2]
        )
    }
    fn cmp_sq_dist_point_plane(p: DVec3, a: DVec3, b: DVec3, c: DVec3, eps2: f64) -> Sign {
        check!(
            "cmp_sq_dist_point_plane",
            A::cmp_sq_dist_point_plane(p, a, b, c, eps2),
            B::cmp_sq_dist_point_plane(p, a, b, c, eps2),
            &[p, a, b, c],
            &[eps2]
        )
    }
    fn cmp_sq_dist_line_line(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3, eps2: f64) -> Sign {
        check!(
            "cmp_sq_dist_line_line",
            A::cmp_sq_dist_line_line(p0, p1, q0, q1, eps2),
            B::cmp_sq_dist_line_line(p0, p1, q0, q1, eps2),
            &[p0, p1, q0, q1],
            &[eps2]
        )
    }
    fn edge_side(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> Sign {
        check!(
            "edge_side",
            A::edge_side(a, b, c, p),
            B::edge_side(a, b, c, p),
            &[a, b, c, p],
            &[]
        )
    }
    fn closest_points_interior(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> bool {
        check!(
            "closest_points_interior",
            A::closest_points_interior(p0, p1, q0, q1),
            B::closest_points_interior(p0, p1, q0, q1),
            &[p0, p1, q0, q1],
            &[]
        )
    }
}
