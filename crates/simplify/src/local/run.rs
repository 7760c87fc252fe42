//! The run loop: the subset run over the removal queue (batched with a first-in-first-out
//! order, see the module docs of `local`), then the moving phase when it is asked for.

use super::moving::moving_phase;
use super::plan::LocalSimplifier;
use super::queue::{RemovalQueue, RingBoxes, independent_batch, queue_vertices};
use super::scheduler::{Awake, plan_each};
use super::verdicts::{Doomed, FillNothing};
use super::{AUTO_MOVING_DIVISOR, Policies, SimplifyError, Stats, rejected};
use crate::grid::FaceGrid;
use crate::rules::{Rejection, Visitor};
use envelope_mesh::{HalfEdgeMesh, VertexId};

/// The counts before a run on `mesh`, which must have manifold vertices only.
fn starting_counts(mesh: &HalfEdgeMesh) -> Result<Stats, SimplifyError> {
    if let Some(v) = mesh.vertices().find(|&v| !mesh.is_manifold_vertex(v)) {
        return Err(SimplifyError::NonManifoldVertex(v));
    }
    Ok(Stats {
        vertices_before: mesh.num_vertices(),
        faces_before: mesh.num_faces(),
        ..Stats::default()
    })
}

pub(super) fn run(
    mesh: &mut HalfEdgeMesh,
    policies: &Policies<'_>,
    seeds: Option<&[VertexId]>,
    visitor: &mut dyn Visitor,
) -> Result<Stats, SimplifyError> {
    let mut stats = starting_counts(mesh)?;
    let mut queue = match seeds {
        None => queue_vertices(mesh, policies.order),
        Some(seeds) => {
            let mut q = RemovalQueue::default();
            for &v in seeds.iter().filter(|&&v| mesh.contains_vertex(v)) {
                q.push(mesh, policies.order, v);
            }
            q
        }
    };
    let batched = policies.order.is_fifo() && !policies.check_each_step;
    // The verdicts are computed on a copy of the starting mesh (see `Doomed`).
    let mut start = (batched && policies.fiber_test.is_some()).then(|| mesh.clone());
    let verdicts = Doomed::new(
        start.as_mut().map(|m| {
            let s = LocalSimplifier::without_grid(m, policies.keep_border)
                .with_keep(policies.keep)
                .with_fiber_test(policies.fiber_test);
            (s, policies.filter)
        }),
        &queue,
    );
    let mut local = LocalSimplifier::without_grid(mesh, policies.keep_border)
        .with_keep(policies.keep)
        .with_fiber_test(policies.fiber_test);
    let mut rings = RingBoxes::default();
    let take_ahead = || verdicts.take_one();
    let awake = Awake::new();
    let mut cancelled = false;
    rayon::in_place_scope(|scope| -> Result<(), SimplifyError> {
        // The other threads take verdicts ahead while this one builds the face index (the
        // verdicts read none), selects and commits.
        if batched {
            awake.hold(scope, &take_ahead);
        }
        local.grid = FaceGrid::from_mesh(local.mesh());
        'run: loop {
            if visitor.cancelled() {
                cancelled = true;
                break;
            }
            let batch: Vec<(VertexId, bool)> = if batched {
                independent_batch(
                    &mut queue,
                    local.mesh(),
                    |m, v| rings.get(m, v),
                    |v| verdicts.holds(v),
                )
            } else {
                queue.pop().into_iter().map(|v| (v, false)).collect()
            };
            if batch.is_empty() {
                break;
            }
            awake.release();
            let plans = {
                let local = &local;
                plan_each(
                    &batch,
                    |&(_, doomed)| doomed,
                    |&(v, _)| {
                        let known = usize::from(verdicts.passed(v));
                        2 * local.mesh().valence(v) + known
                    },
                    |&(v, doomed)| {
                        if doomed {
                            debug_assert_eq!(
                                local.plan(v, policies.filter, &FillNothing).0.err(),
                                Some(Rejection::NoFillAcrossFiber),
                                "the verdict on {v} no longer holds"
                            );
                            (Err(Rejection::NoFillAcrossFiber), 0)
                        } else if verdicts.passed(v) {
                            local.plan_without_fiber_test(v, policies.filter, policies.filler)
                        } else {
                            local.plan(v, policies.filter, policies.filler)
                        }
                    },
                    || verdicts.take_one(),
                )
            };
            if batched {
                awake.hold(scope, &take_ahead);
            }
            // Commit in queue order: the plans are apart; the order fixes the re-queued order.
            for (&(v, ahead), (plan, tests)) in batch.iter().zip(plans) {
                if policies.stop.should_stop(local.mesh().num_faces()) {
                    break 'run;
                }
                stats.attempts += 1;
                stats.answered_ahead += usize::from(ahead);
                visitor.on_attempt(v);
                local.candidate_tests += tests;
                match plan.and_then(|p| local.apply(v, p)) {
                    Ok(removal) => {
                        stats.removed += 1;
                        visitor.on_removed(v, &removal.faces);
                        rings.forget(v);
                        for &w in &removal.hole.vertices {
                            rings.forget(w);
                            verdicts.forget(w);
                            queue.push(local.mesh(), policies.order, w);
                        }
                    }
                    Err(reason) => rejected(&mut stats, visitor, v, reason),
                }
                if policies.check_each_step {
                    let check = local
                        .sanity_check()
                        .and_then(|()| queue.sanity_check(local.mesh()));
                    check.map_err(|message| SimplifyError::SanityCheck { after: v, message })?;
                }
            }
        }
        awake.release();
        Ok(())
    })?;
    if cancelled {
        return Err(SimplifyError::Cancelled);
    }
    local.candidate_tests += verdicts.used_tests();
    let few_left = local.mesh().num_vertices() * AUTO_MOVING_DIVISOR <= stats.vertices_before;
    let light = policies.auto_moving && !few_left;
    if (policies.fibers.is_some() && !light) || policies.collapse {
        stats.moving_phase = true;
        stats.moving_phase_light = light;
        moving_phase(&mut local, policies, &mut stats, visitor, None, light)?;
    }
    stats.candidate_tests = local.candidate_tests;
    stats.vertices_after = local.mesh().num_vertices();
    stats.faces_after = local.mesh().num_faces();
    Ok(stats)
}

/// The tolerance phase's loop (crate module `tolerance`): the moving phase alone, with
/// `policies.filter` the tolerance filter, which reads the approximation up to twice
/// `reads_beyond` outside the box of what an operation changes.
pub(crate) fn tolerance_phase(
    mesh: &mut HalfEdgeMesh,
    policies: &Policies<'_>,
    reads_beyond: f64,
    visitor: &mut dyn Visitor,
) -> Result<Stats, SimplifyError> {
    let mut stats = starting_counts(mesh)?;
    let mut local = LocalSimplifier::without_grid(mesh, policies.keep_border)
        .with_keep(policies.keep)
        .with_fiber_test(None);
    local.grid = FaceGrid::from_mesh(local.mesh());
    moving_phase(
        &mut local,
        policies,
        &mut stats,
        visitor,
        Some(reads_beyond),
        false,
    )?;
    stats.candidate_tests = local.candidate_tests;
    stats.vertices_after = local.mesh().num_vertices();
    stats.faces_after = local.mesh().num_faces();
    stats.tolerance_removed = stats.removed;
    Ok(stats)
}
