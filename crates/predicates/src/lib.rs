//! Exact geometric predicates for guaranteed-error mesh simplification.
//!
//! *Exact predicates, inexact constructions*: every decision this crate makes is the sign the
//! decision would have in infinite-precision arithmetic on the f64 inputs, and comes back as an
//! enum ([`Sign`], [`Orientation`], [`TriangleLocation`], ...). Nothing here constructs points.
//!
//! * Kernels ([`Kernel`]): [`Filtered`] (Shewchuk's adaptive predicates via `robust`, plus
//!   rigorously filtered floating point, falling back to [`Exact`]), [`Exact`] (exact binary fractions, pure Rust), and
//!   [`Checked`] which runs two kernels and panics with a reproduction when they disagree.
//! * Derived predicates in [`generic`] (any kernel) and re-exported here on [`Filtered`]:
//!   segment/triangle and triangle/triangle intersection (also for adjacent mesh faces),
//!   point location in a triangle and in a closed surface, exact distance-vs-tolerance
//!   comparisons, collinearity and T-junction tests.
//! * [`polygon`]: triangulating a polygon face without overlaps (constrained Delaunay in an
//!   axis-aligned projection, simplicity decided exactly).
//! * [`bvh`]: a conservative bounding-volume hierarchy, and [`self_intersections`].
//!
//! Conventions: `orient3d(a, b, c, d)` is the sign of `((b-a)×(c-a))·(d-a)` (CGAL's; positive
//! when `d` is on the side the right-hand normal of `abc` points to); `orient2d` is positive
//! for counter-clockwise turns. Fast paths are used when coordinates are within
//! [`MIN_ALLOWED_MAGNITUDE`]..=[`MAX_ALLOWED_MAGNITUDE`] (or zero); outside, the exact kernel
//! answers. NaN/infinite inputs panic.
#![forbid(unsafe_code)]

pub mod apart;
pub mod arith;
pub mod bvh;
pub mod exact_num;
pub mod generic;
mod kernel;
pub mod polygon;
mod range;
mod sign;

use glam::DVec3;

pub use generic::{Containment, SegmentTriangle, Shared, TriangleLocation};
#[cfg(feature = "gmp")]
pub use kernel::ExactGmp;
pub use kernel::{Checked, Exact, Filtered, Kernel};
pub use range::{MAX_ALLOWED_MAGNITUDE, MIN_ALLOWED_MAGNITUDE, in_exact_range, next_down, next_up};
pub use sign::{Orientation, Sign};

/// A xorshift generator of pseudo-random `u64`s for the unit tests (seeded, reproducible).
#[cfg(test)]
fn xorshift(mut state: u64) -> impl FnMut() -> u64 {
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    }
}

/// The kernel the free functions of this crate use.
pub type DefaultKernel = Filtered;

/// `eps * eps` rounded up to a double (so that comparing with it never under-reports a
/// distance as too large). Use it to turn a tolerance into the `eps2` of the `cmp_*` functions.
///
/// ```
/// use envelope_predicates::square_rounded_up;
/// assert_eq!(square_rounded_up(0.5), 0.25);
/// assert!(square_rounded_up(0.1) >= 0.1 * 0.1);
/// ```
#[must_use]
pub fn square_rounded_up(eps: f64) -> f64 {
    let s = eps * eps;
    // Exact iff the fused remainder is zero.
    if eps.mul_add(eps, -s) > 0.0 {
        next_up(s)
    } else {
        s
    }
}

/// Orientation of `a, b, c` in the plane: `Positive` when counter-clockwise.
///
/// ```
/// use envelope_predicates::{orient2d, Orientation};
/// use glam::DVec2;
/// assert_eq!(orient2d(DVec2::ZERO, DVec2::X, DVec2::Y), Orientation::Positive);
/// ```
#[must_use]
pub fn orient2d(a: glam::DVec2, b: glam::DVec2, c: glam::DVec2) -> Orientation {
    Filtered::orient2d(a, b, c)
}

