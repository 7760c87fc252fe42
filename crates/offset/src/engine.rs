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
//! Candidates: every position a scene face can take lies in its swept box, so each check
//! queries the tree of swept boxes with the box of the star at the proposed positions and
//! filters what it finds by the current boxes, computed from the positions when asked
//! (kept per face, they were another array of boxes as large as the tree's). (A list per
//! mover of every face its star could ever reach grows with (epsilon / edge length)^2 and
//! made the growth quadratic on fine meshes at large epsilon.) A mover's sweep starts
//! where the mover starts (its proved start offset), since it never moves back. A check
//! first tries the face that refused the mover's last step. Before an exact test, a pair is
//! skipped only when f64 arithmetic with a rigorous error bound proves it apart: the
//! unshared vertices of one triangle strictly on one side of the other's plane, or the
//! separating-axis test on the nine edge-cross-edge directions (strictly disjoint
//! projection intervals; with one shared vertex, the two triangles strictly on the two
//! sides of a plane through it). Anything else goes to the exact adjacency-aware test.
//!
//! Step control is the paper's, plus growth: proposed `t' = min(t + step, target)`; after an
//! accepted step the step is multiplied by `growth` (1 = the paper); on rejection, while
//! fewer than `K` steps were taken and fewer than `max_halvings` halvings happened since the
//! last accepted step, the step is halved and retried; otherwise the mover stops.
//!
//! Parallelism with a deterministic result: the paper moves vertices "sequentially". Here the
//! movers are greedily coloured so that no two movers of one colour share a star vertex, and
//! one colour of one group (outer, inner, tubes) is attempted at a time, in parallel, against
//! the frozen scene. Accepted moves whose new star boxes overlap another accepted move's are
//! re-checked one by one in mover order after the others are committed, each against the
//! stars of the earlier ones it conflicts with (see `recheck_in_order`). The outcome depends
//! only on the mover order, not on thread timing.
use std::sync::atomic::AtomicBool;

use envelope_predicates::apart::{Planar, surely_apart};
use envelope_predicates::bvh::{Aabb, Bvh};
use glam::DVec3;
use rayon::prelude::*;

/// A scene: every face that matters, with its current positions.
pub(crate) struct Scene<'a> {
    pub(crate) positions: Vec<DVec3>,
    /// Index used for adjacency (an unmoved vertex aliases the input vertex it sits on).
    pub(crate) alias: Vec<u32>,
    pub(crate) faces: Vec<[u32; 3]>,
    /// Over the swept boxes (every position a face can take while the movers move) of the
    /// faces `fixed.1..` (item `i` is face `fixed.1 + i`), or over the faces
    /// `only` names (item `i` is face `only[i]`).
    pub(crate) bvh: Bvh,
    /// The faces in `bvh` when not all of them ([`Scene::around`]), increasing.
    pub(crate) only: Option<Vec<u32>>,
    /// A tree over the first `fixed.1` faces, which never move, built by the caller with
    /// their boxes (their swept boxes: see [`Scene::with_fixed`]).
    pub(crate) fixed: Option<(&'a Bvh, u32)>,
    /// Pairs `(star face, other face)` never tested.
    pub(crate) exempt: &'a (dyn Fn(u32, u32) -> bool + Sync),
}

impl<'a> Scene<'a> {
    /// A scene over `faces` at `positions`, with the swept box of every face.
    pub(crate) fn new(
        positions: Vec<DVec3>,
        alias: Vec<u32>,
        faces: Vec<[u32; 3]>,
        swept: Vec<Aabb>,
        exempt: &'a (dyn Fn(u32, u32) -> bool + Sync),
    ) -> Self {
        Self::with_fixed(positions, alias, faces, swept, exempt, None)
    }

