//! The moving phase after the subset run ([`Placement::Slide`], [`Placement::Collapse`]):
//! each vertex that is left tries the plain removal, the slide, then the collapses.
//!
//! [`Placement::Slide`]: super::Placement::Slide
//! [`Placement::Collapse`]: super::Placement::Collapse

use super::collapse::{COLLAPSE_TRIES, collapse_candidates};
use super::plan::{LocalSimplifier, Plan};
use super::queue::{independent_batch, queue_vertices};
use super::scheduler::plan_each;
use super::{
    LIGHT_GIVE_UP_BELOW, LIGHT_PROBE, Policies, SimplifyError, Stats, VertexFibers, rejected,
};
use crate::fill::HoleFiller;
use crate::filter::Filter;
use crate::rules::{Fifo, Rejection, Visitor};
use envelope_mesh::{HalfEdgeMesh, VertexId};
use envelope_predicates::bvh::Aabb;
use glam::DVec3;

/// The phase after the subset run ([`Placement::Slide`], [`Placement::Collapse`]): every
/// live vertex in id order, first in first out: the plain removal, else the slide of
/// [`LocalSimplifier::try_slide_remove`] (with fibers), else (with `policies.collapse`) the
/// collapse of [`LocalSimplifier::try_collapse`] on the positions of `collapse_candidates`,
/// cheapest first, until one passes; after a removal the hole's vertices and the neighbours
/// of moved vertices are queued again. The first time round, the plain removal is skipped:
/// the subset run failed it last, and by the paper's rule (only neighbours are queued again)
/// nothing around it changed since; only vertices queued again after a change try it. (A
/// removal near a vertex but not next to it, across a thin part, can unblock it; the subset
/// run gives those up too.)
///
/// Batched like the subset run, with the box of [`moving_box`] (the two-ring and the
/// neighbours' fibers: every face a slide or collapse of the vertex reads or changes) in
/// place of the one-ring's; a slid or collapsed position outside that box is not tried, so
/// the box holds. With `check_each_step`, one vertex at a time (same plans, other re-queue
/// order).
///
/// `light`: no slide, and only each vertex's cheapest collapse position
/// ([`Placement::Auto`] where many vertices are left); it gives up once
/// [`LIGHT_PROBE`] attempts have been made and fewer than one in
/// [`LIGHT_GIVE_UP_BELOW`] of them removed a vertex (decided between batches, so the
/// output does not depend on the thread count).
///
/// With `reads_beyond = Some(margin)` (the tolerance phase, crate module `tolerance`): the
/// first time round tries the plain removal too (the filter is another than the run's
/// before), and the boxes are grown by `margin`: that filter reads the approximation up to
/// twice `margin` beyond [`moving_box`], and plans whose grown boxes are apart change
/// nothing the other reads.
pub(super) fn moving_phase(
    local: &mut LocalSimplifier<'_>,
    policies: &Policies<'_>,
    stats: &mut Stats,
    visitor: &mut dyn Visitor,
    reads_beyond: Option<f64>,
    light: bool,
) -> Result<(), SimplifyError> {
    let tolerance = reads_beyond.is_some();
    let mut queue = queue_vertices(local.mesh(), &Fifo);
    // Whether the vertex's neighbourhood changed since the subset run failed it.
    let mut changed = vec![
        tolerance;
        local
            .mesh()
            .vertices()
            .map(|v| v.index() + 1)
            .max()
            .unwrap_or(0)
    ];
    let fibers = policies.fibers.as_ref();
    let ways = Ways {
        filter: policies.filter,
        filler: policies.filler,
        fibers,
        slide: !light,
        collapse: policies.collapse,
        collapse_tries: if light { 1 } else { COLLAPSE_TRIES },
    };
    let mut boxes = MovingBoxes::default();
    // The light phase's own counts: `stats` holds the subset run's too.
    let (attempts_before, removed_before) = (stats.attempts, stats.removed);
    loop {
        if visitor.cancelled() {
            return Err(SimplifyError::Cancelled);
        }
        let (attempts, removals) = (
            stats.attempts - attempts_before,
            stats.removed - removed_before,
        );
        if light && attempts >= LIGHT_PROBE && removals * LIGHT_GIVE_UP_BELOW < attempts {
            stats.light_gave_up = true;
            return Ok(());
        }
        let batch: Vec<VertexId> = if policies.check_each_step {
            queue.pop().into_iter().collect()
        } else {
            independent_batch(
                &mut queue,
                local.mesh(),
                |m, v| {
                    let b = boxes.get(m, v, fibers);
                    reads_beyond.map_or(b, |margin| b.inflated(margin))
                },
                |_| false,
            )
            .into_iter()
            .map(|(v, _)| v)
            .collect()
        };
        if batch.is_empty() {
            break;
        }
        let jobs: Vec<(VertexId, bool)> = batch
            .iter()
            .map(|&v| (v, std::mem::take(&mut changed[v.index()])))
            .collect();
        let plans = {
            let local = &*local;
            plan_each(
                &jobs,
                |_| false,
                // A guess at the cost, for the threads' balance only: the plain removal's
                // filling, then the collapses' fans, grow with the valence.
                |&(v, plain)| (1 + usize::from(plain)) * local.mesh().valence(v),
                |&(v, plain)| local.plan_stuck(v, plain, &ways),
                || false,
            )
        };
        for (&v, (plan, tests)) in batch.iter().zip(plans) {
            if policies.stop.should_stop(local.mesh().num_faces()) {
                return Ok(());
            }
            stats.attempts += 1;
            visitor.on_attempt(v);
            local.candidate_tests += tests;
            let result = plan.and_then(|(plan, way)| {
                let moved: Vec<VertexId> = plan.moves.iter().map(|m| m.0).collect();
                local.apply(v, plan).map(|removal| (removal, way, moved))
            });
            match result {
                Ok((removal, way, moved)) => {
                    stats.removed += 1;
                    stats.slid += usize::from(way == Way::Slid);
                    stats.collapsed += usize::from(way == Way::Collapsed);
                    visitor.on_removed(v, &removal.faces);
                    debug_assert!(moved.iter().all(|u| removal.hole.vertices.contains(u)));
                    boxes.forget_around(local.mesh(), v, &removal.hole.vertices);
                    let around = moved.iter().flat_map(|&u| local.mesh().vertex_neighbors(u));
                    let again: Vec<VertexId> = removal
                        .hole
                        .vertices
                        .iter()
                        .copied()
                        .chain(around)
                        .collect();
                    for w in again {
                        if local.mesh().contains_vertex(w) {
                            changed[w.index()] = true;
                            queue.push(local.mesh(), &Fifo, w);
                        }
                    }
                }
                Err(reason) => rejected(stats, visitor, v, reason),
            }
            if policies.check_each_step {
                local
                    .sanity_check()
                    .map_err(|message| SimplifyError::SanityCheck { after: v, message })?;
            }
        }
    }
    Ok(())
}

