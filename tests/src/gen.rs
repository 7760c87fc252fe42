//! Deterministic generators of near-degenerate predicate inputs, for the cross-checks against
//! the CGAL oracle (`tests/tests/cross_predicates.rs`) and for fuzz-style property tests.
//!
//! Everything is driven by [`Rng`], a SplitMix64 generator: a `(family, seed)` pair always
//! yields the same points, on every platform, so a failing case is reproducible from its seed
//! (the cross tests also print it as pasteable Rust, see [`rust_point`]).
//!
//! The [`Family`] variants are the classic ways floating-point predicates go wrong: points
//! that are exactly or almost (a few ulps) collinear or coplanar, decimal grids that are not
//! representable, coordinates whose magnitudes differ by 2^200, and cancellation near a large
//! common offset. Points are always finite and nonzero coordinates stay within 2^-110..2^110.

use envelope_predicates::{next_down, next_up};
use glam::{DVec2, DVec3};

/// SplitMix64 (Steele, Lea, Flood 2014): tiny, fast, statistically fine for test generation.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator seeded with `seed`.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Rng(seed ^ 0x5DEE_CE66_D1CE_4E5B)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`, 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform integer in `0..n` (`n > 0`).
    pub fn below(&mut self, n: u64) -> u64 {
        assert!(n > 0, "Rng::below(0)");
        self.next_u64() % n
    }

    /// Uniform integer in `lo..=hi`.
    pub fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + self.below((hi - lo + 1) as u64) as i64
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// A point uniform in `[-s, s]^3`.
    pub fn point(&mut self, s: f64) -> DVec3 {
        DVec3::new(self.range(-s, s), self.range(-s, s), self.range(-s, s))
    }
}

/// `x` moved by `k` ulps (towards +inf for `k > 0`).
#[must_use]
pub fn ulps(mut x: f64, k: i32) -> f64 {
    for _ in 0..k.unsigned_abs() {
        x = if k > 0 { next_up(x) } else { next_down(x) };
    }
    x
}

/// Each coordinate of `p` moved by an independent random amount in `-k..=k` ulps.
pub fn nudge(p: DVec3, rng: &mut Rng, k: i32) -> DVec3 {
    let mut c = p.to_array();
    for x in &mut c {
        *x = ulps(*x, rng.int(-i64::from(k), i64::from(k)) as i32);
    }
    DVec3::from_array(c)
}

/// `a + t (b - a)`, rounded to f64: on the line through `a` and `b` up to rounding.
#[must_use]
pub fn on_line(a: DVec3, b: DVec3, t: f64) -> DVec3 {
    a + (b - a) * t
}

/// `a + s (b - a) + t (c - a)`, rounded to f64: on the plane `abc` up to rounding.
#[must_use]
pub fn on_plane(a: DVec3, b: DVec3, c: DVec3, s: f64, t: f64) -> DVec3 {
    a + (b - a) * s + (c - a) * t
}

/// A coordinate `±m 2^e` with `m` in `[1, 2)` and `e` in `-100..=100`.
pub fn spread_coord(rng: &mut Rng) -> f64 {
    let m = rng.range(1.0, 2.0);
    let e = rng.int(-100, 100) as i32;
    let v = m * 2f64.powi(e);
    if rng.chance(0.5) { -v } else { v }
}

/// A family of generated point configurations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Family {
    /// Independent points uniform in `[-1, 1]^3` (the easy case, as a baseline).
    Uniform,
    /// Points `a + t (b - a)` on one line, snapped to f64 (almost always *not* exactly collinear).
    Line,
    /// Like [`Family::Line`], then every coordinate moved by up to 3 ulps.
    LineUlps,
    /// Points `a + s (b - a) + t (c - a)` on one plane, snapped to f64.
    Plane,
    /// Like [`Family::Plane`], then every coordinate moved by up to 3 ulps.
    PlaneUlps,
    /// Integers in `-4..=4` divided by `10^k`, `k` in `0..=3`: many exact coincidences,
    /// exactly collinear/coplanar triples and quadruples, and non-representable decimals.
    DecimalGrid,
    /// Small integers divided by a power of two (exact), lying on the plane
    /// `x + 2y - z = k`: exactly coplanar, tilted, so no axis projection is trivial.
    DyadicPlane,
    /// Small dyadic rationals `i / 8` anywhere: exact squared distances are constructible.
    Dyadic,
    /// Coordinates `±m 2^e`, `e` in `-100..=100`, mixed within one point.
    ExponentSpread,
    /// A large common offset (`2^20`) plus a small grid (`i 2^-30`): catastrophic cancellation.
    Offset,
}

