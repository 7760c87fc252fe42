//! Correspondences between levels (Cohen et al. 8.1, `envelope_simplify::correspondence`)
//! checked independently of how they are computed:
//!
//! - every listed pair is confirmed on the prism's three tetrahedra (`Prism::tetrahedra`) by
//!   point-in-tetrahedron orientations and triangle-triangle tests, not the polyhedral test
//!   the module uses;
//! - on small closed levels, every pair of faces is tried by brute force: nothing is missing;
//! - sample points of each coarse face lie in a prism listed for it, their distance to the
//!   finer level is within the face's error bound, and the finer face closest to them is
//!   listed or next to a listed one;
//! - every finer face is covered, on generated and corpus meshes, closed and open, and
//!   through the composition down to level 0.

use envelope_mesh::{FaceId, TriangleSoup, generate};
use envelope_offset::{EnvelopeMethod, EnvelopeOptions, Envelopes, EpsilonField, build_envelopes};
use envelope_predicates::{Orientation, orient3d, triangles_intersect};
use envelope_prism::Prism;
use envelope_simplify::{Correspondence, Level, LodOptions, correspondence, lod_chain};
use envelope_tests::oracle::corpus_dir;
use glam::DVec3;

/// The chain at `epsilons` (absolute) with correspondences.
fn chain(soup: &TriangleSoup, epsilons: &[f64]) -> Vec<Level> {
    let options = LodOptions {
        verify: false,
        correspondences: true,
        ..LodOptions::new(epsilons.to_vec())
    };
    lod_chain(soup, &options, &mut (), &mut |_| {}).expect("chain")
}

/// The envelopes the chain's step built around `fine` (the driver's options).
fn step_envelopes(fine: &TriangleSoup, step: f64) -> Envelopes {
    let options = EnvelopeOptions {
        method: EnvelopeMethod::Auto,
        tube_segments: Some(8),
        input_free_of_intersections: true,
        ..EnvelopeOptions::new(EpsilonField::Constant(step))
    };
    build_envelopes(fine, &options).expect("envelopes")
}

/// The fundamental prism of fine face `f` between the envelopes.
fn prism(fine: &TriangleSoup, env: &Envelopes, f: u32) -> (Prism, [u32; 3]) {
    let ids = fine.faces[f as usize].map(|v| v.0);
    let at = |s: &TriangleSoup| ids.map(|v| s.positions[v as usize]);
    (Prism::from_corners(at(&env.inner), at(&env.outer)), ids)
}

/// `q` in the closed tetrahedron `t` (either orientation), exactly.
fn in_tetrahedron(q: DVec3, t: [DVec3; 4]) -> bool {
    let faces = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];
    let signs: Vec<Orientation> = faces
        .iter()
        .map(|f| orient3d(t[f[0]], t[f[1]], t[f[2]], q))
        .collect();
    !signs.contains(&Orientation::Positive) || !signs.contains(&Orientation::Negative)
}

/// The closed triangle `c` meets the closed tetrahedron `t`, exactly.
fn meets_tetrahedron(c: [DVec3; 3], t: [DVec3; 4]) -> bool {
    let faces = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];
    c.iter().any(|&q| in_tetrahedron(q, t))
        || faces
            .iter()
            .any(|f| triangles_intersect(c, [t[f[0]], t[f[1]], t[f[2]]]))
}

fn meets_prism(c: [DVec3; 3], fine: &TriangleSoup, env: &Envelopes, f: u32) -> bool {
    let (p, ids) = prism(fine, env, f);
    p.tetrahedra(ids).iter().any(|&t| meets_tetrahedron(c, t))
}

fn in_prism(q: DVec3, fine: &TriangleSoup, env: &Envelopes, f: u32) -> bool {
    let (p, ids) = prism(fine, env, f);
    p.tetrahedra(ids).iter().any(|&t| in_tetrahedron(q, t))
}

/// Where the interior points of [`samples`] start.
const INTERIOR: usize = 6;

/// Deterministic sample points of a triangle: corners, edge midpoints, interior points.
fn samples(t: [DVec3; 3]) -> Vec<DVec3> {
    let w = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.5, 0.5, 0.0],
        [0.0, 0.5, 0.5],
        [0.5, 0.0, 0.5],
        [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
        [0.7, 0.2, 0.1],
        [0.1, 0.7, 0.2],
        [0.2, 0.1, 0.7],
    ];
    w.iter()
        .map(|b| t[0] * b[0] + t[1] * b[1] + t[2] * b[2])
        .collect()
}

fn point_triangle_distance(p: DVec3, t: [DVec3; 3]) -> f64 {
    envelope_prism::clip::point_triangle_distance(p, t)
}

