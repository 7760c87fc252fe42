//! The exact non-intersection proof (Cohen et al. 4: "the envelopes do not self-intersect").
//!
//! The input, the outer and the inner envelope are put in one soup with *no shared vertex
//! indices between the three* (so an envelope touching the input counts as intersecting),
//! except where an offset is exactly zero (a pinned vertex, see
//! [`crate::Envelopes::pinned`]: there the envelope vertex is the input vertex), and
//! `envelope_predicates::self_intersections` (BVH candidates, exact adjacency-aware tests on
//! the f64 vertices) lists every meeting pair. Each pair is reported with the surfaces it
//! joins, so the one run answers "each alone" (outer-outer, inner-inner, input-input) and
//! "with each other" (outer-input, inner-input, outer-inner) at once. Tubes are proved
//! separately (see [`crate::tubes`]).
use envelope_mesh::FaceId;
use envelope_predicates::bvh::{Aabb, Bvh};
use envelope_predicates::{PreparedFace, prepared_faces_intersect};
use glam::DVec3;
use rayon::prelude::*;

/// Which surface a face belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Surface {
    /// The input mesh.
    Input,
    /// The outer (positive) envelope.
    Outer,
    /// The inner (negative) envelope.
    Inner,
    /// Border tube number `.0`.
    Tube(u32),
}

/// Two faces that meet (exactly decided).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Contact {
    /// First face.
    pub a: (Surface, FaceId),
    /// Second face.
    pub b: (Surface, FaceId),
}

/// The outcome of the exact checks.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Proof {
    /// Meeting face pairs among input, outer and inner (empty when proved).
    pub contacts: Vec<Contact>,
    /// Meeting pairs involving a tube (tube faces are exempt against the input and envelope
    /// faces around their own border vertices; see [`crate::Tube`]).
    pub tube_contacts: Vec<Contact>,
    /// Rounds of "halve the epsilon of offending vertices and re-prove" that were needed.
    pub repair_rounds: u32,
    /// Distinct vertices whose epsilon was halved at least once by the repair.
    pub repaired_vertices: usize,
}

impl Proof {
    /// True when no contact was found: the envelopes are proved free of self-intersections,
    /// of intersections with the input and with each other (and the tubes likewise).
    #[must_use]
    pub fn holds(&self) -> bool {
        self.contacts.is_empty() && self.tube_contacts.is_empty()
    }

    /// True when the envelope part (without tubes) holds.
    #[must_use]
    pub fn envelopes_hold(&self) -> bool {
        self.contacts.is_empty()
    }
}

/// What is already known about the pairs [`prove_envelopes`] would test; each item only
/// stands in for tests whose answers are known, so the contacts found are the same.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Known<'a> {
    /// The input is proved free of self-intersections (the caller checked it, see
    /// [`crate::EnvelopeOptions::input_free_of_intersections`]): input-input pairs are skipped.
    pub(crate) input_free: bool,
    /// Which envelope faces have the positions and vertex indices they had in an earlier
    /// configuration whose proof found the contacts `previous`. A pair of unchanged faces
    /// (the input's never change) is then the same pair as in that proof, with the same
    /// answer: a contact when it is in `previous`, else apart. Only the pairs with a changed
    /// face are tested.
    pub(crate) unchanged: Option<Unchanged<'a>>,
    /// The contacts of that earlier configuration (see `unchanged`).
    pub(crate) previous: &'a [Contact],
}

/// The envelope faces of an earlier configuration that did not change (see [`Known`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Unchanged<'a> {
    /// `faces[k][f]` (`k` = 0 outer, 1 inner): envelope face `f` is as it was.
    pub(crate) faces: [&'a [bool]; 2],
    /// That configuration's tree over the outer and the inner faces, as [`prove_envelopes`]
    /// returned it: the new one is this tree with the changed faces' boxes
    /// ([`Bvh::refit_items`]; an unchanged face has the box it had).
    pub(crate) tree: &'a Bvh,
}