    /// [`Scene::new`] with a tree the caller already has over the first `n` faces (`fixed =
    /// Some((tree, n))`, item `i` of `tree` face `i`): faces that no mover touches, whose
    /// swept boxes are their boxes, each inside the tree's box of it. Only the other faces
    /// get a tree of their own; the candidates are the same.
    pub(crate) fn with_fixed(
        positions: Vec<DVec3>,
        alias: Vec<u32>,
        faces: Vec<[u32; 3]>,
        mut swept: Vec<Aabb>,
        exempt: &'a (dyn Fn(u32, u32) -> bool + Sync),
        fixed: Option<(&'a Bvh, u32)>,
    ) -> Self {
        let n = fixed.map_or(0, |f| f.1 as usize);
        swept.drain(..n);
        Scene {
            bvh: Bvh::from_boxes(swept),
            only: None,
            fixed,
            positions,
            alias,
            faces,
            exempt,
        }
    }

    /// [`Scene::new`] whose tree holds only the faces whose swept box overlaps one of
    /// `reaches` (each mover's, see [`reach`]): the candidates of those movers are the same,
    /// and a tree over a few faces is built for a few movers instead of one over all.
    pub(crate) fn around(
        positions: Vec<DVec3>,
        alias: Vec<u32>,
        faces: Vec<[u32; 3]>,
        swept: Vec<Aabb>,
        exempt: &'a (dyn Fn(u32, u32) -> bool + Sync),
        reaches: &[Aabb],
    ) -> Self {
        let near = Bvh::new(reaches);
        let only: Vec<u32> = (0..faces.len() as u32)
            .into_par_iter()
            .filter(|&f| near.any_overlapping(&swept[f as usize]))
            .collect();
        let kept: Vec<Aabb> = only.iter().map(|&f| swept[f as usize]).collect();
        // Millions of faces at large offsets: one array of boxes at a time.
        drop(swept);
        Scene {
            bvh: Bvh::from_boxes(kept),
            only: Some(only),
            fixed: None,
            positions,
            alias,
            faces,
            exempt,
        }
    }
}

/// Step-size policy.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepPolicy {
    pub(crate) k: u32,
    pub(crate) max_halvings: u32,
    /// Factor applied to the step after every accepted step (1 = the paper's fixed step).
    pub(crate) growth: f64,
}

/// Vertices moving together with one parameter.
#[derive(Clone, Debug)]
pub(crate) struct Mover {
    pub(crate) verts: Vec<u32>,
    pub(crate) base: Vec<DVec3>,
    pub(crate) dirs: Vec<DVec3>,
    pub(crate) star: Vec<u32>,
    pub(crate) group: u32,
    pub(crate) target: f64,
    pub(crate) t: f64,
    pub(crate) step: f64,
    pub(crate) steps: u32,
    pub(crate) halvings: u32,
    pub(crate) done: bool,
}

impl Mover {
    fn positions_at(&self, t: f64) -> Vec<DVec3> {
        self.base
            .iter()
            .zip(&self.dirs)
            .map(|(&b, &d)| envelope_mesh::flush_tiny(b + d * t))
            .collect()
    }
}

/// Exact, adjacency-aware: closed triangles `t1`, `t2` with (aliased) indices `f`, `g` meet
/// away from what they share.
pub(crate) use envelope_predicates::indexed_triangles_intersect as tris_intersect;

/// The union of the swept boxes of `m`'s star: where the star can be at any parameter.
pub(crate) fn reach(swept: &[Aabb], m: &Mover) -> Aabb {
    m.star
        .iter()
        .fold(Aabb::EMPTY, |b, &f| b.union(&swept[f as usize]))
}

/// Exact check of mover `m` at parameter `t` against the scene: each face whose current
/// box overlaps the box of the whole star (found in the trees of swept boxes) against each
/// star face whose box it overlaps, `blocker` (the face that refused the mover's last step)
/// first. `Err` names a face the star at `t` meets. Which one depends on the order, the
/// answer does not.
fn check(scene: &Scene<'_>, m: &Mover, t: f64, blocker: Option<u32>) -> Result<(), u32> {
    check_among(scene, m, t, blocker, None)
}

