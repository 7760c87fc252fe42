//! The moving phase after the subset run.
//!
//! `Placement::Slide` (the paper's section 8): neighbours of a stuck vertex slide along their
//! fibers. Checked: more removals than the subset run on curved meshes, every vertex on its
//! own fiber within the allowed part, the mesh's sanity after every attempt, the certificate,
//! and the subset placement moving nothing.
//!
//! `Placement::Collapse`: after sliding, a stuck vertex goes by an edge collapse into a
//! neighbour moved to a quadric point. Checked: fewer faces than sliding alone, the mesh's
//! sanity after every attempt, the certificate, determinism and independence of the thread
//! count, a refused collapse restoring everything exactly, and the guards (border, non-edge,
//! link condition).
use envelope_mesh::{HalfEdgeMesh, TriangleSoup, VertexId, generate};
use envelope_offset::{EnvelopeOptions, Envelopes, EpsilonField, build_envelopes};
use envelope_simplify::policy::{
    Barriers, EnvelopeFilter, Greedy, LocalSimplifier, Options, Rejection, Stats, VertexFibers,
    simplify_local_from,
};
use envelope_simplify::{Placement, SimplifyOptions, simplify};
use envelope_verify::Verdict;
use glam::DVec3;

/// A bumpy sphere: curvature everywhere, where a chord errs on one side only.
fn bumpy() -> TriangleSoup {
    let mut s = generate::icosphere(3, 1.0);
    for p in &mut s.positions {
        let bump = 1.0 + 0.05 * (7.0 * p.x).sin() * (5.0 * p.y).cos();
        *p *= bump;
    }
    s
}

fn envelopes(s: &TriangleSoup, eps: f64) -> Envelopes {
    let env = build_envelopes(s, &EnvelopeOptions::new(EpsilonField::Constant(eps))).unwrap();
    assert!(env.proof.holds());
    env
}

fn barriers(env: &Envelopes) -> Barriers {
    Barriers::new(vec![env.outer.clone(), env.inner.clone()], vec![]).unwrap()
}

fn run(s: &TriangleSoup, env: &Envelopes, placement: Placement) -> (HalfEdgeMesh, Stats) {
    let fibers = VertexFibers {
        inner: &env.inner.positions,
        outer: &env.outer.positions,
    };
    let options = Options {
        placement,
        check_each_step: true,
        ..Options::default()
    };
    let mut m = HalfEdgeMesh::from_soup(s).unwrap();
    let stats = simplify_local_from(
        &mut m,
        &barriers(env),
        &options,
        None,
        Some(fibers),
        None,
        &mut (),
    )
    .unwrap();
    (m, stats)
}

#[test]
fn slid_vertices_stay_on_their_fibers_and_more_go() {
    let s = bumpy();
    let env = envelopes(&s, 0.01);
    let (subset, st) = run(&s, &env, Placement::Subset);
    let (slid, ss) = run(&s, &env, Placement::Slide);
    assert_eq!(st.slid, 0);
    assert!(ss.slid > 0, "{ss:?}");
    assert!(
        slid.num_faces() < subset.num_faces(),
        "slide {} faces, subset {}",
        slid.num_faces(),
        subset.num_faces()
    );
    // Subset: every vertex where it was. Slide: on the segment from its inner to its outer
    // point, within [0.05, 0.95] of it (f64 tolerance: this is a test of the rule, the
    // guarantee is the filter's and the certificate's).
    for v in subset.vertices() {
        assert_eq!(subset.position(v), s.positions[v.index()]);
    }
    let mut moved = 0;
    for v in slid.vertices() {
        let p = slid.position(v);
        if p == s.positions[v.index()] {
            continue;
        }
        moved += 1;
        let (a, b) = (
            env.inner.positions[v.index()],
            env.outer.positions[v.index()],
        );
        let d = b - a;
        let t = (p - a).dot(d) / d.length_squared();
        let off_line = (p - (a + d * t)).length();
        assert!(off_line <= 1e-12, "vertex {v} off its fiber by {off_line}");
        assert!(
            (0.05 - 1e-9..=0.95 + 1e-9).contains(&t),
            "vertex {v} at {t}"
        );
    }
    assert!(moved > 0);
}

#[test]
fn slide_output_is_certified_and_deterministic() {
    let s = bumpy();
    let eps = 0.01;
    let options = SimplifyOptions {
        placement: Placement::Slide,
        verify: true,
        ..SimplifyOptions::new(EpsilonField::Constant(eps))
    };
    let (a, ra) = simplify(&s, &options, &mut ()).unwrap();
    let (b, _) = simplify(&s, &options, &mut ()).unwrap();
    assert_eq!(a, b);
    assert_eq!(ra.placement, "slide");
    assert!(ra.slid_removals > 0);
    let v = ra.verify.expect("verified");
    assert_eq!(v.verdict, Verdict::Holds, "{v:?}");
    assert!(v.approx_to_orig_upper <= eps && v.orig_to_approx_upper <= eps);
    // Some output vertex is not an input vertex.
    assert!(a.positions.iter().any(|p| !s.positions.contains(p)));
    let subset = simplify(
        &s,
        &SimplifyOptions::new(EpsilonField::Constant(eps)),
        &mut (),
    )
    .unwrap();
    assert!(a.num_faces() < subset.0.num_faces());
    assert!(subset.0.positions.iter().all(|p| s.positions.contains(p)));
}

