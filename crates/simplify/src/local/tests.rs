use super::VertexFibers;
use super::collapse::{COLLAPSE_REACH, COLLAPSE_TRIES, collapse_candidates};
use super::plan::LocalSimplifier;
use super::queue::{
    CHAIN_BATCH, Entry, RemovalQueue, RingBoxes, independent_batch, queue_vertices,
};
use super::scheduler::plan_each;
use super::verdicts::{Doomed, FillNothing, Verdict};
use crate::barriers::Barriers;
use crate::filter::EnvelopeFilter;
use crate::filter::Filter;
use crate::rules::{Fifo, FlatFirst, QueueOrder, Rejection};
use envelope_mesh::{HalfEdgeMesh, VertexId, generate};
use glam::DVec3;
use std::collections::BinaryHeap;
use std::sync::atomic::{AtomicUsize, Ordering as Mem};

/// `plan_each` gives each item's plan in the batch's order, whatever it plans inline,
/// first or in parallel, and whatever the threads do aside while others finish: batches
/// of 0 to 40 items, some inline, costs out of order.
#[test]
fn plan_each_answers_in_batch_order() {
    for n in [0usize, 1, 2, 3, 7, 40] {
        for inline_every in [1usize, 2, 3, 100] {
            let batch: Vec<usize> = (0..n).collect();
            let inline = |&i: &usize| i % inline_every == 1;
            // Work aside for the threads that run out of plans: a bounded count of it.
            let aside = AtomicUsize::new(0);
            let planned = plan_each(
                &batch,
                inline,
                |&i| (i * 7919) % 13,
                |&i| (i, i * i),
                || aside.fetch_add(1, Mem::Relaxed) < 1000,
            );
            let expected: Vec<(usize, usize)> = batch.iter().map(|&i| (i, i * i)).collect();
            assert_eq!(
                planned, expected,
                "{n} items, every {inline_every}th inline"
            );
        }
    }
}

/// A verdict is the plan's own answer on the starting mesh whoever takes it and
/// whenever: on a bumpy sphere, the verdicts taken by other threads ahead of the queue
/// (all of them, in parallel) and those asked one by one on the calling thread alone
/// are the plan's answers; a vertex forgotten before it is asked has none; only the
/// verdicts asked count their candidates. Fails when a forgotten verdict is still given,
/// when a verdict lands on another vertex, or when a thread's verdict is lost.
#[test]
fn verdicts_are_the_plans_answers_whoever_takes_them() {
    use crate::fiber::FiberTest;
    use envelope_offset::{EnvelopeOptions, EpsilonField, build_envelopes};
    let mut soup = generate::icosphere(3, 1.0);
    for p in &mut soup.positions {
        *p *= 1.0 + 0.05 * (7.0 * p.x).sin() * (5.0 * p.y).cos();
    }
    let env = build_envelopes(&soup, &EnvelopeOptions::new(EpsilonField::Constant(0.004))).unwrap();
    assert!(env.proof.holds() && env.pinned.is_empty());
    let fibers = VertexFibers {
        inner: &env.inner.positions,
        outer: &env.outer.positions,
    };
    let test = FiberTest::new(fibers, &soup.faces);
    let barriers = Barriers::new(vec![env.outer.clone(), env.inner.clone()], vec![]).unwrap();
    let filter = EnvelopeFilter::new(&barriers);
    let mesh = HalfEdgeMesh::from_soup(&soup).unwrap();
    let queue = queue_vertices(&mesh, &Fifo);
    // The plan's own answers, one simplifier, no verdicts.
    let mut plain = mesh.clone();
    let plain = LocalSimplifier::without_grid(&mut plain, false).with_fiber_test(Some(&test));
    let answers: Vec<(Verdict, u64)> = mesh
        .vertices()
        .map(|v| match plain.plan(v, &filter, &FillNothing) {
            (Err(Rejection::NoFillAcrossFiber), t) => (Verdict::Doomed, t),
            (_, t) => (Verdict::Passed, t),
        })
        .collect();
    let doomed = answers.iter().filter(|a| a.0 == Verdict::Doomed).count();
    assert!(doomed > 50 && doomed < answers.len(), "{doomed} doomed");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap();
    for ahead in [false, true] {
        let mut copy = mesh.clone();
        let start = LocalSimplifier::without_grid(&mut copy, false).with_fiber_test(Some(&test));
        let verdicts = Doomed::new(Some((start, &filter as &dyn Filter)), &queue);
        let forgotten = |v: VertexId| v.index() % 7 == 3;
        if ahead {
            // Every verdict taken by the pool's threads at once, before anything is asked.
            pool.broadcast(|_| while verdicts.take_one() {});
        }
        let mut expected_tests = 0;
        for (v, &(answer, tests)) in mesh.vertices().zip(&answers) {
            if forgotten(v) {
                verdicts.forget(v);
                assert!(!verdicts.holds(v) && !verdicts.passed(v), "{v} forgotten");
                continue;
            }
            assert_eq!(
                verdicts.holds(v),
                answer == Verdict::Doomed,
                "{v}, ahead {ahead}"
            );
            assert_eq!(
                verdicts.passed(v),
                answer == Verdict::Passed,
                "{v}, ahead {ahead}"
            );
            expected_tests += tests;
        }
        assert_eq!(verdicts.used_tests(), expected_tests, "ahead {ahead}");
    }
    // No verdicts without a starting mesh.
    let none = Doomed::new(None, &queue);
    assert!(mesh.vertices().all(|v| !none.holds(v) && !none.passed(v)));
}

