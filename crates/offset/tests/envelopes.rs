//! Property tests of the envelope guarantee on generated meshes (Cohen et al. 4, 6.2).
use envelope_mesh::{TriangleSoup, generate};
use envelope_offset::{
    EnvelopeError, EnvelopeMethod, EnvelopeOptions, Envelopes, EpsilonField, build_envelopes,
};
use envelope_predicates::{Sign, cmp_point_triangle, self_intersections, square_rounded_up};
use glam::DVec3;
use proptest::prelude::*;

fn build(soup: &TriangleSoup, eps: f64, method: EnvelopeMethod) -> Envelopes {
    let mut o = EnvelopeOptions::new(EpsilonField::Constant(eps));
    o.method = method;
    build_envelopes(soup, &o).expect("acceptable input")
}

/// Input, outer and inner envelope in one soup, no index shared between the three.
fn union_soup(soup: &TriangleSoup, env: &Envelopes) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let n = soup.num_vertices() as u32;
    let mut pos = soup.positions.clone();
    pos.extend_from_slice(&env.outer.positions);
    pos.extend_from_slice(&env.inner.positions);
    let faces = (0..3)
        .flat_map(|k| soup.faces.iter().map(move |f| f.map(|v| v.0 + k * n)))
        .collect();
    (pos, faces)
}

/// The guarantee, re-checked independently: the union soup has no intersecting pair, and
/// every envelope vertex is within its requested epsilon of the input (exact).
fn check(soup: &TriangleSoup, env: &Envelopes) {
    assert!(
        env.proof.holds(),
        "proof failed: {:?}",
        &env.proof.contacts[..env.proof.contacts.len().min(5)]
    );
    let (pos, faces) = union_soup(soup, env);
    assert!(self_intersections(&pos, &faces).is_empty());
    let mut fan = vec![Vec::new(); soup.num_vertices()];
    for (i, f) in soup.faces.iter().enumerate() {
        for v in f {
            fan[v.0 as usize].push(i);
        }
    }
    for v in 0..soup.num_vertices() {
        assert!(env.eps_plus[v] <= env.requested[v] && env.eps_minus[v] <= env.requested[v]);
        assert!(
            env.eps_plus[v] > 0.0 && env.eps_minus[v] > 0.0,
            "vertex {v} did not move"
        );
        let e2 = square_rounded_up(env.requested[v] * (1.0 + 1e-9));
        for p in [env.outer.positions[v], env.inner.positions[v]] {
            // Within eps of the vertex's own incident triangles (hence of the input).
            let near = fan[v].iter().any(|&f| {
                cmp_point_triangle(p, soup.triangle(envelope_mesh::FaceId(f as u32)), e2)
                    != Sign::Positive
            });
            assert!(near, "vertex {v} offset beyond epsilon");
        }
    }
    for t in &env.tubes {
        assert!(t.radius.iter().all(|&r| r > 0.0));
    }
}

#[test]
fn sphere_both_methods_reach_full_epsilon() {
    for sub in [1, 2, 3] {
        let s = generate::icosphere(sub, 1.0);
        for m in [EnvelopeMethod::Numerical, EnvelopeMethod::Analytical] {
            let env = build(&s, 0.02, m);
            check(&s, &env);
            let f = env.achieved_fractions();
            assert!(f[0] > 0.999, "sub {sub} {m:?}: min fraction {}", f[0]);
        }
    }
}

