//! Analytical epsilon (Cohen et al. 4.1).
//!
//! For every fundamental triangle `t = v0 v1 v2` and each side (`s = +1` outer, `-1` inner),
//! the prism of height `2 eps` with corner directions `d_i = 2 s eps_i n_i` (with a
//! per-vertex field each corner rises by its own `2 eps_i`). Every input triangle `Δ`
//! sharing no vertex with `t` whose box meets the prism's box (BVH) is clipped against the
//! prism ([`envelope_prism::clip`], which lists the candidate closest points); `δ` is the
//! Euclidean distance from `t` of the closest candidate, `eps_new(t) = min δ / 2`, and
//! `eps_new(v)` is the minimum over the triangles of `v` (and the requested `eps_v`).
//!
//! The clipping is an f64 construction. The result is not trusted: [`crate::build_envelopes`]
//! follows it with the exact proof, and halves the epsilon of every vertex of an offending
//! envelope face until the proof holds (see the crate docs). The paper's octree is replaced
//! by the BVH of `envelope-predicates`; a triangle the BVH returns is skipped without
//! clipping when it lies apart from the convex hull of the prism's six corners, or farther
//! from `t`'s box than the closest candidate so far (both with a margin, see
//! [`clip::PRUNE_TOLERANCE`]; the offsets are the same either way). The walk skips a whole
//! node on the same two grounds, with its box in place of the triangle
//! ([`clip::HullAxes::misses_box`]): at a large epsilon over small faces the prism's box
//! holds a patch of surface growing with the face count, of which the thin prism meets few
//! triangles.
//!
//! A build over a subset of the faces of an earlier one (the simplify driver's rounds around
//! kept faces each drop a few faces) may take the earlier one's per-face minima
//! ([`AnalyticalFaces`]): a face whose corners have the positions, normals and targets they
//! had, and whose closest triangle is still there, has the same minimum over fewer triangles,
//! so only the others are clipped again. The offsets are the same as without it.
use std::cell::{Cell, OnceCell};
use std::collections::HashMap;

use envelope_mesh::{TriangleSoup, VertexFaces};
use envelope_predicates::bvh::{Aabb, Bvh};
use envelope_prism::clip;
use glam::DVec3;
use rayon::prelude::*;

/// No triangle met the prism: `delta` is infinite.
const NONE: u32 = u32::MAX;

/// A face's minimum on one side: the distance and the face that gave it (or [`NONE`]).
type Minimum = (f64, u32);

/// What the analytical method found for every face of one build, for a later build over a
/// subset of its faces ([`crate::EnvelopeOptions::analytical_memo`]): each face's distance to
/// its closest triangle on each side and that triangle, with the corners' inputs to the
/// clipping (positions, normals, targets) that decide whether a face's minimum still holds.
#[derive(Clone)]
pub struct AnalyticalFaces {
    faces: Vec<[u32; 3]>,
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    targets: Vec<f64>,
    /// Per face and side (outer, inner): the smallest clipped distance.
    delta: Vec<[f64; 2]>,
    /// Per face and side: the face (index into `faces`) that gave `delta`, or [`NONE`].
    nearest: Vec<[u32; 2]>,
}

impl std::fmt::Debug for AnalyticalFaces {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("AnalyticalFaces")
            .field("faces", &self.faces.len())
            .finish_non_exhaustive()
    }
}

