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
//! [`clip::PRUNE_TOLERANCE`]; the offsets are the same either way).
use envelope_mesh::{TriangleSoup, VertexFaces};
use envelope_predicates::bvh::{Aabb, Bvh};
use envelope_prism::clip;
use glam::DVec3;
use rayon::prelude::*;

/// Per-vertex `(eps_plus, eps_minus)` by the analytical method; `bvh` is a tree over the
/// boxes of the input faces (item = face).
pub(crate) fn analytical_eps(
    soup: &TriangleSoup,
    vf: &VertexFaces,
    normals: &[DVec3],
    requested: &[f64],
    bvh: &Bvh,
) -> (Vec<f64>, Vec<f64>) {
    let faces: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
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
    let in_order: Vec<[f64; 2]> = order
        .par_iter()
        .map(|&fi| {
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
            let mut delta = [f64::INFINITY; 2];
            bvh.for_each_overlapping(&sides[0].2.union(&sides[1].2), |g| {
                let gf = faces[g as usize];
                if gf.iter().any(|x| f.contains(x)) {
                    return;
                }
                let tg = gf.map(|i| soup.positions[i as usize]);
                let g_box = Aabb::from_triangle(tg);
                let g_scale = g_box.min.abs().max(g_box.max.abs()).max_element();
                for (k, (d, top, b, scale)) in sides.iter().enumerate() {
                    if !g_box.overlaps(b) {
                        continue;
                    }
                    // Two shortcuts that skip only triangles whose candidate points could
                    // not lower `delta` (see `clip::PRUNE_TOLERANCE`): every point of `tg` is
                    // farther from `t` than the gap between their boxes, and the prism lies
                    // in the convex hull of its six corners.
                    let tol = clip::PRUNE_TOLERANCE * scale.max(g_scale);
                    if clip::box_gap(&t_box, &g_box) > delta[k] + tol
                        || clip::hull_misses(v, *top, tg, tol)
                    {
                        continue;
                    }
                    delta[k] = delta[k].min(clip::closest_in_prism(v, *d, tg));
                }
            });
            delta.map(|x| x / 2.0)
        })
        .collect();
    let mut per_face = vec![[0.0; 2]; faces.len()];
    for (&fi, &d) in order.iter().zip(&in_order) {
        per_face[fi as usize] = d;
    }
    let mut plus = requested.to_vec();
    let mut minus = requested.to_vec();
    for v in 0..soup.num_vertices() {
        for &f in vf.of(v) {
            plus[v] = plus[v].min(per_face[f as usize][0]);
            minus[v] = minus[v].min(per_face[f as usize][1]);
        }
    }
    (plus, minus)
}