/// [`check`] against the faces `among` only, when given (in their order), instead of
/// every face the trees find.
fn check_among(
    scene: &Scene<'_>,
    m: &Mover,
    t: f64,
    blocker: Option<u32>,
    among: Option<&[u32]>,
) -> Result<(), u32> {
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
    let star: Vec<(u32, Planar, [u32; 3], Aabb)> = m
        .star
        .iter()
        .map(|&f| {
            let fv = scene.faces[f as usize];
            let tf = fv.map(pos);
            (f, Planar::new(tf), fv.map(alias), Aabb::from_triangle(tf))
        })
        .collect();
    let all = star.iter().fold(Aabb::EMPTY, |b, s| b.union(&s.3));
    // Every face the star can meet now has its current box (or, in the star, its proposed
    // one) inside its swept box, so it is among the faces whose swept box overlaps `all`:
    // the trees answer that directly, without a walk over everything the star could reach.
    // Whether the star at `t` is clear of face `g`.
    let clear_of = |g: u32| {
        let g_in_star = m.star.binary_search(&g).is_ok();
        let gv = scene.faces[g as usize];
        // A star face is at the proposed positions, any other face where it is now.
        let tg = gv.map(pos);
        let bg = Aabb::from_triangle(tg);
        if !bg.overlaps(&all) {
            return true;
        }
        let ag = gv.map(alias);
        let pg = Planar::new(tg);
        for (f, pf, af, bf) in &star {
            let (f, af) = (*f, *af);
            if g == f || (g_in_star && g < f) || !bf.overlaps(&bg) || (scene.exempt)(f, g) {
                continue;
            }
            if surely_apart(
                pf,
                af.map(|x| ag.contains(&x)),
                &pg,
                ag.map(|x| af.contains(&x)),
            ) {
                continue;
            }
            if tris_intersect(pf.t, af, tg, ag) {
                return false;
            }
        }
        true
    };
    if let Some(faces) = among {
        return faces
            .iter()
            .try_for_each(|&g| if clear_of(g) { Ok(()) } else { Err(g) });
    }
    // The face that stopped this mover last time first: a halved step usually meets it
    // again, and one pair test then answers instead of a walk over the neighbourhood. It
    // is a face of the trees (a walk found it), so the walk would find it too.
    if let Some(g) = blocker
        && !clear_of(g)
    {
        return Err(g);
    }
    match (&scene.only, scene.fixed) {
        (Some(only), _) => all_clear(&scene.bvh, &all, |i| only[i as usize], clear_of),
        (None, Some((tree, n))) => all_clear(tree, &all, |i| i, clear_of)
            .and_then(|()| all_clear(&scene.bvh, &all, |i| i + n, clear_of)),
        (None, None) => all_clear(&scene.bvh, &all, |i| i, clear_of),
    }
}

/// Whether `clear_of` holds for the face `face(i)` of every item `i` of `tree` whose box
/// overlaps `query`; the walk stops at the first that fails, and names it.
fn all_clear(
    tree: &Bvh,
    query: &Aabb,
    face: impl Fn(u32) -> u32,
    clear_of: impl Fn(u32) -> bool,
) -> Result<(), u32> {
    let mut blocked = None;
    tree.for_each_overlapping_while(query, |i| {
        let g = face(i);
        if clear_of(g) {
            true
        } else {
            blocked = Some(g);
            false
        }
    });
    blocked.map_or(Ok(()), Err)
}

fn commit(scene: &mut Scene<'_>, m: &mut Mover, t: f64, policy: StepPolicy) {
    for (k, p) in m.positions_at(t).into_iter().enumerate() {
        let v = m.verts[k] as usize;
        scene.positions[v] = p;
        scene.alias[v] = v as u32;
    }
    m.t = t;
    m.steps += 1;
    m.halvings = 0;
    m.step *= policy.growth;
    if m.t >= m.target {
        finish(m);
    }
}