impl Family {
    /// Every family.
    pub const ALL: [Family; 10] = [
        Family::Uniform,
        Family::Line,
        Family::LineUlps,
        Family::Plane,
        Family::PlaneUlps,
        Family::DecimalGrid,
        Family::DyadicPlane,
        Family::Dyadic,
        Family::ExponentSpread,
        Family::Offset,
    ];

    /// `n` points of this family.
    pub fn points(self, rng: &mut Rng, n: usize) -> Vec<DVec3> {
        match self {
            Family::Uniform => (0..n).map(|_| rng.point(1.0)).collect(),
            Family::Line | Family::LineUlps => {
                let (a, b) = (rng.point(1.0), rng.point(1.0));
                (0..n)
                    .map(|i| {
                        let p = match i {
                            0 => a,
                            1 => b,
                            _ => on_line(a, b, rng.range(-1.5, 2.5)),
                        };
                        if self == Family::LineUlps {
                            nudge(p, rng, 3)
                        } else {
                            p
                        }
                    })
                    .collect()
            }
            Family::Plane | Family::PlaneUlps => {
                let (a, b, c) = (rng.point(1.0), rng.point(1.0), rng.point(1.0));
                (0..n)
                    .map(|i| {
                        let p = match i {
                            0 => a,
                            1 => b,
                            2 => c,
                            _ => on_plane(a, b, c, rng.range(-1.0, 2.0), rng.range(-1.0, 2.0)),
                        };
                        if self == Family::PlaneUlps {
                            nudge(p, rng, 3)
                        } else {
                            p
                        }
                    })
                    .collect()
            }
            Family::DecimalGrid => {
                let scale = 10f64.powi(rng.int(0, 3) as i32);
                (0..n)
                    .map(|_| {
                        DVec3::new(
                            rng.int(-4, 4) as f64 / scale,
                            rng.int(-4, 4) as f64 / scale,
                            rng.int(-4, 4) as f64 / scale,
                        )
                    })
                    .collect()
            }
            Family::DyadicPlane => {
                let k = rng.int(-3, 3);
                let s = 2f64.powi(-(rng.int(0, 40) as i32));
                (0..n)
                    .map(|_| {
                        let (x, y) = (rng.int(-6, 6), rng.int(-6, 6));
                        DVec3::new(x as f64, y as f64, (x + 2 * y - k) as f64) * s
                    })
                    .collect()
            }
            Family::Dyadic => (0..n)
                .map(|_| {
                    DVec3::new(
                        rng.int(-16, 16) as f64 / 8.0,
                        rng.int(-16, 16) as f64 / 8.0,
                        rng.int(-16, 16) as f64 / 8.0,
                    )
                })
                .collect(),
            Family::ExponentSpread => (0..n)
                .map(|_| DVec3::new(spread_coord(rng), spread_coord(rng), spread_coord(rng)))
                .collect(),
            Family::Offset => {
                let base = DVec3::splat(2f64.powi(20));
                (0..n)
                    .map(|_| {
                        base + DVec3::new(
                            rng.int(-3, 3) as f64,
                            rng.int(-3, 3) as f64,
                            rng.int(-3, 3) as f64,
                        ) * 2f64.powi(-30)
                    })
                    .collect()
            }
        }
    }