/// A plan that panics ends `plan_each` with that panic, while the other threads work
/// aside: none of them waits forever for the plan to be counted. Fails (the call does not
/// return within the time allowed) when a panicking plan is not counted as done.
#[test]
fn plan_each_passes_a_panic_on() {
    let (send, receive) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        let batch: Vec<usize> = (0..20).collect();
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            pool.install(|| {
                plan_each(
                    &batch,
                    |_| false,
                    |&i| i,
                    |&i| {
                        assert_ne!(i, 7, "plan 7 fails");
                        std::thread::sleep(std::time::Duration::from_millis(2));
                        i
                    },
                    || false,
                )
            })
        }));
        let _ = send.send(outcome.is_err());
    });
    let panicked = receive.recv_timeout(std::time::Duration::from_secs(20));
    assert_eq!(panicked, Ok(true), "plan_each hung or hid the panic");
}

/// The queue pops in the heap's order (smallest priority, then first queued) whether
/// entries sit in its deque or its heap: first-in-first-out and prioritised pushes
/// mixed, pops, and entries taken and put back as a batch window does, against a plain
/// heap.
#[test]
fn queue_pops_in_heap_order_with_both_stores() {
    let m = HalfEdgeMesh::from_soup(&generate::torus(1.0, 0.4, 12, 8)).unwrap();
    let n = m.vertices().count() as u64;
    let mut next = {
        let mut x = 0x2545_F491_4F6C_DD1D_u64;
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        }
    };
    let mut q = RemovalQueue::default();
    let mut reference = BinaryHeap::new();
    let mut queued = std::collections::HashSet::new();
    let mut seq = 0;
    let (mut from_deque, mut from_heap, mut put_back) = (0, 0, 0);
    for step in 0..4000 {
        let r = next();
        match r % 4 {
            0 | 1 => {
                let v = VertexId((next() % n) as u32);
                // Mostly first-in-first-out runs, with prioritised pushes between them.
                let order: &dyn QueueOrder = if step % 500 < 400 { &Fifo } else { &FlatFirst };
                q.push(&m, order, v);
                if queued.insert(v) {
                    reference.push(Entry {
                        priority: order.priority(&m, v),
                        seq,
                        v,
                    });
                    seq += 1;
                }
            }
            2 => {
                let got = q.pop();
                let want = reference.pop().map(|e| e.v);
                assert_eq!(got, want, "step {step}");
                if let Some(v) = want {
                    queued.remove(&v);
                }
            }
            _ => {
                // A window: take some, put all back.
                let k = (next() % 6) as usize;
                let mut taken = Vec::new();
                for _ in 0..k {
                    let deque_front = q.fifo.front().map(|e| e.seq);
                    let Some(e) = q.pop_entry() else { break };
                    if deque_front == Some(e.seq) {
                        from_deque += 1;
                    } else {
                        from_heap += 1;
                    }
                    taken.push(e);
                }
                put_back += taken.len();
                q.put_back(taken);
            }
        }
        q.sanity_check(&m).unwrap();
        assert_eq!(q.len(), reference.len());
    }
    assert!(
        from_deque > 100 && from_heap > 100 && put_back > 200,
        "{from_deque} {from_heap} {put_back}"
    );
}