/// What the moving phase may try (the thread-safe part of [`Policies`]).
struct Ways<'p> {
    filter: &'p dyn Filter,
    filler: &'p dyn HoleFiller,
    fibers: Option<&'p VertexFibers<'p>>,
    /// Slides (with `fibers`).
    slide: bool,
    collapse: bool,
    /// Collapse positions tried per vertex at most.
    collapse_tries: usize,
}

/// How a removal of the moving phase went.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Way {
    Plain,
    Slid,
    Collapsed,
}

/// The box of `v`'s two-ring and of its neighbours' fibers: every face that a slide or a
/// collapse of `v` reads or changes lies in it, when the slid and collapsed positions do.
fn moving_box(m: &HalfEdgeMesh, v: VertexId, fibers: Option<&VertexFibers<'_>>) -> Aabb {
    let grow = |b: Aabb, p: DVec3| Aabb {
        min: b.min.min(p),
        max: b.max.max(p),
    };
    // The points in a fixed order, one at a time (no list): the same box, bit for bit.
    let mut b = grow(Aabb::EMPTY, m.position(v));
    for u in m.vertex_neighbors(v) {
        b = m.vertex_neighbors(u).fold(b, |b, x| grow(b, m.position(x)));
        if let Some((a, d)) = fibers.and_then(|f| f.segment(u)) {
            b = grow(grow(b, a), a + d);
        }
    }
    b
}