    /// Four points for `orient3d`, the first three of the family and the fourth sometimes a
    /// copy or an ulp-neighbour of one of them or of a point on their plane/lines.
    pub fn orient3d_case(self, rng: &mut Rng) -> [DVec3; 4] {
        let p = self.points(rng, 4);
        let mut q = [p[0], p[1], p[2], p[3]];
        match rng.below(6) {
            0 => q[3] = q[rng.below(3) as usize],
            1 => q[3] = nudge(on_plane(q[0], q[1], q[2], rng.unit(), rng.unit()), rng, 2),
            2 => q[3] = nudge(on_line(q[0], q[1], rng.range(-1.0, 2.0)), rng, 1),
            _ => {}
        }
        permute(rng, &mut q);
        q
    }

    /// Three 2-D points for `orient2d` (the family's points projected to `xy`, sometimes the
    /// third put a few ulps off the line through the first two).
    pub fn orient2d_case(self, rng: &mut Rng) -> [DVec2; 3] {
        let p = self.points(rng, 3);
        let mut q = [p[0].truncate(), p[1].truncate(), p[2].truncate()];
        if rng.chance(0.3) {
            let t = rng.range(-1.0, 2.0);
            let r = q[0] + (q[1] - q[0]) * t;
            let k = rng.int(-2, 2) as i32;
            q[2] = DVec2::new(ulps(r.x, k), ulps(r.y, rng.int(-2, 2) as i32));
        }
        permute(rng, &mut q);
        q
    }

    /// A triangle pair: independent, sharing a vertex or an edge (positions, possibly
    /// nudged by ulps), or the second lying in the (rounded) plane of the first.
    pub fn triangle_pair(self, rng: &mut Rng) -> ([DVec3; 3], [DVec3; 3]) {
        let p = self.points(rng, 6);
        let t1 = [p[0], p[1], p[2]];
        let mut t2 = [p[3], p[4], p[5]];
        match rng.below(8) {
            0 => t2[0] = t1[rng.below(3) as usize],
            1 => {
                let i = rng.below(3) as usize;
                t2[0] = t1[i];
                t2[1] = t1[(i + 1) % 3];
            }
            2 => t2[0] = nudge(t1[rng.below(3) as usize], rng, 1),
            3 => {
                let i = rng.below(3) as usize;
                t2[0] = nudge(t1[i], rng, 1);
                t2[1] = nudge(t1[(i + 1) % 3], rng, 1);
            }
            4 => {
                // Coplanar (up to rounding) with the first triangle, overlapping it or not.
                for v in &mut t2 {
                    *v = on_plane(
                        t1[0],
                        t1[1],
                        t1[2],
                        rng.range(-0.5, 1.2),
                        rng.range(-0.5, 1.2),
                    );
                }
            }
            5 => {
                // A vertex of the second exactly/almost on an edge of the first.
                let i = rng.below(3) as usize;
                t2[0] = nudge(on_line(t1[i], t1[(i + 1) % 3], rng.unit()), rng, 1);
            }
            _ => {}
        }
        if rng.chance(0.5) {
            permute(rng, &mut t2);
        }
        if rng.chance(0.5) { (t2, t1) } else { (t1, t2) }
    }

    /// A segment and a triangle: independent, or the segment starting at/near a triangle
    /// vertex or edge point, or lying in the triangle's (rounded) plane, or a point.
    pub fn segment_triangle(self, rng: &mut Rng) -> ([DVec3; 2], [DVec3; 3]) {
        let p = self.points(rng, 5);
        let t = [p[0], p[1], p[2]];
        let mut s = [p[3], p[4]];
        match rng.below(8) {
            0 => s[0] = t[rng.below(3) as usize],
            1 => {
                let i = rng.below(3) as usize;
                s[0] = nudge(on_line(t[i], t[(i + 1) % 3], rng.unit()), rng, 1);
            }
            2 => {
                for v in &mut s {
                    *v = on_plane(t[0], t[1], t[2], rng.range(-0.5, 1.2), rng.range(-0.5, 1.2));
                }
            }
            3 => {
                // Through a point of the triangle: q = 2x - p, rounded.
                let x = on_plane(t[0], t[1], t[2], rng.unit() * 0.6, rng.unit() * 0.6);
                s[1] = 2.0 * x - s[0];
            }
            4 => s[1] = s[0],
            _ => {}
        }
        if rng.chance(0.5) {
            s.swap(0, 1);
        }
        (s, t)
    }