/// A refused slide leaves every position and the face index exactly as they were.
#[test]
fn a_refused_slide_moves_nothing() {
    let s = bumpy();
    // Epsilon far below the curvature: almost every slide is refused.
    let env = envelopes(&s, 1e-4);
    let barriers = barriers(&env);
    let fibers = VertexFibers {
        inner: &env.inner.positions,
        outer: &env.outer.positions,
    };
    let filter = EnvelopeFilter::new(&barriers);
    let mut m = HalfEdgeMesh::from_soup(&s).unwrap();
    let mut local = LocalSimplifier::new(&mut m, true);
    let (mut refused, mut removed) = (0, 0);
    for v in (0..s.num_vertices() as u32).map(VertexId) {
        let before: Vec<DVec3> = local
            .mesh()
            .vertices()
            .map(|u| local.mesh().position(u))
            .collect();
        match local.try_slide_remove(v, &filter, &Greedy::default(), &fibers) {
            Ok(_) => removed += 1,
            Err(_) => {
                refused += 1;
                let after: Vec<DVec3> = local
                    .mesh()
                    .vertices()
                    .map(|u| local.mesh().position(u))
                    .collect();
                assert_eq!(before, after, "vertex {v}");
            }
        }
        local.sanity_check().unwrap();
    }
    assert!(refused > 100, "{refused} refused, {removed} removed");
}

// ----------------------------------------------------------------- collapses

#[test]
fn collapses_remove_what_sliding_leaves() {
    let s = bumpy();
    let env = envelopes(&s, 0.02);
    let (slid, ss) = run(&s, &env, Placement::Slide);
    let (collapsed, sc) = run(&s, &env, Placement::Collapse);
    assert_eq!(ss.collapsed, 0);
    assert!(sc.collapsed > 0, "{sc:?}");
    assert!(
        collapsed.num_faces() < slid.num_faces(),
        "collapse {} faces, slide {}",
        collapsed.num_faces(),
        slid.num_faces()
    );
    // Genus 0 kept, closed.
    let topo = collapsed.topology();
    assert_eq!((topo.genus, topo.num_border_loops()), (Some(0), 0));
    assert!(topo.consistently_oriented && topo.manifold);
}

#[test]
fn collapse_output_is_certified_and_deterministic() {
    let s = bumpy();
    let eps = 0.02;
    let options = SimplifyOptions {
        placement: Placement::Collapse,
        verify: true,
        ..SimplifyOptions::new(EpsilonField::Constant(eps))
    };
    let (a, ra) = simplify(&s, &options, &mut ()).unwrap();
    let (b, _) = simplify(&s, &options, &mut ()).unwrap();
    assert_eq!(a, b);
    assert_eq!(ra.placement, "collapse");
    assert!(ra.collapsed_removals > 0, "{ra:?}");
    let v = ra.verify.expect("verified");
    assert_eq!(v.verdict, Verdict::Holds, "{v:?}");
    assert!(v.approx_to_orig_upper <= eps && v.orig_to_approx_upper <= eps);
    let slide = SimplifyOptions {
        placement: Placement::Slide,
        ..options
    };
    assert!(a.num_faces() < simplify(&s, &slide, &mut ()).unwrap().0.num_faces());
}

fn positions(m: &HalfEdgeMesh) -> Vec<(VertexId, DVec3)> {
    m.vertices().map(|u| (u, m.position(u))).collect()
}

fn faces(m: &HalfEdgeMesh) -> Vec<[VertexId; 3]> {
    m.faces().map(|f| m.face_vertices(f)).collect()
}

