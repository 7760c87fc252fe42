//! The fiber test: a necessary condition for removing an interior vertex, from its fiber
//! (our addition; the paper has none). At small epsilons almost every removal attempt
//! fails; this test turns most of them away after a few orientation tests and barrier
//! queries, before the ear test and the greedy pass.
//!
//! **The claim.** Let `v` be an interior vertex of the approximation with fan `F` (a disk
//! whose boundary is the link loop `L`), `p` and `q` its points on the inner and outer
//! envelope (vertices of the envelope meshes `E_in`, `E_out`), and `π` a path from `p` to
//! `q`. Suppose
//!
//! 1. every face of the approximation is apart from `E_in` and `E_out`, and so is every
//!    triangle the filter accepts (the envelopes are barriers of the [`EnvelopeFilter`],
//!    proved free of the input; no pins, which let a candidate touch them);
//! 2. the connected component of `E_in` through `p`, and that of `E_out` through `q`, each
//!    have a vertex outside the box `B` of `v` and `L`;
//! 3. `π` crosses `F` with algebraic intersection number `±1` (exact, transversal
//!    crossings only).
//!
//! Then every valid filling `G` of the hole (triangles on `L`'s vertices, each accepted)
//! meets `π`. Proof: `C = F - G` is a closed surface (a 2-cycle) inside `B` (the convex
//! hull of its vertices), apart from `E_in` and `E_out` by 1. Its winding number is
//! constant on connected sets apart from `C` and zero outside `B`, so by 2 it is zero at
//! `p` and at `q`; the intersection number of `π` with `C` is the difference, zero; so
//! `π` meets `G` with intersection number `±1` by 3, in particular `π` meets a triangle of
//! `G`. Hence: **when every triangle on the hole's vertices that meets `π` is refused
//! whatever the approximation ([`Filter::refuses_anyway`], topology guards), no valid
//! filling exists**, and the attempt ends with `Rejection::NoFillAcrossFiber`. In
//! particular when no such triangle meets `π` at all: the link lies entirely below `p`
//! or entirely above `q` along the fiber (a peak or a pit deeper than the envelopes).
//!
//! **The path.** The fiber `[p, q]` itself usually passes exactly through `v` (the two
//! offsets are symmetric constructions), a degenerate crossing of `F`. So `π` is the
//! polyline `p → r → q` with `r = v + u`, `u` perpendicular to `q - p` and a hundredth of
//! its length (an f64 construction: any `r` keeps the claim, it only has to make the
//! crossings transversal). Crossings of `F` through an edge or a vertex, or an endpoint on
//! `F`, leave the count undecided and the test claims nothing.
//!
//! Everything the claim rests on is exact (`segment_triangle`, `orient3d`); the f64 level
//! filter that skips triangles far below or above the path along the fiber has a rounding
//! margin and can only say "apart". The test can only reject, never accept: with fibers of
//! other barriers than the filter's, it would at worst turn away a removable vertex (more
//! faces), never let an invalid filling in.
//!
//! [`EnvelopeFilter`]: crate::filter::EnvelopeFilter
//! [`Filter::refuses_anyway`]: crate::filter::Filter::refuses_anyway

use envelope_mesh::{VertexFaces, VertexId, vertex_components};
use envelope_predicates::bvh::Aabb;
use envelope_predicates::{polyline_crossings, strictly_one_side_of_plane};
use glam::{DVec2, DVec3};

/// The fiber of every vertex (by vertex id): the segment from its inner envelope point to its
/// outer one (f64 constructions of `envelope-offset`), along which the local algorithm's
/// `Placement::Slide` moves it.
#[derive(Clone, Copy, Debug)]
pub struct VertexFibers<'a> {
    /// `v - eps_minus n_v`.
    pub inner: &'a [DVec3],
    /// `v + eps_plus n_v`.
    pub outer: &'a [DVec3],
}

impl VertexFibers<'_> {
    /// `(inner point, outer - inner)` of `v`; `None` without a fiber of positive length.
    pub(crate) fn segment(&self, v: VertexId) -> Option<(DVec3, DVec3)> {
        let (a, b) = (*self.inner.get(v.index())?, *self.outer.get(v.index())?);
        let d = b - a;
        (d.length_squared() > 0.0 && d.is_finite()).then_some((a, d))
    }
}