/// Sign of `((b-a)×(c-a))·(d-a)`: `Positive` when `d` is on the side the right-hand normal of
/// `abc` points to (CGAL's `orientation`; the negation of Shewchuk's `orient3d`).
///
/// ```
/// use envelope_predicates::{orient3d, Orientation};
/// use glam::DVec3;
/// assert_eq!(orient3d(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z), Orientation::Positive);
/// ```
#[must_use]
pub fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Orientation {
    Filtered::orient3d(a, b, c, d)
}

/// Side of `e` relative to the oriented sphere through `a, b, c, d`; see [`Kernel::insphere`].
///
/// ```
/// use envelope_predicates::{insphere, Sign};
/// use glam::DVec3;
/// let (a, b, c, d) = (DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z); // positively oriented
/// assert_eq!(insphere(a, b, c, d, DVec3::splat(0.25)), Sign::Positive);
/// assert_eq!(insphere(a, b, c, d, DVec3::splat(2.0)), Sign::Negative);
/// assert_eq!(insphere(a, b, c, d, DVec3::ONE), Sign::Zero);
/// ```
#[must_use]
pub fn insphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3, e: DVec3) -> Sign {
    Filtered::insphere(a, b, c, d, e)
}

macro_rules! default_kernel {
    ($(#[$m:meta])* $name:ident ( $($arg:ident : $ty:ty),* ) -> $ret:ty) => {
        $(#[$m])*
        #[must_use]
        pub fn $name($($arg: $ty),*) -> $ret {
            generic::$name::<DefaultKernel>($($arg),*)
        }
    };
}

default_kernel!(
    /// Three points on one line; see [`generic::collinear`].
    collinear(a: DVec3, b: DVec3, c: DVec3) -> bool);
default_kernel!(
    /// `p` in the relative interior of segment `ab` (T-junction); see [`generic::point_strictly_inside_segment`].
    point_strictly_inside_segment(p: DVec3, a: DVec3, b: DVec3) -> bool);
default_kernel!(
    /// `p` on the closed segment `ab`; see [`generic::point_on_segment`].
    point_on_segment(p: DVec3, a: DVec3, b: DVec3) -> bool);
default_kernel!(
    /// Closed 3-D segments meet; see [`generic::segments_intersect`].
    segments_intersect(p: DVec3, q: DVec3, a: DVec3, b: DVec3) -> bool);
default_kernel!(
    /// Location of `p` on the closed triangle `t`; see [`generic::point_in_triangle`].
    point_in_triangle(p: DVec3, t: [DVec3; 3]) -> TriangleLocation);
default_kernel!(
    /// Coplanar triangles overlapping with positive area; see [`generic::triangles_overlap_with_area`].
    triangles_overlap_with_area(t1: [DVec3; 3], t2: [DVec3; 3]) -> bool);
default_kernel!(
    /// Sign of `dist(p, segment ab)² − eps2`; see [`generic::cmp_point_segment`].
    cmp_point_segment(p: DVec3, a: DVec3, b: DVec3, eps2: f64) -> Sign);
default_kernel!(
    /// Sign of `dist(p, t)² − eps2`; see [`generic::cmp_point_triangle`].
    cmp_point_triangle(p: DVec3, t: [DVec3; 3], eps2: f64) -> Sign);
default_kernel!(
    /// Sign of `dist(p0p1, q0q1)² − eps2`; see [`generic::cmp_segment_segment`].
    cmp_segment_segment(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3, eps2: f64) -> Sign);
default_kernel!(
    /// Sign of `dist(pq, t)² − eps2`; see [`generic::cmp_segment_triangle`].
    cmp_segment_triangle(p: DVec3, q: DVec3, t: [DVec3; 3], eps2: f64) -> Sign);
default_kernel!(
    /// Sign of `dist(t1, t2)² − eps2`; see [`generic::cmp_triangle_triangle`].
    cmp_triangle_triangle(t1: [DVec3; 3], t2: [DVec3; 3], eps2: f64) -> Sign);
default_kernel!(
    /// Inside/on/outside a closed triangulated surface; see [`generic::point_in_surface`].
    point_in_surface(p: DVec3, positions: &[DVec3], faces: &[[u32; 3]]) -> Containment);

/// The points of one derived predicate all in the adaptive predicates' range: then its
/// orientation tests skip the per-test range check ([`kernel::InRange`]), else they go through
/// [`Filtered`] (which answers out-of-range ones exactly). The same signs either way.
fn in_range<const N: usize>(points: [DVec3; N]) -> bool {
    range::all_in_range(&points)
}

/// How segment `pq` meets triangle `t`; see [`generic::segment_triangle`]. The range of the
/// five points is checked once.
#[must_use]
pub fn segment_triangle(p: DVec3, q: DVec3, t: [DVec3; 3]) -> SegmentTriangle {
    if in_range([p, q, t[0], t[1], t[2]]) {
        generic::segment_triangle::<kernel::InRange>(p, q, t)
    } else {
        generic::segment_triangle::<Filtered>(p, q, t)
    }
}

/// The algebraic number of crossings of a polyline with oriented triangles; see
/// [`generic::polyline_crossings`]. The range of all the points is checked once; in range,
/// the side of each path point against each triangle's plane is asked once, of the plane's
/// error-bounded f64 orientation first ([`apart::Planar`]), of `orient3d` when that cannot
/// tell.
#[must_use]
pub fn polyline_crossings(path: &[DVec3], triangles: &[[DVec3; 3]]) -> Option<i32> {
    if range::all_in_range(path) && triangles.iter().all(|t| range::all_in_range(t)) {
        // In range: each plane side first in error-bounded f64 (the same answers).
        generic::polyline_crossings_prefiltered::<kernel::InRange>(path, triangles)
    } else {
        generic::polyline_crossings::<Filtered>(path, triangles)
    }
}

/// Every point strictly on one side of the plane of `t`; see
/// [`generic::strictly_one_side_of_plane`]. The range of all the points is checked once.
#[must_use]
pub fn strictly_one_side_of_plane(t: [DVec3; 3], points: &[DVec3]) -> bool {
    if range::all_in_range(&t) && range::all_in_range(points) {
        generic::strictly_one_side_of_plane::<kernel::InRange>(t, points)
    } else {
        generic::strictly_one_side_of_plane::<Filtered>(t, points)
    }
}

/// Closed triangles meet; see [`generic::triangles_intersect`]. The range of the six points
/// is checked once; in range, pairs whose orientations f64 decides beyond its error bound
/// (one plane with the other triangle on one side, or crossed pairs by Guigue and
/// Devillers' two orientations, [`apart::straddling_decides`]) are answered from them, the
/// same exact answer.
#[must_use]
pub fn triangles_intersect(t1: [DVec3; 3], t2: [DVec3; 3]) -> bool {
    if in_range([t1[0], t1[1], t1[2], t2[0], t2[1], t2[2]]) {
        if let Some(meet) =
            apart::straddling_decides(&apart::Planar::new(t1), &apart::Planar::new(t2))
        {
            return meet;
        }
        generic::triangles_intersect::<kernel::InRange>(t1, t2)
    } else {
        generic::triangles_intersect::<Filtered>(t1, t2)
    }
}

/// Adjacent faces meet away from what they share; see
/// [`generic::adjacent_triangles_intersect`]. The range of the six points is checked once.
#[must_use]
pub fn adjacent_triangles_intersect(t1: [DVec3; 3], t2: [DVec3; 3], shared: Shared) -> bool {
    if in_range([t1[0], t1[1], t1[2], t2[0], t2[1], t2[2]]) {
        generic::adjacent_triangles_intersect::<kernel::InRange>(t1, t2, shared)
    } else {
        generic::adjacent_triangles_intersect::<Filtered>(t1, t2, shared)
    }
}

/// The vertex indices two faces have in common, as a [`Shared`] (or `None` when disjoint, and
/// `Some(None)` when they share three distinct indices: the same face twice).
fn shared_indices(f: [u32; 3], g: [u32; 3]) -> Option<Option<Shared>> {
    let mut pairs: [(usize, usize); 3] = [(0, 0); 3];
    let mut n = 0;
    for i in 0..3 {
        // Count each distinct index once, even if a face repeats it.
        if f[..i].contains(&f[i]) {
            continue;
        }
        if let Some(j) = g.iter().position(|&x| x == f[i]) {
            pairs[n] = (i, j);
            n += 1;
        }
    }
    match n {
        0 => None,
        1 => Some(Some(Shared::Vertex(pairs[0].0, pairs[0].1))),
        2 => Some(Some(Shared::Edge(
            [pairs[0].0, pairs[1].0],
            [pairs[0].1, pairs[1].1],
        ))),
        _ => Some(None),
    }
}

/// True when triangles `t1` and `t2`, whose corners carry the vertex indices `f` and `g`,
/// intersect, adjacency-aware: triangles sharing indices intersect only if they meet away from
/// the shared vertex/edge; the same three indices twice always count as intersecting (a
/// duplicated face). Indices only name corners here (they may be aliases of the positions),
/// but corners with one index must be one point.
///
/// When no coordinate exceeds [`MAX_ALLOWED_MAGNITUDE`] (so that no f64 product
/// overflows), the f64 pre-tests of [`apart`] run first: they only ever answer "apart" when
/// the exact test would. The exact test decides the rest.
///
/// ```
/// use envelope_predicates::indexed_triangles_intersect;
/// use glam::DVec3;
/// let t1 = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// let t2 = [DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)]; // shares the edge, flat
/// assert!(!indexed_triangles_intersect(t1, [0, 1, 2], t2, [1, 2, 3]));
/// assert!(indexed_triangles_intersect(t1, [0, 1, 2], t2, [4, 5, 6])); // touching, unshared
/// ```
#[must_use]
pub fn indexed_triangles_intersect(
    t1: [DVec3; 3],
    f: [u32; 3],
    t2: [DVec3; 3],
    g: [u32; 3],
) -> bool {
    let shared = shared_indices(f, g);
    if let Some(None) = shared {
        return true;
    }
    if small([t1[0], t1[1], t1[2], t2[0], t2[1], t2[2]]) {
        let (fs, gs) = (f.map(|x| g.contains(&x)), g.map(|x| f.contains(&x)));
        // `apart::surely_apart`, with the second plane made only when the first does not
        // separate (most pairs of neighbouring faces are decided by one of the two).
        let p1 = apart::Planar::new(t1);
        if p1.separates(t2, gs)
            || apart::apart_beyond_first_plane(&p1, fs, &apart::Planar::new(t2), gs)
        {
            return false;
        }
    }
    exact_indexed(t1, t2, shared)
}

/// Whether no coordinate exceeds [`MAX_ALLOWED_MAGNITUDE`]: all the f64 pre-tests of [`apart`]
/// need (their error bounds carry an absolute term for underflow), cheaper than the full
/// range check, which only the exact path needs.
fn small<const N: usize>(points: [DVec3; N]) -> bool {
    points
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs().max_element()))
        <= MAX_ALLOWED_MAGNITUDE
}

