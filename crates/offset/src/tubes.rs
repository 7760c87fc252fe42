//! Border tubes (Cohen et al. 6.2).
//!
//! For every border loop (and open border chain) a tube of `k` vertices per border vertex:
//!
//! * The *normal plane* at border vertex `b_i` has the normal `T_i`, the normalised sum of
//!   the unit directions of the incoming and outgoing border edges (one of them at the ends of
//!   an open chain).
//! * Frames by projection (minimal twist): an arbitrary unit `u_0 ⊥ T_0`; `u_i` is `u_{i-1}`
//!   projected into the normal plane of `b_i` and normalised; `w_i = T_i × u_i`. For a closed
//!   loop the paper averages the last frame with the first; here the whole accumulated twist
//!   `φ` (the angle from `u_{m-1}` transported to `b_0` to `u_0`) is spread evenly, `u_i`
//!   rotated by `φ i / m` about `T_i`, so no single segment carries it. Open chains need no
//!   correction and their tubes are left open at the ends.
//! * Ring `i` is `b_i + r_i (cos θ_j u_i + sin θ_j w_i)`, `θ_j = 2πj/k`; consecutive rings
//!   are joined by two triangles per quad.
//! * Radii start at their target, the requested `eps` of the ring's border vertex; the exact
//!   tube proof keeps there every ring it clears. The rings of a face in a contact start
//!   narrow instead (5 % of the shortest border edge at the vertex, at most a quarter of the
//!   target, halved while they still meet something) and grow with the numerical engine
//!   ([`crate::engine`]), each ring one mover. At small epsilons that is one proof and no
//!   growth; the result is that of starting every ring narrow whenever the growth would have
//!   reached every target anyway.
//!
//! "Until it would intersect the surface": a tube necessarily crosses the surface and the
//! envelopes at its own border, so a tube face between rings `i` and `i+1` is exempt against
//! the input faces incident to `b_i` or `b_{i+1}` and the envelope faces over them; it must
//! miss every other input and envelope face, the other tubes, and its own non-adjacent faces.
//! The paper leaves this rule open; it bounds the radius by roughly the one-ring size.
use envelope_mesh::{FaceId, TriangleSoup, VertexId};
use envelope_predicates::bvh::{Aabb, Bvh};
use envelope_predicates::{PreparedFace, prepared_faces_intersect};
use glam::DVec3;
use rayon::prelude::*;

use crate::engine::{self, Mover, Scene, StepPolicy};
use crate::proof::{Contact, Surface};

/// One border tube.
#[derive(Clone, Debug)]
pub struct Tube {
    /// The border vertices it surrounds, in order.
    pub border: Vec<VertexId>,
    /// A closed loop (else an open chain; the tube is open at both ends).
    pub closed: bool,
    /// The tube surface (`k` vertices per border vertex, ring-major).
    pub mesh: TriangleSoup,
    /// Achieved radius per border vertex.
    pub radius: Vec<f64>,
}

/// Minimal-twist frames `(T, u, w)` along a polyline (see the module docs).
pub(crate) fn frames(pts: &[DVec3], closed: bool) -> Vec<[DVec3; 3]> {
    let m = pts.len();
    let tangent = |i: usize| {
        let prev = (closed || i > 0).then(|| (pts[i] - pts[(i + m - 1) % m]).normalize_or_zero());
        let next = (closed || i + 1 < m).then(|| (pts[(i + 1) % m] - pts[i]).normalize_or_zero());
        let s = prev.unwrap_or(DVec3::ZERO) + next.unwrap_or(DVec3::ZERO);
        s.try_normalize()
            .or_else(|| next.and_then(DVec3::try_normalize))
            .unwrap_or(DVec3::Z)
    };
    let ts: Vec<DVec3> = (0..m).map(tangent).collect();
    let project = |u: DVec3, t: DVec3| {
        (u - t * u.dot(t))
            .try_normalize()
            .unwrap_or_else(|| t.any_orthonormal_vector())
    };
    let mut us = Vec::with_capacity(m);
    us.push(ts[0].any_orthonormal_vector());
    for i in 1..m {
        us.push(project(us[i - 1], ts[i]));
    }
    if closed && m > 1 {
        let end = project(us[m - 1], ts[0]);
        let phi = end.cross(us[0]).dot(ts[0]).atan2(end.dot(us[0]));
        for i in 1..m {
            let q = glam::DQuat::from_axis_angle(ts[i], phi * i as f64 / m as f64);
            us[i] = project(q * us[i], ts[i]);
        }
    }
    (0..m).map(|i| [ts[i], us[i], ts[i].cross(us[i])]).collect()
}