/// Whether the boxes of the faces' prisms (a face's box on the three surfaces together,
/// `boxes`: input, outer, inner, `nf` each) are on the whole more than four times as wide as
/// the faces' own boxes. A search over prisms then meets many more pairs than there are
/// pairs of faces to test (at 1 % of the diagonal on a fine scan the offsets are many edges
/// long); where a prism is not much wider than its face, one search over prisms is cheaper
/// than three over faces (the changelog has the measurements behind the factor).
fn prisms_much_larger(boxes: &[Aabb], nf: usize) -> bool {
    let width = |b: &Aabb| (b.max - b.min).max_element();
    let (prisms, faces) = (0..nf)
        .into_par_iter()
        .map(|f| {
            let own = [boxes[f], boxes[f + nf], boxes[f + 2 * nf]];
            let prism = own[0].union(&own[1]).union(&own[2]);
            (width(&prism), own.iter().map(width).sum::<f64>() / 3.0)
        })
        .reduce(|| (0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1));
    prisms > 4.0 * faces
}

/// Exact contacts among input, outer and inner (same connectivity `faces`), each envelope
/// given with its offsets.
///
/// An envelope vertex whose offset is exactly zero *is* the input vertex (the same f64
/// point): it gets the input's index, so faces around it may meet the input's faces there
/// and only there (adjacency-aware test), as a pinched envelope must. Every other envelope
/// vertex has its own index, and touching the input counts.
///
/// `known` says which pairs need no test because their answer is already known to be
/// "apart" (see [`Known`]); the faces of the one soup are input `0..nf`, outer `nf..2nf`,
/// inner `2nf..3nf`. `input_tree` is a tree over the input faces' boxes (item = face).
///
/// Candidates: one tree per surface, and the pairs within the outer, within the inner, and
/// between any two of the three (within the input only when it is not known free); the same
/// pairs as one tree over all three would give. `prepared_faces_intersect` decides each (the
/// f64 pre-tests on each face's plane, computed once, then the exact test).
///
/// Also returns one tree over the outer and the inner faces (item `f`: outer face `f`, item
/// `nf + f`: inner face `f`), the shape of `input_tree` with both offsets of a face in the
/// leaf of the face ([`Bvh::interleaved`], [`Bvh::refit`]), which the tube stage
/// ([`crate::tubes`]) and the simplifier's barriers reuse.
pub(crate) fn prove_envelopes(
    input: &[DVec3],
    envelopes: [(&[DVec3], &[f64]); 2],
    faces: &[[u32; 3]],
    input_tree: &Bvh,
    known: &Known<'_>,
) -> (Vec<Contact>, Bvh) {
    prove_envelopes_searching(input, envelopes, faces, input_tree, known, None)
}

/// How the full proof finds its candidate pairs (the same pairs either way).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PairSearch {
    /// One search over the faces' prisms (each face's box on the three surfaces together),
    /// then the pairs of their triangles whose boxes overlap.
    Prisms,
    /// One search per pair of surfaces, over the triangles' own boxes.
    Faces,
}

