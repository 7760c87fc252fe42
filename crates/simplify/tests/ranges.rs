//! Epsilon and coordinates at the ends of their ranges: every mesh the checker accepts either
//! simplifies with a certificate or is refused up front, naming the reason.

use envelope_mesh::{TriangleSoup, generate};
use envelope_offset::{EnvelopeError, EpsilonField};
use envelope_simplify::{DriverError, SimplifyOptions, simplify};
use envelope_verify::Verdict;

fn scaled(soup: &TriangleSoup, s: f64) -> TriangleSoup {
    let mut out = soup.clone();
    for p in &mut out.positions {
        *p *= s;
    }
    out
}

fn run(soup: &TriangleSoup, eps: f64) -> Result<(TriangleSoup, f64), DriverError> {
    let options = SimplifyOptions {
        verify: true,
        ..SimplifyOptions::new(EpsilonField::Constant(eps))
    };
    let (out, report) = simplify(soup, &options, &mut ())?;
    assert_eq!(report.verify.unwrap().verdict, Verdict::Holds);
    Ok((out, report.epsilon_abs))
}

#[test]
fn tiny_and_huge_scales_simplify_with_a_certificate() {
    // Vertices with exact zero coordinates: their offsets along rounding-noise normal
    // components land below 2^-120 unless flushed.
    let sphere = generate::icosphere(2, 1.0);
    assert!(sphere.positions.iter().any(|p| p.x == 0.0));
    for s in [2f64.powi(-100), 1e-20, 1.0, 1e20, 2f64.powi(110)] {
        let soup = scaled(&sphere, s);
        let (out, _) = run(&soup, 0.02 * soup.diagonal()).unwrap_or_else(|e| panic!("{s}: {e}"));
        assert!(out.num_faces() < sphere.num_faces(), "scale {s}");
    }
}

#[test]
fn an_epsilon_above_the_diagonal_acts_as_the_diagonal() {
    let sphere = generate::icosphere(2, 1.0);
    for eps in [1e3, 1e20, 1e300] {
        let (_, used) = run(&sphere, eps).unwrap();
        assert_eq!(used, sphere.diagonal(), "{eps}");
    }
}

#[test]
fn an_epsilon_lost_in_rounding_is_refused() {
    let sphere = generate::icosphere(2, 1.0);
    for eps in [1e-13, 1e-16, 1e-30, 1e-200, 5e-324] {
        match run(&sphere, eps) {
            Err(DriverError::Envelope(EnvelopeError::EpsilonTooSmall { epsilon, .. })) => {
                assert_eq!(epsilon, eps);
            }
            other => panic!("{eps}: {:?}", other.map(|(o, e)| (o.num_faces(), e))),
        }
    }
    assert!(run(&sphere, 1e-11).is_ok());
}

#[test]
fn coordinates_near_the_top_of_the_range_are_refused() {
    let soup = scaled(&generate::icosphere(1, 1.0), 2f64.powi(119));
    assert!(matches!(
        run(&soup, 0.01 * soup.diagonal()),
        Err(DriverError::Envelope(
            EnvelopeError::CoordinatesTooLarge { .. }
        ))
    ));
}

#[test]
fn tube_rings_need_three_to_sixty_four_vertices() {
    let mut disk = generate::icosphere(1, 1.0);
    disk.faces.truncate(disk.faces.len() / 2);
    for (k, ok) in [
        (2, false),
        (3, true),
        (64, true),
        (65, false),
        (u32::MAX, false),
    ] {
        let options = SimplifyOptions {
            tube_segments: Some(k),
            ..SimplifyOptions::new(EpsilonField::Constant(0.01))
        };
        let result = simplify(&disk, &options, &mut ());
        match result {
            Err(DriverError::Envelope(EnvelopeError::TubeSegments(got))) => {
                assert!(!ok, "{k}");
                assert_eq!(got, k);
            }
            Ok(_) => assert!(ok, "{k}"),
            Err(e) => panic!("{k}: {e}"),
        }
    }
}
