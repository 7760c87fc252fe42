//! Clipping a triangle against a fundamental prism in f64 (Cohen et al. 4.1): the inexact
//! constructions of `envelope-offset`'s analytical epsilon.
//!
//! The prism over the triangle `t = v0 v1 v2` with corner directions `d_i` is
//! `P(b, λ) = Σ b_i (v_i + λ d_i)`, barycentric `b`, `λ ∈ [0, 1]`: bottom `t`, top
//! `t + d` ([`prism_top`]), and its sides are exactly the paper's bilinear patches (a corner
//! may rise by its own height). [`closest_in_prism`] clips a triangle `Δ` against it; the
//! candidate closest points are the paper's "vertex of `Δ` inside the prism, or intersection
//! of one of its edges with the sides", plus two cases the paper's 2-D figure hides: a prism
//! edge (vertical or of the top cap) piercing `Δ`, and `Δ`'s edges crossing the caps.
//! [`prism_box`], [`hull_misses`] and [`box_gap`] let a caller skip, before clipping, the
//! triangles that cannot give a closer candidate (with the margin [`PRUNE_TOLERANCE`]).
//!
//! Unlike the rest of this crate, whose decisions are exact, everything here is an f64
//! construction (roots of the cubic / quadratic that place a point on a cross-section plane
//! or a patch, by bisection and the quadratic formula). The results are not trusted:
//! `envelope-offset` follows them with its exact proof of the envelopes it places, and
//! repairs what the proof refutes.
use envelope_predicates::bvh::Aabb;
use glam::DVec3;

/// The top cap `t + d` of the prism over `t` with corner directions `d` (f64).
#[must_use]
pub fn prism_top(t: [DVec3; 3], d: [DVec3; 3]) -> [DVec3; 3] {
    [t[0] + d[0], t[1] + d[1], t[2] + d[2]]
}

/// The box of the prism whose bottom has the box `t_box` and whose top is `top`, widened by
/// 1e-12 of its largest coordinate magnitude, and that magnitude (f64).
#[must_use]
pub fn prism_box(t_box: &Aabb, top: [DVec3; 3]) -> (Aabb, f64) {
    let b = t_box.union(&Aabb::from_triangle(top));
    let scale = b.min.abs().max(b.max.abs()).max_element();
    (b.inflated(scale * 1e-12), scale)
}

/// Margin of the two shortcuts that skip a triangle before clipping ([`hull_misses`], and
/// [`box_gap`] against the closest candidate so far, `delta`), relative to the largest
/// coordinate magnitude of the prism's box and of the other triangle: a triangle is skipped
/// only when it is apart from the prism's hull, or from `t`'s box by more than the current
/// `delta`, by more than this. It is far above both the rounding of the f64 projections
/// (about 1e-15 relative) and the slack that [`closest_in_prism`] allows its candidate points
/// (1e-9 of a parameter, 1e-12 of a barycentric coordinate; an edge is at most 2 sqrt(3)
/// times that magnitude), so the shortcuts change no `delta` that [`closest_in_prism`] would
/// find. They are f64 constructions like the rest of this module and, like it, are not
/// trusted: the exact proof follows.
pub const PRUNE_TOLERANCE: f64 = 1e-8;

/// Euclidean distance between two boxes (0 when they overlap; f64).
#[must_use]
pub fn box_gap(a: &Aabb, b: &Aabb) -> f64 {
    let gap = (a.min - b.max).max(b.min - a.max).max(DVec3::ZERO);
    gap.length()
}

/// True when triangle `g` is apart, by more than `tol`, from the convex hull of the prism's
/// six corners `t` and `top` (which holds the prism: every point of it is a convex
/// combination of the corners). Separating axes: the normals of `t`, `top` and `g`, and the
/// in-plane normals of the edges of `t` and of `top`; each is normalised, so `tol` is a
/// length. f64; used only to skip work (see [`PRUNE_TOLERANCE`]).
#[must_use]
pub fn hull_misses(t: [DVec3; 3], top: [DVec3; 3], g: [DVec3; 3], tol: f64) -> bool {
    HullAxes::new(t, top).misses(g, tol)
}