/// Everything the tube stage needs from the envelope stage.
pub(crate) struct TubeInput<'a> {
    pub(crate) soup: &'a TriangleSoup,
    pub(crate) faces: &'a [[u32; 3]],
    pub(crate) outer: &'a [DVec3],
    pub(crate) inner: &'a [DVec3],
    pub(crate) requested: &'a [f64],
    pub(crate) diagonal: f64,
    /// Trees over the boxes of the input, outer and inner faces (face `f` of the three in
    /// that order, at these positions), when the envelope proof left them: part
    /// `(tree, first)` holds face `first + i` as item `i`, the parts in order, each face in
    /// one.
    pub(crate) surfaces: Option<&'a [(&'a Bvh, u32)]>,
}

struct Layout {
    positions: Vec<DVec3>,
    faces: Vec<[u32; 3]>,
    /// Per tube face (index − 3F): its two border vertices and tube number.
    seg: Vec<([u32; 2], u32)>,
    /// Per tube: first global vertex.
    first_vertex: Vec<u32>,
    /// Per tube: first global face.
    first_face: Vec<u32>,
}

fn exempt(input_faces: &[[u32; 3]], nf3: u32, seg: &[([u32; 2], u32)], f: u32, g: u32) -> bool {
    let (t, o) = if f >= nf3 { (f, g) } else { (g, f) };
    if o >= nf3 || t < nf3 {
        return false;
    }
    let [a, b] = seg[(t - nf3) as usize].0;
    let face = input_faces[(o % (nf3 / 3)) as usize];
    face.contains(&a) || face.contains(&b)
}

/// The tree over the input and envelope faces of `layout` (the first `3F`), which the tube
/// stage never moves: built once, queried by every [`tube_contacts`].
fn surface_tree(layout: &Layout, nf3: u32) -> Bvh {
    Bvh::from_triangles(&layout.positions, &layout.faces[..nf3 as usize])
}

/// The pairs `(k, f)` of an item `k` of `tree` and a surface face `f` (global id) whose
/// boxes overlap and that `keep`: one search per part of `surfaces` (see
/// [`TubeInput::surfaces`]), so that no tree over all the surfaces is needed.
fn pairs_with_surfaces(
    tree: &Bvh,
    surfaces: &[(&Bvh, u32)],
    keep: impl Fn(u32, u32) -> bool + Sync,
) -> Vec<(u32, u32)> {
    let mut pairs = Vec::new();
    for &(part, first) in surfaces {
        let found = tree.pairs_with_where(part, |k, f| keep(k, f + first));
        pairs.extend(found.into_iter().map(|(k, f)| (k, f + first)));
    }
    pairs
}

/// Whether faces `i` and `j` (global ids) of `layout` meet and are not exempt (see the
/// module docs): the question every tube proof asks of a candidate pair.
fn meeting(layout: &Layout, input: &TubeInput<'_>, nf3: u32, i: u32, j: u32) -> bool {
    !exempt(input.faces, nf3, &layout.seg, i, j)
        && envelope_predicates::faces_intersect(
            &layout.positions,
            layout.faces[i as usize],
            layout.faces[j as usize],
        )
}

