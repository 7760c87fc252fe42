//! The numerical epsilon of section 4.2: the growth of every offset by exact-checked steps
//! (the [`engine`](crate::engine)), on the mesh renumbered in Z-order, or on the part of it a
//! few movers reach ([`Near`]).
use std::sync::atomic::AtomicBool;

use envelope_mesh::{TriangleSoup, VertexFaces, VertexId};
use envelope_predicates::bvh::{Aabb, Bvh};
use glam::DVec3;

use crate::engine::{self, Mover, Scene, StepPolicy};
use crate::morton::morton;
use crate::options::NumericalParams;

/// Proved per-vertex offsets `(plus, minus)` a growth starts from.
pub(crate) type Offsets<'a> = (&'a [f64], &'a [f64]);

/// Per-vertex `(eps_plus, eps_minus)` by the numerical method (section 4.2).
///
/// The mesh is first renumbered in Z-order (vertices by position, faces by centroid) so that
/// the movers of one batch and the faces each check touches are close in memory; a scanned
/// mesh's own order makes every check a string of cache misses. The renumbering changes
/// only the order of moves (the result depends on it, as the paper's sequential order
/// does), not what is checked.
///
/// With `start`, the growth begins at those proved offsets (`(plus, minus)`, an envelope
/// pair whose proof holds): only the vertices short of `requested` move, the others stay
/// where they are as part of the scene. Every offset ends at least at its start. Once
/// `stop` is set the growth ends at its next pass, short (see [`engine::grow`]).
pub(crate) fn numerical_eps(
    soup: &TriangleSoup,
    vf: &VertexFaces,
    normals: &[DVec3],
    requested: &[f64],
    params: &NumericalParams,
    diagonal: f64,
    (start, stop): (Option<Offsets<'_>>, Option<&AtomicBool>),
) -> (Vec<f64>, Vec<f64>) {
    let bounds = Aabb::from_points(&soup.positions);
    if let Some(start) = start {
        let near = Near {
            soup,
            vf,
            normals,
            requested,
            start,
            bounds: &bounds,
            stop,
        };
        if let Some(grown) = near.grow(params, diagonal) {
            return grown;
        }
    }
    numerical_eps_sorted(
        soup,
        normals,
        requested,
        params,
        diagonal,
        (start, stop),
        &bounds,
    )
}

/// [`numerical_eps`] on the whole mesh, renumbered in Z-order in `bounds` (the box of its
/// vertices).
pub(crate) fn numerical_eps_sorted(
    soup: &TriangleSoup,
    normals: &[DVec3],
    requested: &[f64],
    params: &NumericalParams,
    diagonal: f64,
    (start, stop): (Option<Offsets<'_>>, Option<&AtomicBool>),
    bounds: &Aabb,
) -> (Vec<f64>, Vec<f64>) {
    use rayon::slice::ParallelSliceMut;
    let bounds = *bounds;
    let n = soup.num_vertices();
    let mut order: Vec<u32> = (0..n as u32).collect();
    // Keys are distinct (the ids break ties): the parallel sorts give the one order.
    order.par_sort_by_cached_key(|&v| (morton(soup.positions[v as usize], &bounds), v));
    let mut rank = vec![0u32; n];
    for (new, &old) in order.iter().enumerate() {
        rank[old as usize] = new as u32;
    }
    let mut faces: Vec<[VertexId; 3]> = soup
        .faces
        .iter()
        .map(|f| f.map(|v| VertexId(rank[v.0 as usize])))
        .collect();
    let key = |f: &[VertexId; 3]| {
        let c = order_pos(soup, &order, f[0]) + order_pos(soup, &order, f[1]);
        morton((c + order_pos(soup, &order, f[2])) / 3.0, &bounds)
    };
    faces.par_sort_by_cached_key(|f| (key(f), f.map(|v| v.0)));
    let sorted = TriangleSoup::new(
        order.iter().map(|&v| soup.positions[v as usize]).collect(),
        faces,
    );
    let pick = |a: &[f64]| -> Vec<f64> { order.iter().map(|&v| a[v as usize]).collect() };
    let sorted_normals: Vec<DVec3> = order.iter().map(|&v| normals[v as usize]).collect();
    let vf = VertexFaces::new(n, &sorted.faces);
    let zeros = vec![0.0; n];
    let (start_plus, start_minus) =
        start.map_or((pick(&zeros), pick(&zeros)), |(p, m)| (pick(p), pick(m)));
    let (p, m) = numerical_eps_ordered(
        &sorted,
        &vf,
        &sorted_normals,
        &pick(requested),
        params,
        diagonal,
        [&start_plus, &start_minus],
        (FEW_MOVERS, stop),
    );
    let back = |a: &[f64]| -> Vec<f64> { rank.iter().map(|&r| a[r as usize]).collect() };
    (back(&p), back(&m))
}

/// The growth from proved offsets where a few vertices fell short (the automatic method
/// after the analytical one), on the part of the mesh they can reach: the faces around
/// every mover and every face with a copy (input, outer or inner, at the start) whose box
/// overlaps a mover's reach, renumbered in the whole mesh's Z-order. The same growth as on
/// the whole mesh:
///
/// - the movers are the same, in the same order (Z-order in the whole mesh's box, ties by
///   vertex id), with the same stars (a mover's fan is all there) and the same steps (from
///   its fan's edges);
/// - every face a mover's check can meet has a swept box overlapping its reach: a face
///   around a mover, or one that never moves (its swept box is its box at the start);
///   both are there, so every check tests the same pairs, exactly, and the colouring sees
///   the same movers sharing the same vertices;
/// - what is left out never moves and meets no reach. More faces than needed change only
///   the work (every face of an input face's three copies is taken).
///
/// Why: for a few movers, renumbering the whole mesh and building its scene's arrays would
/// be nearly all of the work.
pub(crate) struct Near<'a> {
    pub(crate) soup: &'a TriangleSoup,
    pub(crate) vf: &'a VertexFaces,
    pub(crate) normals: &'a [DVec3],
    pub(crate) requested: &'a [f64],
    pub(crate) start: Offsets<'a>,
    /// The box of the whole mesh's vertices (the Z-order's).
    pub(crate) bounds: &'a Aabb,
    /// See [`numerical_eps`].
    pub(crate) stop: Option<&'a AtomicBool>,
}

impl Near<'_> {
    /// Offsets grown on the part of the mesh the movers reach, or `None` when the movers
    /// are not few (one per [`FEW_MOVERS`] scene faces or more).
    pub(crate) fn grow(
        &self,
        params: &NumericalParams,
        diagonal: f64,
    ) -> Option<(Vec<f64>, Vec<f64>)> {
        use rayon::prelude::*;
        let (soup, (plus, minus)) = (self.soup, self.start);
        let n = soup.num_vertices();
        // Side 1 (outer) and 2 (inner) of vertex `v` moves: its start falls short.
        let moves = |v: usize, side: u32| {
            let s0 = if side == 1 { plus[v] } else { minus[v] };
            // As `numerical_eps_ordered` skips a side: unless `s0 >= target`.
            let reached = matches!(
                s0.partial_cmp(&self.requested[v]),
                Some(std::cmp::Ordering::Greater | std::cmp::Ordering::Equal)
            );
            !self.vf.of(v).is_empty() && !reached
        };
        let movers: Vec<(usize, u32)> = (0..n)
            .flat_map(|v| [(v, 1), (v, 2)])
            .filter(|&(v, side)| moves(v, side))
            .collect();
        if movers.len().saturating_mul(FEW_MOVERS) >= 3 * soup.num_faces() {
            return None;
        }
        // Where copy `side` of vertex `v` can be: its start position, or for a mover the
        // sweep to its target (as `numerical_eps_ordered` places and sweeps them).
        let reach_of = |v: usize, side: u32| {
            let p = soup.positions[v];
            if side == 0 {
                return Aabb::from_points(&[p]);
            }
            let dir = self.normals[v] * if side == 1 { 1.0 } else { -1.0 };
            let s0 = if side == 1 { plus[v] } else { minus[v] };
            if moves(v, side) {
                engine::sweep_box_from(p, dir, s0.max(0.0), self.requested[v])
            } else if s0 > 0.0 {
                Aabb::from_points(&[p + dir * s0])
            } else {
                Aabb::from_points(&[p])
            }
        };
        let reaches: Vec<Aabb> = movers
            .iter()
            .map(|&(v, side)| {
                self.vf.of(v).iter().fold(Aabb::EMPTY, |b, &f| {
                    soup.faces[f as usize]
                        .iter()
                        .fold(b, |b, u| b.union(&reach_of(u.index(), side)))
                })
            })
            .collect();
        let mut kept = vec![false; soup.num_faces()];
        for &(v, _) in &movers {
            for &f in self.vf.of(v) {
                kept[f as usize] = true;
            }
        }
        let prism = |f: usize| {
            soup.faces[f].iter().fold(Aabb::EMPTY, |b, u| {
                let v = u.index();
                b.union(&reach_of(v, 0))
                    .union(&reach_of(v, 1))
                    .union(&reach_of(v, 2))
            })
        };
        // A tree over the reaches: a scan of all of them per face is quadratic when the
        // movers are a few percent of a large mesh.
        let near = Bvh::new(&reaches);
        let faces: Vec<usize> = (0..soup.num_faces())
            .into_par_iter()
            .filter(|&f| kept[f] || near.any_overlapping(&prism(f)))
            .collect();
        // The part's vertices in the whole mesh's Z-order (ties by id).
        let mut verts: Vec<u32> = faces
            .iter()
            .flat_map(|&f| soup.faces[f].map(|u| u.0))
            .collect();
        verts.sort_unstable();
        verts.dedup();
        verts.sort_by_cached_key(|&v| (morton(soup.positions[v as usize], self.bounds), v));
        let mut local = vec![u32::MAX; n];
        for (l, &v) in (0u32..).zip(&verts) {
            local[v as usize] = l;
        }
        let part = TriangleSoup::new(
            verts.iter().map(|&v| soup.positions[v as usize]).collect(),
            faces
                .iter()
                .map(|&f| soup.faces[f].map(|u| VertexId(local[u.index()])))
                .collect(),
        );
        let pick = |a: &[f64]| -> Vec<f64> { verts.iter().map(|&v| a[v as usize]).collect() };
        let part_normals: Vec<DVec3> = verts.iter().map(|&v| self.normals[v as usize]).collect();
        let part_vf = VertexFaces::new(part.num_vertices(), &part.faces);
        let (p, m) = numerical_eps_ordered(
            &part,
            &part_vf,
            &part_normals,
            &pick(self.requested),
            params,
            diagonal,
            [&pick(plus), &pick(minus)],
            (FEW_MOVERS, self.stop),
        );
        let (mut out_plus, mut out_minus) = (plus.to_vec(), minus.to_vec());
        for (l, &v) in verts.iter().enumerate() {
            out_plus[v as usize] = p[l];
            out_minus[v as usize] = m[l];
        }
        Some((out_plus, out_minus))
    }
}

