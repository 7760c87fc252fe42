//! Self-intersecting input: the faces around the intersecting pairs are kept as they are,
//! the rest is simplified, and the certificate holds with the input's own intersections
//! allowed (every intersecting pair of the output is a pair of unchanged input faces).

use envelope_check::intersecting_pairs;
use envelope_mesh::{TriangleSoup, VertexId, analyze, generate};
use envelope_offset::EpsilonField;
use envelope_simplify::{DriverError, Placement, SimplifyOptions, simplify};
use envelope_verify::{Options, Verdict, certify};
use glam::DVec3;

/// `a` and `b` as one soup, `b` moved by `offset`.
fn union(a: &TriangleSoup, b: &TriangleSoup, offset: DVec3) -> TriangleSoup {
    let n = a.num_vertices() as u32;
    let mut s = a.clone();
    s.positions.extend(b.positions.iter().map(|&p| p + offset));
    s.faces
        .extend(b.faces.iter().map(|f| f.map(|v| VertexId(v.0 + n))));
    s
}

fn options(eps: f64, placement: Placement) -> SimplifyOptions {
    SimplifyOptions {
        placement,
        verify: true,
        ..SimplifyOptions::new(EpsilonField::Constant(eps))
    }
}

/// The two spheres meet along a circle: the faces there stay, the rest simplifies, and the
/// only intersecting pairs of the output are input pairs.
#[test]
fn interpenetrating_spheres_simplify_around_their_circle() {
    let sphere = generate::icosphere(4, 1.0);
    let soup = union(&sphere, &sphere, DVec3::new(1.2, 0.1, 0.05));
    let pairs = intersecting_pairs(&soup, None).expect("decided");
    assert!(!pairs.is_empty());
    for placement in [Placement::Subset, Placement::Collapse] {
        let (out, report) = simplify(&soup, &options(0.02, placement), &mut ()).unwrap();
        let kept = report.kept.clone().expect("kept around the crossings");
        assert_eq!(kept.intersecting_pairs, pairs.len());
        assert!(kept.kept_faces >= 2 && kept.shared_vertices > 0);
        assert!(
            out.num_faces() < soup.num_faces() / 3,
            "{placement:?}: {} of {} faces",
            out.num_faces(),
            soup.num_faces()
        );
        let v = report.verify.expect("certified");
        assert_eq!(v.verdict, Verdict::Holds, "{:?}", v.violations);
        assert!(!v.certificate.kept_intersections.is_empty());
        // Independently: strict, the output's intersections are all there, each a pair of
        // input faces, and nothing else is violated.
        let strict = certify(&soup, &out, &Options::new(0.02));
        assert_eq!(strict.violations(), vec!["self_intersections"]);
        assert_eq!(
            strict.self_intersections.as_ref().unwrap().len(),
            v.certificate.kept_intersections.len()
        );
        let (a, b) = (analyze(&soup), analyze(&out));
        assert_eq!((a.genus, a.components.len()), (b.genus, b.components.len()));
    }
}

/// A torus pushed through a sphere: two components meeting along two circles.
#[test]
fn torus_through_sphere() {
    let torus = generate::torus(1.0, 0.25, 48, 16);
    let sphere = generate::icosphere(3, 0.6);
    let soup = union(&torus, &sphere, DVec3::new(1.0, 0.0, 0.0));
    let (out, report) = simplify(&soup, &options(0.01, Placement::Auto), &mut ()).unwrap();
    assert!(report.kept.is_some());
    assert!(out.num_faces() < soup.num_faces() / 2);
    assert_eq!(report.verify.unwrap().verdict, Verdict::Holds);
    assert_eq!(analyze(&out).genus, Some(1));
}

/// An input meeting itself nowhere is simplified as before: no kept report.
#[test]
fn clean_input_keeps_nothing() {
    let sphere = generate::icosphere(3, 1.0);
    let (_, report) = simplify(&sphere, &options(0.02, Placement::Subset), &mut ()).unwrap();
    assert!(report.kept.is_none());
}

/// Other error classes are still refused.
#[test]
fn non_manifold_input_still_refused() {
    let soup = generate::three_triangles_on_edge();
    assert!(matches!(
        simplify(&soup, &options(0.02, Placement::Subset), &mut ()),
        Err(DriverError::Unacceptable(_))
    ));
}