/// [`prove_envelopes`] with the full proof's pair search chosen by the caller (`None`: by
/// [`prisms_much_larger`]).
pub(crate) fn prove_envelopes_searching(
    input: &[DVec3],
    envelopes: [(&[DVec3], &[f64]); 2],
    faces: &[[u32; 3]],
    input_tree: &Bvh,
    known: &Known<'_>,
    search: Option<PairSearch>,
) -> (Vec<Contact>, Bvh) {
    let n = input.len() as u32;
    let nf = faces.len() as u32;
    debug_assert_eq!(input_tree.len(), faces.len());
    let mut positions = Vec::with_capacity(3 * input.len());
    positions.extend_from_slice(input);
    for (env, _) in envelopes {
        positions.extend_from_slice(env);
    }
    // The vertex indices of face `g` of the one soup (input `0..nf`, outer, inner).
    let face_of = |g: u32| -> [u32; 3] {
        let (k, f) = (g / nf, faces[(g % nf) as usize]);
        if k == 0 {
            return f;
        }
        let (env, eps) = envelopes[k as usize - 1];
        f.map(|v| {
            if eps[v as usize] == 0.0 && env[v as usize] == input[v as usize] {
                v
            } else {
                v + k * n
            }
        })
    };
    let box_of = |g: u32| Aabb::from_triangle(face_of(g).map(|v| positions[v as usize]));
    let which = |f: u32| {
        let s = match f / nf {
            0 => Surface::Input,
            1 => Surface::Outer,
            _ => Surface::Inner,
        };
        (s, FaceId(f % nf))
    };
    // Whether faces `i`, `j` (global ids, two different faces) meet. Each face's plane is
    // prepared per pair rather than kept for all three surfaces at 120 bytes a face (the
    // memory it saves is in the changelog).
    let meet = |i: u32, j: u32| {
        let face = |k: u32| PreparedFace::new(&positions, face_of(k));
        prepared_faces_intersect(&face(i), &face(j))
    };
    let (envelope_tree, mut pairs) = match known.unchanged {
        None => {
            let all: Vec<[u32; 3]> = (0..3 * nf).into_par_iter().map(face_of).collect();
            // Each face's box once; the envelopes' tree is the input's with both offsets of
            // each face in its leaf, refitted (the same answers as a tree built over these
            // boxes, see `Bvh::refit`; an envelope face lies near its input face).
            let boxes: Vec<Aabb> = all
                .par_iter()
                .map(|f| Aabb::from_triangle(f.map(|v| positions[v as usize])))
                .collect();
            let first = u32::from(known.input_free);
            let search = search.unwrap_or_else(|| {
                if prisms_much_larger(&boxes, nf as usize) {
                    PairSearch::Faces
                } else {
                    PairSearch::Prisms
                }
            });
            if search == PairSearch::Faces {
                // Large offsets against the faces: a prism's box (a face on all three
                // surfaces) meets far more prisms than its faces meet faces, so each pair
                // of surfaces is searched with the faces' own boxes, one tree per envelope
                // (the input's, refitted): a node of a tree holding both envelopes would be
                // as thick as the two offsets, and meet every node within that distance.
                // Outer with itself, inner with itself, outer with inner, each with the
                // input, and the input with itself when it is not known free. The same
                // pairs.
                let refit =
                    |k: u32| input_tree.refit(&boxes[(k * nf) as usize..((k + 1) * nf) as usize]);
                let (outer, inner) = rayon::join(|| refit(1), || refit(2));
                let on = |k: u32| move |a: u32, b: u32| meet(a + k * nf, b + k * nf);
                let ((outer_self, inner_self), (between, (with_input, within))) = rayon::join(
                    || {
                        rayon::join(
                            || outer.self_pairs_where(on(1)),
                            || inner.self_pairs_where(on(2)),
                        )
                    },
                    || {
                        rayon::join(
                            || outer.pairs_with_where(&inner, |a, b| meet(a + nf, b + 2 * nf)),
                            || {
                                rayon::join(
                                    || {
                                        // (input face, envelope face) for either envelope.
                                        let with_input = |tree: &Bvh, k: u32| {
                                            tree.pairs_with_where(input_tree, |a, g| {
                                                meet(a + k * nf, g)
                                            })
                                            .into_iter()
                                            .map(move |(a, g)| (g, a + k * nf))
                                        };
                                        with_input(&outer, 1)
                                            .chain(with_input(&inner, 2))
                                            .collect::<Vec<_>>()
                                    },
                                    || {
                                        if !known.input_free {
                                            input_tree.self_pairs_where(meet)
                                        } else {
                                            Vec::new()
                                        }
                                    },
                                )
                            },
                        )
                    },
                );
                let mut pairs: Vec<(u32, u32)> = Vec::new();
                pairs.extend(outer_self.into_iter().map(|(a, b)| (a + nf, b + nf)));
                pairs.extend(
                    inner_self
                        .into_iter()
                        .map(|(a, b)| (a + 2 * nf, b + 2 * nf)),
                );
                pairs.extend(between.into_iter().map(|(a, b)| (a + nf, b + 2 * nf)));
                pairs.extend(with_input);
                pairs.extend(within);
                // The tree returned, once the two searched are gone (the same memory).
                drop((outer, inner));
                (
                    input_tree.interleaved_refit(2, &boxes[nf as usize..]),
                    pairs,
                )
            } else {
                // The envelopes' tree is only returned: refitted beside the search.
                let refit = || input_tree.interleaved_refit(2, &boxes[nf as usize..]);
                rayon::join(refit, || {
                    // One pass over pairs of input faces `f`, `g` whose prisms' boxes (the
                    // union of the face's box on each surface) overlap, then every pair of
                    // their triangles on any two surfaces (within the input only when it is
                    // not known free) whose own boxes overlap: the same pairs as one search
                    // per pair of surfaces would give (two triangles' boxes overlap only
                    // where their prisms' do), for one tree walk instead of five.
                    let prism: Vec<Aabb> = (0..nf as usize)
                        .into_par_iter()
                        .map(|f| {
                            boxes[f]
                                .union(&boxes[f + nf as usize])
                                .union(&boxes[f + 2 * nf as usize])
                        })
                        .collect();
                    let prism_tree = input_tree.refit(&prism);
                    let test = |x: u32, y: u32, out: &mut Vec<(u32, u32)>| {
                        if boxes[x as usize].overlaps(&boxes[y as usize]) && meet(x, y) {
                            out.push((x.min(y), x.max(y)));
                        }
                    };
                    let mut pairs = prism_tree.self_pairs_emit(|f, g, out| {
                        for s in 0..3 {
                            for t in 0..3 {
                                if s.max(t) >= first {
                                    test(s * nf + f, t * nf + g, out);
                                }
                            }
                        }
                    });
                    // The triangles of one face on two surfaces.
                    let own: Vec<(u32, u32)> = (0..nf)
                        .into_par_iter()
                        .flat_map_iter(|f| {
                            let mut out = Vec::new();
                            for (s, t) in [(0, 1), (0, 2), (1, 2)] {
                                test(s * nf + f, t * nf + f, &mut out);
                            }
                            out
                        })
                        .collect();
                    pairs.extend(own);
                    pairs
                })
            }
        }
        Some(u) => {
            // Only the changed faces, each against every face (a pair of two changed faces
            // once: from the lower id); the pairs of unchanged faces keep their answers.
            let is_changed = |f: u32| f >= nf && !u.faces[(f / nf - 1) as usize][(f % nf) as usize];
            let changed: Vec<u32> = (nf..3 * nf).filter(|&f| is_changed(f)).collect();
            let boxes: Vec<Aabb> = changed.iter().map(|&f| box_of(f)).collect();
            // The earlier envelopes' tree with the changed faces' boxes (item `g - nf`).
            let moved: Vec<(u32, Aabb)> = changed
                .iter()
                .zip(&boxes)
                .map(|(&g, &b)| (g - nf, b))
                .collect();
            let envelope_tree = u.tree.refit_items(&moved);
            debug_assert!(
                envelope_tree.has_item_boxes_of(2 * nf as usize, |i| box_of(i + nf)),
                "an unchanged face with another box"
            );
            let trees = [(input_tree, 0), (&envelope_tree, nf)];
            let mut pairs = Vec::new();
            let changed_tree = Bvh::new(&boxes);
            for &(tb, ob) in &trees {
                let found = changed_tree.pairs_with_where(tb, |k, x| {
                    let (c, x) = (changed[k as usize], x + ob);
                    c != x && (!is_changed(x) || c < x) && meet(c, x)
                });
                pairs.extend(found.into_iter().map(|(k, x)| {
                    let c = changed[k as usize];
                    (c.min(x + ob), c.max(x + ob))
                }));
            }
            let global = |(s, f): (Surface, FaceId)| match s {
                Surface::Input => f.0,
                Surface::Outer => nf + f.0,
                _ => 2 * nf + f.0,
            };
            pairs.extend(
                known
                    .previous
                    .iter()
                    .map(|c| (global(c.a), global(c.b)))
                    .filter(|&(a, b)| !is_changed(a) && !is_changed(b)),
            );
            (envelope_tree, pairs)
        }
    };
    pairs.sort_unstable();
    let contacts = pairs
        .into_iter()
        .map(|(a, b)| Contact {
            a: which(a),
            b: which(b),
        })
        .collect();
    (contacts, envelope_tree)
}
