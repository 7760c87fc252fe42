//! Border walls: half-tubes glued to the outer and inner envelopes along every border loop of
//! the input, so that the space between the envelopes is closed along the border (section
//! 6.2).
//!
//! # Why
//!
//! The outer and inner envelopes of a mesh with borders are open surfaces whose boundary
//! edges lie about `eps+ + eps-` apart, one above and one below each input border edge. The
//! border tubes only constrain *new border edges*; an interior candidate triangle next to a
//! border can leave the space between the envelopes through that gap without touching any
//! envelope triangle (a chord across a hole, far from the input). A wall is a strip that joins the outer envelope's boundary to the inner one's on
//! the outward side of the border; walls are *full* barriers
//! ([`crate::barriers::BarrierKind::Wall`]): no candidate triangle may touch them.
//!
//! # Construction
//!
//! For a border vertex `v` with input position `c`, outer envelope position `a+` and inner
//! envelope position `a-` (bit-exactly the f64 points of the envelope soups), let `n` be the
//! unit vector along `a+ - a-` (the vertex normal the envelopes used), and `o` the outward
//! direction in the plane perpendicular to `n`: `normalize((e_in + e_out) x n)` with
//! `e_in = c - c_prev`, `e_out = c_next - c` along the loop. Loops run as their faces run
//! the border edges; with counter-clockwise faces seen from outside, the face interior lies
//! along `n x e` of a border edge `e`, so `e x n` points away from the surface. Degenerate
//! cases fall back to `e_out x n`, then to any unit vector perpendicular to `n`, so every
//! border vertex gets a ring and the wall has no gap.
//!
//! The ring of `v` has `m + 1` points ([`WALL_SEGMENTS`] `= m`): `p_0 = a+`, `p_m = a-`
//! exactly, and for `0 < k < m`, with `theta = k pi / m`,
//! `p_k = c + max(cos theta, 0)(a+ - c) + max(-cos theta, 0)(a- - c) + sin theta r o`,
//! `r = min(|a+ - c|, |a- - c|)`. Since `a+ - c` and `a- - c` are parallel to `n` and `o`
//! is perpendicular to `n`, `|p_k - c|^2 = cos^2 theta |a+- - c|^2 + sin^2 theta r^2`, so
//! every ring point lies within `max(eps+, eps-)` of `c` (up to f64 rounding of the
//! construction, far below eps). Consecutive rings `a`, `b` of a loop are joined by the
//! quads `(p_k(a), p_k(b), p_{k+1}(b), p_{k+1}(a))`, two triangles each. A point of a wall
//! triangle is a convex combination of ring points of `a` and `b`, so by convexity of the
//! norm it lies within `max(eps_a, eps_b)` of the same convex combination of `c_a` and
//! `c_b`, a point of the border edge: the volume closed off by the envelopes and the walls
//! stays within epsilon of the input.
//!
//! The first and last quads of each strip contain the envelopes' boundary edges
//! `(a+, b+)` and `(a-, b-)` as triangle edges, with the same f64 endpoints, so envelope,
//! wall and envelope meet without a crack.
//!
//! # Skipped
//!
//! Border chains (open border paths, only next to non-manifold edges) get no wall, and a
//! loop segment is skipped when one of its ends is a non-manifold border vertex (more than
//! two border edges: a pinch), where "the outward side" is not defined by one fan. Acceptable
//! input (the driver's `input_problems`) has neither.

use envelope_mesh::{Topology, TriangleSoup, VertexId};
use glam::DVec3;

/// Segments of a wall ring (`m`): `m + 1` points from the outer to the inner envelope.
pub const WALL_SEGMENTS: usize = 4;

/// The wall along one border loop.
#[derive(Clone, Debug, PartialEq)]
pub struct Wall {
    /// The loop's vertices, in loop order.
    pub vertices: Vec<VertexId>,
    /// The ring of each vertex (same order): `WALL_SEGMENTS + 1` points, the first the outer
    /// envelope's vertex, the last the inner envelope's vertex (bit-exact copies).
    pub rings: Vec<Vec<DVec3>>,
    /// Whether the segment from vertex `i` to vertex `i + 1` (cyclically) has a strip.
    pub segments: Vec<bool>,
    /// The strip triangles; vertex `i * (WALL_SEGMENTS + 1) + k` is `rings[i][k]`.
    pub mesh: TriangleSoup,
}

/// The walls of every border loop of `input` (`topology = analyze(input)`), between the
/// envelopes `outer` and `inner` (input connectivity: vertex `v` of the input is vertex `v`
/// of both).
#[must_use]
pub fn border_walls(
    input: &TriangleSoup,
    topology: &Topology,
    outer: &TriangleSoup,
    inner: &TriangleSoup,
) -> Vec<Wall> {
    let mut border_degree = vec![0u32; input.num_vertices()];
    for e in &topology.border_edges {
        for v in e {
            border_degree[v.index()] += 1;
        }
    }
    topology
        .border_loops
        .iter()
        .filter(|l| l.len() >= 2)
        .map(|l| wall(input, l, &border_degree, outer, inner))
        .collect()
}