/// The exact adjacency-aware test (no pre-test), `shared` from [`shared_indices`].
fn exact_indexed(t1: [DVec3; 3], t2: [DVec3; 3], shared: Option<Option<Shared>>) -> bool {
    let fast = in_range([t1[0], t1[1], t1[2], t2[0], t2[1], t2[2]]);
    match (shared, fast) {
        (None, true) => generic::triangles_intersect::<kernel::InRange>(t1, t2),
        (None, false) => generic::triangles_intersect::<Filtered>(t1, t2),
        (Some(Some(s)), true) => {
            generic::adjacent_triangles_intersect::<kernel::InRange>(t1, t2, s)
        }
        (Some(Some(s)), false) => generic::adjacent_triangles_intersect::<Filtered>(t1, t2, s),
        (Some(None), _) => true,
    }
}

/// A mesh face made ready for many [`prepared_faces_intersect`] tests: its vertex indices,
/// corners and f64 plane, and whether its coordinates allow the pre-tests. Worth it when each
/// face meets several others (the envelope proof: about a dozen candidates per face).
#[derive(Clone, Copy, Debug)]
pub struct PreparedFace {
    ids: [u32; 3],
    plane: apart::Planar,
    /// No coordinate above [`MAX_ALLOWED_MAGNITUDE`] (see [`indexed_triangles_intersect`]).
    small: bool,
}

