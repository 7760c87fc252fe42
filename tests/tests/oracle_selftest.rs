//! Self-test of the CGAL/OpenMesh oracle against hand-known answers, plus a topology sweep of
//! the libcgal-demo corpus. Skips (loudly) when the oracle is unavailable, fails under CI=true.

use std::path::{Path, PathBuf};

use envelope_tests::oracle::{MeshKind, Oracle, corpus_meshes, oracle_or_skip};
use glam::{DVec2, DVec3};

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// Writes OFF text for `(points, triangles)` into `dir/name`.
fn write_off(dir: &Path, name: &str, pts: &[[f64; 3]], faces: &[Vec<usize>]) -> PathBuf {
    let mut s = format!("OFF\n{} {} 0\n", pts.len(), faces.len());
    for p in pts {
        s.push_str(&format!("{} {} {}\n", p[0], p[1], p[2]));
    }
    for f in faces {
        s.push_str(&f.len().to_string());
        for i in f {
            s.push_str(&format!(" {i}"));
        }
        s.push('\n');
    }
    let path = dir.join(name);
    std::fs::write(&path, s).expect("write temp OFF");
    path
}

fn tetra(dir: &Path) -> PathBuf {
    write_off(
        dir,
        "tetra.off",
        &[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
        &[vec![0, 2, 1], vec![0, 1, 3], vec![0, 3, 2], vec![1, 2, 3]],
    )
}

/// An n×m quad-grid torus, triangulated (genus 1, chi 0).
fn torus(dir: &Path, n: usize, m: usize) -> PathBuf {
    let (big, small) = (2.0f64, 0.5f64);
    let mut pts = Vec::new();
    for i in 0..n {
        let u = i as f64 / n as f64 * std::f64::consts::TAU;
        for j in 0..m {
            let w = j as f64 / m as f64 * std::f64::consts::TAU;
            let r = big + small * w.cos();
            pts.push([r * u.cos(), r * u.sin(), small * w.sin()]);
        }
    }
    let id = |i: usize, j: usize| (i % n) * m + (j % m);
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..m {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push(vec![id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    write_off(dir, "torus.off", &pts, &faces)
}

fn oracle() -> Option<Oracle> {
    oracle_or_skip()
}

#[test]
fn version_reports_cgal_and_openmesh() {
    let Some(o) = oracle() else { return };
    let f = o.version();
    assert_eq!(f.get("protocol").map(String::as_str), Some("1"));
    assert!(f.get("cgal").is_some_and(|c| c.starts_with("5.")), "{f:?}");
}

#[test]
fn orient3d_uses_cgal_sign_convention() {
    let Some(o) = oracle() else { return };
    let (a, e1, e2, e3) = (DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z);
    let tiny = f64::from_bits(1); // smallest subnormal: must survive the trip exactly
    let got = o.orient3d_batch(&[
        [a, e1, e2, e3],                 // ((b-a)x(c-a)).(d-a) = 1
        [a, e2, e1, e3],                 // swapped: -1
        [a, e1, e2, v(0.3, 0.4, 0.0)],   // coplanar: 0
        [a, e1, e2, v(5.0, 7.0, tiny)],  // just above the plane: +1
        [a, e1, e2, v(5.0, 7.0, -tiny)], // just below: -1
        // Nearly collinear input where naive evaluation is unreliable: d on the plane z = x.
        [
            v(0.1, 0.0, 0.1),
            v(0.7, 1.0, 0.7),
            v(0.3, 3.0, 0.3),
            v(0.5, 0.5, 0.5),
        ],
    ]);
    assert_eq!(got, vec![1, -1, 0, 1, -1, 0]);
}

#[test]
fn orient2d_counter_clockwise_is_positive() {
    let Some(o) = oracle() else { return };
    let got = o.orient2d_batch(&[
        [DVec2::ZERO, DVec2::X, DVec2::Y],
        [DVec2::ZERO, DVec2::Y, DVec2::X],
        [DVec2::ZERO, DVec2::ONE, DVec2::new(3.0, 3.0)],
    ]);
    assert_eq!(got, vec![1, -1, 0]);
}

#[test]
fn tri_tri_and_seg_tri_known_cases() {
    let Some(o) = oracle() else { return };
    let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
    let got = o.tri_tri_batch(&[
        (t, [v(0.2, 0.2, -1.0), v(0.2, 0.2, 1.0), v(0.3, 0.3, 1.0)]), // pierces
        (t, [v(5.0, 5.0, 5.0), v(6.0, 5.0, 5.0), v(5.0, 6.0, 5.0)]),  // far away
        (t, [v(0.1, 0.1, 0.0), v(2.0, 0.1, 0.0), v(0.1, 2.0, 0.0)]),  // coplanar overlap
        (t, [v(1.0, 1.0, 0.0), v(2.0, 1.0, 0.0), v(1.0, 2.0, 0.0)]),  // coplanar, disjoint
        (t, [v(1.0, 0.0, 0.0), v(2.0, 0.0, 1.0), v(2.0, 1.0, 1.0)]),  // touch at a vertex (closed)
        (t, [v(0.0, 0.0, 1e-300), v(1.0, 0.0, 1.0), v(0.0, 1.0, 1.0)]), // misses by 1e-300
        (t, [v(0.5, -1.0, 0.0), v(0.5, 1.0, 0.0), v(0.5, 2.0, 0.0)]), // degenerate (segment) crossing
        (t, [v(3.0, 3.0, 3.0), v(3.0, 3.0, 3.0), v(3.0, 3.0, 3.0)]),  // degenerate point, outside
    ]);
    assert_eq!(
        got,
        vec![true, false, true, false, true, false, true, false]
    );

    let got = o.seg_tri_batch(&[
        ([v(0.2, 0.2, -1.0), v(0.2, 0.2, 1.0)], t), // through
        ([v(0.2, 0.2, 1.0), v(0.2, 0.2, 2.0)], t),  // above
        ([v(0.2, 0.2, 0.0), v(0.2, 0.2, 2.0)], t),  // endpoint on the triangle
        ([v(-1.0, 0.5, 0.0), v(2.0, 0.5, 0.0)], t), // coplanar crossing
        ([v(0.6, 0.6, -1.0), v(0.6, 0.6, 1.0)], t), // passes beside the hypotenuse
        ([v(0.5, 0.5, 0.0), v(0.5, 0.5, 0.0)], t),  // degenerate point on the hypotenuse
    ]);
    assert_eq!(got, vec![true, false, true, true, false, true]);
}

#[test]
fn point_tri_sqdist_compare_is_exact() {
    let Some(o) = oracle() else { return };
    let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
    let p = v(0.25, 0.25, 1.0); // distance 1 to the interior
    let q = v(2.0, 0.0, 0.0); // distance 1 to vertex (1,0,0)
    let r = v(1.0, 1.0, 0.0); // distance^2 1/2 to the hypotenuse: not a double, so never 0
    let line = [DVec3::ZERO, DVec3::X, v(2.0, 0.0, 0.0)]; // degenerate triangle = segment [0, 2]
    let got = o.point_tri_sqdist_cmp_batch(&[
        (p, t, 1.0),
        (p, t, 0.5),
        (p, t, 2.0),
        (q, t, 1.0),
        (q, t, f64::from_bits(1.0f64.to_bits() - 1)),
        (r, t, 0.5),
        (v(1.0, 1.0, 0.0), line, 1.0),
        (v(3.0, 0.0, 0.0), line, 1.0),
        (v(3.0, 0.0, 0.0), line, 0.5),
    ]);
    assert_eq!(got, vec![0, 1, -1, 0, 1, 0, 0, 0, 1]);
}

#[test]
fn self_intersections_in_file_order() {
    let Some(o) = oracle() else { return };
    let dir = tempfile::tempdir().unwrap();
    // Faces 0 and 2 are far away; face 1 (z=0) is pierced by face 3 (vertical).
    let path = write_off(
        dir.path(),
        "si.off",
        &[
            [10., 10., 10.],
            [11., 10., 10.],
            [10., 11., 10.],
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [20., 20., 20.],
            [21., 20., 20.],
            [20., 21., 20.],
            [0.2, 0.2, -1.],
            [0.2, 0.2, 1.],
            [0.3, 0.3, 1.],
        ],
        &[vec![0, 1, 2], vec![3, 4, 5], vec![6, 7, 8], vec![9, 10, 11]],
    );
    let si = o.try_self_intersections(&path, false).unwrap();
    assert_eq!(si.kind, MeshKind::Mesh);
    assert_eq!((si.vertices, si.faces), (12, 4));
    assert_eq!(si.pairs, vec![(1, 3)]);
    let soup = o.try_self_intersections(&path, true).unwrap();
    assert_eq!(soup.kind, MeshKind::Soup);
    assert_eq!(soup.pairs, vec![(1, 3)]);
    let timing = o.time_does_self_intersect(&path).unwrap();
    assert!(timing.intersects && timing.seconds >= 0.0);

    // A closed tetrahedron does not self-intersect.
    let tet = tetra(dir.path());
    assert_eq!(o.self_intersections(&tet), vec![]);
    assert!(!o.time_does_self_intersect(&tet).unwrap().intersects);
}

#[test]
fn self_intersections_on_non_manifold_soup() {
    let Some(o) = oracle() else { return };
    let dir = tempfile::tempdir().unwrap();
    // Four triangles on the edge (0,1): a non-manifold edge, so not a polygon mesh.
    // Face 3 folds onto face 0 (coplanar, same side of the edge); faces 1 and 2 do not touch 0.
    // Face 4 is degenerate (collinear): reported as (4, 4). Face 5 shares vertex 0 with faces 0
    // and 3 and crosses both away from that vertex (it meets z=0 along (0,0)-(0.4,0.3)).
    let path = write_off(
        dir.path(),
        "nm.off",
        &[
            [0., 0., 0.],
            [1., 0., 0.],
            [0.5, 1., 0.],
            [0.5, -1., 0.],
            [0.5, 0., 1.],
            [0.5, 0.5, 0.],
            [2., 0., 0.],
            [0.4, 0.3, -1.],
            [0.4, 0.3, 1.],
        ],
        &[
            vec![0, 1, 2],
            vec![1, 0, 3],
            vec![0, 1, 4],
            vec![1, 0, 5],
            vec![0, 1, 6],
            vec![0, 7, 8],
        ],
    );
    let si = o.try_self_intersections(&path, false).unwrap();
    assert_eq!(si.kind, MeshKind::Soup);
    assert_eq!(si.pairs, vec![(0, 3), (0, 5), (3, 5), (4, 4)]);
}

#[test]
fn non_triangle_file_is_an_error() {
    let Some(o) = oracle() else { return };
    let dir = tempfile::tempdir().unwrap();
    let quad = write_off(
        dir.path(),
        "quad.off",
        &[[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]],
        &[vec![0, 1, 2, 3]],
    );
    let e = o
        .try_self_intersections(&quad, false)
        .unwrap_err()
        .to_string();
    assert!(e.contains("only triangle meshes"), "{e}");
    assert!(
        o.try_self_intersections(&dir.path().join("missing.off"), false)
            .is_err()
    );
}

#[test]
fn hausdorff_of_shifted_triangle() {
    let Some(o) = oracle() else { return };
    let dir = tempfile::tempdir().unwrap();
    let tri = |z: f64| [[0., 0., z], [1., 0., z], [0., 1., z]];
    let a = write_off(dir.path(), "a.off", &tri(0.0), &[vec![0, 1, 2]]);
    let b = write_off(dir.path(), "b.off", &tri(0.5), &[vec![0, 1, 2]]);
    let big = write_off(
        dir.path(),
        "big.off",
        &[[-1., -1., 0.], [3., -1., 0.], [-1., 3., 0.]],
        &[vec![0, 1, 2]],
    );
    let d = o.hausdorff(&a, &b, 1e-6);
    assert!((d - 0.5).abs() <= 1e-6, "{d}");
    // One-sided: A inside BIG gives 0, BIG to A does not.
    assert!(o.hausdorff(&a, &big, 1e-6) <= 1e-6);
    let back = o.hausdorff(&big, &a, 1e-6);
    assert!((back - 5.0f64.sqrt()).abs() <= 1e-5, "{back}"); // corner (3,-1,0) to (1,0,0)
    let approx = o.hausdorff_approx(&a, &b, 100).unwrap();
    assert!((approx - 0.5).abs() <= 1e-9, "{approx}");
}

#[test]
fn topology_of_tetrahedron_torus_and_open_pieces() {
    let Some(o) = oracle() else { return };
    let dir = tempfile::tempdir().unwrap();
    let tet = o.topology(&tetra(dir.path()));
    for c in [tet.openmesh.as_ref().unwrap(), tet.cgal.as_ref().unwrap()] {
        assert_eq!(
            (c.v, c.f, c.e, c.borders, c.components, c.chi, c.genus),
            (4, 4, 6, 0, 1, 2, Some(0))
        );
    }
    let tor = o.topology(&torus(dir.path(), 8, 6));
    for c in [tor.openmesh.as_ref().unwrap(), tor.cgal.as_ref().unwrap()] {
        assert_eq!(
            (c.v, c.f, c.e, c.borders, c.components, c.chi, c.genus),
            (48, 96, 144, 0, 1, 0, Some(1))
        );
    }
    // Two separate triangles plus an unused vertex: 2 components, 2 borders, 1 isolated vertex.
    let two = write_off(
        dir.path(),
        "two.off",
        &[
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [5., 0., 0.],
            [6., 0., 0.],
            [5., 1., 0.],
            [9., 9., 9.],
        ],
        &[vec![0, 1, 2], vec![3, 4, 5]],
    );
    let t = o.topology(&two);
    for c in [t.openmesh.as_ref().unwrap(), t.cgal.as_ref().unwrap()] {
        assert_eq!(
            (c.v, c.isolated, c.borders, c.components, c.chi, c.genus),
            (7, 1, 2, 2, 2, Some(0))
        );
    }
    assert_eq!(t.file_polygons, Some(2));
}

/// Files above this size are left out of the corpus sweep to keep it quick.
const SWEEP_MAX_BYTES: u64 = 4 << 20;

#[test]
fn topology_sweep_over_corpus() {
    let Some(o) = oracle() else { return };
    let files: Vec<PathBuf> = corpus_meshes()
        .into_iter()
        .filter(|p| {
            let len = std::fs::metadata(p).map(|m| m.len()).unwrap_or(0);
            if len > SWEEP_MAX_BYTES {
                println!("skipping {} ({len} bytes > {SWEEP_MAX_BYTES})", p.display());
            }
            len <= SWEEP_MAX_BYTES
        })
        .collect();
    if files.is_empty() {
        return; // corpus_meshes() already complained (or panicked under CI)
    }
    let topo = o.topology_batch(&files);
    println!(
        "{:<34} {:>7} {:>7} {:>4} {:>4} {:>6}  note",
        "file", "V", "F", "bord", "comp", "genus"
    );
    let (mut both, mut disagree) = (0, Vec::new());
    for (p, t) in files.iter().zip(&topo) {
        let name = p.file_name().unwrap().to_string_lossy();
        let note = match (&t.openmesh, &t.cgal) {
            (Ok(a), Ok(b)) => {
                both += 1;
                let same = (a.v, a.isolated, a.borders, a.components, a.chi, a.genus)
                    == (b.v, b.isolated, b.borders, b.components, b.chi, b.genus);
                // OpenMesh silently drops faces it cannot insert: only compare complete loads.
                if !same && t.file_polygons == Some(b.f) && a.f >= b.f {
                    disagree.push(name.to_string());
                }
                if same {
                    String::new()
                } else {
                    format!("DIFFERS from CGAL {b:?}")
                }
            }
            (Ok(_), Err(c)) => format!("cgal: {c}"),
            (Err(e), Ok(_)) => format!("openmesh: {e}"),
            (Err(e), Err(c)) => format!("openmesh: {e}; cgal: {c}"),
        };
        let show = t.openmesh.as_ref().or(t.cgal.as_ref()).ok();
        match show {
            Some(c) => println!(
                "{name:<34} {:>7} {:>7} {:>4} {:>4} {:>6}  {note}",
                c.v,
                c.f,
                c.borders,
                c.components,
                c.genus.map_or("-".into(), |g| g.to_string())
            ),
            None => println!(
                "{name:<34} {:>7} {:>7} {:>4} {:>4} {:>6}  {note}",
                "-", "-", "-", "-", "-"
            ),
        }
    }
    println!("{} files, {both} loaded by both libraries", files.len());
    assert!(
        both * 10 >= files.len() * 8,
        "too few corpus meshes load in both libraries: {both}/{}",
        files.len()
    );
    assert!(
        disagree.is_empty(),
        "OpenMesh and CGAL disagree on complete loads: {disagree:?}"
    );
}

/// The soup re-implementation must match PMP::self_intersections on valid meshes (small files).
#[test]
fn soup_self_intersections_match_pmp_on_corpus() {
    let Some(o) = oracle() else { return };
    let mut compared = 0;
    for p in corpus_meshes() {
        if std::fs::metadata(&p).map(|m| m.len()).unwrap_or(u64::MAX) > 200_000 {
            continue;
        }
        let Ok(mesh) = o.try_self_intersections(&p, false) else {
            continue;
        }; // polygons, unreadable
        if mesh.kind != MeshKind::Mesh {
            continue;
        }
        let soup = o.try_self_intersections(&p, true).unwrap();
        assert_eq!(mesh.pairs, soup.pairs, "{}", p.display());
        compared += 1;
    }
    if !corpus_meshes().is_empty() {
        assert!(compared >= 20, "only {compared} corpus meshes compared");
    }
}

/// Limits stop a long Hausdorff request instead of letting it run (the corpus sweep met
/// one): one CPU second against a fine torus pair at a tiny error bound
/// ends with `OracleError::Limit`, and the same limited oracle still answers a cheap request.
#[test]
fn limits_stop_a_long_request() {
    use envelope_tests::oracle::{Limits, OracleError};
    let Some(o) = oracle() else { return };
    let dir = tempfile::tempdir().unwrap();
    let named = |n: usize, m: usize, name: &str| {
        let q = dir.path().join(name);
        std::fs::rename(torus(dir.path(), n, m), &q).unwrap();
        q
    };
    let fine = named(400, 200, "fine.off");
    let coarse = named(60, 30, "coarse.off");
    let limited = o.with_limits(Limits {
        cpu_seconds: Some(1),
        address_space_bytes: None,
    });
    match limited.try_hausdorff(&fine, &coarse, 1e-9) {
        Err(OracleError::Limit(m)) => assert!(m.contains("CPU"), "{m}"),
        other => panic!("expected the CPU limit to stop it, got {other:?}"),
    }
    assert_eq!(
        limited.version().get("protocol").map(String::as_str),
        Some("1")
    );
    let small = o.with_limits(Limits {
        cpu_seconds: None,
        address_space_bytes: Some(64 << 20),
    });
    match small.try_hausdorff(&fine, &coarse, 1e-9) {
        Err(OracleError::Limit(m)) => assert!(m.contains("address-space"), "{m}"),
        other => panic!("expected the memory limit to stop it, got {other:?}"),
    }
}