/// The separating axes of a prism's hull that do not depend on the other triangle (those of
/// `t` and `top`, see [`hull_misses`]), with the hull's extent on each: computed once per
/// prism for [`HullAxes::misses`] and [`HullAxes::misses_box`].
#[derive(Clone, Copy, Debug)]
pub struct HullAxes {
    hull: [DVec3; 6],
    axes: [(DVec3, f64, f64); 8],
    len: usize,
}

impl HullAxes {
    /// The axes of the prism's hull with bottom `t` and top `top` (f64).
    #[must_use]
    pub fn new(t: [DVec3; 3], top: [DVec3; 3]) -> Self {
        let mut axes = [(DVec3::ZERO, 0.0, 0.0); 8];
        let mut len = 0;
        for a in hull_axes(t, top) {
            axes[len] = a;
            len += 1;
        }
        let hull = [t[0], t[1], t[2], top[0], top[1], top[2]];
        Self { hull, axes, len }
    }

    /// [`hull_misses`] for this prism.
    #[must_use]
    pub fn misses(&self, g: [DVec3; 3], tol: f64) -> bool {
        let normal = |c: [DVec3; 3]| (c[1] - c[0]).cross(c[2] - c[0]);
        let apart = |(a, hlo, hhi): (DVec3, f64, f64)| {
            let (glo, ghi) = projection(a, &g);
            glo > hhi + tol || ghi < hlo - tol
        };
        self.axes[..self.len].iter().copied().any(apart)
            || unit(normal(g)).is_some_and(|a| {
                let (hlo, hhi) = projection(a, &self.hull);
                apart((a, hlo, hhi))
            })
    }

    /// True only when [`hull_misses`] is true, with any `tol` up to this one, for every
    /// triangle whose corners lie in the closed box `b`: the box is apart from the hull along
    /// one of these axes by `tol` plus the rounding of the projections. Lets a tree walk skip
    /// a whole node (f64, like the rest).
    #[must_use]
    pub fn misses_box(&self, b: &Aabb, tol: f64) -> bool {
        // A corner's computed projection is within 3.4e-16 |a|_1 |p|_max of the exact one,
        // the box's extreme likewise (|a|_1 <= sqrt 3): 4e-15 of the magnitude covers both,
        // and the rounding of the subtraction.
        let round = 4e-15 * b.min.abs().max(b.max.abs()).max_element();
        self.axes[..self.len].iter().any(|&(a, hlo, hhi)| {
            let lo = DVec3::select(a.cmpge(DVec3::ZERO), b.min, b.max);
            let hi = DVec3::select(a.cmpge(DVec3::ZERO), b.max, b.min);
            a.dot(lo) - round > hhi + tol || a.dot(hi) + round < hlo - tol
        })
    }
}

/// `axis` normalised, when it has a finite non-zero length.
fn unit(axis: DVec3) -> Option<DVec3> {
    let len = axis.length();
    (len > 0.0 && len.is_finite()).then(|| axis / len)
}

/// The smallest and largest `a . p` over `points` (f64).
fn projection(a: DVec3, points: &[DVec3]) -> (f64, f64) {
    points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            let x = a.dot(*p);
            (lo.min(x), hi.max(x))
        })
}

/// The separating axes of the prism's hull that do not depend on the other triangle (the
/// normals of `t` and `top`, the in-plane normals of their edges), unit, each with the hull's
/// projection onto it.
fn hull_axes(t: [DVec3; 3], top: [DVec3; 3]) -> impl Iterator<Item = (DVec3, f64, f64)> {
    let hull = [t[0], t[1], t[2], top[0], top[1], top[2]];
    let normal = |c: [DVec3; 3]| (c[1] - c[0]).cross(c[2] - c[0]);
    let (nt, ntop) = (normal(t), normal(top));
    let edges = (0..3).flat_map(move |i| {
        let j = (i + 1) % 3;
        [(t[j] - t[i]).cross(nt), (top[j] - top[i]).cross(ntop)]
    });
    [nt, ntop]
        .into_iter()
        .chain(edges)
        .filter_map(unit)
        .map(move |a| {
            let (lo, hi) = projection(a, &hull);
            (a, lo, hi)
        })
}