/// A batch's planned vertices have pairwise apart one-ring boxes. Where the queue is a chain
/// (a torus numbered ring after ring: each vertex a neighbour of the one before), a vertex
/// next to one taken does not hold back those after it, so the first window still plans
/// dozens. The vertices passed over keep their order at the front of the queue.
#[test]
fn a_chain_of_neighbours_does_not_shrink_the_batch() {
    let m = HalfEdgeMesh::from_soup(&generate::torus(1.0, 0.3, 64, 64)).unwrap();
    let mut q = queue_vertices(&m, &Fifo);
    let mut rings = RingBoxes::default();
    let batch = independent_batch(&mut q, &m, |m, v| rings.get(m, v), |_| false);
    let taken: Vec<VertexId> = batch.iter().map(|&(v, _)| v).collect();
    // Every third ring's every third vertex, about; the rule before this one planned 1.
    assert!(taken.len() >= 32, "{taken:?}");
    assert_eq!(taken[0], VertexId(0));
    for (i, &a) in taken.iter().enumerate() {
        for &b in &taken[..i] {
            assert!(!rings.get(&m, a).overlaps(&rings.get(&m, b)), "{a} and {b}");
        }
    }
    // The rest, in id order: those passed over first, then those not looked at.
    let mut rest = Vec::new();
    while let Some(v) = q.pop() {
        rest.push(v);
    }
    let expected: Vec<VertexId> = m.vertices().filter(|v| !taken.contains(v)).collect();
    assert_eq!(rest, expected);
}

/// Where the queue is not a chain (the torus's vertices numbered at random), a batch keeps
/// the one-at-a-time order: each planned vertex's box is apart from those of all vertices
/// queued before it, planned or passed over.
#[test]
fn a_batch_off_a_chain_keeps_the_queue_order() {
    let mut s = generate::torus(1.0, 0.3, 64, 64);
    // A fixed shuffle of the ids (xorshift, Fisher-Yates).
    let n = s.positions.len();
    let mut new_id: Vec<u32> = (0..n as u32).collect();
    let mut x = 0x9E37_79B9_7F4A_7C15_u64;
    for i in (1..n).rev() {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        new_id.swap(i, (x % (i as u64 + 1)) as usize);
    }
    let mut positions = vec![DVec3::ZERO; n];
    for (old, &new) in new_id.iter().enumerate() {
        positions[new as usize] = s.positions[old];
    }
    s.positions = positions;
    for f in &mut s.faces {
        *f = f.map(|v| VertexId(new_id[v.index()]));
    }
    let m = HalfEdgeMesh::from_soup(&s).unwrap();
    let mut q = queue_vertices(&m, &Fifo);
    let mut rings = RingBoxes::default();
    let batch = independent_batch(&mut q, &m, |m, v| rings.get(m, v), |_| false);
    assert!(batch.len() >= CHAIN_BATCH, "{batch:?}");
    let last = batch.last().unwrap().0;
    for &(t, _) in &batch {
        // Queued before `t`: the smaller ids (the queue starts in id order).
        for u in (0..t.0).map(VertexId) {
            if batch.iter().all(|&(b, _)| b != u) {
                assert!(
                    !rings.get(&m, t).overlaps(&rings.get(&m, u)),
                    "{u} before {t}"
                );
            }
        }
    }
    // Those passed over are back in front, in id order, then the rest.
    let rest: Vec<VertexId> = std::iter::from_fn(|| q.pop()).collect();
    let expected: Vec<VertexId> = m
        .vertices()
        .filter(|v| batch.iter().all(|&(b, _)| b != *v))
        .collect();
    assert_eq!(rest, expected);
    assert!(rest.iter().filter(|v| v.0 < last.0).count() > 0);
}

/// Collapse positions beyond [`COLLAPSE_REACH`] times the local offset are dropped; the
/// rest come cheapest first, at most [`COLLAPSE_TRIES`].
#[test]
fn collapse_positions_stay_within_reach_of_the_fibers() {
    let m = HalfEdgeMesh::from_soup(&generate::icosphere(1, 1.0)).unwrap();
    let v = m.vertices().next().unwrap();
    let fibers_of = |h: f64| {
        let inner: Vec<DVec3> = m.vertices().map(|u| m.position(u) * (1.0 - h)).collect();
        let outer: Vec<DVec3> = m.vertices().map(|u| m.position(u) * (1.0 + h)).collect();
        (inner, outer)
    };
    let unbounded = collapse_candidates(&m, v, None);
    assert_eq!(unbounded.len(), COLLAPSE_TRIES);
    assert!(unbounded.windows(2).all(|w| w[0].0 <= w[1].0));
    for (h, expect_all) in [(1.0, true), (1e-9, false)] {
        let (inner, outer) = fibers_of(h);
        let fibers = VertexFibers {
            inner: &inner,
            outer: &outer,
        };
        let within = collapse_candidates(&m, v, Some(&fibers));
        let reach = COLLAPSE_REACH * h;
        assert!(within.iter().all(|c| c.0 <= reach * reach), "h = {h}");
        if expect_all {
            assert_eq!(within, unbounded);
        } else {
            // On a sphere no position lies on every plane around an edge.
            assert!(within.is_empty(), "h = {h}: {within:?}");
        }
    }
}
