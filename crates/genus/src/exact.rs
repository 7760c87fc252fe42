//! Exact tests on rationals used by the genus reduction (sections 3.4 and 4.2): L-infinity
//! closeness of two vertices and coverage of a triangle by the alpha-cubes of its corners.
//!
//! Inputs are f64 and `alpha` is f64; every comparison here is made on the exact rational
//! values (`v ± alpha` is never rounded).

use envelope_predicates::arith::rational;
use envelope_predicates::exact_num::Rational;
use envelope_predicates::{Filtered, Kernel, Sign};
use glam::DVec3;

/// The projection onto the coordinate plane that `normal` (an f64 construction) is most
/// aligned with: dropping a coordinate is exact, so for points in one plane not parallel to
/// the dropped axis the projected orientations are the points' own.
pub(crate) fn dominant_projection(normal: DVec3) -> impl Fn(DVec3) -> glam::DVec2 {
    let a = normal.abs();
    let drop = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    move |p: DVec3| match drop {
        0 => glam::DVec2::new(p.y, p.z),
        1 => glam::DVec2::new(p.z, p.x),
        _ => glam::DVec2::new(p.x, p.y),
    }
}

/// Exactly collinear (or coincident) points.
pub(crate) fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
    envelope_predicates::collinear(a, b, c)
}

/// For collinear `c, n, r` with `r` and `n` on the same side of `c`: `r` is strictly farther
/// from `c` than `n` (exact sign of `(n - c)·(r - n)`).
pub(crate) fn farther(c: DVec3, n: DVec3, r: DVec3) -> bool {
    Filtered::dot(c, n, n, r) == Sign::Positive
}

/// Whether `|p - q|_inf <= 2 alpha`, exactly: a cube of side `2 alpha` can hold both points
/// (the paper's diagonal-edge rule of section 3.4).
///
/// ```
/// use envelope_genus::details::linf_close;
/// use glam::DVec3;
/// assert!(linf_close(DVec3::ZERO, DVec3::new(1.0, 0.5, -1.0), 0.5));
/// assert!(!linf_close(DVec3::ZERO, DVec3::new(1.0, 0.5, -1.0 - 1e-15), 0.5));
/// ```
#[must_use]
pub fn linf_close(p: DVec3, q: DVec3, alpha: f64) -> bool {
    let two_alpha = rational(alpha) * 2u32;
    (0..3).all(|a| {
        let d = (rational(p[a]) - rational(q[a])).abs();
        d <= two_alpha
    })
}

/// Whether the closed triangle `t` is covered by the union of the three closed axis-aligned
/// cubes of radius `alpha` centred at its corners, decided exactly.
///
/// The triangle is cut (in rationals) by the 18 planes `x_a = v_a ± alpha`; inside each
/// resulting convex piece coverage is constant, so a piece is tested through the centroid of
/// its corners (a point of its relative interior). A collinear (degenerate) triangle gets
/// `false` (conservative: such triangles are never added).
///
/// ```
/// use envelope_genus::details::covered_by_corner_cubes;
/// use glam::DVec3;
/// let t = [DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.0, 1.0, 0.0)];
/// assert!(covered_by_corner_cubes(t, 0.5));
/// assert!(!covered_by_corner_cubes(t, 0.3));
/// ```
#[must_use]
pub fn covered_by_corner_cubes(t: [DVec3; 3], alpha: f64) -> bool {
    if collinear(t[0], t[1], t[2]) || !(alpha.is_finite() && alpha > 0.0) {
        return false;
    }
    let al = rational(alpha);
    let corners: Vec<[Rational; 3]> = t
        .iter()
        .map(|p| [rational(p.x), rational(p.y), rational(p.z)])
        .collect();
    let mut pieces: Vec<Vec<[Rational; 3]>> = vec![corners.clone()];
    for axis in 0..3 {
        let mut cuts: Vec<Rational> = Vec::new();
        for c in &corners {
            cuts.push(&c[axis] - &al);
            cuts.push(&c[axis] + &al);
        }
        cuts.sort();
        cuts.dedup();
        for cut in &cuts {
            let mut next = Vec::with_capacity(pieces.len() * 2);
            for piece in pieces {
                let (below, above) = split(&piece, axis, cut);
                if below.len() >= 3 {
                    next.push(below);
                }
                if above.len() >= 3 {
                    next.push(above);
                }
            }
            pieces = next;
        }
    }
    pieces.iter().all(|piece| {
        let n = Rational::from(piece.len() as u32);
        let centroid: [Rational; 3] = std::array::from_fn(|a| {
            let s: Rational = piece.iter().map(|p| &p[a]).sum();
            s / &n
        });
        corners
            .iter()
            .any(|c| (0..3).all(|a| (&centroid[a] - &c[a]).abs() <= al))
    })
}

/// Splits a convex polygon (rational corners) by the plane `x_axis = cut` into the closed
/// parts below and above (Sutherland-Hodgman). A polygon lying in the plane goes below.
fn split(
    poly: &[[Rational; 3]],
    axis: usize,
    cut: &Rational,
) -> (Vec<[Rational; 3]>, Vec<[Rational; 3]>) {
    let side: Vec<std::cmp::Ordering> = poly.iter().map(|p| p[axis].cmp(cut)).collect();
    use std::cmp::Ordering::{Equal, Greater, Less};
    if side.iter().all(|s| *s != Greater) {
        return (poly.to_vec(), Vec::new());
    }
    if side.iter().all(|s| *s != Less) {
        return (Vec::new(), poly.to_vec());
    }
    let (mut below, mut above) = (Vec::new(), Vec::new());
    let n = poly.len();
    for i in 0..n {
        let j = (i + 1) % n;
        let (p, q) = (&poly[i], &poly[j]);
        match side[i] {
            Less => below.push(p.clone()),
            Greater => above.push(p.clone()),
            Equal => {
                below.push(p.clone());
                above.push(p.clone());
            }
        }
        if (side[i] == Less && side[j] == Greater) || (side[i] == Greater && side[j] == Less) {
            // p + s (q - p) with s = (cut - p_a) / (q_a - p_a).
            let s = (cut - &p[axis]) / (&q[axis] - &p[axis]);
            let x: [Rational; 3] = std::array::from_fn(|a| {
                if a == axis {
                    cut.clone()
                } else {
                    (&q[a] - &p[a]) * &s + &p[a]
                }
            });
            below.push(x.clone());
            above.push(x);
        }
    }
    (below, above)
}