/// Distance from `t` of the closest point of triangle `g` inside the prism of `t` with
/// corner directions `d` (infinity when `g` misses the prism; f64).
#[must_use]
pub fn closest_in_prism(t: [DVec3; 3], d: [DVec3; 3], g: [DVec3; 3]) -> f64 {
    let mut best = f64::INFINITY;
    let mut consider = |p: DVec3| best = best.min(point_triangle_distance(p, t));
    let top = [t[0] + d[0], t[1] + d[1], t[2] + d[2]];
    for &p in &g {
        if point_in_prism(p, t, d) {
            consider(p);
        }
    }
    for i in 0..3 {
        let (p, q) = (g[i], g[(i + 1) % 3]);
        for j in 0..3 {
            let (a, b) = (j, (j + 1) % 3);
            for x in segment_patch(p, q, t[a], t[b], d[a], d[b]) {
                consider(x);
            }
        }
        for cap in [t, top] {
            if let Some(x) = segment_triangle_point(p, q, cap) {
                consider(x);
            }
        }
        // Prism edges piercing g: vertical edges and top-cap edges.
        if let Some(x) = segment_triangle_point(t[i], top[i], g) {
            consider(x);
        }
        if let Some(x) = segment_triangle_point(top[i], top[(i + 1) % 3], g) {
            consider(x);
        }
    }
    best
}

fn cross_section(t: [DVec3; 3], d: [DVec3; 3], l: f64) -> [DVec3; 3] {
    [t[0] + d[0] * l, t[1] + d[1] * l, t[2] + d[2] * l]
}

fn plane_value(t: [DVec3; 3], d: [DVec3; 3], l: f64, p: DVec3) -> f64 {
    let c = cross_section(t, d, l);
    (c[1] - c[0]).cross(c[2] - c[0]).dot(p - c[0])
}

/// `p` lies on some cross-section `T(λ)`, `λ ∈ [0, 1]`, inside it (f64, approximate).
fn point_in_prism(p: DVec3, t: [DVec3; 3], d: [DVec3; 3]) -> bool {
    const N: usize = 8;
    let mut prev = plane_value(t, d, 0.0, p);
    for k in 1..=N {
        let l1 = k as f64 / N as f64;
        let cur = plane_value(t, d, l1, p);
        if prev == 0.0 || (prev < 0.0) != (cur < 0.0) || cur == 0.0 {
            let (mut lo, mut hi, mut flo) = ((k - 1) as f64 / N as f64, l1, prev);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let fm = plane_value(t, d, mid, p);
                if (fm < 0.0) == (flo < 0.0) && fm != 0.0 {
                    lo = mid;
                    flo = fm;
                } else {
                    hi = mid;
                }
            }
            if barycentric_inside(p, cross_section(t, d, 0.5 * (lo + hi))) {
                return true;
            }
        }
        prev = cur;
    }
    false
}

fn barycentric_inside(p: DVec3, c: [DVec3; 3]) -> bool {
    let n = (c[1] - c[0]).cross(c[2] - c[0]);
    let nn = n.length_squared();
    if nn.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return false;
    }
    let tol = -1e-9 * nn;
    (0..3).all(|i| (c[(i + 1) % 3] - c[i]).cross(p - c[i]).dot(n) >= tol)
}

