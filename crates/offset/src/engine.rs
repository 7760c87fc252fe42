//! The iterative growth engine of the numerical method (Cohen et al. 4.2), shared by the
//! envelopes and the border tubes (6.2: "we then expand these narrow tubes using the same
//! technique").
//!
//! A *mover* owns a few scene vertices that all move with one parameter `t` (the offset of
//! an envelope vertex along its normal; the radius of a tube ring): `p_k(t) = base_k + t dir_k`
//! (an f64 construction). Each attempted step is checked **exactly**: every face of the
//! mover's star, at the proposed positions, against every scene face whose *swept* box (the
//! box of all positions the face can ever take, rounded outward) overlaps it, with the
//! adjacency-aware exact triangle test. Vertices that still coincide with the input vertex
//! they started from carry that vertex's index (`alias`) so that the untouched envelope is
//! "adjacent", not "intersecting", to the input.
//!
//! Step control is the paper's: proposed `t' = min(t + step, target)`; on rejection, while
//! fewer than `K` steps were taken and fewer than `max_halvings` halvings happened since the
//! last accepted step, the step is halved and retried; otherwise the mover stops.
//!
//! Parallelism with a deterministic result: the paper moves vertices "sequentially". Here the
//! movers are greedily coloured so that no two movers of one colour share a star face, and
//! one colour of one group (outer, inner, tubes) is attempted at a time, in parallel, against
//! the frozen scene. Accepted moves whose new star boxes overlap another accepted move's are
//! re-checked one by one in mover order after the others are committed. The outcome depends
//! only on the mover order, not on thread timing.
use envelope_predicates::bvh::{Aabb, Bvh};
use envelope_predicates::{Shared, adjacent_triangles_intersect, triangles_intersect};
use glam::DVec3;
use rayon::prelude::*;

/// A scene: every face that matters, with its current positions.
pub(crate) struct Scene<'a> {
    pub positions: Vec<DVec3>,
    /// Index used for adjacency (an unmoved vertex aliases the input vertex it sits on).
    pub alias: Vec<u32>,
    pub faces: Vec<[u32; 3]>,
    /// Over the swept boxes of `faces`.
    pub bvh: Bvh,
    /// Pairs `(star face, other face)` never tested.
    pub exempt: &'a (dyn Fn(u32, u32) -> bool + Sync),
}

/// Step-size policy.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepPolicy {
    pub k: u32,
    pub max_halvings: u32,
}

/// Vertices moving together with one parameter.
#[derive(Clone, Debug)]
pub(crate) struct Mover {
    pub verts: Vec<u32>,
    pub base: Vec<DVec3>,
    pub dirs: Vec<DVec3>,
    pub star: Vec<u32>,
    pub group: u32,
    pub target: f64,
    pub t: f64,
    pub step: f64,
    pub steps: u32,
    pub halvings: u32,
    pub done: bool,
}

impl Mover {
    fn positions_at(&self, t: f64) -> Vec<DVec3> {
        self.base
            .iter()
            .zip(&self.dirs)
            .map(|(&b, &d)| b + d * t)
            .collect()
    }
}

/// The vertex indices two faces share (by alias), `Err(())` when all three.
fn shared(f: [u32; 3], g: [u32; 3]) -> Result<Option<Shared>, ()> {
    let mut pairs = [(0usize, 0usize); 3];
    let mut n = 0;
    for i in 0..3 {
        if f[..i].contains(&f[i]) {
            continue;
        }
        if let Some(j) = g.iter().position(|&x| x == f[i]) {
            pairs[n] = (i, j);
            n += 1;
        }
    }
    match n {
        0 => Ok(None),
        1 => Ok(Some(Shared::Vertex(pairs[0].0, pairs[0].1))),
        2 => Ok(Some(Shared::Edge(
            [pairs[0].0, pairs[1].0],
            [pairs[0].1, pairs[1].1],
        ))),
        _ => Err(()),
    }
}

/// Exact, adjacency-aware: closed triangles `t1`, `t2` with (aliased) indices `f`, `g` meet
/// away from what they share.
pub(crate) fn tris_intersect(t1: [DVec3; 3], f: [u32; 3], t2: [DVec3; 3], g: [u32; 3]) -> bool {
    match shared(f, g) {
        Ok(None) => triangles_intersect(t1, t2),
        Ok(Some(s)) => adjacent_triangles_intersect(t1, t2, s),
        Err(()) => true,
    }
}

/// Exact check of mover `m` at parameter `t` against the scene.
fn check(scene: &Scene<'_>, m: &Mover, t: f64) -> bool {
    let new = m.positions_at(t);
    let pos = |i: u32| match m.verts.iter().position(|&x| x == i) {
        Some(k) => new[k],
        None => scene.positions[i as usize],
    };
    let alias = |i: u32| {
        if m.verts.contains(&i) {
            i
        } else {
            scene.alias[i as usize]
        }
    };
    for &f in &m.star {
        let fv = scene.faces[f as usize];
        let tf = fv.map(pos);
        let af = fv.map(alias);
        let bf = Aabb::from_triangle(tf);
        let mut hit = false;
        scene.bvh.for_each_overlapping(&bf, |g| {
            if hit || g == f {
                return;
            }
            if g < f && m.star.contains(&g) {
                return; // tested from g's side
            }
            if (scene.exempt)(f, g) {
                return;
            }
            let gv = scene.faces[g as usize];
            let tg = gv.map(pos);
            if !bf.overlaps(&Aabb::from_triangle(tg)) {
                return;
            }
            if tris_intersect(tf, af, tg, gv.map(alias)) {
                hit = true;
            }
        });
        if hit {
            return false;
        }
    }
    true
}