fn wall(
    input: &TriangleSoup,
    loop_: &[VertexId],
    border_degree: &[u32],
    outer: &TriangleSoup,
    inner: &TriangleSoup,
) -> Wall {
    let n = loop_.len();
    let c = |i: usize| input.positions[loop_[i % n].index()];
    let rings: Vec<Vec<DVec3>> = (0..n)
        .map(|i| {
            let v = loop_[i].index();
            ring(
                c(i + n - 1),
                c(i),
                c(i + 1),
                outer.positions[v],
                inner.positions[v],
            )
        })
        .collect();
    let manifold = |i: usize| border_degree[loop_[i % n].index()] == 2;
    let segments: Vec<bool> = (0..n).map(|i| manifold(i) && manifold(i + 1)).collect();
    let stride = WALL_SEGMENTS + 1;
    let id = |i: usize, k: usize| VertexId(((i % n) * stride + k) as u32);
    let mut faces = Vec::new();
    for i in (0..n).filter(|&i| segments[i]) {
        for k in 0..WALL_SEGMENTS {
            let (a0, b0, b1, a1) = (id(i, k), id(i + 1, k), id(i + 1, k + 1), id(i, k + 1));
            faces.push([a0, b0, b1]);
            faces.push([a0, b1, a1]);
        }
    }
    let positions = rings.iter().flatten().copied().collect();
    Wall {
        vertices: loop_.to_vec(),
        rings,
        segments,
        mesh: TriangleSoup::new(positions, faces),
    }
}

/// The outward direction at `c` perpendicular to `n` (see the module docs).
fn outward(prev: DVec3, c: DVec3, next: DVec3, n: DVec3) -> DVec3 {
    let (e_in, e_out) = (c - prev, next - c);
    [(e_in + e_out).cross(n), e_out.cross(n), e_in.cross(n)]
        .into_iter()
        .find_map(|d| d.try_normalize())
        .unwrap_or_else(|| n.any_orthonormal_vector())
}

/// The ring of a border vertex at `c` (see the module docs).
fn ring(prev: DVec3, c: DVec3, next: DVec3, a_plus: DVec3, a_minus: DVec3) -> Vec<DVec3> {
    let n = (a_plus - a_minus).try_normalize().unwrap_or(DVec3::Z);
    let o = outward(prev, c, next, n);
    let (up, down) = (a_plus - c, a_minus - c);
    let r = up.length().min(down.length());
    let m = WALL_SEGMENTS;
    (0..=m)
        .map(|k| {
            if k == 0 {
                return a_plus;
            }
            if k == m {
                return a_minus;
            }
            let theta = std::f64::consts::PI * k as f64 / m as f64;
            let (s, co) = theta.sin_cos();
            let p = c + co.max(0.0) * up + (-co).max(0.0) * down + s * r * o;
            // A product of small components (cos(pi/2) times a tiny component of `up`) can
            // fall below the exact predicates' range (2^-120) where the loop touches a
            // coordinate plane (the corpus mesh poly2x^2+y^2-0.062500): such a coordinate
            // becomes 0, a move below 1e-30, far below the construction's rounding.
            p.map(|x| if x.abs() < 1e-30 { 0.0 } else { x })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::{analyze, generate};

    #[test]
    fn ring_points_stay_in_the_predicates_range() {
        // A border running along x through the origin of x, whose normal leans towards x: the
        // envelope points have x = 2e-36 (in range), the ring points between them
        // cos(theta) times that, below 2^-120 (7.5e-37) near theta = pi/2.
        let c = DVec3::new(0.0, 1.0, 0.0);
        let up = DVec3::new(2e-36, 0.0, 1e-3);
        let r = ring(c - DVec3::X * 0.1, c, c + DVec3::X * 0.1, c + up, c - up);
        assert_eq!(r.len(), WALL_SEGMENTS + 1);
        for p in r {
            for x in p.to_array() {
                assert!(envelope_mesh::check_coordinate(x).is_ok(), "{p:?}");
            }
        }
    }

    #[test]
    fn outward_points_away_from_the_face_interior() {
        // Disk in z = 0 with normal +z: the outer loop's rings bulge away from the centre,
        // the hole's rings towards the hole's centre.
        let soup = generate::disk_with_holes(1);
        let t = analyze(&soup);
        let up = |d: f64| {
            let mut s = soup.clone();
            s.positions.iter_mut().for_each(|p| p.z += d);
            s
        };
        let walls = border_walls(&soup, &t, &up(0.1), &up(-0.1));
        assert_eq!(walls.len(), 2);
        let centre = DVec3::new(1.5, 1.5, 0.0);
        for w in &walls {
            let outer_loop = w
                .vertices
                .iter()
                .any(|v| soup.positions[v.index()].x == 0.0);
            for (v, r) in w.vertices.iter().zip(&w.rings) {
                let c = soup.positions[v.index()];
                let mid = r[WALL_SEGMENTS / 2];
                let away = (mid - c).dot(c - centre) > 0.0;
                assert_eq!(away, outer_loop, "vertex {c}");
                assert!(r.iter().all(|p| (*p - c).length() <= 0.1 + 1e-12));
            }
        }
    }
}