/// A refused collapse leaves every position, face and index exactly as they were; an
/// accepted one removes `v`, moves `w` to `p` and nothing else.
#[test]
fn a_refused_collapse_changes_nothing() {
    let s = bumpy();
    let env = envelopes(&s, 0.01);
    let b = barriers(&env);
    let filter = EnvelopeFilter::new(&b);
    let mut m = HalfEdgeMesh::from_soup(&s).unwrap();
    let mut local = LocalSimplifier::new(&mut m, true);
    let (mut refused, mut removed) = (0, 0);
    for v in (0..s.num_vertices() as u32).map(VertexId) {
        let Some(w) = local.mesh().vertex_neighbors(v).next() else {
            continue;
        };
        let (pv, pw) = (local.mesh().position(v), local.mesh().position(w));
        // Alternately a point far outside the envelopes (always refused) and the midpoint.
        let far = v.0 % 2 == 0;
        let p = if far { pw * 1.5 } else { 0.5 * (pv + pw) };
        let (before, fb) = (positions(local.mesh()), faces(local.mesh()));
        match local.try_collapse(v, w, p, &filter) {
            Ok(removal) => {
                assert!(!far, "a point 0.5 out was accepted at {v}");
                removed += 1;
                assert!(!local.mesh().contains_vertex(v));
                assert_eq!(local.mesh().position(w), p);
                assert!(
                    removal
                        .faces
                        .iter()
                        .all(|&f| local.mesh().face_vertices(f).contains(&w))
                );
                let after = positions(local.mesh());
                let expected: Vec<_> = before
                    .iter()
                    .filter(|x| x.0 != v)
                    .map(|&(u, q)| (u, if u == w { p } else { q }))
                    .collect();
                assert_eq!(after, expected);
            }
            Err(_) => {
                refused += 1;
                assert_eq!(positions(local.mesh()), before, "vertex {v}");
                assert_eq!(faces(local.mesh()), fb, "vertex {v}");
            }
        }
        local.sanity_check().unwrap();
    }
    assert!(
        refused > 100 && removed > 10,
        "{refused} refused, {removed} removed"
    );
}

#[test]
fn collapse_guards() {
    let s = bumpy();
    let env = envelopes(&s, 0.02);
    let b = barriers(&env);
    let filter = EnvelopeFilter::new(&b);
    let mut m = HalfEdgeMesh::from_soup(&s).unwrap();
    let mut local = LocalSimplifier::new(&mut m, true);
    let v = VertexId(0);
    let w = local.mesh().vertex_neighbors(v).next().unwrap();
    let far = local
        .mesh()
        .vertices()
        .find(|&u| u != v && local.mesh().find_halfedge(v, u).is_none())
        .unwrap();
    let p = local.mesh().position(w);
    // Not an edge.
    assert_eq!(
        local.try_collapse(v, far, p, &filter).unwrap_err(),
        Rejection::NotAVertex
    );
    // A coordinate outside the predicates' range.
    assert!(
        local
            .try_collapse(v, w, DVec3::new(1e200, 0.0, 0.0), &filter)
            .is_err()
    );
    assert!(
        local
            .try_collapse(v, w, DVec3::new(f64::NAN, 0.0, 0.0), &filter)
            .is_err()
    );
    local.sanity_check().unwrap();

    // A border vertex is never collapsed (its tube would not be checked).
    let open = generate::open_cylinder(1.0, 1.0, 16, 4);
    let mut c = HalfEdgeMesh::from_soup(&open).unwrap();
    let mut local = LocalSimplifier::new(&mut c, false);
    let border = local
        .mesh()
        .vertices()
        .find(|&u| local.mesh().is_border_vertex(u))
        .unwrap();
    let n = local.mesh().vertex_neighbors(border).next().unwrap();
    let pn = local.mesh().position(n);
    let none = Barriers::none();
    assert!(
        local
            .try_collapse(border, n, pn, &EnvelopeFilter::new(&none))
            .is_err()
    );
}

/// The link condition: on a tetrahedron every edge collapse would leave two faces on the
/// same three vertices; refused by the topology guards with no barrier at all.
#[test]
fn a_tetrahedron_keeps_its_vertices() {
    let mut m = HalfEdgeMesh::from_soup(&generate::tetrahedron()).unwrap();
    let mut local = LocalSimplifier::new(&mut m, true);
    let none = Barriers::none();
    let filter = EnvelopeFilter::new(&none);
    for v in (0..4).map(VertexId) {
        for w in (0..4).map(VertexId).filter(|&w| w != v) {
            let p = local.mesh().position(w);
            assert!(local.try_collapse(v, w, p, &filter).is_err(), "{v} -> {w}");
        }
    }
    assert_eq!(local.mesh().num_faces(), 4);
}

