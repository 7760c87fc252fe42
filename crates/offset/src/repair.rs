//! Step 6 of [`crate::build_envelopes`]: place the envelope vertices, prove them exactly,
//! and halve the offsets of every vertex of an offending face until the proof holds.
use std::sync::atomic::AtomicBool;

use envelope_mesh::TriangleSoup;
use envelope_predicates::bvh::Bvh;
use glam::DVec3;

use crate::options::raised;
use crate::proof::{self, Proof, Surface};

/// Offsets after the exact proof and repair, with the envelope vertices.
pub(crate) struct Proved {
    pub(crate) eps_plus: Vec<f64>,
    pub(crate) eps_minus: Vec<f64>,
    pub(crate) outer: Vec<DVec3>,
    pub(crate) inner: Vec<DVec3>,
    pub(crate) proof: Proof,
    /// The proof's tree over the outer then the inner faces at these positions.
    pub(crate) tree: Bvh,
}

impl Proved {
    /// Sum of the offsets over vertices and both sides.
    pub(crate) fn total(&self) -> f64 {
        self.eps_plus.iter().chain(&self.eps_minus).sum()
    }
}

/// Step 6: places the envelope vertices, proves them exactly, and halves the offsets of
/// every vertex of an offending face until the proof holds (at most `max_rounds` rounds,
/// and none more once `abandon` is set: the caller no longer wants the result).
///
/// `known`: whether the input is known free of self-intersections, and a configuration over
/// the same input that was proved without any contact; the first proof then tests only the
/// pairs with a face that differs from it (see [`proof::Known`]). Each repair round tests
/// only the pairs with a face it moved, and keeps the other answers of the round before.
pub(crate) fn prove_and_repair(
    soup: &TriangleSoup,
    normals: &[DVec3],
    faces: &[[u32; 3]],
    (mut eps_plus, mut eps_minus): (Vec<f64>, Vec<f64>),
    (input_free, base): (bool, Option<&Proved>),
    input_tree: &Bvh,
    (max_rounds, abandon): (u32, Option<&AtomicBool>),
) -> Proved {
    let place = |eps: &[f64], s: f64| -> Vec<DVec3> {
        soup.positions
            .iter()
            .zip(normals)
            .zip(eps)
            // Flushed into the predicates' range: a coordinate at zero moved by a rounding-noise
            // normal component would otherwise land below 2^-120.
            .map(|((&p, &n), &e)| envelope_mesh::flush_tiny(p + (n * s) * e))
            .collect()
    };
    let mut outer = place(&eps_plus, 1.0);
    let mut inner = place(&eps_minus, -1.0);
    // Envelope faces whose three vertices sit where, and with the offset, they had in `base`
    // (the offset decides the vertex index of a pinned corner, see `prove_envelopes`).
    let unchanged = |env: &[DVec3], eps: &[f64], b_env: &[DVec3], b_eps: &[f64]| -> Vec<bool> {
        let same = |v: u32| {
            let v = v as usize;
            env[v].to_array().map(f64::to_bits) == b_env[v].to_array().map(f64::to_bits)
                && eps[v].to_bits() == b_eps[v].to_bits()
        };
        faces.iter().map(|f| f.iter().all(|&v| same(v))).collect()
    };
    let base_unchanged = base.map(|b| {
        [
            unchanged(&outer, &eps_plus, &b.outer, &b.eps_plus),
            unchanged(&inner, &eps_minus, &b.inner, &b.eps_minus),
        ]
    });
    let first = proof::Known {
        input_free,
        unchanged: base
            .zip(base_unchanged.as_ref())
            .map(|(b, [o, i])| proof::Unchanged {
                faces: [&o[..], &i[..]],
                tree: &b.tree,
            }),
        previous: &[],
    };
    let (contacts, mut tree) = proof::prove_envelopes(
        &soup.positions,
        [(&outer, &eps_plus), (&inner, &eps_minus)],
        faces,
        input_tree,
        &first,
    );
    let mut proof = Proof {
        contacts,
        ..Proof::default()
    };
    let mut repaired = vec![false; soup.num_vertices()];
    while !proof.contacts.is_empty() && proof.repair_rounds < max_rounds && !raised(abandon) {
        let mut halve_plus = vec![false; soup.num_vertices()];
        let mut halve_minus = vec![false; soup.num_vertices()];
        for c in &proof.contacts {
            for (s, f) in [c.a, c.b] {
                let h = match s {
                    Surface::Outer => &mut halve_plus,
                    Surface::Inner => &mut halve_minus,
                    _ => continue,
                };
                for v in faces[f.0 as usize] {
                    h[v as usize] = true;
                }
            }
        }
        let (before_plus, before_minus) = (eps_plus.clone(), eps_minus.clone());
        let mut changed = false;
        for v in 0..soup.num_vertices() {
            for (h, eps) in [
                (halve_plus[v], &mut eps_plus),
                (halve_minus[v], &mut eps_minus),
            ] {
                if h && eps[v] > 0.0 {
                    eps[v] *= 0.5;
                    repaired[v] = true;
                    changed = true;
                }
            }
        }
        if !changed {
            break; // only input-input contacts, or vertices already at zero
        }
        let (new_outer, new_inner) = (place(&eps_plus, 1.0), place(&eps_minus, -1.0));
        // Only the faces the halving moved are tested again: the other pairs are those of
        // the round before, with its answers (see `proof::Known`).
        let moved = [
            unchanged(&new_outer, &eps_plus, &outer, &before_plus),
            unchanged(&new_inner, &eps_minus, &inner, &before_minus),
        ];
        (outer, inner) = (new_outer, new_inner);
        proof.repair_rounds += 1;
        let previous = std::mem::take(&mut proof.contacts);
        let earlier = tree;
        let since = proof::Known {
            input_free,
            unchanged: Some(proof::Unchanged {
                faces: [&moved[0], &moved[1]],
                tree: &earlier,
            }),
            previous: &previous,
        };
        (proof.contacts, tree) = proof::prove_envelopes(
            &soup.positions,
            [(&outer, &eps_plus), (&inner, &eps_minus)],
            faces,
            input_tree,
            &since,
        );
    }
    proof.repaired_vertices = repaired.iter().filter(|&&r| r).count();
    Proved {
        eps_plus,
        eps_minus,
        outer,
        inner,
        proof,
        tree,
    }
}