/// Intersections of segment `pq` with the bilinear patch `(1-s)(a + λ da) + s(b + λ db)`.
fn segment_patch(p: DVec3, q: DVec3, a: DVec3, b: DVec3, da: DVec3, db: DVec3) -> Vec<DVec3> {
    let e = q - p;
    // f(λ) = det[B(λ) - A(λ), p - A(λ), e] is quadratic in λ: fit it from three samples.
    let f = |l: f64| {
        let (al, bl) = (a + da * l, b + db * l);
        (bl - al).cross(p - al).dot(e)
    };
    let (f0, fh, f1) = (f(0.0), f(0.5), f(1.0));
    let qa = 2.0 * f1 - 4.0 * fh + 2.0 * f0;
    let qb = -f1 + 4.0 * fh - 3.0 * f0;
    let qc = f0;
    let mut roots = Vec::with_capacity(2);
    let scale = qa.abs().max(qb.abs()).max(qc.abs());
    if scale == 0.0 {
        return Vec::new(); // coplanar for every λ: covered by the other candidates
    }
    if qa.abs() <= 1e-12 * scale {
        if qb != 0.0 {
            roots.push(-qc / qb);
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let s = disc.sqrt();
            let q0 = -0.5 * (qb + qb.signum() * s);
            roots.push(q0 / qa);
            if q0 != 0.0 {
                roots.push(qc / q0);
            }
        }
    }
    let mut out = Vec::new();
    for l in roots {
        if !(-1e-12..=1.0 + 1e-12).contains(&l) {
            continue;
        }
        let l = l.clamp(0.0, 1.0);
        let (al, bl) = (a + da * l, b + db * l);
        if let Some((u, s)) = line_params(p, e, al, bl - al)
            && (-1e-9..=1.0 + 1e-9).contains(&u)
            && (-1e-9..=1.0 + 1e-9).contains(&s)
        {
            out.push(p + e * u.clamp(0.0, 1.0));
        }
    }
    out
}

/// Parameters of the closest points of lines `p + u e` and `a + s w`.
fn line_params(p: DVec3, e: DVec3, a: DVec3, w: DVec3) -> Option<(f64, f64)> {
    let r = p - a;
    let (ee, ew, ww) = (e.dot(e), e.dot(w), w.dot(w));
    let (er, wr) = (e.dot(r), w.dot(r));
    let den = ee * ww - ew * ew;
    if den.partial_cmp(&(1e-14 * ee * ww)) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let u = (ew * wr - ww * er) / den;
    let s = (ee * wr - ew * er) / den;
    Some((u, s))
}

/// Where segment `pq` crosses triangle `t` (Möller-Trumbore, f64).
fn segment_triangle_point(p: DVec3, q: DVec3, t: [DVec3; 3]) -> Option<DVec3> {
    let e = q - p;
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let h = e.cross(e2);
    let det = e1.dot(h);
    if det.abs() <= 1e-300 {
        return None;
    }
    let s = p - t[0];
    let u = s.dot(h) / det;
    let qv = s.cross(e1);
    let v = e.dot(qv) / det;
    let w = e2.dot(qv) / det;
    let tol = 1e-12;
    (u >= -tol && v >= -tol && u + v <= 1.0 + tol && (-tol..=1.0 + tol).contains(&w))
        .then(|| p + e * w.clamp(0.0, 1.0))
}

