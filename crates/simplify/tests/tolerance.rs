//! The tolerance phase (module `tolerance`): on thin shapes at epsilons above half their
//! thickness, where the envelopes are cut back and stop the step, it goes on, and every
//! output still passes the certificate with the input's topology.

use envelope_mesh::{TriangleSoup, analyze, generate};
use envelope_offset::EpsilonField;
use envelope_simplify::{SimplifyOptions, SimplifyReport, simplify};
use envelope_verify::Verdict;
use glam::DVec3;
use proptest::prelude::*;

fn scaled(mut soup: TriangleSoup, by: DVec3) -> TriangleSoup {
    for p in &mut soup.positions {
        *p *= by;
    }
    soup
}

/// A flattened sphere (an ear), a thin ring, a spindle (a thin cylinder closed at both
/// ends), a block with a narrow fin and a flattened open cylinder (two border loops): each
/// far thinner (the fin: its fin) than the epsilons below.
fn thin_shapes() -> Vec<(&'static str, TriangleSoup)> {
    vec![
        (
            "ear",
            scaled(generate::icosphere(4, 1.0), DVec3::new(1.0, 0.7, 0.02)),
        ),
        ("ring", generate::torus(1.0, 0.02, 96, 8)),
        (
            "spindle",
            scaled(
                generate::uv_sphere(12, 48, 1.0),
                DVec3::new(0.03, 0.03, 1.0),
            ),
        ),
        ("fin", generate::block_with_fin(0.04)),
        (
            "flat open tube",
            scaled(
                generate::open_cylinder(1.0, 2.0, 64, 8),
                DVec3::new(1.0, 0.03, 1.0),
            ),
        ),
    ]
}

fn run(soup: &TriangleSoup, percent: f64, phase: bool) -> (TriangleSoup, SimplifyReport) {
    let mut options =
        SimplifyOptions::new(EpsilonField::Constant(percent / 100.0 * soup.diagonal()));
    options.verify = true;
    options.tolerance_phase = phase;
    simplify(soup, &options, &mut ()).expect("simplify")
}

/// The certificate holds and the topology is the input's.
fn assert_certified(name: &str, input: &TriangleSoup, out: &TriangleSoup, r: &SimplifyReport) {
    let v = r.verify.as_ref().expect("certified");
    assert_eq!(v.verdict, Verdict::Holds, "{name}: {:?}", v.violations);
    let (a, b) = (analyze(input), analyze(out));
    assert_eq!(
        (a.genus, a.components.len(), a.num_border_loops()),
        (b.genus, b.components.len(), b.num_border_loops()),
        "{name}: topology"
    );
}

#[test]
fn thin_shapes_go_on_past_the_envelopes() {
    for (name, soup) in thin_shapes() {
        let mut faces = Vec::new();
        for percent in [2.0, 4.0] {
            let (plain, plain_report) = run(&soup, percent, false);
            let (past, report) = run(&soup, percent, true);
            assert_certified(name, &soup, &plain, &plain_report);
            assert_certified(name, &soup, &past, &report);
            eprintln!(
                "{name} at {percent}%: {} -> {} faces, {} with the phase",
                soup.num_faces(),
                plain.num_faces(),
                past.num_faces()
            );
            let phase = report.tolerance_phase.as_ref().expect("the phase ran");
            assert!(phase.removed_vertices > 0, "{name} at {percent}%");
            assert!(
                past.num_faces() < plain.num_faces(),
                "{name} at {percent}%: {} faces, {} without the phase",
                past.num_faces(),
                plain.num_faces()
            );
            // Above the cap the envelopes are built at the cap.
            assert!(phase.envelope_epsilon_abs <= report.epsilon_abs);
            faces.push(past.num_faces());
        }
        // Doubling epsilon keeps paying: no plateau.
        assert!(
            faces[1] < faces[0] || faces[1] <= 8,
            "{name}: {faces:?} faces at 2% and 4%"
        );
    }
}

/// The border vertices on a loop of `soup`.
fn border_vertices(soup: &TriangleSoup) -> usize {
    let mesh = envelope_mesh::HalfEdgeMesh::from_soup(soup).expect("a manifold mesh");
    mesh.vertices()
        .filter(|&v| mesh.is_border_vertex(v))
        .count()
}

#[test]
fn the_phase_removes_border_vertices() {
    // Two circles of 96 segments, round within a thousandth: at 4 % (the envelopes built
    // at the 1 % cap) the phase goes on along the borders past where the step at 1 % left
    // them, and the two loops stay.
    let soup = generate::open_cylinder(1.0, 0.5, 96, 4);
    let (at_cap, cap_report) = run(&soup, 1.0, true);
    let (past, report) = run(&soup, 4.0, true);
    assert_certified("open cylinder", &soup, &at_cap, &cap_report);
    assert_certified("open cylinder", &soup, &past, &report);
    let (before, after) = (border_vertices(&at_cap), border_vertices(&past));
    eprintln!("open cylinder: {before} border vertices at 1 %, {after} at 4 %");
    assert!(report.tolerance_phase.is_some());
    assert!(
        3 * after < 2 * before,
        "{after} border vertices at 4 %, {before} at 1 %"
    );
}

#[test]
fn the_phase_waits_for_envelopes_that_bind() {
    // A round sphere at a small epsilon: nothing is cut back, the phase does not run.
    let soup = generate::icosphere(3, 1.0);
    let (_, report) = run(&soup, 0.25, true);
    assert!(report.tolerance_phase.is_none());
    assert!(report.envelope.achieved_p5 >= envelope_simplify::TOLERANCE_WHEN_CUT_BELOW);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]
    /// Flattened spheres of random thickness, tilt and epsilon: every output passes the
    /// certificate with the input's topology.
    #[test]
    fn thin_outputs_are_certified(
        thickness in 0.005f64..0.08,
        tilt in 0.0f64..1.5,
        percent in prop::sample::select(vec![0.5, 1.0, 2.0, 4.0, 8.0]),
    ) {
        let (s, c) = tilt.sin_cos();
        let mut soup = scaled(generate::icosphere(3, 1.0), DVec3::new(1.0, 0.8, thickness));
        for p in &mut soup.positions {
            *p = DVec3::new(c * p.x - s * p.z, p.y, s * p.x + c * p.z);
        }
        let (out, report) = run(&soup, percent, true);
        assert_certified("flattened sphere", &soup, &out, &report);
    }
}