/// What the fiber test needs beyond the fibers: the connected components of the envelope
/// meshes and the box of each (condition 2 of the module docs).
///
/// ```
/// use envelope_mesh::generate;
/// use envelope_simplify::policy::{FiberTest, VertexFibers};
/// let sphere = generate::icosphere(2, 1.0);
/// let scaled = |s: f64| sphere.positions.iter().map(|&p| p * s).collect::<Vec<_>>();
/// let (inner, outer) = (scaled(0.99), scaled(1.01));
/// let test = FiberTest::new(VertexFibers { inner: &inner, outer: &outer }, &sphere.faces);
/// assert_eq!(test.components(), 1);
/// ```
#[derive(Clone, Debug)]
pub struct FiberTest<'a> {
    fibers: VertexFibers<'a>,
    /// Component of each vertex (`None` for one in no face).
    component: Vec<Option<u32>>,
    /// Per component: the boxes of its inner and of its outer envelope points.
    boxes: Vec<(Aabb, Aabb)>,
    /// The faces around each vertex.
    fans: VertexFaces,
}

impl<'a> FiberTest<'a> {
    /// The test for envelopes whose vertex `i` is `fibers.inner[i]` / `fibers.outer[i]` and
    /// whose faces are `faces` (both envelopes; in `envelope simplify`, the input's faces).
    /// The caller promises condition 1 of the module docs for the simplification it
    /// is given to; the driver's `simplify` gives it only with proved envelopes and no pins.
    #[must_use]
    pub fn new(fibers: VertexFibers<'a>, faces: &[[VertexId; 3]]) -> Self {
        let n = fibers.inner.len().min(fibers.outer.len());
        let (component, count) = vertex_components(n, faces);
        let mut boxes = vec![(Aabb::EMPTY, Aabb::EMPTY); count];
        for (v, c) in component.iter().enumerate() {
            if let Some(c) = *c {
                let (bi, bo) = &mut boxes[c as usize];
                *bi = bi.union(&Aabb::from_points(&[fibers.inner[v]]));
                *bo = bo.union(&Aabb::from_points(&[fibers.outer[v]]));
            }
        }
        Self {
            fibers,
            component,
            boxes,
            fans: VertexFaces::new(n, faces),
        }
    }

    /// The faces (of the `faces` given to [`Self::new`]) around vertex `v`: their envelope
    /// triangles are where the fiber test's candidates are mostly refused (a hint for
    /// [`crate::filter::Filter::within_near`]).
    #[must_use]
    pub fn faces_around(&self, v: VertexId) -> &[u32] {
        self.fans.of(v.index())
    }

    /// Number of connected components of the envelope meshes.
    #[must_use]
    pub fn components(&self) -> usize {
        self.boxes.len()
    }

    /// The path `p → r → q` of the [module docs](self) for removing `v` at `position` with
    /// link positions `link`, when conditions 2 holds and the path is well defined; `None`
    /// otherwise (the test then claims nothing).
    pub(crate) fn path(&self, v: VertexId, position: DVec3, link: &[DVec3]) -> Option<FiberPath> {
        let i = v.index();
        let (p, q) = (*self.fibers.inner.get(i)?, *self.fibers.outer.get(i)?);
        let c = (*self.component.get(i)?)?;
        let (inner_box, outer_box) = *self.boxes.get(c as usize)?;
        let mut b = Aabb::from_points(link);
        b = b.union(&Aabb::from_points(&[position]));
        let within = |x: &Aabb| b.min.cmple(x.min).all() && x.max.cmple(b.max).all();
        if within(&inner_box) || within(&outer_box) {
            return None;
        }
        let d = q - p;
        // A direction perpendicular to the fiber: across the axis it is least aligned with.
        let a = d.abs();
        let axis = if a.x <= a.y && a.x <= a.z {
            DVec3::X
        } else if a.y <= a.z {
            DVec3::Y
        } else {
            DVec3::Z
        };
        let e1 = d.cross(axis).normalize_or_zero();
        let e2 = d.cross(e1).normalize_or_zero();
        let r = position + e1 * (d.length() * 0.01);
        let points = [p, r, q];
        (points.iter().all(|x| x.is_finite()) && e1 != DVec3::ZERO && e2 != DVec3::ZERO)
            .then(|| FiberPath::new(points, d, position, e1, e2))
    }
}

