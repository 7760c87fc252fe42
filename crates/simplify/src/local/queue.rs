//! The removal queue (section 5.2) and the batches taken off it for parallel planning:
//! vertices whose boxes are apart from everything queued before them, or on chains of
//! neighbours from those taken.

use crate::rules::QueueOrder;
use envelope_mesh::{HalfEdgeMesh, VertexId};
use envelope_predicates::bvh::Aabb;
use std::cmp::Ordering;
use std::collections::{BinaryHeap, VecDeque};

#[derive(Clone, Copy, Debug)]
pub(super) struct Entry {
    pub(super) priority: f64,
    pub(super) seq: u64,
    pub(super) v: VertexId,
}

impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    /// Reversed: the heap pops the smallest priority, then the earliest queued.
    fn cmp(&self, o: &Self) -> Ordering {
        o.priority
            .total_cmp(&self.priority)
            .then(o.seq.cmp(&self.seq))
    }
}

/// The removal queue: each vertex at most once, smallest priority first, then first queued.
#[derive(Clone, Debug, Default)]
pub(crate) struct RemovalQueue {
    heap: BinaryHeap<Entry>,
    /// Entries in the order the heap would pop them, at constant cost each: those queued
    /// with a first-in-first-out order ([`QueueOrder::is_fifo`]: one priority for every
    /// vertex) and those put back by a batch window. [`RemovalQueue::pop`] takes the first
    /// of both stores.
    pub(super) fifo: VecDeque<Entry>,
    pub(super) queued: Vec<bool>,
    seq: u64,
}

impl RemovalQueue {
    /// Queues `v` unless it is queued already or is not a live vertex.
    pub fn push(&mut self, mesh: &HalfEdgeMesh, order: &dyn QueueOrder, v: VertexId) {
        if !mesh.contains_vertex(v) {
            return;
        }
        if self.queued.len() <= v.index() {
            self.queued.resize(v.index() + 1, false);
        }
        if self.queued[v.index()] {
            return;
        }
        self.queued[v.index()] = true;
        let e = Entry {
            priority: order.priority(mesh, v),
            seq: self.seq,
            v,
        };
        // The deque stays in heap order while its priorities are one (a single order).
        if order.is_fifo() && self.fifo.back().is_none_or(|b| b.priority == e.priority) {
            self.fifo.push_back(e);
        } else {
            self.heap.push(e);
        }
        self.seq += 1;
    }

    /// Takes the next entry (the heap's order over both stores).
    pub(super) fn pop_entry(&mut self) -> Option<Entry> {
        let from_heap = match (self.heap.peek(), self.fifo.front()) {
            (Some(h), Some(f)) => h > f,
            (h, _) => h.is_some(),
        };
        if from_heap {
            self.heap.pop()
        } else {
            self.fifo.pop_front()
        }
    }

    /// Puts back the entries just taken by [`RemovalQueue::pop_entry`] (in the order taken,
    /// nothing queued since, still flagged as queued). They come before every entry left,
    /// so in front of the deque, in order, they are where the heap would keep them.
    pub(super) fn put_back(&mut self, entries: Vec<Entry>) {
        debug_assert!(
            entries.windows(2).all(|w| w[0] > w[1]),
            "not in the order taken"
        );
        debug_assert!(
            entries
                .last()
                .is_none_or(|e| self.fifo.front().is_none_or(|f| e > f)
                    && self.heap.peek().is_none_or(|h| e > h)),
            "queued since"
        );
        for e in entries.into_iter().rev() {
            self.fifo.push_front(e);
        }
    }

    /// Takes the next vertex.
    pub fn pop(&mut self) -> Option<VertexId> {
        let e = self.pop_entry()?;
        self.queued[e.v.index()] = false;
        Some(e.v)
    }

    /// Number of queued vertices (the tests compare it with a plain heap's).
    #[cfg(test)]
    #[must_use]
    pub(crate) fn len(&self) -> usize {
        self.heap.len() + self.fifo.len()
    }

