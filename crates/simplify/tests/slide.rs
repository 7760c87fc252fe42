//! `Placement::Slide` (the paper's section 8): neighbours of a stuck vertex slide along their
//! fibers. Checked: more removals than the subset run on curved meshes, every vertex on its
//! own fiber within the allowed part, the mesh's sanity after every attempt, the certificate,
//! and the subset placement moving nothing.
use envelope_mesh::{HalfEdgeMesh, TriangleSoup, generate};
use envelope_offset::{EnvelopeOptions, Envelopes, EpsilonField, build_envelopes};
use envelope_simplify::{
    Barriers, EnvelopeFilter, Greedy, LocalSimplifier, Options, Placement, SimplifyOptions, Stats,
    VertexFibers, simplify, simplify_local_sliding,
};
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

fn run(s: &TriangleSoup, env: &Envelopes, placement: Placement) -> (HalfEdgeMesh, Stats) {
    let barriers = Barriers::new(vec![env.outer.clone(), env.inner.clone()], vec![]).unwrap();
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
    let stats =
        simplify_local_sliding(&mut m, &barriers, &options, None, Some(fibers), &mut ()).unwrap();
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
    let barriers = Barriers::new(vec![env.outer.clone(), env.inner.clone()], vec![]).unwrap();
    let fibers = VertexFibers {
        inner: &env.inner.positions,
        outer: &env.outer.positions,
    };
    let filter = EnvelopeFilter::new(&barriers);
    let mut m = HalfEdgeMesh::from_soup(&s).unwrap();
    let mut local = LocalSimplifier::new(&mut m, true);
    let (mut refused, mut removed) = (0, 0);
    for v in (0..s.num_vertices() as u32).map(envelope_mesh::VertexId) {
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
