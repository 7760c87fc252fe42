//! Envelope guarantee (Cohen et al. 4): on a perturbed icosphere or torus with a random
//! epsilon and method, `build_envelopes` returns envelopes whose proof holds; the proof is
//! re-checked independently with `self_intersections` on the union soup (input + outer +
//! inner, no shared indices except where an offset is zero, as at pinned vertices), and
//! every achieved offset is within the requested epsilon.
//! The input prints as pasteable Rust (`{:?}` of the decoded case) on failure.
#![no_main]

use arbitrary::Arbitrary;
use envelope_mesh::generate;
use envelope_offset::{EnvelopeMethod, EnvelopeOptions, EpsilonField, build_envelopes};
use envelope_predicates::self_intersections;
use glam::DVec3;
use libfuzzer_sys::fuzz_target;

#[derive(Arbitrary, Debug)]
struct Case {
    torus: bool,
    subdivisions: u8,
    /// Epsilon as a fraction of the diagonal: `(eps_code as f64 + 1) / 2048`.
    eps_code: u8,
    analytical: bool,
    /// Radial perturbation per vertex, in 1/512 of the radius (cycled).
    bumps: Vec<i8>,
}

fuzz_target!(|case: Case| {
    let mut soup = if case.torus {
        let n = 6 + u32::from(case.subdivisions % 8) * 2;
        generate::torus(1.0, 0.35, 2 * n, n)
    } else {
        generate::icosphere(u32::from(case.subdivisions % 3), 1.0)
    };
    if !case.bumps.is_empty() {
        for (i, p) in soup.positions.iter_mut().enumerate() {
            let b = f64::from(case.bumps[i % case.bumps.len()]) / 512.0;
            *p *= 1.0 + b;
        }
    }
    let eps = (f64::from(case.eps_code) + 1.0) / 2048.0 * soup.diagonal();
    let mut options = EnvelopeOptions::new(EpsilonField::Constant(eps));
    options.method = if case.analytical {
        EnvelopeMethod::Analytical
    } else {
        EnvelopeMethod::Numerical
    };
    let env = match build_envelopes(&soup, &options) {
        Ok(e) => e,
        Err(e) => panic!("{case:?}: unexpected error {e}"),
    };
    // An input that self-intersects after perturbation cannot be proved; skip it.
    let faces: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
    if !self_intersections(&soup.positions, &faces).is_empty() {
        return;
    }
    assert!(
        env.proof.holds(),
        "{case:?}: proof failed {:?}",
        env.proof.contacts
    );
    let n = soup.num_vertices() as u32;
    for v in &env.pinned {
        assert_eq!(
            (env.eps_plus[v.index()], env.eps_minus[v.index()]),
            (0.0, 0.0)
        );
    }
    let mut pos: Vec<DVec3> = soup.positions.clone();
    pos.extend_from_slice(&env.outer.positions);
    pos.extend_from_slice(&env.inner.positions);
    // A zero offset is the input vertex itself (checked), so it shares the input's index.
    let offsets = [&env.eps_plus, &env.eps_minus];
    let mut all: Vec<[u32; 3]> = faces.clone();
    for (k, eps) in (1u32..).zip(offsets) {
        all.extend(faces.iter().map(|f| {
            f.map(|v| {
                if eps[v as usize] == 0.0 {
                    assert_eq!(pos[(v + k * n) as usize], pos[v as usize]);
                    v
                } else {
                    v + k * n
                }
            })
        }));
    }
    assert!(
        self_intersections(&pos, &all).is_empty(),
        "{case:?}: independent re-check failed"
    );
    for v in 0..soup.num_vertices() {
        assert!(
            env.eps_plus[v] <= eps && env.eps_minus[v] <= eps,
            "{case:?}: vertex {v} beyond epsilon"
        );
    }
});
