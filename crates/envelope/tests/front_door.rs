//! The front door's promises: validation before work, one error type, cancellation, and the
//! defaults.

use std::ops::ControlFlow;
use std::sync::Mutex;

use envelope::{
    Epsilon, Error, Event, Genus, Lod, Mesh, MeshError, Method, Placement, Simplifier, Stage,
    Verdict,
};

fn cup() -> Mesh {
    Mesh::demo()
}

#[test]
fn mesh_new_names_the_bad_element() {
    let e = Mesh::new(vec![[0.0; 3], [1.0, f64::NAN, 0.0]], vec![]).unwrap_err();
    assert!(
        matches!(e, MeshError::NonFiniteCoordinate { vertex: 1, .. }),
        "{e}"
    );
    let e = Mesh::new(vec![[0.0; 3]; 3], vec![[0, 1, 2], [0, 1, 3]]).unwrap_err();
    assert!(
        matches!(
            e,
            MeshError::IndexOutOfRange {
                triangle: 1,
                vertices: 3,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("triangle 1 [0, 1, 3]"), "{e}");
    let square = Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    assert_eq!(square.positions().nth(2), Some([1.0, 1.0, 0.0]));
    assert_eq!(
        square.triangles().collect::<Vec<_>>(),
        [[0, 1, 2], [0, 2, 3]]
    );
    assert!((square.diagonal() - 2f64.sqrt()).abs() < 1e-15);
}

#[test]
fn files_round_trip_and_refuse_unknown_formats() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["obj", "off", "ply", "stl"] {
        let path = dir.path().join(format!("cup.{ext}"));
        envelope::save(&cup(), &path).unwrap();
        let back = envelope::load(&path).unwrap();
        assert_eq!(back.num_faces(), cup().num_faces(), "{ext}");
    }
    let e = envelope::save(&cup(), dir.path().join("cup.txt")).unwrap_err();
    assert!(matches!(e, Error::UnknownFormat(_)), "{e}");
    assert!(!dir.path().join("cup.txt").exists());
    std::fs::write(dir.path().join("bad.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n").unwrap();
    let e = envelope::load(dir.path().join("bad.off")).unwrap_err();
    assert!(matches!(e, Error::Read(_)), "{e}");
    assert!(e.to_string().contains("bad.off"), "{e}");
}

#[test]
fn arguments_are_refused_before_any_work() {
    let said = Mutex::new(Vec::new());
    let record = |e: Event| {
        said.lock().unwrap().push(e);
        ControlFlow::Continue(())
    };
    let run = |s: Simplifier<'_>| s.run(&cup()).map(|_| ()).unwrap_err();
    let e = run(Simplifier::new(Epsilon::percent(-1.0)).progress(record));
    assert!(matches!(e, Error::InvalidEpsilon(_)), "{e}");
    let e = run(Simplifier::new(Epsilon::absolute(f64::INFINITY)).progress(record));
    assert!(matches!(e, Error::InvalidEpsilon(_)), "{e}");
    let e = run(Simplifier::per_vertex(vec![Epsilon::percent(1.0); 3]).progress(record));
    assert!(e.to_string().contains("3 per-vertex epsilons"), "{e}");
    let e = run(Simplifier::new(Epsilon::percent(1.0))
        .method(Method::Global)
        .placement(Placement::Collapse)
        .progress(record));
    assert!(matches!(e, Error::InvalidArgument(_)), "{e}");
    let e = run(Simplifier::new(Epsilon::percent(1.0))
        .threads(0)
        .progress(record));
    assert!(matches!(e, Error::InvalidArgument(_)), "{e}");
    let e = run(Simplifier::new(Epsilon::percent(1.0))
        .tube_segments(Some(2))
        .progress(record));
    assert!(matches!(e, Error::InvalidArgument(_)), "{e}");
    assert!(
        said.lock().unwrap().is_empty(),
        "work began: {:?}",
        said.lock().unwrap()
    );
    let e = Lod::new(vec![Epsilon::percent(1.0), Epsilon::percent(0.5)])
        .run(&cup())
        .unwrap_err();
    assert!(e.to_string().contains("must increase"), "{e}");
    let e = Genus::new(Epsilon::percent(1.0))
        .beta_degrees(180.0)
        .run(&cup())
        .unwrap_err();
    assert!(matches!(e, Error::Genus(_)), "{e}");
    assert!("1/0%".parse::<Epsilon>().is_err());
}

#[test]
fn a_callback_hears_the_stages_and_can_cancel() {
    let said = Mutex::new(Vec::new());
    let done = Simplifier::new(Epsilon::percent(1.0))
        .threads(2)
        .progress(|e| {
            said.lock().unwrap().push(e);
            ControlFlow::Continue(())
        })
        .run(&cup())
        .unwrap();
    assert!(done.is_certified(), "{:?}", done.violations());
    let said = said.into_inner().unwrap();
    let stages: Vec<Stage> = said
        .iter()
        .filter_map(|e| match e {
            Event::Stage(s) => Some(*s),
            _ => None,
        })
        .collect();
    assert_eq!(stages.first(), Some(&Stage::Check));
    assert_eq!(stages.last(), Some(&Stage::Verify));

    for stop_at in [Stage::Envelopes, Stage::Simplify { vertices: 0 }] {
        let e = Simplifier::new(Epsilon::percent(1.0))
            .progress(|e| match e {
                Event::Stage(s)
                    if std::mem::discriminant(&s) == std::mem::discriminant(&stop_at) =>
                {
                    ControlFlow::Break(())
                }
                _ => ControlFlow::Continue(()),
            })
            .run(&cup())
            .map(|_| ())
            .unwrap_err();
        assert!(matches!(e, Error::Cancelled), "stop at {stop_at:?}: {e}");
    }
    let e = Lod::new(vec![Epsilon::percent(0.5), Epsilon::percent(1.0)])
        .progress(|e| match e {
            Event::Level { index: 2, .. } => ControlFlow::Break(()),
            _ => ControlFlow::Continue(()),
        })
        .run(&cup())
        .unwrap_err();
    assert!(matches!(e, Error::Cancelled), "{e}");
}

#[test]
fn defaults_certify_and_keep_the_topology() {
    let cup = cup();
    let done = Simplifier::new("1%".parse().unwrap()).run(&cup).unwrap();
    let c = done.certificate().expect("certified by default");
    assert_eq!(c.verdict, Verdict::Holds);
    assert!(c.approx_to_orig.upper <= Epsilon::percent(1.0).resolve(&cup));
    assert_eq!(done.report().genus_out, done.report().genus_in);
    assert!(done.mesh().num_faces() < cup.num_faces() / 4);
    let again = envelope::verify(&cup, done.mesh(), Epsilon::percent(1.0)).unwrap();
    assert!(again.holds());
    let too_tight = envelope::verify(&cup, done.mesh(), Epsilon::percent(0.01)).unwrap();
    assert_eq!(too_tight.verdict, Verdict::Violated);
    let unchecked = Simplifier::new(Epsilon::percent(1.0))
        .certify(false)
        .run(&cup)
        .unwrap();
    assert!(unchecked.certificate().is_none() && !unchecked.is_certified());
    assert_eq!(
        unchecked.mesh(),
        done.mesh(),
        "certifying changes no output"
    );
    assert!(envelope::check(&cup).acceptable());
}