/// The moving phase is batched like the subset run (plans in parallel, carried out in queue
/// order): the same mesh and counts for 1 and 3 threads, and the same guarantees as the
/// one-at-a-time run with every sanity check.
#[test]
fn the_moving_phase_does_not_depend_on_the_thread_count() {
    let s = bumpy();
    let env = envelopes(&s, 0.02);
    let b = barriers(&env);
    let fibers = VertexFibers {
        inner: &env.inner.positions,
        outer: &env.outer.positions,
    };
    let options = Options {
        placement: Placement::Collapse,
        ..Options::default()
    };
    let threaded = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut m = HalfEdgeMesh::from_soup(&s).unwrap();
        let stats = pool
            .install(|| {
                simplify_local_from(&mut m, &b, &options, None, Some(fibers), None, &mut ())
            })
            .unwrap();
        m.sanity_check().unwrap();
        (m.to_soup(), stats)
    };
    let (one, s1) = threaded(1);
    let (three, s3) = threaded(3);
    assert!(s1.collapsed > 0 && s1.slid > 0, "{s1:?}");
    assert_eq!(one, three);
    assert_eq!(s1, s3);
    // The one-at-a-time run (other re-queue order) ends within a few faces of it.
    let (sequential, _) = run(&s, &env, Placement::Collapse);
    let (a, b) = (one.num_faces() as f64, sequential.num_faces() as f64);
    assert!((a - b).abs() <= 0.1 * b, "batched {a}, one at a time {b}");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 24, ..Default::default() })]

    /// Collapses to arbitrary positions (anywhere along the edge, up to twice epsilon off the
    /// surface): whatever the filter lets through keeps every guarantee. The mesh's sanity
    /// after each attempt; at the end the input's topology, no self-intersection, and the
    /// certificate (two-sided distance within epsilon).
    #[test]
    fn arbitrary_collapses_keep_every_guarantee(
        amp in 0.0f64..0.08,
        eps in 0.005f64..0.04,
        tries in proptest::collection::vec(
            (0u32..162, 0usize..8, 0.0f64..=1.0, -2.0f64..2.0),
            20..80,
        ),
    ) {
        let mut s = generate::icosphere(2, 1.0);
        for p in &mut s.positions {
            *p *= 1.0 + amp * (7.0 * p.x).sin() * (5.0 * p.y).cos();
        }
        let env = build_envelopes(&s, &EnvelopeOptions::new(EpsilonField::Constant(eps))).unwrap();
        proptest::prop_assume!(env.proof.holds());
        let b = barriers(&env);
        let filter = EnvelopeFilter::new(&b);
        let mut m = HalfEdgeMesh::from_soup(&s).unwrap();
        let mut local = LocalSimplifier::new(&mut m, true);
        let mut accepted = 0;
        for (vi, k, t, off) in tries {
            let v = VertexId(vi);
            if !local.mesh().contains_vertex(v) {
                continue;
            }
            let ring: Vec<VertexId> = local.mesh().vertex_neighbors(v).collect();
            let w = ring[k % ring.len()];
            let (pv, pw) = (local.mesh().position(v), local.mesh().position(w));
            let p = pv.lerp(pw, t) + pv.normalize() * (off * eps);
            accepted += usize::from(local.try_collapse(v, w, p, &filter).is_ok());
            local.sanity_check().unwrap();
        }
        let out = local.mesh().to_soup();
        let (t0, t1) = (envelope_mesh::analyze(&s), envelope_mesh::analyze(&out));
        proptest::prop_assert_eq!(
            (t1.genus, t1.num_border_loops(), t1.components.len()),
            (t0.genus, t0.num_border_loops(), t0.components.len())
        );
        let cert = envelope_verify::certify(&s, &out, &envelope_verify::Options::new(eps));
        proptest::prop_assert_eq!(cert.verdict, Verdict::Holds, "{} accepted: {:?}", accepted, cert);
    }
}

#[test]
fn auto_moves_vertices_in_full_only_when_the_subset_run_left_few() {
    let s = bumpy();
    let before = HalfEdgeMesh::from_soup(&s).unwrap().num_vertices();
    let mut branches = Vec::new();
    for eps in [0.005, 0.15] {
        let env = envelopes(&s, eps);
        let (subset, _) = run(&s, &env, Placement::Subset);
        let (collapse, sc) = run(&s, &env, Placement::Collapse);
        let (auto, sa) = run(&s, &env, Placement::Auto);
        let few_left =
            subset.num_vertices() * envelope_simplify::policy::AUTO_MOVING_DIVISOR <= before;
        assert!(sa.moving_phase && sc.moving_phase, "eps {eps}");
        assert_eq!(sa.moving_phase_light, !few_left, "eps {eps}");
        if few_left {
            // The full phase: the collapse placement's output.
            assert_eq!(auto.to_soup(), collapse.to_soup(), "eps {eps}");
            assert_ne!(
                collapse.to_soup(),
                subset.to_soup(),
                "eps {eps}: nothing moved"
            );
        } else {
            // The light phase: no slide, collapses that remove what the subset run left.
            assert_eq!(sa.slid, 0, "eps {eps}");
            assert!(sa.collapsed > 0, "eps {eps}: nothing collapsed");
            assert!(
                auto.num_faces() < subset.num_faces(),
                "eps {eps}: {} faces, subset {}",
                auto.num_faces(),
                subset.num_faces()
            );
        }
        branches.push(few_left);
    }
    // One epsilon on each side of the rule, and the moving phase changed something there.
    assert_eq!(branches, [false, true]);
}