/// The meeting face pairs (global ids, sorted) of [`tube_contacts`].
///
/// Each tube face meets a dozen candidates or more (its neighbours around and along the
/// tube): its plane is computed once ([`PreparedFace`]; the answers of [`meeting`]).
fn tube_pairs(layout: &Layout, input: &TubeInput<'_>, surfaces: &[(&Bvh, u32)]) -> Vec<(u32, u32)> {
    let nf3 = 3 * input.faces.len() as u32;
    let tube_faces = &layout.faces[nf3 as usize..];
    let (tubes, prepared) = rayon::join(
        || Bvh::from_triangles(&layout.positions, tube_faces),
        || {
            tube_faces
                .par_iter()
                .map(|&f| PreparedFace::new(&layout.positions, f))
                .collect::<Vec<_>>()
        },
    );
    // Two tube faces are never exempt.
    let mut pairs: Vec<(u32, u32)> = tubes
        .self_pairs_where(|a, b| {
            prepared_faces_intersect(&prepared[a as usize], &prepared[b as usize])
        })
        .into_iter()
        .map(|(a, b)| (a + nf3, b + nf3))
        .collect();
    pairs.extend(
        pairs_with_surfaces(&tubes, surfaces, |t, f| {
            !exempt(input.faces, nf3, &layout.seg, f, t + nf3)
                && prepared_faces_intersect(
                    &PreparedFace::new(&layout.positions, layout.faces[f as usize]),
                    &prepared[t as usize],
                )
        })
        .into_iter()
        .map(|(t, f)| (f, t + nf3)),
    );
    pairs.sort_unstable();
    pairs
}