impl AnalyticalFaces {
    /// Per face of `faces`: the earlier minima still true for it (`None` for a side to clip
    /// again), or `None` when `faces` is not a subset of the earlier faces on the same
    /// positions (then nothing is taken).
    pub(crate) fn reusable(
        &self,
        faces: &[[u32; 3]],
        positions: &[DVec3],
        normals: &[DVec3],
        targets: &[f64],
    ) -> Option<Vec<[Option<Minimum>; 2]>> {
        let n = positions.len();
        if [self.positions.len(), self.normals.len(), self.targets.len()] != [n; 3] {
            return None;
        }
        let same_position = |v: u32| {
            let v = v as usize;
            positions[v].to_array().map(f64::to_bits)
                == self.positions[v].to_array().map(f64::to_bits)
        };
        let index: HashMap<[u32; 3], u32> = self
            .faces
            .iter()
            .enumerate()
            .map(|(i, f)| (*f, i as u32))
            .collect();
        // Earlier face -> its index now (NONE: dropped).
        let mut now = vec![NONE; self.faces.len()];
        for (i, f) in faces.iter().enumerate() {
            let before = *index.get(f)?;
            if !f.iter().all(|&v| (v as usize) < n && same_position(v)) {
                return None;
            }
            now[before as usize] = i as u32;
        }
        let same_corner = |v: u32| {
            let v = v as usize;
            normals[v].to_array().map(f64::to_bits) == self.normals[v].to_array().map(f64::to_bits)
                && targets[v].to_bits() == self.targets[v].to_bits()
        };
        Some(
            faces
                .iter()
                .map(|f| {
                    let before = index[f] as usize;
                    if !f.iter().all(|&v| same_corner(v)) {
                        return [None, None];
                    }
                    [0, 1].map(|k| match self.nearest[before][k] {
                        NONE => Some((self.delta[before][k], NONE)),
                        g if now[g as usize] != NONE => {
                            Some((self.delta[before][k], now[g as usize]))
                        }
                        _ => None,
                    })
                })
                .collect(),
        )
    }
}

