//! `envelope_verify::certify` against CGAL's `PMP::bounded_error_Hausdorff_distance`, both
//! directions, on libcgal-demo corpus meshes and approximations built here.
//!
//! Approximations (no CGAL/OpenMesh simplifier is driven by the oracle yet): `noise`, every
//! vertex moved by a pseudo-random vector shorter than `t D` (`D` the bounding-box diagonal,
//! same connectivity, so CGAL loads it as a mesh), at `t` = 1/16 %, 1/4 % and 1 %.
//! Epsilon is `t D`: the distance verdicts must hold (every point moves less than `t D`), and
//! CGAL's value (error bound `1e-3 eps`) must lie in our certified interval in both directions.
//! Then epsilon `0.5 x` CGAL's value must be violated with a witness.

use std::path::Path;

use envelope_io::{Format, read_path, write_path};
use envelope_mesh::TriangleSoup;
use envelope_tests::oracle::{corpus_meshes, oracle_or_skip};
use envelope_verify::{Options, Verdict, certify};
use glam::DVec3;

/// Largest corpus file used (keeps the debug run short).
const MAX_BYTES: u64 = 200_000;
/// Meshes used (the first that qualify, in name order).
const MAX_MESHES: usize = 8;

fn noise(soup: &TriangleSoup, r: f64, seed: u64) -> TriangleSoup {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut out = soup.clone();
    for p in &mut out.positions {
        *p += DVec3::new(next(), next(), next()) * (0.999 * r / 3f64.sqrt());
    }
    out
}

fn written(path: &Path, soup: &TriangleSoup) -> TriangleSoup {
    write_path(path, soup, Format::Off).unwrap();
    read_path(path).unwrap().0
}

#[test]
fn intervals_contain_cgal_bounded_error_hausdorff() {
    let Some(oracle) = oracle_or_skip() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let mut checked = 0;
    let mut meshes = 0;
    for path in corpus_meshes() {
        if meshes == MAX_MESHES {
            break;
        }
        if std::fs::metadata(&path).map_or(true, |m| m.len() > MAX_BYTES) {
            continue;
        }
        let Ok((orig, report)) = read_path(&path) else {
            continue;
        };
        let topo = envelope_mesh::analyze(&orig);
        if report.polygons_triangulated > 0 || !topo.manifold || orig.faces.len() < 100 {
            continue;
        }
        meshes += 1;
        // Exactly the doubles CGAL reads.
        let orig_path = dir.path().join("orig.off");
        let orig = written(&orig_path, &orig);
        let d = orig.diagonal();
        for (k, t) in [1.0 / 1600.0, 0.0025, 0.01].into_iter().enumerate() {
            let eps = t * d;
            let approx_path = dir.path().join("approx.off");
            let approx = written(&approx_path, &noise(&orig, eps, k as u64 + 1));
            let bound = 1e-3 * eps;
            let (Ok(h_ao), Ok(h_oa)) = (
                oracle.try_hausdorff(&approx_path, &orig_path, bound),
                oracle.try_hausdorff(&orig_path, &approx_path, bound),
            ) else {
                eprintln!("{}: CGAL refused the pair", path.display());
                continue;
            };
            let c = certify(&orig, &approx, &Options::distance_only(eps));
            let name = path.file_name().unwrap().to_string_lossy();
            assert_eq!(c.verdict, Verdict::Holds, "{name} t={t}: {c:#?}");
            for (s, h) in [(&c.approx_to_orig, h_ao), (&c.orig_to_approx, h_oa)] {
                assert!(
                    s.lower <= h + bound && h - bound <= s.upper,
                    "{name} t={t}: CGAL {h} outside [{}, {}]",
                    s.lower,
                    s.upper
                );
            }
            // Half of CGAL's value (well beyond its error bound): violated, with a witness.
            let h = h_ao.max(h_oa);
            if h > 10.0 * bound {
                let c = certify(&orig, &approx, &Options::distance_only(0.5 * h));
                assert_eq!(c.verdict, Verdict::Violated, "{name} t={t}");
                let w = c
                    .approx_to_orig
                    .witness
                    .as_ref()
                    .or(c.orig_to_approx.witness.as_ref())
                    .unwrap();
                assert!(w.distance > 0.5 * h);
            }
            checked += 1;
        }
    }
    eprintln!("{checked} pairs checked against CGAL");
    assert!(checked > 0 || corpus_meshes().is_empty());
}