/// A polyline from an inner envelope point to an outer one, with two f64 filters that can
/// only say "apart": levels along the fiber direction `d`, and a projection along `d`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FiberPath {
    points: [DVec3; 3],
    d: DVec3,
    /// Lowest and highest level `(x - p) · d` of the path's points, with their rounding
    /// margins (a lower and an upper bound of the exact levels).
    low: f64,
    high: f64,
    /// The projection `x -> ((x - origin) · e1, (x - origin) · e2)` (any linear map would
    /// do; this one, nearly along `d`, maps the path into a small disc)...
    origin: DVec3,
    e1: DVec3,
    e2: DVec3,
    /// ... and the radius of a disc about zero that holds the exact images of the path's
    /// points (so of the whole path).
    radius: f64,
}

/// Relative rounding margin of an f64 dot product `(x - o) · e` against `Σ |x_i - o_i| |e_i|`:
/// the error is below `4u` (`u = 2^-53`) times that sum; this is a hundred times more.
const DOT_MARGIN: f64 = 1e-13;

/// The buffers of [`FiberPath::any_triangle_that_may_meet`], kept per thread.
#[derive(Default)]
struct Scratch {
    below: Vec<bool>,
    above: Vec<bool>,
    images: Vec<DVec2>,
    c: Vec<f64>,
    w: Vec<f64>,
}

thread_local! {
    static SCRATCH: std::cell::Cell<Scratch> = std::cell::Cell::default();
}

impl FiberPath {
    fn new(points: [DVec3; 3], d: DVec3, origin: DVec3, e1: DVec3, e2: DVec3) -> Self {
        let mut path = Self {
            points,
            d,
            low: f64::INFINITY,
            high: f64::NEG_INFINITY,
            origin,
            e1,
            e2,
            radius: 0.0,
        };
        for x in points {
            let (level, margin) = path.level(x);
            path.low = path.low.min(level - margin);
            path.high = path.high.max(level + margin);
            let (image, error) = path.project(x);
            path.radius = path.radius.max(image.length() + 2.0 * error);
        }
        path.radius *= 1.0 + 1e-12;
        path
    }

    /// The f64 level of `x` and its rounding margin.
    fn level(&self, x: DVec3) -> (f64, f64) {
        let e = x - self.points[0];
        let level = e.dot(self.d);
        let size = (e.abs() * self.d.abs()).element_sum();
        (level, size * DOT_MARGIN + f64::MIN_POSITIVE)
    }

    /// The f64 image of `x` under the projection and a bound of the error of each of its
    /// two coordinates.
    fn project(&self, x: DVec3) -> (DVec2, f64) {
        let e = x - self.origin;
        let image = DVec2::new(e.dot(self.e1), e.dot(self.e2));
        let size = e.abs().element_sum() * self.e1.abs().max(self.e2.abs()).max_element();
        (image, size * DOT_MARGIN + f64::MIN_POSITIVE)
    }

    /// Calls `f` on every triangle of `corners` (positions `i < j < k`) that may meet the
    /// path, until `f` returns true; returns whether it did. A triangle left out surely
    /// misses the path: all its corners lie strictly below or strictly above every point
    /// of the path along `d`, or the disc holding the path's image lies strictly outside
    /// the image of the triangle (both f64 with rounding bounds).
    pub(crate) fn any_triangle_that_may_meet(
        &self,
        corners: &[DVec3],
        f: impl FnMut([usize; 3]) -> bool,
    ) -> bool {
        // This thread's buffers, taken for the call (a call from within `f` would get
        // fresh ones) and put back after: no allocation per attempt.
        let mut scratch = SCRATCH.take();
        let found = self.any_triangle_that_may_meet_in(&mut scratch, corners, f);
        SCRATCH.set(scratch);
        found
    }