    /// Each queued vertex is live, flagged, and stored once; the deque is in queue order.
    pub fn sanity_check(&self, mesh: &HalfEdgeMesh) -> Result<(), String> {
        let mut seen = vec![false; self.queued.len()];
        if self
            .fifo
            .iter()
            .zip(self.fifo.iter().skip(1))
            .any(|(a, b)| a <= b)
        {
            return Err("first-in-first-out entries out of order".into());
        }
        for e in self.heap.iter().chain(&self.fifo) {
            let i = e.v.index();
            if !self.queued[i] || seen[i] {
                return Err(format!("queue entry {} unflagged or repeated", e.v));
            }
            if !mesh.contains_vertex(e.v) {
                return Err(format!("queued vertex {} is dead", e.v));
            }
            seen[i] = true;
        }
        if seen != self.queued {
            return Err("queue flags disagree with the heap".into());
        }
        Ok(())
    }
}

/// How far [`independent_batch`] looks into the queue, and how many it takes at most.
/// Larger batches wake the other threads less often and leave less of the batch's last plan
/// alone on one thread, but the selection is serial and its box tests grow with the square
/// of the window; these sizes balance the two.
const BATCH_WINDOW: usize = 512;
const BATCH_LIMIT: usize = 128;
/// A full window that plans fewer vertices than this in queue order is a chain of
/// neighbours, and is taken again with the rule that lets vertices pass (see
/// [`independent_batch`]).
pub(super) const CHAIN_BATCH: usize = BATCH_LIMIT / 8;

/// Takes vertices off a first-in-first-out queue for one round of planning: the front
/// vertex, then, among the next ones, every vertex whose closed box `reach(mesh, v)` is
/// apart from the boxes of all vertices before it (taken or not), until [`BATCH_LIMIT`]
/// are taken or [`BATCH_WINDOW`] are looked at. The box must hold everything a plan of the
/// vertex reads or its removal changes (the subset run: the one-ring box, [`one_ring_box`],
/// which holds the vertex's fan and every candidate triangle of its hole): the removals of
/// a batch do not see each other, nor do they see the skipped vertices' removals, and
/// carrying them out before those changes nothing but the order in which re-queued
/// neighbours are appended. Skipped vertices keep their places.
///
/// Where the queue is a chain of neighbours (a grid numbered row after row), each vertex
/// holds back the next and that rule plans one vertex per batch. When a full window plans
/// fewer than [`CHAIN_BATCH`], it is taken again holding vertices back only by the boxes
/// of those *taken* before them: the removals still do not see each other, and the
/// vertices passed over go back to the front of the queue in their order, to be planned on
/// the mesh the batch leaves. They are then attempted after vertices queued behind them: a
/// departure from the paper's one-at-a-time order, for chains only, that trades a few faces
/// either way for batches (the changelog has the measurements).
///
/// Vertices `doomed` (their attempt is known to change nothing, see [`Doomed`]) are taken
/// as they come, marked `true`, without a box: they hold back no one and are held back by
/// no one, and do not count towards the window and the limit. One whose fan a removal
/// earlier in the batch changes is on that removal's hole, so it is queued again and
/// attempted anew; the only departure from one-at-a-time order is that its first attempt
/// came before the removal. (Holding doomed vertices back like the others made the
/// batches mostly skipped vertices, and small.)
///
/// The batches depend on the queue and the mesh only, never on the number of threads, so
/// the output does not either.
pub(super) fn independent_batch(
    queue: &mut RemovalQueue,
    mesh: &HalfEdgeMesh,
    mut reach: impl FnMut(&HalfEdgeMesh, VertexId) -> Aabb,
    doomed: impl Fn(VertexId) -> bool,
) -> Vec<(VertexId, bool)> {
    let window = select(queue, mesh, &mut reach, &doomed, true);
    let chain =
        window.planned < CHAIN_BATCH && window.planned + window.skipped.len() == BATCH_WINDOW;
    if !chain {
        queue.put_back(window.skipped);
        return window.batch;
    }
    for e in &window.popped {
        queue.queued[e.v.index()] = true;
    }
    queue.put_back(window.popped);
    let window = select(queue, mesh, &mut reach, &doomed, false);
    queue.put_back(window.skipped);
    window.batch
}