impl PreparedFace {
    /// Face `f` of `positions`.
    ///
    /// ```
    /// use envelope_predicates::{prepared_faces_intersect, PreparedFace};
    /// use glam::DVec3;
    /// let pos = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.2, 0.2, 1.0)];
    /// let prep = |f| PreparedFace::new(&pos, f);
    /// assert!(!prepared_faces_intersect(&prep([0, 1, 2]), &prep([2, 1, 3]))); // flat, sharing an edge
    /// assert!(prepared_faces_intersect(&prep([0, 1, 2]), &prep([0, 1, 2]))); // the same face twice
    /// ```
    #[must_use]
    pub fn new(positions: &[DVec3], f: [u32; 3]) -> Self {
        let t = f.map(|i| positions[i as usize]);
        PreparedFace {
            ids: f,
            plane: apart::Planar::new(t),
            small: small(t),
        }
    }
}

/// [`faces_intersect`] on two prepared faces: the same answer (the same pre-tests on the
/// stored planes, then the same exact test), without recomputing either plane.
#[must_use]
pub fn prepared_faces_intersect(a: &PreparedFace, b: &PreparedFace) -> bool {
    let (f, g) = (&a.ids, &b.ids);
    // Most pairs share no index (an envelope face against another surface's): nine
    // comparisons without a branch tell, and only a pair that shares one is matched up.
    let [g0, g1, g2] = *g;
    let in_g = |x: u32| (x == g0) | (x == g1) | (x == g2);
    let fs = [in_g(f[0]), in_g(f[1]), in_g(f[2])];
    let any = fs[0] | fs[1] | fs[2];
    let shared = if any { shared_indices(*f, *g) } else { None };
    if let Some(None) = shared {
        return true;
    }
    if a.small && b.small {
        let gs = if any {
            g.map(|x| f.contains(&x))
        } else {
            [false; 3]
        };
        if apart::surely_apart(&a.plane, fs, &b.plane, gs) {
            return false;
        }
    }
    exact_indexed(a.plane.t, b.plane.t, shared)
}