    fn any_triangle_that_may_meet_in(
        &self,
        scratch: &mut Scratch,
        corners: &[DVec3],
        mut f: impl FnMut([usize; 3]) -> bool,
    ) -> bool {
        let n = corners.len();
        let Scratch {
            below,
            above,
            images,
            c,
            w,
        } = scratch;
        // Per corner: below the path, above it (strictly, with margins); its image.
        below.clear();
        above.clear();
        images.clear();
        let mut worst = 0.0f64;
        for &x in corners {
            let (l, m) = self.level(x);
            below.push(l + m < self.low);
            above.push(l - m > self.high);
            let (image, error) = self.project(x);
            images.push(image);
            worst = worst.max(error);
        }
        // Cross products `c_ij = P_i × P_j` (the orientation of zero against edge i -> j)
        // and how far from zero the disc reaches across that edge, with rounding bounds:
        // every image coordinate is off by at most `worst`, every |P| at most `scale`.
        let scale = images
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max)
            + worst;
        let cross_error = 8.0 * scale * worst + 1e-12 * scale * scale + f64::MIN_POSITIVE;
        // Every entry read below (`i != j`) is written first.
        c.resize(n * n, 0.0);
        w.resize(n * n, 0.0);
        for i in 0..n {
            for j in i + 1..n {
                let x = images[i].perp_dot(images[j]);
                let reach =
                    self.radius * ((images[j] - images[i]).length() + 3.0 * worst) * (1.0 + 1e-12);
                c[i * n + j] = x;
                c[j * n + i] = -x;
                w[i * n + j] = reach + cross_error;
                w[j * n + i] = reach + cross_error;
            }
        }
        let apart_in_image = |t: [usize; 3]| {
            let edges = [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])];
            let area: f64 = edges.iter().map(|&(a, b)| c[a * n + b]).sum();
            if area > 3.0 * cross_error {
                edges
                    .iter()
                    .any(|&(a, b)| c[a * n + b] + w[a * n + b] < 0.0)
            } else if area < -3.0 * cross_error {
                edges
                    .iter()
                    .any(|&(a, b)| c[a * n + b] - w[a * n + b] > 0.0)
            } else {
                false
            }
        };
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    let by_level =
                        (below[i] && below[j] && below[k]) || (above[i] && above[j] && above[k]);
                    if !by_level
                        && !apart_in_image([i, j, k])
                        && !strictly_one_side_of_plane(
                            [corners[i], corners[j], corners[k]],
                            &self.points,
                        )
                        && f([i, j, k])
                    {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// The algebraic number of crossings of the path with the oriented triangles `fan`,
    /// when every crossing is transversal through a triangle's interior; `None` otherwise
    /// (exact, [`polyline_crossings`]; a triangle all of whose corners lie strictly below
    /// or above the path along `d` is left out first, f64 with margins; `fan` is filtered
    /// in place).
    pub(crate) fn crossings(&self, mut fan: Vec<[DVec3; 3]>) -> Option<i32> {
        fan.retain(|t| !self.apart_by_level(t));
        polyline_crossings(&self.points, &fan)
    }

    /// Whether all corners of `t` lie strictly below or strictly above every point of the
    /// path along `d` (f64 with margins: it can only say "apart").
    fn apart_by_level(&self, t: &[DVec3; 3]) -> bool {
        let levels = t.map(|x| self.level(x));
        levels.iter().all(|&(l, m)| l + m < self.low)
            || levels.iter().all(|&(l, m)| l - m > self.high)
    }

    /// Condition 3 of the [module docs](self) for the oriented fan triangles `fan`.
    pub(crate) fn crosses_once(&self, fan: Vec<[DVec3; 3]>) -> bool {
        matches!(self.crossings(fan), Some(1 | -1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_predicates::segment_triangle;
    use proptest::prelude::*;

    /// A path for a vertex at `v` with fiber `v ± h n`, through `FiberTest::path`'s
    /// construction (one component reaching far beyond any link).
    fn path_for(v: DVec3, n: DVec3, h: f64, link: &[DVec3]) -> FiberPath {
        let far = 1e3 * link.iter().fold(v.length(), |m, x| m.max(x.length()));
        let inner = vec![v - n * h, DVec3::splat(-far), DVec3::new(-far, far, 0.0)];
        let outer = vec![v + n * h, DVec3::splat(far), DVec3::new(far, -far, 0.0)];
        let fibers = VertexFibers {
            inner: &inner,
            outer: &outer,
        };
        let test = FiberTest::new(fibers, &[[VertexId(0), VertexId(1), VertexId(2)]]);
        test.path(VertexId(0), v, link).expect("a path")
    }

    fn hexagon(z: impl Fn(usize) -> f64) -> Vec<DVec3> {
        (0..6)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 6.0;
                DVec3::new(a.cos(), a.sin(), z(i))
            })
            .collect()
    }

    fn fan(v: DVec3, link: &[DVec3]) -> Vec<[DVec3; 3]> {
        (0..link.len())
            .map(|i| [v, link[i], link[(i + 1) % link.len()]])
            .collect()
    }

    /// A peak higher than its fiber: no triangle on the link meets the path (none is
    /// asked about), and the path crosses the fan once; lower than the fiber, the central
    /// triangles are asked about.
    #[test]
    fn a_peak_above_the_fiber_has_no_filling_across() {
        let link = hexagon(|_| 0.0);
        for (height, fiber, across) in [(0.5, 0.1, false), (0.05, 0.1, true)] {
            let v = DVec3::new(0.1, 0.05, height);
            let path = path_for(v, DVec3::Z, fiber, &link);
            let mut asked = 0;
            let found = path.any_triangle_that_may_meet(&link, |_| {
                asked += 1;
                false
            });
            assert!(!found);
            assert_eq!(asked > 0, across, "height {height}: {asked} asked");
            assert!(path.crosses_once(fan(v, &link)));
        }
    }

    /// A fan folded over itself along the fiber (a flap that the path crosses twice more,
    /// or passes twice) is not crossed once: the test claims nothing there.
    #[test]
    fn a_fan_crossed_three_times_is_not_crossed_once() {
        let v = DVec3::ZERO;
        let link = hexagon(|_| -0.5);
        let path = path_for(v, DVec3::Z, 0.1, &link);
        let mut triangles = fan(v, &link);
        assert_eq!(path.crossings(triangles.clone()).map(i32::abs), Some(1));
        // Two more sheets across the fiber, one each way: the count stays odd but the
        // crossings are three; reversed, the count is three.
        let sheet = |z: f64| {
            [
                DVec3::new(-1.0, -1.0, z),
                DVec3::new(2.0, -1.0, z),
                DVec3::new(-1.0, 2.0, z),
            ]
        };
        let flip = |t: [DVec3; 3]| [t[0], t[2], t[1]];
        let once = path.crossings(triangles.clone()).unwrap();
        let s = sheet(0.05);
        triangles.push(if once == 1 { s } else { flip(s) });
        triangles.push(if once == 1 {
            sheet(-0.05)
        } else {
            flip(sheet(-0.05))
        });
        assert_eq!(path.crossings(triangles.clone()).map(i32::abs), Some(3));
        assert!(!path.crosses_once(triangles.clone()));
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

        /// The f64 filters never leave out a triangle that meets the path (exact
        /// `segment_triangle` on its two segments): random links around random vertices,
        /// fibers in random directions and lengths from tiny to longer than the link.
        #[test]
        fn no_triangle_that_meets_the_path_is_left_out(
            zs in prop::collection::vec(-1.0f64..1.0, 3..9),
            v in (-0.3f64..0.3, -0.3f64..0.3, -0.5f64..0.5),
            n in (-0.5f64..0.5, -0.5f64..0.5, 0.5f64..1.0),
            log_h in -6.0f64..0.5,
            scale in prop::sample::select(vec![1.0, 1e-3, 1e4]),
        ) {
            let k = zs.len();
            let link: Vec<DVec3> = (0..k)
                .map(|i| {
                    let a = i as f64 * std::f64::consts::TAU / k as f64;
                    DVec3::new(a.cos(), a.sin(), zs[i]) * scale
                })
                .collect();
            let v = DVec3::new(v.0, v.1, v.2) * scale;
            let n = DVec3::new(n.0, n.1, n.2).normalize();
            let path = path_for(v, n, 10f64.powf(log_h) * scale, &link);
            let mut asked = Vec::new();
            path.any_triangle_that_may_meet(&link, |t| {
                asked.push(t);
                false
            });
            for i in 0..k {
                for j in i + 1..k {
                    for l in j + 1..k {
                        let t = [link[i], link[j], link[l]];
                        let meets = path.points.windows(2).any(|s| segment_triangle(s[0], s[1], t).intersects());
                        prop_assert!(!meets || asked.contains(&[i, j, l]), "{:?} meets the path but was left out", [i, j, l]);
                    }
                }
            }
        }
    }
}