#[test]
fn thin_plate_inner_envelopes_stop_in_the_middle() {
    let s = generate::box_mesh(DVec3::new(1.0, 1.0, 0.02), 4);
    for m in [EnvelopeMethod::Numerical, EnvelopeMethod::Analytical] {
        let env = build(&s, 0.05, m);
        check(&s, &env);
        // Vertices with a vertical normal cannot reach the opposite face (0.02); top and
        // bottom together cannot pass each other.
        for (v, n) in env.normals.iter().enumerate() {
            if n.z.abs() > 0.99 {
                assert!(
                    env.eps_minus[v] < 0.02,
                    "{m:?}: vertex {v} {}",
                    env.eps_minus[v]
                );
                let p = s.positions[v];
                if let Some(u) = s
                    .positions
                    .iter()
                    .position(|q| q.x == p.x && q.y == p.y && q.z == -p.z)
                {
                    assert!(env.eps_minus[v] + env.eps_minus[u] < 0.02);
                }
            }
        }
    }
}

#[test]
fn torus_with_small_tube_and_sharp_box() {
    let t = generate::torus(1.0, 0.05, 24, 8);
    let b = generate::box_mesh(DVec3::ONE, 2);
    for m in [EnvelopeMethod::Numerical, EnvelopeMethod::Analytical] {
        let env = build(&t, 0.1, m);
        check(&t, &env);
        let env = build(&b, 0.05, m);
        check(&b, &env);
    }
}

#[test]
fn bordered_meshes_get_tubes() {
    let c = generate::open_cylinder(1.0, 1.0, 16, 4);
    let d = generate::disk_with_holes(2);
    for s in [c, d] {
        for m in [EnvelopeMethod::Numerical, EnvelopeMethod::Analytical] {
            let env = build(&s, 0.05, m);
            check(&s, &env);
            assert!(!env.tubes.is_empty());
            assert!(env.proof.tube_contacts.is_empty());
        }
    }
}

#[test]
fn per_vertex_and_function_fields() {
    let s = generate::icosphere(2, 1.0);
    let vals: Vec<f64> = (0..s.num_vertices())
        .map(|i| 0.01 + 0.001 * (i % 7) as f64)
        .collect();
    let env = build_envelopes(
        &s,
        &EnvelopeOptions::new(EpsilonField::PerVertex(vals.clone())),
    )
    .unwrap();
    check(&s, &env);
    assert_eq!(env.requested, vals);
    let f = EpsilonField::distance_to_viewpoint(DVec3::new(5.0, 0.0, 0.0), 0.001, 0.01);
    let env = build_envelopes(&s, &EnvelopeOptions::new(f)).unwrap();
    check(&s, &env);
    assert!(matches!(
        build_envelopes(
            &s,
            &EnvelopeOptions::new(EpsilonField::PerVertex(vec![0.1; 3]))
        ),
        Err(EnvelopeError::EpsilonCount { .. })
    ));
    assert!(matches!(
        build_envelopes(&s, &EnvelopeOptions::new(EpsilonField::Constant(-1.0))),
        Err(EnvelopeError::BadEpsilon { .. })
    ));
}

#[test]
fn unacceptable_input_is_a_typed_error() {
    assert_eq!(
        build_envelopes(
            &generate::bow_tie(),
            &EnvelopeOptions::new(EpsilonField::Constant(0.1))
        )
        .unwrap_err(),
        EnvelopeError::NotManifold
    );
    let mut s = generate::icosphere(1, 1.0);
    s.faces[0].swap(0, 1);
    assert_eq!(
        build_envelopes(&s, &EnvelopeOptions::new(EpsilonField::Constant(0.1))).unwrap_err(),
        EnvelopeError::NotOriented
    );
}

#[test]
fn an_abandoned_build_stops_and_says_so() {
    use std::sync::Arc;
    use std::sync::atomic::AtomicBool;
    let s = generate::torus(1.0, 0.3, 32, 12);
    for method in [
        EnvelopeMethod::Analytical,
        EnvelopeMethod::Numerical,
        EnvelopeMethod::Auto,
    ] {
        let options = |flag: bool| EnvelopeOptions {
            method,
            abandon: Some(Arc::new(AtomicBool::new(flag))),
            ..EnvelopeOptions::new(EpsilonField::Constant(0.2))
        };
        assert_eq!(
            build_envelopes(&s, &options(true)).unwrap_err(),
            EnvelopeError::Abandoned
        );
        // A flag that stays down changes nothing.
        let kept = build_envelopes(&s, &options(false)).unwrap();
        let plain = build(&s, 0.2, method);
        assert_eq!(kept.eps_plus, plain.eps_plus);
        assert_eq!(kept.eps_minus, plain.eps_minus);
    }
}