/// True when mesh faces `f` and `g` intersect, adjacency-aware; see
/// [`indexed_triangles_intersect`] (with its f64 pre-tests).
///
/// ```
/// use envelope_predicates::faces_intersect;
/// use glam::DVec3;
/// let pos = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.2, 0.2, 1.0)];
/// assert!(!faces_intersect(&pos, [0, 1, 2], [2, 1, 3])); // flat, sharing an edge
/// assert!(!faces_intersect(&pos, [0, 1, 2], [0, 4, 1])); // folded up, sharing an edge
/// assert!(faces_intersect(&pos, [0, 1, 2], [0, 1, 2])); // the same face twice
/// ```
#[must_use]
pub fn faces_intersect(positions: &[DVec3], f: [u32; 3], g: [u32; 3]) -> bool {
    let corners = |h: [u32; 3]| h.map(|i| positions[i as usize]);
    indexed_triangles_intersect(corners(f), f, corners(g), g)
}

/// All pairs of intersecting faces, `(i, j)` with `i < j`, sorted.
///
/// Faces are closed triangles; faces that share vertex indices count only when they meet away
/// from what they share (see [`adjacent_triangles_intersect`]); faces that touch at equal
/// positions with different indices (an unwelded seam) do count. Candidates come from the
/// [`bvh`] (exact boxes); tests run in parallel; the output is deterministic.
///
/// ```
/// use envelope_predicates::self_intersections;
/// use glam::DVec3;
/// let pos = [DVec3::ZERO, DVec3::X, DVec3::Y, // face 0
///            DVec3::new(0.2, 0.2, -1.0), DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.4, 0.4, 0.0), // face 1 pierces 0
///            DVec3::new(1.0, 1.0, 0.0)]; // face 2 shares the edge (1, 2) with face 0, flat
/// let faces = [[0, 1, 2], [3, 4, 5], [2, 1, 6]];
/// assert_eq!(self_intersections(&pos, &faces), vec![(0, 1)]);
/// ```
#[must_use]
pub fn self_intersections(positions: &[DVec3], faces: &[[u32; 3]]) -> Vec<(u32, u32)> {
    let tree = bvh::Bvh::from_triangles(positions, faces);
    tree.self_pairs_where(|i, j| faces_intersect(positions, faces[i as usize], faces[j as usize]))
}
