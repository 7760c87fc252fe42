//! `envelope_offset::build_envelopes` (Cohen et al. 4.1, 4.2) against CGAL.
//!
//! On generated meshes (icosphere, torus, open cylinder, box) and one small corpus mesh, both
//! methods, epsilon 1/4 % and 1 % of the diagonal:
//!
//! 1. **Non-intersection.** Input, outer and inner envelope are written as one OFF with no
//!    shared vertices between the three (so a touching envelope counts), exactly the doubles
//!    our proof ran on; CGAL's `PMP::self_intersections` must find no pair.
//! 2. **Distance.** CGAL's `bounded_error_Hausdorff_distance` envelope → input (one-sided,
//!    error bound `b`) must lie in `[lo - b - s, hi + b + s]` (`s = 1e-9 D` covers the f64
//!    arithmetic of our bounds), where
//!    - `hi = max_v |v' - v|`: every envelope point is a convex combination `Σλ_i v'_i` of an
//!      envelope face's vertices, at distance `<= Σλ_i |v'_i - v_i| <= hi` from the point
//!      `Σλ_i v_i` of the input face; `hi <= max_v eps_v (1 + 1e-12)` is asserted too,
//!    - `lo = max_v d(v', input)`: the one-sided distance is at least the distance of any
//!      envelope point, in particular of each offset vertex (brute force, f64).
//!
//!    Both bounds are attained near offset vertices on a closed, well-shaped envelope, so
//!    the interval is narrow in practice; it is sound regardless.

use std::path::Path;

use envelope_io::{Format, read_path, write_path};
use envelope_mesh::{TriangleSoup, generate};
use envelope_offset::{EnvelopeMethod, EnvelopeOptions, Envelopes, EpsilonField, build_envelopes};
use envelope_tests::r#gen::sq_dist_point_triangle_f64;
use envelope_tests::oracle::{Oracle, corpus_meshes, oracle_or_skip};
use glam::DVec3;

/// Largest corpus file tried (keeps the debug run short).
const MAX_BYTES: u64 = 40_000;

fn union(parts: &[&TriangleSoup]) -> TriangleSoup {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for p in parts {
        let base = positions.len() as u32;
        positions.extend_from_slice(&p.positions);
        faces.extend(
            p.faces
                .iter()
                .map(|f| f.map(|v| envelope_mesh::VertexId(v.0 + base))),
        );
    }
    TriangleSoup::new(positions, faces)
}

/// Writes `soup` and checks that CGAL reads back exactly these doubles.
fn write_exact(path: &Path, soup: &TriangleSoup) {
    write_path(path, soup, Format::Off).unwrap();
    assert_eq!(&read_path(path).unwrap().0, soup, "{}", path.display());
}

fn max_dist_to(points: &[DVec3], soup: &TriangleSoup) -> f64 {
    points
        .iter()
        .map(|&p| {
            soup.faces
                .iter()
                .map(|f| sq_dist_point_triangle_f64(p, f.map(|v| soup.positions[v.0 as usize])))
                .fold(f64::INFINITY, f64::min)
                .sqrt()
        })
        .fold(0.0, f64::max)
}

fn check_case(oracle: &Oracle, dir: &Path, name: &str, input: &TriangleSoup) -> usize {
    let input_path = dir.join("input.off");
    write_exact(&input_path, input);
    let d = input.diagonal();
    let mut checked = 0;
    for method in [EnvelopeMethod::Numerical, EnvelopeMethod::Analytical] {
        for t in [0.0025, 0.01] {
            let label = format!("{name} {method:?} eps={t}D");
            let mut o = EnvelopeOptions::new(EpsilonField::Constant(t * d));
            o.method = method;
            o.tube_segments = None;
            let env: Envelopes =
                build_envelopes(input, &o).unwrap_or_else(|e| panic!("{label}: {e}"));
            assert!(env.proof.envelopes_hold(), "{label}: our proof failed");
            // 1. CGAL finds no self-intersection in input + outer + inner.
            let all_path = dir.join("union.off");
            write_exact(&all_path, &union(&[input, &env.outer, &env.inner]));
            let pairs = oracle.self_intersections(&all_path);
            assert!(
                pairs.is_empty(),
                "{label}: CGAL finds {} pairs: {:?}",
                pairs.len(),
                &pairs[..pairs.len().min(8)]
            );
            // 2. One-sided distance envelope -> input.
            for (side, soup, eps) in [
                ("outer", &env.outer, &env.eps_plus),
                ("inner", &env.inner, &env.eps_minus),
            ] {
                let path = dir.join(format!("{side}.off"));
                write_exact(&path, soup);
                let hi = soup
                    .positions
                    .iter()
                    .zip(&input.positions)
                    .map(|(a, b)| (*a - *b).length())
                    .fold(0.0, f64::max);
                let max_eps = eps.iter().copied().fold(0.0, f64::max);
                assert!(
                    hi <= max_eps * (1.0 + 1e-12),
                    "{label} {side}: offset {hi} > eps {max_eps}"
                );
                let lo = max_dist_to(&soup.positions, input);
                let bound = 1e-3 * t * d;
                let slack = bound + 1e-9 * d;
                let h = oracle.hausdorff(&path, &input_path, bound);
                assert!(
                    lo - slack <= h && h <= hi + slack,
                    "{label} {side}: CGAL {h} outside [{lo}, {hi}] (+- {slack})"
                );
                assert!(
                    lo > 0.0,
                    "{label} {side}: an offset vertex lies on the input"
                );
                eprintln!(
                    "{label} {side}: CGAL {h:.3e} in [{lo:.3e}, {hi:.3e}], max eps {max_eps:.3e}"
                );
            }
            checked += 1;
        }
    }
    checked
}

#[test]
fn envelopes_agree_with_cgal_on_generated_meshes() {
    let Some(oracle) = oracle_or_skip() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("icosphere(2)", generate::icosphere(2, 1.0)),
        ("torus 24x10", generate::torus(1.0, 0.3, 24, 10)),
        (
            "open cylinder 16x4",
            generate::open_cylinder(0.5, 1.5, 16, 4),
        ),
        (
            "box 1x2x3",
            generate::box_mesh(DVec3::new(1.0, 2.0, 3.0), 3),
        ),
    ];
    let mut checked = 0;
    for (name, soup) in &cases {
        checked += check_case(&oracle, dir.path(), name, soup);
    }
    assert_eq!(checked, 4 * 4);
}

#[test]
fn envelopes_agree_with_cgal_on_a_corpus_mesh() {
    let Some(oracle) = oracle_or_skip() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    for path in corpus_meshes() {
        if std::fs::metadata(&path).map_or(true, |m| m.len() > MAX_BYTES) {
            continue;
        }
        let Ok((soup, report)) = read_path(&path) else {
            continue;
        };
        let topo = envelope_mesh::analyze(&soup);
        if report.polygons_triangulated > 0
            || !topo.manifold
            || !topo.consistently_oriented
            || soup.faces.len() < 200
            || build_envelopes(
                &soup,
                &EnvelopeOptions::new(EpsilonField::Constant(1e-3 * soup.diagonal())),
            )
            .is_err()
            || !oracle.self_intersections(&path).is_empty()
        {
            continue;
        }
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let checked = check_case(&oracle, dir.path(), &name, &soup);
        assert_eq!(checked, 4, "{name}");
        return;
    }
    assert!(corpus_meshes().is_empty(), "no corpus mesh qualified");
}