    /// A point, a triangle and an `eps2`: zero, the f64 estimate of the squared distance
    /// (exact for the axis-aligned dyadic constructions used here half of the time), or one
    /// ulp either side of it.
    pub fn point_triangle_eps(self, rng: &mut Rng) -> (DVec3, [DVec3; 3], f64) {
        let (p, t) = if matches!(self, Family::Dyadic | Family::DyadicPlane) && rng.chance(0.5) {
            axis_aligned_dyadic_case(rng)
        } else {
            let v = self.points(rng, 4);
            (v[3], [v[0], v[1], v[2]])
        };
        let d2 = sq_dist_point_triangle_f64(p, t);
        let eps2 = match rng.below(5) {
            0 => 0.0,
            1 => next_up(d2),
            2 => next_down(d2).max(0.0),
            3 => d2 * rng.range(0.5, 2.0),
            _ => d2,
        };
        (p, t, eps2)
    }
}

/// A dyadic triangle in an axis plane and a dyadic point whose exact squared distance is a
/// small dyadic rational, so the f64 estimate below is exact: point above the interior
/// (distance = height), beyond a vertex, or beside an axis-aligned edge.
fn axis_aligned_dyadic_case(rng: &mut Rng) -> (DVec3, [DVec3; 3]) {
    let d = |rng: &mut Rng| rng.int(-16, 16) as f64 / 8.0;
    let (x0, y0, z0) = (d(rng), d(rng), d(rng));
    let (w, h) = (rng.int(1, 16) as f64 / 8.0, rng.int(1, 16) as f64 / 8.0);
    // Right triangle with legs along x and y, in the plane z = z0.
    let t = [
        DVec3::new(x0, y0, z0),
        DVec3::new(x0 + w, y0, z0),
        DVec3::new(x0, y0 + h, z0),
    ];
    let up = d(rng);
    let p = match rng.below(3) {
        0 => DVec3::new(x0 + w / 4.0, y0 + h / 4.0, z0 + up),
        1 => DVec3::new(
            x0 - rng.int(0, 8) as f64 / 8.0,
            y0 - rng.int(0, 8) as f64 / 8.0,
            z0 + up,
        ),
        _ => DVec3::new(x0 + w / 2.0, y0 - rng.int(0, 8) as f64 / 8.0, z0 + up),
    };
    let mut pts = [t[0], t[1], t[2]];
    permute(rng, &mut pts);
    // Swap axes so not all cases are in a z plane.
    let axes = rng.below(3);
    let rot = |v: DVec3| match axes {
        0 => v,
        1 => DVec3::new(v.y, v.z, v.x),
        _ => DVec3::new(v.z, v.x, v.y),
    };
    (rot(p), pts.map(rot))
}

/// Squared distance from `p` to the closed triangle `t` in plain f64 (Ericson's closest-point
/// algorithm, *Real-Time Collision Detection* 5.1.5). Only an estimate: used to pick `eps2`
/// values close to the true squared distance.
#[must_use]
pub fn sq_dist_point_triangle_f64(p: DVec3, t: [DVec3; 3]) -> f64 {
    let [a, b, c] = t;
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    let closest = if d1 <= 0.0 && d2 <= 0.0 {
        a
    } else {
        let bp = p - b;
        let (d3, d4) = (ab.dot(bp), ac.dot(bp));
        let cp = p - c;
        let (d5, d6) = (ab.dot(cp), ac.dot(cp));
        let vc = d1 * d4 - d3 * d2;
        let vb = d5 * d2 - d1 * d6;
        let va = d3 * d6 - d5 * d4;
        if d3 >= 0.0 && d4 <= d3 {
            b
        } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            a + ab * (d1 / (d1 - d3))
        } else if d6 >= 0.0 && d5 <= d6 {
            c
        } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            a + ac * (d2 / (d2 - d6))
        } else if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
            b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))
        } else {
            let denom = 1.0 / (va + vb + vc);
            if !denom.is_finite() {
                // Degenerate triangle: fall back to the nearest vertex.
                return [a, b, c]
                    .iter()
                    .map(|v| (p - *v).length_squared())
                    .fold(f64::INFINITY, f64::min);
            }
            a + ab * (vb * denom) + ac * (vc * denom)
        }
    };
    let r = (p - closest).length_squared();
    if r.is_finite() { r } else { 0.0 }
}