/// One window of [`independent_batch`], its skipped entries not yet put back.
struct Window {
    batch: Vec<(VertexId, bool)>,
    planned: usize,
    skipped: Vec<Entry>,
    /// Every entry taken off the queue, in order.
    popped: Vec<Entry>,
}

/// [`independent_batch`]'s selection, the skipped vertices holding back those after them
/// (`in_order`) or not.
fn select(
    queue: &mut RemovalQueue,
    mesh: &HalfEdgeMesh,
    reach: &mut impl FnMut(&HalfEdgeMesh, VertexId) -> Aabb,
    doomed: &impl Fn(VertexId) -> bool,
    in_order: bool,
) -> Window {
    let mut w = Window {
        batch: Vec::new(),
        planned: 0,
        skipped: Vec::new(),
        popped: Vec::new(),
    };
    let mut boxes: Vec<Aabb> = Vec::new();
    // Only vertices to be planned are skipped: doomed ones are always taken.
    while w.planned < BATCH_LIMIT && w.planned + w.skipped.len() < BATCH_WINDOW {
        let Some(e) = queue.pop_entry() else {
            break;
        };
        w.popped.push(e);
        let v = e.v;
        if doomed(v) {
            queue.queued[v.index()] = false;
            w.batch.push((v, true));
            continue;
        }
        let b = reach(mesh, v);
        // Latest first: a vertex's neighbours in the queue are mostly just before it.
        if boxes.iter().rev().any(|x| x.overlaps(&b)) {
            w.skipped.push(e);
            if in_order {
                boxes.push(b);
            }
        } else {
            queue.queued[v.index()] = false;
            w.batch.push((v, false));
            w.planned += 1;
            boxes.push(b);
        }
    }
    w
}

/// The [`one_ring_box`]es of the subset run, kept while the one-ring stays: a vertex's box
/// changes only when its neighbours do (no vertex moves there), that is when it is on the
/// hole of a removal ([`RingBoxes::forget`] it then). Vertices skipped by a batch are taken
/// up again by the next, with the box computed the first time.
#[derive(Default)]
pub(super) struct RingBoxes(Vec<Option<Aabb>>);

impl RingBoxes {
    pub(super) fn get(&mut self, mesh: &HalfEdgeMesh, v: VertexId) -> Aabb {
        let i = v.index();
        if self.0.len() <= i {
            self.0.resize(i + 1, None);
        }
        *self.0[i].get_or_insert_with(|| one_ring_box(mesh, v))
    }

    pub(super) fn forget(&mut self, v: VertexId) {
        if let Some(b) = self.0.get_mut(v.index()) {
            *b = None;
        }
    }
}

/// The box of `v` and its neighbours.
fn one_ring_box(mesh: &HalfEdgeMesh, v: VertexId) -> Aabb {
    mesh.vertex_neighbors(v)
        .fold(Aabb::from_points(&[mesh.position(v)]), |b, w| {
            b.union(&Aabb::from_points(&[mesh.position(w)]))
        })
}

/// Every live vertex, in id order, prioritised by `order` (section 5.2: "placing all
/// vertices in a queue").
#[must_use]
pub(crate) fn queue_vertices(mesh: &HalfEdgeMesh, order: &dyn QueueOrder) -> RemovalQueue {
    let mut q = RemovalQueue::default();
    for v in mesh.vertices() {
        q.push(mesh, order, v);
    }
    q
}
