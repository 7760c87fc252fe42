//! Error maps: the per-face and per-vertex bounds of `Options::map` against brute force and
//! against the certificate's own bounds.

use envelope_mesh::generate::{icosphere, torus};
use envelope_mesh::{TriangleSoup, VertexId};
use envelope_verify::{Certificate, Options, Verdict, certify};
use glam::DVec3;

/// The closest point of triangle `abc` to `p` (Ericson, Real-Time Collision Detection 5.1.5),
/// in f64: an oracle for the tests, not a certified value.
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// Brute-force distance of `p` to every triangle of `soup`.
fn distance(p: DVec3, soup: &TriangleSoup) -> f64 {
    soup.faces
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| soup.positions[v.index()]);
            (p - closest_on_triangle(p, a, b, c)).length()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Points of the face: corners, edge midpoints, the centroid and a few inside.
fn samples(t: [DVec3; 3]) -> Vec<DVec3> {
    let weights = [
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
    weights
        .iter()
        .map(|w| t[0] * w[0] + t[1] * w[1] + t[2] * w[2])
        .collect()
}

/// Every sampled point of every face of `from` is within the face's upper bound of `to`, and
/// every lower bound is at most its upper bound.
fn assert_faces_bound_samples(
    from: &TriangleSoup,
    to: &TriangleSoup,
    bounds: &[envelope_verify::FaceBound],
) {
    assert_eq!(bounds.len(), from.faces.len());
    for (f, b) in from.faces.iter().zip(bounds) {
        assert!(b.lower <= b.upper, "{b:?}");
        let t = f.map(|v| from.positions[v.index()]);
        for p in samples(t) {
            let d = distance(p, to);
            // The oracle's own rounding is far below 1e-12 on these unit-sized meshes.
            assert!(
                d <= b.upper + 1e-12,
                "face {f:?}: sample at {d} > bound {}",
                b.upper
            );
        }
    }
}

/// The map's guarantees that hold for any certificate.
fn assert_map_guarantees(c: &Certificate) {
    let map = c.map.as_ref().expect("asked for a map");
    let worst = map.max_vertex_value();
    assert!(
        worst >= c.approx_to_orig.lower,
        "{worst} < {}",
        c.approx_to_orig.lower
    );
    if c.approx_to_orig.verdict == Verdict::Holds {
        assert!(map.approx_vertices.iter().all(|&x| x <= c.epsilon));
        assert!(map.approx_faces.iter().all(|b| b.upper <= c.epsilon));
    }
    if c.two_sided && c.orig_to_approx.verdict == Verdict::Holds {
        let orig = map.orig_faces.as_ref().expect("two-sided");
        assert!(orig.iter().all(|b| b.upper <= c.epsilon));
    }
}

/// A deterministic jitter in `-1..1` per vertex and axis.
fn jitter(i: usize, k: usize) -> f64 {
    let mut h = (i as u64 * 3 + k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    h ^= h >> 31;
    h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    h ^= h >> 29;
    (h >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

#[test]
fn no_map_unless_asked() {
    let t = icosphere(1, 1.0);
    let c = certify(&t, &t, &Options::new(1e-3));
    assert!(c.map.is_none() && c.to_json().get("map").is_none());
}

#[test]
fn a_displaced_vertex_is_the_worst_and_the_rest_is_zero() {
    let orig = icosphere(3, 1.0);
    let d = 0.01;
    let k = 17;
    let mut approx = orig.clone();
    // On a sphere the vertex normal is the position's direction.
    let n = approx.positions[k].normalize();
    approx.positions[k] += n * d;
    let near: Vec<bool> = {
        // Vertices sharing a face with k.
        let mut near = vec![false; approx.positions.len()];
        for f in approx
            .faces
            .iter()
            .filter(|f| f.contains(&VertexId(k as u32)))
        {
            for v in f {
                near[v.index()] = true;
            }
        }
        near
    };
    for eps in [2.0 * d, 0.5 * d] {
        let c = certify(
            &orig,
            &approx,
            &Options {
                map: true,
                ..Options::new(eps)
            },
        );
        assert_eq!(c.holds(), eps > d, "{:?}", c.violations());
        assert_map_guarantees(&c);
        let map = c.map.as_ref().unwrap();
        let worst = map.max_vertex_value();
        // The moved vertex is d from the (convex) sphere: its normal is in the normal cone.
        assert!(worst >= d * (1.0 - 1e-9), "{worst}");
        assert_eq!(map.approx_vertices[k], worst);
        if eps > d {
            // Tightened below the epsilon the face was proved at (a proof at (d + 2d) / 2).
            assert!(worst <= 1.5 * d, "{worst}");
        }
        for (v, &x) in map.approx_vertices.iter().enumerate() {
            if x == worst {
                assert!(near[v], "vertex {v} also at the worst value");
            }
            if !near[v] {
                // Its faces are faces of orig, unchanged: distance 0, proved.
                assert_eq!(x, 0.0, "vertex {v}");
            }
        }
        // The faces at k have a lower bound near d where it is violated (their witness).
        if eps < d {
            let best_lower = map.approx_faces.iter().map(|b| b.lower).fold(0.0, f64::max);
            assert!(best_lower >= eps);
        }
        assert_faces_bound_samples(&approx, &orig, &map.approx_faces);
        assert_faces_bound_samples(&orig, &approx, map.orig_faces.as_ref().unwrap());
    }
}

#[test]
fn face_bounds_cover_sampled_distances_of_a_jittered_torus() {
    let orig = torus(2.0, 0.5, 24, 12);
    let mut approx = orig.clone();
    let amp = 0.02;
    for (i, p) in approx.positions.iter_mut().enumerate() {
        *p += DVec3::new(jitter(i, 0), jitter(i, 1), jitter(i, 2)) * amp;
    }
    for eps in [0.05, 0.02, 0.01] {
        let c = certify(
            &orig,
            &approx,
            &Options {
                map: true,
                ..Options::distance_only(eps)
            },
        );
        assert_ne!(c.verdict, Verdict::Undecided);
        assert_map_guarantees(&c);
        let map = c.map.as_ref().unwrap();
        assert_faces_bound_samples(&approx, &orig, &map.approx_faces);
        assert_faces_bound_samples(&orig, &approx, map.orig_faces.as_ref().unwrap());
        // A vertex's value bounds the samples of every face around it.
        for (f, b) in approx.faces.iter().zip(&map.approx_faces) {
            for v in f {
                assert!(map.approx_vertices[v.index()] >= b.upper);
            }
        }
        let json = c.to_json();
        assert_eq!(
            json["map"]["approx_faces"]["upper"]
                .as_array()
                .unwrap()
                .len(),
            approx.faces.len()
        );
        assert_eq!(
            json["map"]["orig_faces"]["lower"].as_array().unwrap().len(),
            orig.faces.len()
        );
    }
}

#[test]
fn one_sided_map_has_no_orig_faces() {
    let orig = icosphere(2, 1.0);
    let c = certify(
        &orig,
        &orig,
        &Options {
            map: true,
            ..Options::envelope_of(1e-3)
        },
    );
    let map = c.map.unwrap();
    assert!(map.orig_faces.is_none());
    // Identical meshes: every face is shared, every bound 0.
    assert!(map.approx_vertices.iter().all(|&x| x == 0.0));
}