/// Two spheres touching at one point through two vertices at the same position (what repair
/// leaves of a pinch): duplicate vertices whose faces meet there, kept as they are.
#[test]
fn spheres_touching_at_a_duplicated_vertex() {
    let sphere = generate::icosphere(3, 1.0);
    // The icosphere is symmetric through its centre: the second one, moved by twice vertex
    // 0, touches the first there with its antipode of vertex 0.
    let p0 = sphere.positions[0];
    let antipode = sphere
        .positions
        .iter()
        .position(|&p| p == -p0)
        .expect("an antipodal vertex");
    let soup = union(&sphere, &sphere, 2.0 * p0);
    assert_eq!(
        soup.positions[0],
        soup.positions[sphere.num_vertices() + antipode]
    );
    let (out, report) = simplify(&soup, &options(0.02, Placement::Subset), &mut ()).unwrap();
    let kept = report.kept.expect("kept around the touching point");
    assert!(kept.kept_faces >= 10, "{kept:?}");
    assert!(out.num_faces() < soup.num_faces() / 2);
    assert_eq!(report.verify.unwrap().verdict, Verdict::Holds);
}

/// Envelopes that cannot be proved in one place (two parallel sheets 2^-50 apart, beside a
/// sphere): the sheets' faces are kept as they are, the sphere is simplified.
#[test]
fn unprovable_part_is_kept_and_the_rest_simplified() {
    let d = 8.881784197001252e-16;
    let sheets = TriangleSoup::from_raw(
        &[
            [0., 0., 0.],
            [1., 0., 0.],
            [1., 1., 0.],
            [0., 1., 0.],
            [0., 0., d],
            [1., 0., d],
            [1., 1., d],
            [0., 1., d],
        ],
        &[[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]],
    );
    let sphere = generate::icosphere(3, 1.0);
    let soup = union(&sphere, &sheets, DVec3::new(3.0, 0.0, 0.0));
    assert!(intersecting_pairs(&soup, None).unwrap().is_empty());
    let (out, report) = simplify(&soup, &options(0.02, Placement::Subset), &mut ()).unwrap();
    let kept = report.kept.expect("kept where unproved");
    assert_eq!((kept.intersecting_pairs, kept.kept_faces), (0, 4));
    assert!(out.num_faces() < sphere.num_faces() / 3);
    assert_eq!(report.verify.unwrap().verdict, Verdict::Holds);
    // The sheets alone: everything would be kept, so nothing is made.
    assert!(matches!(
        simplify(&sheets, &options(0.02, Placement::Subset), &mut ()),
        Err(DriverError::UnprovedEnvelopes { .. })
    ));
}

/// A flat plate whose top border zigzags (every border edge turns back by almost half a
/// turn, jittered out of the plane): the border tube meets itself there at any radius, which
/// names no input face. The faces around those border vertices are kept, and the rest of
/// the plate is simplified; before, every round kept the same (nothing) and no output was
/// made.
#[test]
fn a_border_turning_back_on_itself_is_kept_and_the_rest_simplified() {
    let (columns, rows, dx) = (12, 10, 0.02);
    let mut state = 7919u64;
    let mut jitter = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        0.01 * ((state % 10_000) as f64 / 10_000.0 - 0.5)
    };
    let mut positions = Vec::new();
    for r in 0..rows {
        for c in 0..columns {
            positions.push(DVec3::new(c as f64 * dx, -(r as f64) * 0.1, 0.0));
        }
    }
    for c in 0..columns {
        let up = 1.0 + (c % 2) as f64;
        positions.push(DVec3::new(c as f64 * dx + jitter(), up, jitter()));
    }
    let at = |r: usize, c: usize| {
        VertexId(if r == 0 {
            rows * columns + c
        } else {
            (r - 1) * columns + c
        } as u32)
    };
    let mut faces = Vec::new();
    for r in 0..rows {
        for c in 0..columns - 1 {
            // Row r (0: the zigzag) above row r + 1.
            let (a, b, d, e) = (at(r + 1, c), at(r + 1, c + 1), at(r, c + 1), at(r, c));
            faces.push([a, b, d]);
            faces.push([a, d, e]);
        }
    }
    let soup = TriangleSoup::new(positions, faces);
    assert!(analyze(&soup).manifold);
    let (out, report) = simplify(&soup, &options(0.05, Placement::Subset), &mut ()).unwrap();
    let kept = report.kept.expect("kept where the tube meets itself");
    assert_eq!(kept.intersecting_pairs, 0);
    // The zigzag row and the ring around it at most.
    assert!(
        kept.kept_faces > 0 && kept.kept_faces <= 4 * (columns - 1),
        "{kept:?}"
    );
    assert!(
        out.num_faces() < soup.num_faces() / 2,
        "{}",
        out.num_faces()
    );
    assert_eq!(report.verify.unwrap().verdict, Verdict::Holds);
}