/// The [`moving_box`]es of the moving phase, kept while the two-ring stays: the batches
/// look at a vertex again each time it is skipped. A removal changes the box of a vertex
/// only within two rings of its hole (the hole's vertices gain and lose neighbours, and
/// the moved vertices are on the hole), which [`MovingBoxes::forget_around`] forgets.
#[derive(Default)]
struct MovingBoxes(Vec<Option<Aabb>>);

impl MovingBoxes {
    fn get(&mut self, m: &HalfEdgeMesh, v: VertexId, fibers: Option<&VertexFibers<'_>>) -> Aabb {
        let i = v.index();
        if self.0.len() <= i {
            self.0.resize(i + 1, None);
        }
        let b = *self.0[i].get_or_insert_with(|| moving_box(m, v, fibers));
        debug_assert_eq!(b, moving_box(m, v, fibers), "stale moving box of {v}");
        b
    }

    /// Forgets the removed vertex and every vertex within two rings of `hole` (the mesh
    /// after the removal: the edges of a path from a vertex to the hole outside the removed
    /// vertex's star all stay).
    fn forget_around(&mut self, m: &HalfEdgeMesh, removed: VertexId, hole: &[VertexId]) {
        let mut forget = |x: VertexId| {
            if let Some(b) = self.0.get_mut(x.index()) {
                *b = None;
            }
        };
        forget(removed);
        for &h in hole.iter().filter(|&&h| m.contains_vertex(h)) {
            forget(h);
            for u in m.vertex_neighbors(h) {
                forget(u);
                m.vertex_neighbors(u).for_each(&mut forget);
            }
        }
    }
}

impl LocalSimplifier<'_> {
    /// The moving phase's plan for `v` (read only): the plain removal when `plain`, else or
    /// then the slide, then the collapses (see `moving_phase`), each position inside
    /// [`moving_box`]. Also returns the filter calls.
    fn plan_stuck(
        &self,
        v: VertexId,
        plain: bool,
        ways: &Ways<'_>,
    ) -> (Result<(Plan, Way), Rejection>, u64) {
        let (filter, filler) = (ways.filter, ways.filler);
        let mut tests = 0;
        if plain {
            let (plan, t) = self.plan(v, filter, filler);
            tests += t;
            match plan {
                Ok(plan) => return (Ok((plan, Way::Plain)), tests),
                Err(Rejection::NoValidFill | Rejection::NoFillAcrossFiber) => {}
                Err(other) => return (Err(other), tests),
            }
        }
        let m = &*self.mesh;
        if !m.contains_vertex(v) || m.is_isolated(v) {
            return (Err(Rejection::NotAVertex), tests);
        }
        let fibers = ways.fibers;
        let reach = moving_box(m, v, fibers);
        let slide = fibers.filter(|_| ways.slide);
        if let Some(moves) = slide.and_then(|f| self.slide_moves(v, f).ok()) {
            if moves.iter().all(|&(_, q)| reach.contains(q)) {
                let (plan, t) = self.plan_moved(v, moves, filter, filler);
                tests += t;
                if let Ok(plan) = plan {
                    return (Ok((plan, Way::Slid)), tests);
                }
            }
        }
        if ways.collapse {
            for (_, w, p) in collapse_candidates(m, v, fibers)
                .into_iter()
                .take(ways.collapse_tries)
            {
                if !reach.contains(p) {
                    continue;
                }
                let (plan, t) = self.plan_collapse(v, w, p, filter);
                tests += t;
                if let Ok(plan) = plan {
                    return (Ok((plan, Way::Collapsed)), tests);
                }
            }
        }
        (Err(Rejection::NoValidFill), tests)
    }
}
