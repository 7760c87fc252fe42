//! Random small mesh pairs: whenever `certify` says a direction holds, dense exact sampling
//! (barycentric grid points, checked with rational arithmetic through `cmp_point_triangle`
//! on f64 points that lie on the face within rounding) must find no point farther than
//! epsilon; a violated answer's witness must be farther than epsilon from every triangle.
#![no_main]

use arbitrary::Arbitrary;
use envelope_mesh::{TriangleSoup, VertexId};
use envelope_predicates::{Sign, cmp_point_triangle, square_rounded_up};
use envelope_verify::{Options, Verdict, certify};
use glam::DVec3;
use libfuzzer_sys::fuzz_target;

#[derive(Arbitrary, Debug)]
struct Input {
    a: Vec<[i8; 9]>,
    b: Vec<[i8; 9]>,
    eps: u8,
}

fn soup(tris: &[[i8; 9]]) -> TriangleSoup {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for t in tris.iter().take(6) {
        let base = positions.len() as u32;
        for k in 0..3 {
            positions
                .push(DVec3::new(t[3 * k] as f64, t[3 * k + 1] as f64, t[3 * k + 2] as f64) / 16.0);
        }
        faces.push([VertexId(base), VertexId(base + 1), VertexId(base + 2)]);
    }
    TriangleSoup::new(positions, faces)
}

/// Some triangle of `to` within eps of p (eps2 rounded up: sampling may only err towards
/// "within", so a sampled point farther than eps is a real counterexample).
fn within(p: DVec3, to: &TriangleSoup, eps2: f64) -> bool {
    to.faces.iter().any(|f| {
        let t = f.map(|v| to.positions[v.index()]);
        cmp_point_triangle(p, t, eps2) != Sign::Positive
    })
}

fn check(from: &TriangleSoup, to: &TriangleSoup, eps: f64, side: &envelope_verify::OneSided) {
    let eps2 = square_rounded_up(eps);
    match side.verdict {
        Verdict::Holds => {
            const N: u32 = 24;
            for f in &from.faces {
                let [a, b, c] = f.map(|v| from.positions[v.index()]);
                for i in 0..=N {
                    for j in 0..=N - i {
                        let (u, v) = (f64::from(i) / f64::from(N), f64::from(j) / f64::from(N));
                        let p = a + (b - a) * u + (c - a) * v;
                        // p is within a few ulps of the face; allow that much.
                        let slack = 1e-12;
                        assert!(
                            within(p, to, square_rounded_up(eps + slack)),
                            "holds, but {p:?} is farther than {eps} (+{slack})"
                        );
                    }
                }
            }
            assert!(side.upper <= eps);
        }
        Verdict::Violated => {
            let w = side.witness.as_ref().expect("witness");
            if w.exact_f64 {
                assert!(!within(w.point, to, eps2), "witness {w:?} is within eps");
            }
            // The witness proves dist > eps strictly; the float bound may equal eps only
            // when the excess is below what it resolves.
            assert!(w.distance >= eps && side.lower >= w.distance);
        }
        Verdict::Undecided => {}
    }
    assert!(side.lower <= side.upper);
}

fuzz_target!(|input: Input| {
    let (a, b) = (soup(&input.a), soup(&input.b));
    if a.faces.is_empty() || b.faces.is_empty() {
        return;
    }
    let eps = f64::from(input.eps.max(1)) / 64.0;
    let c = certify(&a, &b, &Options::distance_only(eps));
    check(&b, &a, eps, &c.approx_to_orig);
    check(&a, &b, eps, &c.orig_to_approx);
});