#[test]
fn output_is_deterministic() {
    let s = generate::torus(1.0, 0.3, 32, 12);
    let a = build(&s, 0.2, EnvelopeMethod::Numerical);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let b = pool.install(|| build(&s, 0.2, EnvelopeMethod::Numerical));
    assert_eq!(a.eps_plus, b.eps_plus);
    assert_eq!(a.eps_minus, b.eps_minus);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]
    #[test]
    fn perturbed_spheres_are_proved(seed in 0u64..1000, eps in 0.005f64..0.3, analytical: bool) {
        let mut s = generate::icosphere(2, 1.0);
        let mut x = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
        for p in &mut s.positions {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let r = 0.8 + 0.4 * ((x >> 11) as f64 / (1u64 << 53) as f64);
            *p *= r;
        }
        let m = if analytical { EnvelopeMethod::Analytical } else { EnvelopeMethod::Numerical };
        let env = build(&s, eps, m);
        check(&s, &env);
    }
}

/// `EnvelopeMethod::Auto` keeps the analytical offsets when they reach epsilon everywhere, and
/// otherwise grows the short ones numerically from the proved analytical envelopes: every
/// offset at least the analytical one, the proof holding; its envelopes pass the same
/// independent check.
#[test]
fn auto_keeps_the_better_method() {
    // Small epsilon on a sphere: analytical reaches it everywhere.
    let sphere = generate::icosphere(2, 1.0);
    let auto = build(&sphere, 0.01, EnvelopeMethod::Auto);
    check(&sphere, &auto);
    assert_eq!(auto.method, EnvelopeMethod::Analytical);
    assert!(auto.eps_plus.iter().all(|&e| e == 0.01));
    // Epsilon larger than a torus's tube radius or a tunnel's half-width: offsets get cut.
    let mut numerical_kept = 0;
    let mut grown = 0;
    for (mesh, eps) in [
        (generate::torus(1.0, 0.2, 24, 12), 0.3),
        (generate::box_with_tunnel(), 0.4),
        (generate::box_with_tunnel(), 1.5),
    ] {
        let auto = build(&mesh, eps, EnvelopeMethod::Auto);
        check(&mesh, &auto);
        assert!(auto.proof.holds());
        let a = build(&mesh, eps, EnvelopeMethod::Analytical);
        let full = |e: &Envelopes| e.eps_plus.iter().chain(&e.eps_minus).all(|&x| x == eps);
        match auto.method {
            EnvelopeMethod::Analytical => {
                assert_eq!(
                    (&auto.eps_plus, &auto.eps_minus),
                    (&a.eps_plus, &a.eps_minus)
                );
            }
            EnvelopeMethod::Numerical => {
                assert!(
                    a.proof.holds() && !full(&a),
                    "numerical only where analytical fell short"
                );
                numerical_kept += 1;
                let sides = [
                    (&auto.eps_plus, &a.eps_plus),
                    (&auto.eps_minus, &a.eps_minus),
                ];
                for (x, y) in sides {
                    assert!(
                        x.iter().zip(y).all(|(x, y)| x >= y),
                        "an offset went below the start"
                    );
                    grown += x.iter().zip(y).filter(|(x, y)| x > y).count();
                }
            }
            EnvelopeMethod::Auto => panic!("auto names the method it kept"),
        }
        if a.proof.holds() && full(&a) {
            assert_eq!(auto.method, EnvelopeMethod::Analytical);
        }
    }
    assert!(
        grown > 0,
        "the growth from the analytical offsets moved nothing"
    );
    assert!(numerical_kept > 0, "no case exercised the numerical branch");
}