/// Per-vertex `(eps_plus, eps_minus)` by the analytical method; `bvh` is a tree over the
/// boxes of the input faces (item = face). With `before` (an earlier build's faces, a
/// superset of these), the minima that still hold are taken from it; with `keep`, this
/// build's are returned for a later one. Once `stopped` says so the remaining faces are
/// skipped (the caller discards the result).
pub(crate) fn analytical_eps(
    soup: &TriangleSoup,
    vf: &VertexFaces,
    normals: &[DVec3],
    requested: &[f64],
    bvh: &Bvh,
    (before, keep): (Option<&AnalyticalFaces>, bool),
    stopped: &(dyn Fn() -> bool + Sync),
) -> (Vec<f64>, Vec<f64>, Option<AnalyticalFaces>) {
    let faces: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
    let known = before.and_then(|b| b.reusable(&faces, &soup.positions, normals, requested));
    // The faces in the tree's leaf order: each one's query then walks the nodes, and reads the
    // faces and positions, that the one before read (in the input's order they may be far
    // apart). Each face's result depends on nothing else, so the order changes no number.
    let in_id_order: Vec<u32>;
    let order: &[u32] = match bvh.leaf_order() {
        o if o.len() == faces.len() => o,
        _ => {
            in_id_order = (0..faces.len() as u32).collect();
            &in_id_order
        }
    };
    let in_order: Vec<[Minimum; 2]> = order
        .par_iter()
        .map(|&fi| {
            let known = known.as_ref().map_or([None, None], |k| k[fi as usize]);
            if let [Some(outer), Some(inner)] = known {
                return [outer, inner];
            }
            if stopped() {
                return [(f64::INFINITY, NONE); 2];
            }
            let f = &faces[fi as usize];
            let v = f.map(|i| soup.positions[i as usize]);
            let t_box = Aabb::from_triangle(v);
            // Both sides' prisms, asked of the tree in one query over the union of their
            // boxes; each side then takes the triangles whose boxes meet its own box (the
            // same triangles, in the same order, as a query of its own would give).
            let side = |s: f64| {
                let d = f.map(|i| normals[i as usize] * (2.0 * s * requested[i as usize]));
                let top = clip::prism_top(v, d);
                let (b, scale) = clip::prism_box(&t_box, top);
                (d, top, b, scale)
            };
            let sides = [side(1.0), side(-1.0)];
            let delta = Cell::new(known.map(|k| k.map_or(f64::INFINITY, |(d, _)| d)));
            let mut nearest = known.map(|k| k.map_or(NONE, |(_, g)| g));
            let todo = known.map(|k| k.is_none());
            let query = sides[0].2.union(&sides[1].2);
            // Only worth its cost where the prisms reach far beyond the face.
            let tall =
                (query.max - query.min).max_element() > 8.0 * (t_box.max - t_box.min).max_element();
            // Each side's hull axes, once, when a node or a triangle asks.
            let axes = [OnceCell::new(), OnceCell::new()];
            let axes_of = |k: usize| axes[k].get_or_init(|| clip::HullAxes::new(v, sides[k].1));
            // A node is entered only when a triangle in it could pass the two shortcuts
            // below on some side (the box forms of both skip nothing the triangle forms
            // would not): the same triangles are clipped, in the same order, and at a large
            // epsilon over small faces most of the query box is skipped whole.
            let enter = |b: &Aabb| {
                b.overlaps(&query)
                    && (!tall
                        || (0..2).any(|k| {
                            let (_, _, sb, scale) = &sides[k];
                            let tol = clip::PRUNE_TOLERANCE
                                * scale.max(b.min.abs().max(b.max.abs()).max_element());
                            todo[k]
                                && b.overlaps(sb)
                                && clip::box_gap(&t_box, b) <= delta.get()[k] + tol
                                && !axes_of(k).misses_box(b, tol)
                        }))
            };
            bvh.for_each_entering(enter, |g| {
                let gf = faces[g as usize];
                if gf.iter().any(|x| f.contains(x)) {
                    return true;
                }
                let tg = gf.map(|i| soup.positions[i as usize]);
                let g_box = Aabb::from_triangle(tg);
                let g_scale = g_box.min.abs().max(g_box.max.abs()).max_element();
                for (k, (d, _, b, scale)) in sides.iter().enumerate() {
                    if !todo[k] || !g_box.overlaps(b) {
                        continue;
                    }
                    // Two shortcuts that skip only triangles whose candidate points could
                    // not lower `delta` (see `clip::PRUNE_TOLERANCE`): every point of `tg` is
                    // farther from `t` than the gap between their boxes, and the prism lies
                    // in the convex hull of its six corners.
                    let tol = clip::PRUNE_TOLERANCE * scale.max(g_scale);
                    let mut dk = delta.get();
                    if clip::box_gap(&t_box, &g_box) > dk[k] + tol || axes_of(k).misses(tg, tol) {
                        continue;
                    }
                    let c = clip::closest_in_prism(v, *d, tg);
                    if c < dk[k] {
                        (dk[k], nearest[k]) = (c, g);
                        delta.set(dk);
                    }
                }
                true
            });
            let delta = delta.get();
            [0, 1].map(|k| (delta[k], nearest[k]))
        })
        .collect();
    let mut found = vec![[(0.0, NONE); 2]; faces.len()];
    for (&fi, &d) in order.iter().zip(&in_order) {
        found[fi as usize] = d;
    }
    let per_face: Vec<[f64; 2]> = found.iter().map(|d| d.map(|(x, _)| x / 2.0)).collect();
    let mut plus = requested.to_vec();
    let mut minus = requested.to_vec();
    for v in 0..soup.num_vertices() {
        for &f in vf.of(v) {
            plus[v] = plus[v].min(per_face[f as usize][0]);
            minus[v] = minus[v].min(per_face[f as usize][1]);
        }
    }
    let memo = keep.then(|| AnalyticalFaces {
        delta: found.iter().map(|d| d.map(|(x, _)| x)).collect(),
        nearest: found.iter().map(|d| d.map(|(_, g)| g)).collect(),
        faces,
        positions: soup.positions.clone(),
        normals: normals.to_vec(),
        targets: requested.to_vec(),
    });
    (plus, minus, memo)
}