/// Euclidean distance from `p` to triangle `t` (Ericson's closest point, f64).
///
/// ```
/// use envelope_prism::clip::point_triangle_distance;
/// use glam::DVec3;
/// let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// assert_eq!(point_triangle_distance(DVec3::new(0.25, 0.25, 2.0), t), 2.0);
/// assert_eq!(point_triangle_distance(DVec3::new(-3.0, 0.0, 4.0), t), 5.0);
/// ```
#[must_use]
pub fn point_triangle_distance(p: DVec3, t: [DVec3; 3]) -> f64 {
    let [a, b, c] = t;
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return p.distance(a);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return p.distance(b);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return p.distance(a + ab * v);
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return p.distance(c);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return p.distance(a + ac * w);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return p.distance(b + (c - b) * w);
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    p.distance(a + ab * v + ac * w)
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: [DVec3; 3] = [DVec3::ZERO, DVec3::X, DVec3::Y];

    /// Marsaglia's xorshift64 from `seed` (the randomized tests below).
    fn xorshift(mut state: u64) -> impl FnMut() -> u64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        }
    }

    /// The top is the bottom moved by the corner directions; the box holds the six corners,
    /// with a margin, and its scale is their largest coordinate magnitude.
    #[test]
    fn top_and_box_of_a_slanted_prism() {
        let d = [
            DVec3::new(0.0, -1.0, 2.0),
            DVec3::Z * 2.0,
            DVec3::new(3.0, 0.0, 1.0),
        ];
        let top = prism_top(T, d);
        assert_eq!(
            top,
            [
                DVec3::new(0.0, -1.0, 2.0),
                DVec3::new(1.0, 0.0, 2.0),
                DVec3::new(3.0, 1.0, 1.0)
            ]
        );
        let (b, scale) = prism_box(&Aabb::from_triangle(T), top);
        assert_eq!(scale, 3.0);
        for p in T.iter().chain(&top) {
            assert!(b.min.cmplt(*p).all() && p.cmplt(b.max).all(), "{p:?} {b:?}");
        }
        assert!(b.max.x - 3.0 < 1e-11 && b.min.y + 1.0 > -1e-11);
    }

    #[test]
    fn triangle_above_inside_prism() {
        let d = [DVec3::Z * 2.0; 3];
        let g = [
            DVec3::new(0.1, 0.1, 0.5),
            DVec3::new(0.3, 0.1, 0.7),
            DVec3::new(0.1, 0.3, 0.9),
        ];
        assert!((closest_in_prism(T, d, g) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn triangle_beside_prism_is_ignored() {
        let d = [DVec3::Z * 2.0; 3];
        let g = [
            DVec3::new(2.0, 2.0, 0.5),
            DVec3::new(3.0, 2.0, 0.5),
            DVec3::new(2.0, 3.0, 0.5),
        ];
        assert_eq!(closest_in_prism(T, d, g), f64::INFINITY);
    }

    #[test]
    fn large_triangle_slicing_the_prism() {
        // A horizontal triangle at height 0.4 covering the whole prism: pierced by the
        // vertical prism edges.
        let d = [DVec3::Z * 2.0; 3];
        let g = [
            DVec3::new(-5.0, -5.0, 0.4),
            DVec3::new(10.0, -5.0, 0.4),
            DVec3::new(-5.0, 10.0, 0.4),
        ];
        assert!((closest_in_prism(T, d, g) - 0.4).abs() < 1e-12);
    }

    #[test]
    fn edge_through_slanted_side() {
        // Diverging normals: the side over edge (0,0)-(1,0) leans outward (-y); a segment at
        // y = -0.25, z = 1 is inside the prism between the sides.
        let d = [
            DVec3::new(0.0, -0.5, 1.0) * 2.0,
            DVec3::new(0.0, -0.5, 1.0) * 2.0,
            DVec3::Z * 2.0,
        ];
        let g = [
            DVec3::new(0.2, -0.25, 1.0),
            DVec3::new(0.6, -0.25, 1.0),
            DVec3::new(0.4, -3.0, 1.0),
        ];
        let delta = closest_in_prism(T, d, g);
        assert!((1.0..1.1).contains(&delta), "{delta}");
    }

    /// The two shortcuts (`hull_misses`, `box_gap`) skip only triangles that
    /// `closest_in_prism` finds no point of (or none closer than a known `delta`): random prisms (diverging,
    /// converging and tilted corner directions) against random triangles near them, many of
    /// them clipped, many just outside.
    #[test]
    fn shortcuts_skip_only_triangles_that_cannot_lower_delta() {
        let mut p = random_points(0x2545_F491_4F6C_DD1D);
        let (mut skipped, mut met) = (0, 0);
        for _ in 0..20_000 {
            let Some(Case { t, d, top, g, tol }) = prism_and_triangle(&mut p, DVec3::ZERO) else {
                continue;
            };
            let delta = closest_in_prism(t, d, g);
            if delta.is_finite() {
                met += 1;
            }
            if hull_misses(t, top, g, tol) {
                skipped += 1;
                assert_eq!(
                    delta,
                    f64::INFINITY,
                    "skipped a clipped triangle: {t:?} {d:?} {g:?}"
                );
            }
            let gap = box_gap(&Aabb::from_triangle(t), &Aabb::from_triangle(g));
            assert!(
                gap <= delta + tol,
                "box gap {gap} above the distance {delta}"
            );
        }
        assert!(
            skipped > 2_000 && met > 2_000,
            "skipped {skipped}, met {met}"
        );
    }

    /// `p(s)`: a random point of the cube of side `s` around the origin, from `seed`.
    fn random_points(seed: u64) -> impl FnMut(f64) -> DVec3 {
        let mut bits = xorshift(seed);
        let mut next = move || (bits() >> 11) as f64 / (1u64 << 53) as f64;
        move |s: f64| {
            let (x, y, z) = (next(), next(), next());
            DVec3::new(x - 0.5, y - 0.5, z - 0.5) * s
        }
    }

    /// A prism (bottom `t`, corner directions `d`, top `top`), a triangle `g` near it, and
    /// the shortcuts' margin for the two.
    struct Case {
        t: [DVec3; 3],
        d: [DVec3; 3],
        top: [DVec3; 3],
        g: [DVec3; 3],
        tol: f64,
    }

    /// A random prism around `shift` (diverging, converging and tilted corner directions)
    /// and a random triangle near it, from [`random_points`]; `None` for a degenerate bottom.
    fn prism_and_triangle(p: &mut impl FnMut(f64) -> DVec3, shift: DVec3) -> Option<Case> {
        let t = [p(2.0) + shift, p(2.0) + shift, p(2.0) + shift];
        let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
        if n == DVec3::ZERO {
            return None;
        }
        let h = 0.05 + p(2.0).x.abs();
        let d = [(n + p(1.2)) * h, (n + p(1.2)) * h, (n + p(1.2)) * h];
        let top = prism_top(t, d);
        let c = (t[0] + t[1] + t[2] + top[0] + top[1] + top[2]) / 6.0;
        let g = [c + p(3.0), c + p(3.0), c + p(3.0)];
        let scale = [t, top, g]
            .iter()
            .flatten()
            .map(|q| q.abs().max_element())
            .fold(0.0, f64::max);
        let tol = PRUNE_TOLERANCE * scale;
        Some(Case { t, d, top, g, tol })
    }

    /// A box the hull axes turn away holds only triangles that `hull_misses` skips: the
    /// triangle the box was made from, and triangles on the box's corners.
    #[test]
    fn box_shortcut_skips_only_what_the_triangle_shortcut_skips() {
        let mut p = random_points(0x9E37_79B9_7F4A_7C15);
        let (mut boxes_skipped, mut boxes_kept) = (0, 0);
        for i in 0..20_000 {
            // Far from the origin every other time: the rounding grows with the magnitude.
            let shift = if i % 2 == 0 { DVec3::ZERO } else { p(2e3) };
            let Some(Case { t, top, g, tol, .. }) = prism_and_triangle(&mut p, shift) else {
                continue;
            };
            let b = Aabb::from_triangle(g);
            if !HullAxes::new(t, top).misses_box(&b, tol) {
                boxes_kept += 1;
                continue;
            }
            boxes_skipped += 1;
            let corner = |k: usize| {
                DVec3::new(
                    if k & 1 == 0 { b.min.x } else { b.max.x },
                    if k & 2 == 0 { b.min.y } else { b.max.y },
                    if k & 4 == 0 { b.min.z } else { b.max.z },
                )
            };
            for tol in [tol, tol / 2.0, 0.0] {
                assert!(hull_misses(t, top, g, tol), "{t:?} {top:?} {g:?}");
                for k in 0..8 {
                    let on = [corner(k), corner(7 - k), corner((k + 3) % 8)];
                    assert!(hull_misses(t, top, on, tol), "{t:?} {top:?} {on:?}");
                }
            }
        }
        assert!(
            boxes_skipped > 2_000 && boxes_kept > 2_000,
            "skipped {boxes_skipped}, kept {boxes_kept}"
        );
    }
}