/// Checks one level's correspondence against `fine` and its step's envelopes; `closed`
/// turns on the claims that hold only between the envelopes of a closed level, `brute` the
/// all-pairs search.
fn check_level(
    fine: &TriangleSoup,
    coarse: &TriangleSoup,
    step: f64,
    c: &Correspondence,
    closed: bool,
    brute: bool,
) {
    let env = step_envelopes(fine, step);
    // The same prisms as the chain's step: the map computed here is the chain's.
    assert_eq!(&correspondence(fine, &env, coarse), c);
    assert_eq!(
        (c.coarse_faces, c.fine_faces),
        (coarse.num_faces(), fine.num_faces())
    );
    assert!(c.is_onto(), "a finer face is covered by no coarser face");
    if closed {
        assert!(c.by_nearest.is_empty(), "closed level: {:?}", c.by_nearest);
    }
    for (ci, list) in c.covers.iter().enumerate() {
        let ct = coarse.triangle(FaceId(ci as u32));
        assert!(list.windows(2).all(|w| w[0] < w[1]), "sorted, no repeats");
        for &f in list {
            assert!(
                c.by_nearest.binary_search(&f).is_ok() || meets_prism(ct, fine, &env, f),
                "coarse {ci} listed with fine {f}, whose prism it does not meet"
            );
        }
        if brute {
            for f in 0..fine.num_faces() as u32 {
                if list.binary_search(&f).is_err() {
                    assert!(
                        !meets_prism(ct, fine, &env, f),
                        "coarse {ci} meets the prism of fine {f}, not listed"
                    );
                }
            }
        }
        if !closed {
            continue;
        }
        let scale = fine.diagonal();
        for (k, p) in samples(ct).into_iter().enumerate() {
            // Only the interior samples: a corner or edge midpoint may lie on a prism's side,
            // and its rounding (a constructed point) can move it off the face into that prism.
            assert!(
                k < INTERIOR || list.iter().any(|&f| in_prism(p, fine, &env, f)),
                "a point of coarse {ci} is in no prism listed for it"
            );
            let (nearest, d) = (0..fine.num_faces() as u32)
                .map(|f| (f, point_triangle_distance(p, fine.triangle(FaceId(f)))))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap();
            assert!(
                d <= c.error[ci] + 1e-12 * scale,
                "coarse {ci}: a point at {d} from the finer level, bound {}",
                c.error[ci]
            );
            let near = fine.faces[nearest as usize];
            assert!(
                list.iter()
                    .any(|&f| f == nearest
                        || fine.faces[f as usize].iter().any(|v| near.contains(v))),
                "coarse {ci}: the closest finer face {nearest} is not listed nor next to a listed face"
            );
        }
    }
    assert!(
        c.error.iter().all(|&e| e <= step * (1.0 + 1e-9)),
        "every bound within the step"
    );
}

fn check_chain(soup: &TriangleSoup, epsilons: &[f64], closed: bool, brute: bool) {
    let levels = chain(soup, epsilons);
    let mut composed: Option<Correspondence> = None;
    for (i, l) in levels.iter().enumerate() {
        let fine = if i == 0 { soup } else { &levels[i - 1].mesh };
        let c = l.correspondence.as_ref().expect("asked for");
        check_level(fine, &l.mesh, l.step, c, closed, brute);
        let down = composed.as_ref().map_or_else(|| c.clone(), |f| c.then(f));
        assert!(down.is_onto(), "level {} to level 0 misses a face", l.index);
        assert_eq!(down.fine_faces, soup.num_faces());
        // The composed bound is at most the sum of the steps, the cumulative bound.
        assert!(down.error.iter().all(|&e| e <= l.cumulative * (1.0 + 1e-9)));
        composed = Some(down);
    }
    assert!(levels.last().unwrap().mesh.num_faces() < soup.num_faces());
}

#[test]
fn closed_generated_levels_are_covered_exactly() {
    let sphere = generate::icosphere(3, 1.0);
    check_chain(&sphere, &[0.02, 0.05], true, true);
    let torus = generate::torus(1.0, 0.35, 40, 16);
    check_chain(&torus, &[0.01, 0.03], true, true);
}

#[test]
fn open_levels_are_covered_with_the_nearest_fallback() {
    // An open cylinder: the coarser border may retreat into the tube.
    let tube = generate::open_cylinder(1.0, 2.0, 40, 10);
    check_chain(&tube, &[0.02, 0.06], false, true);
    let cup = generate::demo_model();
    let d = cup.diagonal();
    check_chain(&cup, &[0.005 * d, 0.01 * d], false, false);
}

#[test]
fn corpus_levels_are_covered() {
    let Some(dir) = corpus_dir() else { return };
    for (name, closed) in [("elephant.off", true), ("mushroom.off", false)] {
        let path = dir.join(name);
        let soup = envelope_io::read_path(&path).expect("corpus mesh").0;
        let d = soup.diagonal();
        check_chain(&soup, &[0.005 * d, 0.01 * d], closed, false);
    }
}