/// A vertex whose faces fit in no open hemisphere (a fold taken from `hand.off`) is pinned:
/// normal zero, both offsets zero, and the proof holds with the envelopes passing through
/// it (they meet the input there and nowhere else). Every other vertex still moves. Before
/// pinning, such a mesh was refused.
#[test]
fn folded_vertex_is_pinned_and_the_proof_holds() {
    let s = generate::folded_vertex();
    assert_eq!(
        envelope_offset::vertex_normals(&s).invalid,
        vec![envelope_mesh::VertexId(4)]
    );
    for m in [
        EnvelopeMethod::Numerical,
        EnvelopeMethod::Analytical,
        EnvelopeMethod::Auto,
    ] {
        let env = build(&s, 0.05 * s.diagonal(), m);
        assert!(env.proof.holds(), "{m:?}: {:?}", env.proof.contacts);
        assert_eq!(env.pinned, vec![envelope_mesh::VertexId(4)], "{m:?}");
        assert_eq!(env.normals[4], DVec3::ZERO);
        assert_eq!((env.eps_plus[4], env.eps_minus[4]), (0.0, 0.0), "{m:?}");
        assert_eq!(env.outer.positions[4], s.positions[4]);
        assert_eq!(env.inner.positions[4], s.positions[4]);
        assert_eq!(
            env.requested[4],
            0.05 * s.diagonal(),
            "the request is kept as given"
        );
        for v in (0..9).filter(|&v| v != 4) {
            assert!(
                env.eps_plus[v] > 0.0 && env.eps_minus[v] > 0.0,
                "{m:?}: vertex {v}"
            );
        }
        // The pinch is the only meeting point: with the pinned copies given their own
        // indices, the union soup has contacts, and each involves a face of vertex 4.
        let n = s.num_vertices() as u32;
        let (pos, faces) = union_soup(&s, &env);
        let contacts = self_intersections(&pos, &faces);
        assert!(!contacts.is_empty());
        for (a, b) in contacts {
            for f in [a, b] {
                assert!(
                    faces[f as usize].iter().any(|&v| v % n == 4),
                    "{m:?}: face {f}"
                );
            }
        }
    }
}

/// Tube rings start at their target radius; the rings of faces the proof finds in a
/// contact go back to a narrow start and grow from there. Small epsilon on a disk with
/// holes: every ring at its target. Large (0.7, the holes a unit apart): the holes' tubes would meet, some rings stay
/// below their target, and the union is still free of intersections (brute force).
#[test]
fn tube_rings_at_their_target_unless_blocked() {
    let d = generate::disk_with_holes(2);
    let below = |env: &Envelopes| {
        env.tubes
            .iter()
            .flat_map(|t| t.border.iter().zip(&t.radius))
            .filter(|&(v, &r)| r < env.requested[v.index()])
            .count()
    };
    let env = build(&d, 0.01, EnvelopeMethod::Numerical);
    check(&d, &env);
    assert_eq!(below(&env), 0);
    let env = build(&d, 0.7, EnvelopeMethod::Numerical);
    check(&d, &env);
    assert!(env.proof.tube_contacts.is_empty());
    assert!(below(&env) > 0, "every ring at its target at 0.7");
    // Brute force: no two tubes meet (at their targets the holes' tubes would).
    let tris = |t: &envelope_offset::Tube| -> Vec<[DVec3; 3]> {
        (0..t.mesh.num_faces())
            .map(|f| t.mesh.triangle(envelope_mesh::FaceId(f as u32)))
            .collect()
    };
    for (i, a) in env.tubes.iter().enumerate() {
        for b in &env.tubes[i + 1..] {
            for ta in tris(a) {
                assert!(
                    tris(b)
                        .iter()
                        .all(|&tb| !envelope_predicates::triangles_intersect(ta, tb))
                );
            }
        }
    }
}
