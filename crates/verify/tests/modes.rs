//! The envelope-of mode, the first-intersection mode and the shared-triangle shortcut, on
//! meshes whose answers are known by hand.

use envelope_mesh::{TriangleSoup, generate};
use envelope_verify::{Options, Verdict, certify, first_self_intersection};

fn tri(z: f64, size: f64) -> TriangleSoup {
    TriangleSoup::from_raw(&[[0., 0., z], [size, 0., z], [0., size, z]], &[[0, 1, 2]])
}

#[test]
fn envelope_of_checks_only_approx_to_orig() {
    let (big, small) = (tri(0.0, 4.0), tri(1.0, 1.0));
    // The small triangle floats 1 above the big one: inside its 1-envelope, though the big one
    // reaches far from the small one.
    let c = certify(&big, &small, &Options::envelope_of(1.0));
    assert_eq!(c.envelope_of(), Verdict::Holds);
    assert_eq!(c.verdict, Verdict::Holds);
    assert!(!c.two_sided && c.orig_to_approx.upper.is_infinite());
    assert!(c.to_json()["orig_to_approx"].is_null());
    assert_eq!(c.to_json()["envelope_of"], "holds");
    let two = certify(&big, &small, &Options::new(1.0));
    assert_eq!(two.envelope_of(), Verdict::Holds);
    assert_eq!(two.verdict, Verdict::Violated);
    // Below 1 the small triangle leaves the envelope.
    let c = certify(&big, &small, &Options::envelope_of(0.999));
    assert_eq!(c.envelope_of(), Verdict::Violated);
    assert_eq!(c.verdict, Verdict::Violated);
}

#[test]
fn identical_meshes_are_proved_at_distance_zero() {
    let t = generate::torus(2.0, 0.5, 40, 20);
    let c = certify(&t, &t, &Options::new(1e-9));
    assert_eq!(c.verdict, Verdict::Holds);
    for s in [&c.approx_to_orig, &c.orig_to_approx] {
        assert_eq!((s.lower, s.upper), (0.0, 0.0));
        assert_eq!(s.subdivisions, t.faces.len() as u64);
    }
    // Same triangles with the corners listed in another order, one vertex moved outward
    // along the normal (vertex 0 is the outermost point (R + r, 0, 0), normal +x).
    let mut a = t.clone();
    for f in &mut a.faces {
        f.rotate_left(1);
    }
    assert_eq!(a.positions[0], glam::DVec3::new(2.5, 0.0, 0.0));
    a.positions[0].x += 1e-3;
    let c = certify(&t, &a, &Options::distance_only(1e-3 * 0.99));
    assert_eq!(c.verdict, Verdict::Violated);
    assert!(c.approx_to_orig.witness.is_some());
}

#[test]
fn first_intersection_agrees_with_the_full_list() {
    // Two tori crossing each other (one shifted by 0.3), and one alone.
    let a = generate::torus(2.0, 0.5, 24, 12);
    let mut b = a.clone();
    for p in &mut b.positions {
        p.x += 0.3;
    }
    let n = a.positions.len() as u32;
    let mut both = a.clone();
    both.positions.extend(b.positions.iter().copied());
    both.faces.extend(
        b.faces
            .iter()
            .map(|f| f.map(|v| envelope_mesh::VertexId(v.0 + n))),
    );
    let raw = |s: &TriangleSoup| s.faces.iter().map(|f| f.map(|v| v.0)).collect::<Vec<_>>();
    let all = envelope_predicates::self_intersections(&both.positions, &raw(&both));
    assert!(!all.is_empty());
    let first = first_self_intersection(&both.positions, &raw(&both)).unwrap();
    assert!(all.contains(&first));
    assert_eq!(first_self_intersection(&a.positions, &raw(&a)), None);
    let opts = Options {
        first_intersection_only: true,
        ..Options::new(1e-3)
    };
    let c = certify(&both, &both, &opts);
    assert_eq!(c.self_intersections.as_ref().unwrap().len(), 1);
    assert!(!c.self_intersections_complete);
    assert_eq!(c.violations(), vec!["self_intersections"]);
}