fn commit(scene: &mut Scene<'_>, m: &mut Mover, t: f64) {
    for (k, p) in m.positions_at(t).into_iter().enumerate() {
        let v = m.verts[k] as usize;
        scene.positions[v] = p;
        scene.alias[v] = v as u32;
    }
    m.t = t;
    m.steps += 1;
    m.halvings = 0;
    if m.t >= m.target {
        m.done = true;
    }
}

fn reject(m: &mut Mover, policy: StepPolicy) {
    if m.steps < policy.k && m.halvings < policy.max_halvings {
        m.step *= 0.5;
        m.halvings += 1;
    } else {
        m.done = true;
    }
}

/// Batches of movers: by group, then greedy colour (no two movers of a batch share a face).
fn batches(movers: &[Mover], num_faces: usize) -> Vec<Vec<u32>> {
    let mut face_movers: Vec<Vec<u32>> = vec![Vec::new(); num_faces];
    for (i, m) in movers.iter().enumerate() {
        for &f in &m.star {
            face_movers[f as usize].push(i as u32);
        }
    }
    let mut color = vec![u32::MAX; movers.len()];
    let mut used: Vec<bool> = Vec::new();
    for i in 0..movers.len() {
        used.clear();
        for &f in &movers[i].star {
            for &o in &face_movers[f as usize] {
                let c = color[o as usize];
                if c != u32::MAX {
                    if used.len() <= c as usize {
                        used.resize(c as usize + 1, false);
                    }
                    used[c as usize] = true;
                }
            }
        }
        color[i] = used.iter().position(|&u| !u).unwrap_or(used.len()) as u32;
    }
    let mut keys: Vec<(u32, u32, u32)> = movers
        .iter()
        .enumerate()
        .map(|(i, m)| (m.group, color[i], i as u32))
        .collect();
    keys.sort_unstable();
    let mut out: Vec<Vec<u32>> = Vec::new();
    let mut last = None;
    for (g, c, i) in keys {
        if last != Some((g, c)) {
            out.push(Vec::new());
            last = Some((g, c));
        }
        out.last_mut().expect("pushed").push(i);
    }
    out
}

fn star_box(scene: &Scene<'_>, m: &Mover, t: f64) -> Aabb {
    let new = m.positions_at(t);
    let mut b = Aabb::EMPTY;
    for &f in &m.star {
        for i in scene.faces[f as usize] {
            let p = match m.verts.iter().position(|&x| x == i) {
                Some(k) => new[k],
                None => scene.positions[i as usize],
            };
            b = b.union(&Aabb::from_points(&[p]));
        }
    }
    b
}

/// Grows every mover as far as the exact checks allow (see the module docs).
pub(crate) fn grow(scene: &mut Scene<'_>, movers: &mut [Mover], policy: StepPolicy) {
    for m in movers.iter_mut() {
        if !(m.target > m.t) || !(m.step > 0.0) {
            m.done = true;
        }
    }
    let batches = batches(movers, scene.faces.len());
    loop {
        let mut any = false;
        for batch in &batches {
            let active: Vec<u32> = batch
                .iter()
                .copied()
                .filter(|&i| !movers[i as usize].done)
                .collect();
            if active.is_empty() {
                continue;
            }
            any = true;
            let frozen: &Scene<'_> = scene;
            let ms: &[Mover] = movers;
            let results: Vec<(u32, f64, bool)> = active
                .par_iter()
                .map(|&i| {
                    let m = &ms[i as usize];
                    let t = (m.t + m.step).min(m.target);
                    (i, t, check(frozen, m, t))
                })
                .collect();
            let accepted: Vec<(u32, f64)> =
                results.iter().filter(|r| r.2).map(|r| (r.0, r.1)).collect();
            let mut conflicted = vec![false; accepted.len()];
            if accepted.len() > 1 {
                let boxes: Vec<Aabb> = accepted
                    .par_iter()
                    .map(|&(i, t)| star_box(frozen, &ms[i as usize], t))
                    .collect();
                for (a, b) in Bvh::new(&boxes).self_pairs() {
                    conflicted[a as usize] = true;
                    conflicted[b as usize] = true;
                }
            }
            for (k, &(i, t)) in accepted.iter().enumerate() {
                if !conflicted[k] {
                    commit(scene, &mut movers[i as usize], t);
                }
            }
            for (k, &(i, t)) in accepted.iter().enumerate() {
                if conflicted[k] {
                    if check(scene, &movers[i as usize], t) {
                        commit(scene, &mut movers[i as usize], t);
                    } else {
                        reject(&mut movers[i as usize], policy);
                    }
                }
            }
            for r in results.iter().filter(|r| !r.2) {
                reject(&mut movers[r.0 as usize], policy);
            }
        }
        if !any {
            break;
        }
    }
}

/// The swept box of every face: the union of its vertices' sweep boxes.
pub(crate) fn swept_face_boxes(faces: &[[u32; 3]], sweep: &[Aabb]) -> Vec<Aabb> {
    faces
        .par_iter()
        .map(|f| {
            sweep[f[0] as usize]
                .union(&sweep[f[1] as usize])
                .union(&sweep[f[2] as usize])
        })
        .collect()
}

/// The box of every position `base + t dir`, `t` in `[0, target]` as f64 constructions:
/// the exact segment box inflated by a bound on the construction's rounding.
pub(crate) fn sweep_box(base: DVec3, dir: DVec3, target: f64) -> Aabb {
    let end = base + dir * target;
    let scale = base.abs().max(end.abs()).max_element();
    Aabb::from_points(&[base, end]).inflated(scale * 8.0 * f64::EPSILON)
}