/// Commits move `(i, t)` when its check passed, else rejects it and keeps the face that
/// refused it as mover `i`'s blocker; true when committed.
fn settle(
    scene: &mut Scene<'_>,
    movers: &mut [Mover],
    blockers: &mut [Option<u32>],
    (i, t): (u32, f64),
    answer: Result<(), u32>,
    policy: StepPolicy,
) -> bool {
    match answer {
        Ok(()) => commit(scene, &mut movers[i as usize], t, policy),
        Err(g) => {
            blockers[i as usize] = Some(g);
            reject(&mut movers[i as usize], policy);
        }
    }
    answer.is_ok()
}

fn reject(m: &mut Mover, policy: StepPolicy) {
    if m.steps < policy.k && m.halvings < policy.max_halvings {
        m.step *= 0.5;
        m.halvings += 1;
    } else {
        finish(m);
    }
}

fn finish(m: &mut Mover) {
    m.done = true;
}

/// Batches of movers: by group, then greedy colour such that no two movers of a batch have
/// stars sharing a vertex (so concurrent moves rarely need the sequential re-check).
fn batches(movers: &[Mover], faces: &[[u32; 3]], num_vertices: usize) -> Vec<Vec<u32>> {
    let mut vert_movers: Vec<Vec<u32>> = vec![Vec::new(); num_vertices];
    for (i, m) in movers.iter().enumerate() {
        for &f in &m.star {
            for v in faces[f as usize] {
                let l = &mut vert_movers[v as usize];
                if l.last() != Some(&(i as u32)) {
                    l.push(i as u32);
                }
            }
        }
    }
    let mut color = vec![u32::MAX; movers.len()];
    let mut used: Vec<bool> = Vec::new();
    for i in 0..movers.len() {
        used.clear();
        for v in movers[i].star.iter().flat_map(|&f| faces[f as usize]) {
            for &o in &vert_movers[v as usize] {
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

/// Grows every mover as far as the exact checks allow (see the module docs), or, once
/// `stop` is set (the caller no longer wants the result), until the pass under way ends:
/// every mover is then left where it is, each of its steps checked.
pub(crate) fn grow(
    scene: &mut Scene<'_>,
    movers: &mut [Mover],
    policy: StepPolicy,
    stop: Option<&AtomicBool>,
) {
    grow_rechecking(scene, movers, policy, stop, recheck_in_order);
}

/// How the accepted moves of a batch whose stars' boxes meet are checked again (see
/// [`recheck_in_order`]).
type Recheck =
    fn(&mut Scene<'_>, &mut [Mover], &[(u32, f64)], &[Vec<u32>], &mut [Option<u32>], StepPolicy);

/// [`grow`], with the re-check of conflicting moves given.
fn grow_rechecking(
    scene: &mut Scene<'_>,
    movers: &mut [Mover],
    policy: StepPolicy,
    stop: Option<&AtomicBool>,
    recheck: Recheck,
) {
    for m in movers.iter_mut() {
        let positive = |x: f64| x.partial_cmp(&0.0) == Some(std::cmp::Ordering::Greater);
        if !positive(m.target - m.t) || !positive(m.step) {
            m.done = true;
        }
    }
    for m in movers.iter_mut() {
        m.star.sort_unstable(); // for `check`'s binary search; the star's order decides nothing
    }
    let batches = batches(movers, &scene.faces, scene.positions.len());
    // Per mover, the face that refused its last step (see `check`).
    let mut blockers: Vec<Option<u32>> = vec![None; movers.len()];
    loop {
        if crate::options::raised(stop) {
            break;
        }
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
            let last: &[Option<u32>] = &blockers;
            let results: Vec<(u32, f64, Result<(), u32>)> = active
                .par_iter()
                .map(|&i| {
                    let m = &ms[i as usize];
                    let t = (m.t + m.step).min(m.target);
                    (i, t, check(frozen, m, t, last[i as usize]))
                })
                .collect();
            let accepted: Vec<(u32, f64)> = results
                .iter()
                .filter(|r| r.2.is_ok())
                .map(|r| (r.0, r.1))
                .collect();
            let mut conflicted = vec![false; accepted.len()];
            let mut pairs = Vec::new();
            if accepted.len() > 1 {
                let boxes: Vec<Aabb> = accepted
                    .par_iter()
                    .map(|&(i, t)| star_box(frozen, &ms[i as usize], t))
                    .collect();
                pairs = Bvh::new(&boxes).self_pairs();
                for &(a, b) in &pairs {
                    conflicted[a as usize] = true;
                    conflicted[b as usize] = true;
                }
            }
            for (k, &(i, t)) in accepted.iter().enumerate() {
                if !conflicted[k] {
                    commit(scene, &mut movers[i as usize], t, policy);
                }
            }
            // The conflicting moves in order, and for each the earlier ones it conflicts with.
            let mut slot = vec![u32::MAX; accepted.len()];
            let mut pending: Vec<(u32, f64)> = Vec::new();
            for (k, &c) in conflicted.iter().enumerate() {
                if c {
                    slot[k] = pending.len() as u32;
                    pending.push(accepted[k]);
                }
            }
            let mut earlier: Vec<Vec<u32>> = vec![Vec::new(); pending.len()];
            for &(a, b) in &pairs {
                let (a, b) = (slot[a as usize], slot[b as usize]);
                earlier[a.max(b) as usize].push(a.min(b));
            }
            recheck(scene, movers, &pending, &earlier, &mut blockers, policy);
            for &(i, t, answer) in &results {
                if answer.is_err() {
                    settle(scene, movers, &mut blockers, (i, t), answer, policy);
                }
            }
        }
        if !any {
            break;
        }
    }
}

/// Checks the accepted moves `pending` (in mover order) again, each against the scene as
/// the moves before it in that order left it, and commits or rejects it: the outcome of
/// [`check`] one by one in order. Each passed [`check`] against the scene before any of
/// them moved, and the moves before it changed only the faces of their own stars (their
/// old positions leave: nothing can meet them any more; the vertices they move are in no
/// other star of the batch, so no other face changes, nor any alias another star face
/// has). So it fails exactly when its star meets, at their new positions, the star of an
/// earlier move that was committed and whose star's box meets its own (`earlier[k]`, by
/// position in `pending`): those faces are all it is checked against.
fn recheck_in_order(
    scene: &mut Scene<'_>,
    movers: &mut [Mover],
    pending: &[(u32, f64)],
    earlier: &[Vec<u32>],
    blockers: &mut [Option<u32>],
    policy: StepPolicy,
) {
    let mut committed = vec![false; pending.len()];
    let mut faces: Vec<u32> = Vec::new();
    for (k, &(i, t)) in pending.iter().enumerate() {
        faces.clear();
        for &j in &earlier[k] {
            if committed[j as usize] {
                faces.extend(&movers[pending[j as usize].0 as usize].star);
            }
        }
        let answer = check_among(scene, &movers[i as usize], t, None, Some(&faces));
        committed[k] = settle(scene, movers, blockers, (i, t), answer, policy);
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
    sweep_box_from(base, dir, 0.0, target)
}

/// The box of every position `base + t dir`, `t` in `[from, target]`, as f64 constructions:
/// rounding is monotone, so each coordinate of a constructed point lies between those of
/// the two constructed ends; the inflation covers the flush of tiny coordinates. A mover
/// that starts at `from` never goes back, so this is where it can be.
pub(crate) fn sweep_box_from(base: DVec3, dir: DVec3, from: f64, target: f64) -> Aabb {
    let start = base + dir * from;
    let end = base + dir * target;
    let scale = start.abs().max(end.abs()).max_element();
    Aabb::from_points(&[start, end]).inflated(scale * 8.0 * f64::EPSILON)
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::{VertexFaces, VertexId, generate};
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Moves re-checked by [`recheck_one_by_one`] over all its calls.
    static RECHECKED: AtomicUsize = AtomicUsize::new(0);

    /// [`recheck_in_order`] as it was: each move's full [`check`], one after the other.
    fn recheck_one_by_one(
        scene: &mut Scene<'_>,
        movers: &mut [Mover],
        pending: &[(u32, f64)],
        _: &[Vec<u32>],
        blockers: &mut [Option<u32>],
        policy: StepPolicy,
    ) {
        RECHECKED.fetch_add(pending.len(), Ordering::Relaxed);
        for &(i, t) in pending {
            let answer = check(scene, &movers[i as usize], t, blockers[i as usize]);
            settle(scene, movers, blockers, (i, t), answer, policy);
        }
    }

    /// Every vertex of two unit spheres 0.2 apart moving out along its normal towards 0.3:
    /// the fronts meet in the gap, where the moves of one batch block each other (their
    /// stars' boxes meet, and which one goes first decides where both stop).
    fn grown(recheck: Recheck) -> (Vec<DVec3>, Vec<f64>) {
        let sphere = generate::icosphere(3, 1.0);
        let n = sphere.num_vertices();
        let centre = |v: usize| {
            if v < n {
                DVec3::ZERO
            } else {
                DVec3::new(2.2, 0.0, 0.0)
            }
        };
        let mut positions = sphere.positions.clone();
        positions.extend(sphere.positions.iter().map(|&p| p + centre(n)));
        let mut faces: Vec<[u32; 3]> = sphere.faces.iter().map(|f| f.map(|v| v.0)).collect();
        faces.extend(sphere.faces.iter().map(|f| f.map(|v| v.0 + n as u32)));
        let vf = VertexFaces::new(
            2 * n,
            &faces.iter().map(|f| f.map(VertexId)).collect::<Vec<_>>(),
        );
        let target = 0.3;
        let dir = |v: usize| (positions[v] - centre(v)).normalize();
        let sweep: Vec<Aabb> = (0..2 * n)
            .map(|v| sweep_box(positions[v], dir(v), target))
            .collect();
        let swept = swept_face_boxes(&faces, &sweep);
        let alias: Vec<u32> = (0..positions.len() as u32).collect();
        let exempt = |_: u32, _: u32| false;
        let mut scene = Scene::new(positions.clone(), alias, faces, swept, &exempt);
        let mut movers: Vec<Mover> = (0..2 * n)
            .map(|v| Mover {
                verts: vec![v as u32],
                base: vec![positions[v]],
                dirs: vec![dir(v)],
                star: vf.of(v).to_vec(),
                group: 0,
                target,
                t: 0.0,
                step: 0.01,
                steps: 0,
                halvings: 0,
                done: false,
            })
            .collect();
        let policy = StepPolicy {
            k: 40,
            max_halvings: 6,
            growth: 1.5,
        };
        grow_rechecking(&mut scene, &mut movers, policy, None, recheck);
        (scene.positions, movers.iter().map(|m| m.t).collect())
    }

    #[test]
    fn rechecks_against_the_earlier_stars_end_as_full_checks() {
        let (against_stars, one_by_one) = (grown(recheck_in_order), grown(recheck_one_by_one));
        assert!(RECHECKED.load(Ordering::Relaxed) > 100, "few conflicts");
        assert_eq!(against_stars, one_by_one);
        // The fronts stopped each other in the gap; the rest reached the target.
        let t = &one_by_one.1;
        assert!(t.iter().any(|&t| t < 0.1), "{t:?}");
        assert!(
            t.iter().filter(|&&t| t == 0.3).count() > t.len() / 2,
            "{t:?}"
        );
    }
}