/// A random permutation of `v` (Fisher-Yates).
pub fn permute<T>(rng: &mut Rng, v: &mut [T]) {
    for i in (1..v.len()).rev() {
        v.swap(i, rng.below(i as u64 + 1) as usize);
    }
}

/// `p` as pasteable Rust (`{:?}` of an f64 round-trips exactly).
#[must_use]
pub fn rust_point(p: DVec3) -> String {
    format!("DVec3::new({:?}, {:?}, {:?})", p.x, p.y, p.z)
}

/// `p` as pasteable Rust.
#[must_use]
pub fn rust_point2(p: DVec2) -> String {
    format!("DVec2::new({:?}, {:?})", p.x, p.y)
}

/// A triangle as pasteable Rust.
#[must_use]
pub fn rust_triangle(t: [DVec3; 3]) -> String {
    format!(
        "[{}, {}, {}]",
        rust_point(t[0]),
        rust_point(t[1]),
        rust_point(t[2])
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deterministic_and_finite() {
        for f in Family::ALL {
            let a = f.points(&mut Rng::new(7), 8);
            let b = f.points(&mut Rng::new(7), 8);
            assert_eq!(a, b, "{f:?}");
            assert!(a.iter().all(|p| p.is_finite()), "{f:?}");
        }
    }

    #[test]
    fn dyadic_plane_is_exactly_coplanar() {
        let mut rng = Rng::new(3);
        for _ in 0..100 {
            let p = Family::DyadicPlane.points(&mut rng, 4);
            assert_eq!(
                envelope_predicates::orient3d(p[0], p[1], p[2], p[3]),
                envelope_predicates::Orientation::Degenerate
            );
        }
    }

    #[test]
    fn ulps_moves_by_ulps() {
        assert_eq!(ulps(1.0, 1), 1.0 + f64::EPSILON);
        assert_eq!(ulps(1.0, -2), 1.0 - f64::EPSILON);
    }
}

// ---------------------------------------------------------------------------- self-intersections

/// What [`compare_self_intersections`] saw when our answer and CGAL's agree.
#[derive(Clone, Debug)]
pub struct SelfIntersectionAgreement {
    /// Which CGAL path answered (valid `Surface_mesh`, or the oracle's soup rule).
    pub kind: crate::oracle::MeshKind,
    /// Intersecting pairs of non-degenerate faces (equal on both sides).
    pub pairs: Vec<(u32, u32)>,
    /// Degenerate faces: our zero-area class, CGAL's `(i, i)` pairs (equal on both sides).
    pub degenerate: Vec<u32>,
    /// Pairs we report that involve a degenerate face (CGAL does not test those; not compared).
    pub ours_with_degenerate: usize,
}

/// Compares `envelope_check::check`'s intersecting pairs (the full list) for `soup` with
/// CGAL's `self_intersections` of the file at `path` (the same mesh, same face order).
///
/// Also checks that `check`'s list equals [`envelope_predicates::self_intersections`] on the
/// raw faces. CGAL reports a degenerate (collinear or repeated-index) face `i` as the pair
/// `(i, i)` and tests it against nothing; we test degenerate faces like any closed point set.
/// So the `(i, i)` pairs are compared with our zero-area class, and the other pairs with ours
/// minus those involving a zero-area face. `Err` describes any difference, with reproductions.
pub fn compare_self_intersections(
    oracle: &crate::oracle::Oracle,
    path: &std::path::Path,
    soup: &envelope_mesh::TriangleSoup,
) -> Result<SelfIntersectionAgreement, String> {
    use envelope_check::{CheckOptions, DegeneracyClass, Element, check};
    use std::collections::BTreeSet;
    let opts = CheckOptions {
        max_examples: usize::MAX,
        ..CheckOptions::default()
    };
    let report = check(soup, &opts);
    let ours: Vec<(u32, u32)> = report
        .finding(DegeneracyClass::IntersectingTriangles)
        .examples
        .iter()
        .filter_map(|e| match e {
            Element::FacePair { faces } => Some((faces[0].0, faces[1].0)),
            _ => None,
        })
        .collect();
    let zero_area: BTreeSet<u32> = report
        .finding(DegeneracyClass::ZeroAreaTriangles)
        .examples
        .iter()
        .filter_map(|e| match e {
            Element::Face { face, .. } => Some(face.0),
            _ => None,
        })
        .collect();
    let raw: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
    let lib = envelope_predicates::self_intersections(&soup.positions, &raw);
    let mut problems = Vec::new();
    if lib != ours {
        problems.push(format!(
            "check() lists {} intersecting pairs, self_intersections() {}",
            ours.len(),
            lib.len()
        ));
    }
    let cgal = oracle
        .try_self_intersections(path, false)
        .map_err(|e| format!("oracle failed on {}: {e}", path.display()))?;
    if cgal.vertices != soup.positions.len() as u64 || cgal.faces != soup.faces.len() as u64 {
        problems.push(format!(
            "CGAL read V={} F={}, we read V={} F={}",
            cgal.vertices,
            cgal.faces,
            soup.positions.len(),
            soup.faces.len()
        ));
    }
    let cgal_degenerate: BTreeSet<u32> = cgal
        .pairs
        .iter()
        .filter(|p| p.0 == p.1)
        .map(|p| p.0)
        .collect();
    let cgal_pairs: BTreeSet<(u32, u32)> =
        cgal.pairs.iter().copied().filter(|p| p.0 != p.1).collect();
    let ours_set: BTreeSet<(u32, u32)> = ours
        .iter()
        .copied()
        .filter(|(i, j)| !zero_area.contains(i) && !zero_area.contains(j))
        .collect();
    let ours_with_degenerate = ours.len() - ours_set.len();
    if cgal_degenerate != zero_area {
        let only_ours: Vec<_> = zero_area.difference(&cgal_degenerate).take(10).collect();
        let only_cgal: Vec<_> = cgal_degenerate.difference(&zero_area).take(10).collect();
        problems.push(format!(
            "degenerate faces: ours {} vs CGAL {}; only ours {only_ours:?}, only CGAL {only_cgal:?}",
            zero_area.len(),
            cgal_degenerate.len()
        ));
    }
    if cgal_pairs != ours_set {
        let only_ours: Vec<_> = ours_set.difference(&cgal_pairs).copied().collect();
        let only_cgal: Vec<_> = cgal_pairs.difference(&ours_set).copied().collect();
        let mut msg = format!(
            "intersecting pairs: ours {} vs CGAL {}; only ours {} {:?}, only CGAL {} {:?}",
            ours_set.len(),
            cgal_pairs.len(),
            only_ours.len(),
            &only_ours[..only_ours.len().min(10)],
            only_cgal.len(),
            &only_cgal[..only_cgal.len().min(10)]
        );
        for &(i, j) in only_ours.iter().chain(&only_cgal).take(3) {
            let f = |k: u32| soup.faces[k as usize].map(|v| v.0);
            msg.push_str(&format!(
                "\n  faces {i} {:?} / {j} {:?} (envelope_predicates::faces_intersect on these indices):\n    let t1 = {};\n    let t2 = {};",
                f(i),
                f(j),
                rust_triangle(soup.triangle(envelope_mesh::FaceId(i))),
                rust_triangle(soup.triangle(envelope_mesh::FaceId(j)))
            ));
        }
        problems.push(msg);
    }
    if problems.is_empty() {
        Ok(SelfIntersectionAgreement {
            kind: cgal.kind,
            pairs: ours_set.into_iter().collect(),
            degenerate: zero_area.into_iter().collect(),
            ours_with_degenerate,
        })
    } else {
        Err(problems.join("\n"))
    }
}
