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

/// Unit roundoff of f64.
const U: f64 = f64::EPSILON / 2.0;

/// `|p - q|_inf <= r` decided in f64 where the rounding cannot change the answer, `None`
/// where it could. A computed difference is the true one times `(1 + d)`, `|d| <= U`, so a
/// margin of `4 U` relative to `r` on either side leaves the comparison certain (an
/// overflowing difference is infinite, correctly beyond any finite `r`).
fn linf_within_filter(p: DVec3, q: DVec3, r: f64) -> Option<bool> {
    if !r.is_finite() {
        return None;
    }
    let d = (p - q).abs().max_element();
    if d <= r * (1.0 - 4.0 * U) {
        Some(true)
    } else if d >= r * (1.0 + 4.0 * U) {
        Some(false)
    } else {
        None
    }
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
    if let Some(known) = linf_within_filter(p, q, 2.0 * alpha) {
        return known;
    }
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
    // Filters with certain answers. Corners pairwise within alpha: every point of the
    // triangle, a convex combination, is within alpha of each corner.
    let pairwise = [(0, 1), (1, 2), (2, 0)].map(|(i, j)| linf_within_filter(t[i], t[j], alpha));
    if pairwise.iter().all(|&k| k == Some(true)) {
        return true;
    }
    // The centroid beyond every corner's cube by more than its rounding (a generous bound
    // on the error of the f64 centroid and differences): not covered.
    let scale = t
        .iter()
        .map(|p| p.abs().max_element())
        .fold(alpha, f64::max);
    let centroid = (t[0] + t[1] + t[2]) / 3.0;
    let beyond = alpha + 16.0 * U * scale;
    if t.iter()
        .all(|&p| (centroid - p).abs().max_element() > beyond)
    {
        return false;
    }
    covered_exactly(t, alpha)
}

/// [`covered_by_corner_cubes`] without its filters: the triangle cut on rationals.
fn covered_exactly(t: [DVec3; 3], alpha: f64) -> bool {
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// [`linf_close`] on rationals only.
    fn close_exactly(p: DVec3, q: DVec3, alpha: f64) -> bool {
        let two_alpha = rational(alpha) * 2u32;
        (0..3).all(|a| (rational(p[a]) - rational(q[a])).abs() <= two_alpha)
    }

    proptest! {
        /// The f64 filters give the rational answer, also where alpha is exactly a
        /// coordinate difference (the boundary) or a rounding away from it.
        #[test]
        fn filters_agree_with_the_exact_tests(
            c in prop::array::uniform9(-4.0f64..4.0),
            scale in prop::sample::select(vec![1e-3, 1.0, 1e5]),
            pick in 0usize..9,
            nudge in -2i32..3,
        ) {
            let t = [0, 3, 6].map(|i| DVec3::new(c[i], c[i + 1], c[i + 2]) * scale);
            // alpha on a coordinate difference, possibly moved by a few ulps.
            let (i, a) = (pick / 3, pick % 3);
            let mut alpha = (t[i][a] - t[(i + 1) % 3][a]).abs().max(1e-300);
            for _ in 0..nudge.unsigned_abs() {
                alpha = if nudge > 0 { alpha.next_up() } else { alpha.next_down() };
            }
            for half in [alpha, alpha / 2.0] {
                prop_assert_eq!(
                    covered_by_corner_cubes(t, half),
                    !collinear(t[0], t[1], t[2]) && covered_exactly(t, half)
                );
                prop_assert_eq!(linf_close(t[0], t[1], half), close_exactly(t[0], t[1], half));
            }
        }
    }
}