/// [`numerical_eps_ordered`] builds its tree over the faces its movers can reach only when
/// there are fewer movers than one per this many scene faces (the growth from proved
/// offsets where a few fell short: then a tree over the few faces they can reach is cheaper
/// to build than one over the whole scene).
const FEW_MOVERS: usize = 64;

fn order_pos(soup: &TriangleSoup, order: &[u32], v: VertexId) -> DVec3 {
    soup.positions[order[v.0 as usize] as usize]
}

/// [`numerical_eps`] on a renumbered mesh: outer and inner vertices are movers of one scene
/// (input + outer + inner, interleaved: copy `s` of vertex `v` is `3 v + s`, of face `f` is
/// `3 f + s`, with `s` 0 input, 1 outer, 2 inner), see [`engine`].
pub(crate) fn numerical_eps_ordered(
    soup: &TriangleSoup,
    vf: &VertexFaces,
    normals: &[DVec3],
    requested: &[f64],
    params: &NumericalParams,
    diagonal: f64,
    start: [&[f64]; 2],
    (few_movers, stop): (usize, Option<&AtomicBool>),
) -> (Vec<f64>, Vec<f64>) {
    let n = soup.num_vertices();
    let mut positions = Vec::with_capacity(3 * n);
    for &p in &soup.positions {
        positions.extend_from_slice(&[p, p, p]);
    }
    let mut alias: Vec<u32> = (0..3 * n as u32).map(|i| i - i % 3).collect();
    let mut plus = start[0].to_vec();
    let mut minus = start[1].to_vec();
    let mut faces: Vec<[u32; 3]> = Vec::with_capacity(3 * soup.num_faces());
    for f in &soup.faces {
        for s in 0..3 {
            faces.push(f.map(|v| 3 * v.0 + s));
        }
    }
    let mut sweep: Vec<Aabb> = positions.iter().map(|&p| Aabb::from_points(&[p])).collect();
    let mut movers = Vec::with_capacity(2 * n);
    for v in 0..n {
        let fan = vf.of(v);
        if fan.is_empty() {
            continue;
        }
        let p = soup.positions[v];
        for (side, sign) in [(1u32, 1.0), (2u32, -1.0)] {
            let dir = normals[v] * sign;
            let target = requested[v];
            let gv = 3 * v as u32 + side;
            let s0 = start[side as usize - 1][v];
            if s0 > 0.0 {
                // Proved start offset: the vertex sits there (its own index, not the input's).
                positions[gv as usize] = p + dir * s0;
                alias[gv as usize] = gv;
                sweep[gv as usize] = Aabb::from_points(&[positions[gv as usize]]);
            }
            if s0 >= target {
                continue;
            }
            // Local step: shortest incident edge within 90 degrees of the offset direction.
            let mut shortest = f64::INFINITY;
            let mut shortest_any = f64::INFINITY;
            for &f in fan {
                for u in soup.faces[f as usize] {
                    let e = soup.positions[u.0 as usize] - p;
                    let len = e.length();
                    if len > 0.0 {
                        shortest_any = shortest_any.min(len);
                        if e.dot(dir) > 0.0 {
                            shortest = shortest.min(len);
                        }
                    }
                }
            }
            if !shortest.is_finite() {
                shortest = shortest_any;
            }
            let step = (params.global_fraction * diagonal)
                .min(target / params.k as f64)
                .min(params.local_fraction * shortest);
            sweep[gv as usize] = engine::sweep_box_from(p, dir, s0.max(0.0), target);
            movers.push(Mover {
                verts: vec![gv],
                base: vec![p],
                dirs: vec![dir],
                star: fan.iter().map(|&f| 3 * f + side).collect(),
                group: side,
                target,
                t: s0,
                step,
                steps: 0,
                halvings: 0,
                done: false,
            });
        }
    }
    let boxes = engine::swept_face_boxes(&faces, &sweep);
    drop(sweep);
    let never = |_: u32, _: u32| false;
    // A few movers (the growth from proved offsets where a few fell short): a tree over
    // the faces they can reach only.
    let mut scene = if movers.len().saturating_mul(few_movers) < faces.len() {
        let reaches: Vec<Aabb> = movers.iter().map(|m| engine::reach(&boxes, m)).collect();
        Scene::around(positions, alias, faces, boxes, &never, &reaches)
    } else {
        Scene::new(positions, alias, faces, boxes, &never)
    };
    let policy = StepPolicy {
        k: params.k,
        max_halvings: params.max_halvings,
        growth: params.step_growth,
    };
    engine::grow(&mut scene, &mut movers, policy, stop);
    for m in &movers {
        let v = (m.verts[0] / 3) as usize;
        if m.group == 1 {
            plus[v] = m.t;
        } else {
            minus[v] = m.t;
        }
    }
    (plus, minus)
}