/// The meeting pairs (global ids, sorted) with a face of `moved` (tube faces, global ids,
/// sorted) in them: after those faces moved, the pairs of [`tube_pairs`] that can differ
/// from a proof before (a pair of faces that did not move keeps its answer). A small tree
/// over the moved faces against the surfaces' tree and one over every tube face.
fn tube_pairs_moved(
    layout: &Layout,
    input: &TubeInput<'_>,
    surfaces: &[(&Bvh, u32)],
    moved: &[u32],
) -> Vec<(u32, u32)> {
    let nf3 = 3 * input.faces.len() as u32;
    let moved_faces: Vec<[u32; 3]> = moved.iter().map(|&f| layout.faces[f as usize]).collect();
    let small = Bvh::from_triangles(&layout.positions, &moved_faces);
    let tubes = Bvh::from_triangles(&layout.positions, &layout.faces[nf3 as usize..]);
    let meets = |i: u32, j: u32| meeting(layout, input, nf3, i, j);
    let mut pairs: Vec<(u32, u32)> = small
        .pairs_with_where(&tubes, |k, t| {
            let (a, b) = (moved[k as usize], t + nf3);
            a != b && meets(a.min(b), a.max(b))
        })
        .into_iter()
        .map(|(k, t)| {
            let (a, b) = (moved[k as usize], t + nf3);
            (a.min(b), a.max(b))
        })
        .collect();
    pairs.extend(
        pairs_with_surfaces(&small, surfaces, |k, f| meets(f, moved[k as usize]))
            .into_iter()
            .map(|(k, f)| (f, moved[k as usize])),
    );
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

/// Every meeting pair with a tube face in it: tube against tube (a tree over the tube faces)
/// and tube against `surfaces` (the input and envelope faces, [`surface_tree`]). The same
/// pairs as one tree over all faces keeping those with a tube face, without walking the
/// surface-surface pairs that the envelope proof already decided.
fn tube_contacts(layout: &Layout, input: &TubeInput<'_>, surfaces: &[(&Bvh, u32)]) -> Vec<Contact> {
    contacts_of(layout, input, tube_pairs(layout, input, surfaces))
}

/// The meeting pairs of [`tube_pairs`] as contacts.
fn contacts_of(layout: &Layout, input: &TubeInput<'_>, pairs: Vec<(u32, u32)>) -> Vec<Contact> {
    let nf = input.faces.len() as u32;
    let nf3 = 3 * nf;
    let which = |f: u32| {
        if f < nf3 {
            let s = [Surface::Input, Surface::Outer, Surface::Inner][(f / nf) as usize];
            (s, FaceId(f % nf))
        } else {
            let tube = layout.seg[(f - nf3) as usize].1;
            (
                Surface::Tube(tube),
                FaceId(f - layout.first_face[tube as usize]),
            )
        }
    };
    pairs
        .into_iter()
        .map(|(a, b)| Contact {
            a: which(a),
            b: which(b),
        })
        .collect()
}

/// Builds, grows and proves the tubes of `loops` (closed) and `chains` (open).
pub(crate) fn build_tubes(
    input: &TubeInput<'_>,
    loops: &[(Vec<VertexId>, bool)],
    k: u32,
    policy: StepPolicy,
    global_fraction: f64,
) -> (Vec<Tube>, Vec<Contact>) {
    let k = k.max(3) as usize;
    let soup = input.soup;
    let n = soup.num_vertices() as u32;
    let nf3 = 3 * input.faces.len() as u32;
    let mut positions = Vec::with_capacity(3 * n as usize);
    positions.extend_from_slice(&soup.positions);
    positions.extend_from_slice(input.outer);
    positions.extend_from_slice(input.inner);
    let mut faces: Vec<[u32; 3]> = Vec::with_capacity(nf3 as usize);
    for s in 0..3 {
        faces.extend(input.faces.iter().map(|f| f.map(|i| i + s * n)));
    }
    let mut layout = Layout {
        positions,
        faces,
        seg: Vec::new(),
        first_vertex: Vec::new(),
        first_face: Vec::new(),
    };
    let mut movers: Vec<Mover> = Vec::new();
    // Per mover, the narrow start radius; per tube face, its two rings' movers.
    let mut narrow: Vec<f64> = Vec::new();
    let mut face_movers: Vec<[usize; 2]> = Vec::new();
    for (tube, (border, closed)) in loops.iter().enumerate() {
        let m = border.len();
        let pts: Vec<DVec3> = border.iter().map(|&v| soup.position(v)).collect();
        let fr = frames(&pts, *closed);
        let v0 = layout.positions.len() as u32;
        layout.first_vertex.push(v0);
        layout.first_face.push(layout.faces.len() as u32);
        let first_mover = movers.len();
        for i in 0..m {
            let e_prev = (*closed || i > 0).then(|| pts[i].distance(pts[(i + m - 1) % m]));
            let e_next = (*closed || i + 1 < m).then(|| pts[i].distance(pts[(i + 1) % m]));
            let shortest = e_prev
                .unwrap_or(f64::INFINITY)
                .min(e_next.unwrap_or(f64::INFINITY));
            let target = input.requested[border[i].0 as usize];
            let [_, u, w] = fr[i];
            let dirs: Vec<DVec3> = (0..k)
                .map(|j| {
                    let th = std::f64::consts::TAU * j as f64 / k as f64;
                    u * th.cos() + w * th.sin()
                })
                .collect();
            let r0 = (0.05 * shortest).min(target / 4.0);
            narrow.push(r0);
            let verts: Vec<u32> = (0..k as u32).map(|j| v0 + (i * k) as u32 + j).collect();
            for &d in &dirs {
                layout
                    .positions
                    .push(envelope_mesh::flush_tiny(pts[i] + d * target));
            }
            movers.push(Mover {
                verts,
                base: vec![pts[i]; k],
                dirs,
                star: Vec::new(),
                group: 2,
                target,
                t: target,
                step: (0.5 * shortest)
                    .min(global_fraction * input.diagonal)
                    .min(target / policy.k as f64),
                steps: 0,
                halvings: 0,
                done: false,
            });
        }
        let segs = if *closed { m } else { m - 1 };
        for i in 0..segs {
            let i1 = (i + 1) % m;
            for j in 0..k {
                let j1 = (j + 1) % k;
                let (a, b) = (v0 + (i * k + j) as u32, v0 + (i * k + j1) as u32);
                let (c, d) = (v0 + (i1 * k + j1) as u32, v0 + (i1 * k + j) as u32);
                for f in [[a, b, c], [a, c, d]] {
                    let id = layout.faces.len() as u32;
                    layout.faces.push(f);
                    layout.seg.push(([border[i].0, border[i1].0], tube as u32));
                    face_movers.push([first_mover + i, first_mover + i1]);
                    movers[first_mover + i].star.push(id);
                    movers[first_mover + i1].star.push(id);
                }
            }
        }
    }
    // Optimistic start: every ring at its target radius. The exact tube proof keeps there
    // the rings it clears (their movers are done); the rings of every face in a contact go
    // back to the narrow start (5 % of the shortest border edge at the vertex, at most a
    // quarter of the target) and are halved while they still meet something; only those
    // grow (at small epsilons usually none: one proof in all).
    let built;
    let whole;
    let surfaces: &[(&Bvh, u32)] = match input.surfaces {
        Some(parts) => {
            debug_assert!(
                parts
                    .iter()
                    .try_fold(0, |first, &(t, f)| (f == first).then(|| f + t.len() as u32))
                    == Some(nf3)
            );
            debug_assert!(parts.iter().all(|&(tree, first)| {
                (0..tree.len() as u32).all(|i| {
                    let f = first + i;
                    let b = Aabb::from_triangle(
                        layout.faces[f as usize].map(|v| layout.positions[v as usize]),
                    );
                    tree.overlapping(&b).contains(&i)
                })
            }));
            parts
        }
        None => {
            built = surface_tree(&layout, nf3);
            whole = [(&built, 0)];
            &whole
        }
    };
    let mut set_back = vec![false; movers.len()];
    // The tube faces of the given movers' stars (global ids, sorted).
    let stars_of = |movers: &[Mover], which: &dyn Fn(usize) -> bool| -> Vec<u32> {
        let mut f: Vec<u32> = (0..movers.len())
            .filter(|&i| which(i))
            .flat_map(|i| movers[i].star.iter().copied())
            .collect();
        f.sort_unstable();
        f.dedup();
        f
    };
    let mut pairs = tube_pairs(&layout, input, surfaces);
    for _ in 0..13 {
        if pairs.is_empty() {
            break;
        }
        let mut offending = vec![false; movers.len()];
        for &(a, b) in &pairs {
            for f in [a, b].into_iter().filter(|&f| f >= nf3) {
                for i in face_movers[(f - nf3) as usize] {
                    offending[i] = true;
                }
            }
        }
        for (i, m) in movers.iter_mut().enumerate().filter(|(i, _)| offending[*i]) {
            m.t = if set_back[i] { m.t * 0.5 } else { narrow[i] };
            set_back[i] = true;
            for (kk, &v) in m.verts.iter().enumerate() {
                layout.positions[v as usize] =
                    envelope_mesh::flush_tiny(m.base[kk] + m.dirs[kk] * m.t);
            }
        }
        // Every contact had a face of an offending ring: only pairs with a moved face can
        // meet now.
        let moved = stars_of(&movers, &|i| offending[i]);
        pairs = tube_pairs_moved(&layout, input, surfaces, &moved);
    }
    let grown = set_back.iter().any(|&b| b);
    // Grow (only rings set back; none at small epsilons, and then no scene is built).
    if grown {
        let mut sweep: Vec<Aabb> = layout
            .positions
            .iter()
            .map(|&p| Aabb::from_points(&[p]))
            .collect();
        for m in &movers {
            for (kk, &v) in m.verts.iter().enumerate() {
                sweep[v as usize] = engine::sweep_box(m.base[kk], m.dirs[kk], m.target.max(m.t));
            }
        }
        let boxes = engine::swept_face_boxes(&layout.faces, &sweep);
        let ex = |f: u32, g: u32| exempt(input.faces, nf3, &layout.seg, f, g);
        let alias: Vec<u32> = (0..layout.positions.len() as u32).collect();
        // The input and envelope faces do not move here: their swept boxes are their boxes,
        // which `surfaces` was built over.
        debug_assert!((0..nf3 as usize).all(|f| boxes[f]
            == Aabb::from_triangle(layout.faces[f].map(|v| layout.positions[v as usize]))));
        // The scene takes one tree over the surfaces.
        let joined;
        let fixed = match surfaces {
            [(tree, 0)] => *tree,
            [(first, 0), rest @ ..] => {
                joined = rest.iter().fold((*first).clone(), |t, (r, _)| t.joined(r));
                &joined
            }
            _ => unreachable!("the parts start at face 0"),
        };
        let mut scene = Scene::with_fixed(
            layout.positions.clone(),
            alias,
            layout.faces.clone(),
            boxes,
            &ex,
            Some((fixed, nf3)),
        );
        engine::grow(&mut scene, &mut movers, policy, None);
        layout.positions = scene.positions;
    }
    debug_assert!(
        layout.positions[..3 * n as usize]
            .iter()
            .zip(soup.positions.iter().chain(input.outer).chain(input.inner))
            .all(|(a, b)| a == b),
        "the tube stage moved an input or envelope vertex"
    );
    // Nothing moved since the last proof unless some ring grew; then only the grown rings
    // moved, and when the last proof found nothing, only pairs with their faces can meet.
    let contacts = if !grown {
        contacts_of(&layout, input, pairs)
    } else if pairs.is_empty() {
        let moved = stars_of(&movers, &|i| set_back[i]);
        contacts_of(
            &layout,
            input,
            tube_pairs_moved(&layout, input, surfaces, &moved),
        )
    } else {
        tube_contacts(&layout, input, surfaces)
    };
    // Output meshes.
    let mut tubes = Vec::with_capacity(loops.len());
    let mut mover_at = 0;
    for (tube, (border, closed)) in loops.iter().enumerate() {
        let m = border.len();
        let v0 = layout.first_vertex[tube] as usize;
        let f0 = layout.first_face[tube] as usize;
        let f1 = layout
            .first_face
            .get(tube + 1)
            .map_or(layout.faces.len(), |&x| x as usize);
        let positions = layout.positions[v0..v0 + m * k].to_vec();
        let tfaces = layout.faces[f0..f1]
            .iter()
            .map(|f| f.map(|i| VertexId(i - v0 as u32)))
            .collect();
        let radius = movers[mover_at..mover_at + m]
            .iter()
            .map(|mv| mv.t)
            .collect();
        mover_at += m;
        tubes.push(Tube {
            border: border.clone(),
            closed: *closed,
            mesh: TriangleSoup::new(positions, tfaces),
            radius,
        });
    }
    (tubes, contacts)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tube proof against one tree over every face, keeping the pairs with a tube face:
    /// the same contacts, on random tube triangles around a bumpy grid and its envelopes.
    #[test]
    fn tube_contacts_are_those_of_one_tree_over_everything() {
        let mut next = crate::tests::xorshift(0x0DDB_1A5E_5BAD_5EED);
        let mut unit = || (next() >> 11) as f64 / (1u64 << 53) as f64;
        // A 4 x 4 vertex grid, z bumpy; envelopes 0.1 above and below.
        let mut positions = Vec::new();
        for j in 0..4 {
            for i in 0..4 {
                positions.push(DVec3::new(f64::from(i), f64::from(j), 0.2 * unit()));
            }
        }
        let mut faces = Vec::new();
        for j in 0..3u32 {
            for i in 0..3u32 {
                let a = j * 4 + i;
                faces.push([a, a + 1, a + 5]);
                faces.push([a, a + 5, a + 4]);
            }
        }
        let soup = TriangleSoup::new(
            positions.clone(),
            faces.iter().map(|f| f.map(VertexId)).collect(),
        );
        let outer: Vec<DVec3> = positions.iter().map(|p| *p + DVec3::Z * 0.1).collect();
        let inner: Vec<DVec3> = positions.iter().map(|p| *p - DVec3::Z * 0.1).collect();
        let requested = vec![0.1; positions.len()];
        let input = TubeInput {
            soup: &soup,
            faces: &faces,
            outer: &outer,
            inner: &inner,
            requested: &requested,
            diagonal: 5.0,
            surfaces: None,
        };
        let n = positions.len() as u32;
        let nf3 = 3 * faces.len() as u32;
        let (mut found, mut found_moved) = (0, 0);
        for _ in 0..40 {
            let mut all_positions: Vec<DVec3> = positions
                .iter()
                .chain(&outer)
                .chain(&inner)
                .copied()
                .collect();
            let mut all_faces: Vec<[u32; 3]> = (0..3)
                .flat_map(|s| faces.iter().map(move |f| f.map(|i| i + s * n)))
                .collect();
            let mut seg = Vec::new();
            for t in 0..12u32 {
                let c = DVec3::new(3.0 * unit(), 3.0 * unit(), 0.4 * unit() - 0.2);
                let v0 = all_positions.len() as u32;
                for _ in 0..3 {
                    let d = DVec3::new(unit() - 0.5, unit() - 0.5, unit() - 0.5);
                    all_positions.push(c + d * 0.6);
                }
                all_faces.push([v0, v0 + 1, v0 + 2]);
                // Border vertices: some on the grid (exempting the faces around them).
                let b = (unit() * f64::from(n)) as u32 % n;
                seg.push(([b, (b + 1) % n], t % 3));
            }
            let layout = Layout {
                positions: all_positions,
                faces: all_faces,
                seg,
                first_vertex: vec![0; 3],
                first_face: vec![nf3, nf3 + 4, nf3 + 8],
            };
            let fast = tube_pairs(&layout, &input, &[(&surface_tree(&layout, nf3), 0)]);
            // The surfaces in two parts (as the envelope stage hands them over).
            let nf = nf3 / 3;
            let (head, tail) = layout.faces[..nf3 as usize].split_at(nf as usize);
            let parts = (
                Bvh::from_triangles(&layout.positions, head),
                Bvh::from_triangles(&layout.positions, tail),
            );
            let two = [(&parts.0, 0), (&parts.1, nf)];
            assert_eq!(tube_pairs(&layout, &input, &two), fast);
            let everything = Bvh::from_triangles(&layout.positions, &layout.faces);
            let reference: Vec<(u32, u32)> = everything.self_pairs_where(|i, j| {
                (i >= nf3 || j >= nf3)
                    && !exempt(input.faces, nf3, &layout.seg, i, j)
                    && envelope_predicates::faces_intersect(
                        &layout.positions,
                        layout.faces[i as usize],
                        layout.faces[j as usize],
                    )
            });
            assert_eq!(fast, reference);
            found += fast.len();
            // The pairs with a face of a random subset of the tube faces: the reference's.
            let moved: Vec<u32> = (nf3..layout.faces.len() as u32)
                .filter(|_| unit() < 0.4)
                .collect();
            let with_moved: Vec<(u32, u32)> = reference
                .iter()
                .copied()
                .filter(|(i, j)| moved.contains(i) || moved.contains(j))
                .collect();
            let surfaces = surface_tree(&layout, nf3);
            assert_eq!(
                tube_pairs_moved(&layout, &input, &[(&surfaces, 0)], &moved),
                with_moved
            );
            assert_eq!(tube_pairs_moved(&layout, &input, &two, &moved), with_moved);
            found_moved += with_moved.len();
        }
        assert!(
            found > 0 && found_moved > 0,
            "no contact in any trial: the test would prove nothing"
        );
    }

    #[test]
    fn frames_are_orthonormal_and_close_on_a_circle() {
        let pts: Vec<DVec3> = (0..24)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 24.0;
                DVec3::new(a.cos(), a.sin(), 0.1 * (3.0 * a).sin())
            })
            .collect();
        let fr = frames(&pts, true);
        for (i, [t, u, w]) in fr.iter().enumerate() {
            assert!(
                t.dot(*u).abs() < 1e-9
                    && (u.length() - 1.0).abs() < 1e-9
                    && (w.length() - 1.0).abs() < 1e-9
            );
            // Minimal twist: consecutive u nearly parallel.
            let next = fr[(i + 1) % fr.len()][1];
            assert!(u.dot(next) > 0.9, "twist at {i}");
        }
    }
}
