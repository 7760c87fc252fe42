//! Correspondences between levels of detail (Cohen et al. 8.1): which faces of the finer level
//! each face of the coarser level covers.
//!
//! The paper approximates each fundamental prism's bilinear sides by triangles, cuts the
//! prisms into tetrahedra and stabs the coarser level's edges through them. Here the same
//! relation is decided face by face: **coarse face `C` covers fine face `F` when the closed
//! triangle `C` meets the closed polyhedral prism of `F`** (exact: `envelope-prism`'s
//! [`PolyhedralPrism::intersects_triangle`], orientation tests and ray parity). The prism of
//! `F` is the one between the fine level's inner and outer envelope over `F`, the envelopes
//! the coarse level was simplified within, with its sides split by the vertex ids
//! ([`Split::Ids`]): it is the union of the three tetrahedra of
//! [`Prism::tetrahedra`](envelope_prism::Prism::tetrahedra), and two prisms sharing an edge
//! split their common side alike, so the polyhedral prisms tile the space between the
//! envelopes as the bilinear ones do (the two unions have the same top and bottom faces).
//!
//! **Why every fine face is covered** (closed fine level, envelopes as the simplifier used
//! them): the coarse level lies between the envelopes, so each of its points is in some
//! prism, which it therefore covers; and it separates the outer envelope from the inner one,
//! so every fiber of every prism crosses it. Where that argument does not apply (the coarse
//! border may retreat into a border tube and leave a fine border sliver's prism untouched; a
//! level simplified around kept faces was made within other envelopes), the fine faces no
//! coarse face meets are given to the coarse face closest to their centroid (an f64
//! construction) and listed in [`Correspondence::by_nearest`], so the map is still onto and
//! says where it is not exact.
//!
//! **The error of a coarse face** ([`Correspondence::error`]): each point of `C` lies in a
//! prism `C` covers, and the distance to a triangle is convex (its maximum over a convex set
//! is at a corner), so it is within `max over covered F of min(max over the 6 corners k of
//! F's prism of dist(k, F), max over the corners v of C of dist(v, F))` of the fine level.
//! The distances are f64 constructions; the bound holds where the coarse face lies between
//! the envelopes, which the simplifier guarantees for every face it makes.
//!
//! Choices the paper leaves open, made here: triangle-against-prism tests instead of edge
//! stabbing (the same incidence, without building the overlay), the id split (consistent
//! between neighbours), and the nearest-face fallback above.

use envelope_mesh::TriangleSoup;
use envelope_offset::{Envelopes, face_tree};
use envelope_predicates::bvh::{Aabb, Bvh};
use envelope_prism::clip::point_triangle_distance;
use envelope_prism::{PolyhedralPrism, Prism, Split};
use glam::DVec3;
use rayon::prelude::*;
use serde_json::{Value, json};

/// Which faces of a finer level each face of a coarser level covers (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Correspondence {
    /// Faces of the coarser level.
    pub coarse_faces: usize,
    /// Faces of the finer level.
    pub fine_faces: usize,
    /// For each coarse face, the sorted fine faces it covers.
    pub covers: Vec<Vec<u32>>,
    /// Fine faces whose prism no coarse face meets, given to the coarse face closest to their
    /// centroid instead (sorted; empty on a closed level).
    pub by_nearest: Vec<u32>,
    /// For each coarse face, a bound of its distance to the finer level from the prisms it
    /// meets (f64 constructions; see the module docs). Empty when no bound is given: the
    /// coarse level was simplified around kept faces, within other envelopes.
    pub error: Vec<f64>,
}

impl Correspondence {
    /// Composes `self` (level `i` over level `i - 1`) with `finer` (level `i - 1` over
    /// level `j`): the faces of level `j` each face of level `i` covers, through the faces
    /// of level `i - 1` it covers. Errors add up (the triangle inequality).
    ///
    /// ```
    /// use envelope_simplify::Correspondence;
    /// let a = Correspondence { coarse_faces: 1, fine_faces: 2, covers: vec![vec![0, 1]], by_nearest: vec![], error: vec![0.5] };
    /// let b = Correspondence { coarse_faces: 2, fine_faces: 3, covers: vec![vec![0, 1], vec![1, 2]], by_nearest: vec![2], error: vec![0.25, 0.5] };
    /// let c = a.then(&b);
    /// assert_eq!(c.covers, vec![vec![0, 1, 2]]);
    /// assert_eq!(c.error, vec![1.0]);
    /// ```
    #[must_use]
    pub fn then(&self, finer: &Correspondence) -> Correspondence {
        let covers = self
            .covers
            .iter()
            .map(|mids| {
                let mut out: Vec<u32> = mids
                    .iter()
                    .flat_map(|&m| finer.covers[m as usize].iter().copied())
                    .collect();
                out.sort_unstable();
                out.dedup();
                out
            })
            .collect();
        // An empty table is a bound not given (a level made around kept faces).
        let bounded = !(self.error.is_empty() || finer.error.is_empty());
        let error = self
            .covers
            .iter()
            .filter(|_| bounded)
            .zip(&self.error)
            .map(|(mids, e)| {
                e + mids
                    .iter()
                    .map(|&m| finer.error[m as usize])
                    .fold(0.0, f64::max)
            })
            .collect();
        Correspondence {
            coarse_faces: self.coarse_faces,
            fine_faces: finer.fine_faces,
            covers,
            by_nearest: finer.by_nearest.clone(),
            error,
        }
    }

    /// Whether every fine face is covered by at least one coarse face.
    #[must_use]
    pub fn is_onto(&self) -> bool {
        let mut hit = vec![false; self.fine_faces];
        for &f in self.covers.iter().flatten() {
            hit[f as usize] = true;
        }
        hit.iter().all(|&h| h)
    }

    /// The JSON of a correspondence file: `coarse_faces`, `fine_faces`, `covers`,
    /// `by_nearest`, `error`.
    #[must_use]
    pub fn to_json(&self) -> Value {
        json!({
            "coarse_faces": self.coarse_faces,
            "fine_faces": self.fine_faces,
            "covers": self.covers,
            "by_nearest": self.by_nearest,
            "error": (!self.error.is_empty() || self.coarse_faces == 0).then_some(&self.error),
        })
    }
}

/// The polyhedral prism of every face of `fine` between `envelopes`' inner and outer
/// envelope (module docs), split by vertex ids.
fn fine_prisms(fine: &TriangleSoup, envelopes: &Envelopes) -> Vec<PolyhedralPrism> {
    fine.faces
        .par_iter()
        .map(|f| {
            let ids = f.map(|v| v.0);
            let at = |s: &TriangleSoup| ids.map(|v| s.positions[v as usize]);
            let prism = Prism::from_corners(at(&envelopes.inner), at(&envelopes.outer));
            PolyhedralPrism::new(&prism, Split::Ids(ids))
        })
        .collect()
}

/// Which faces of `fine` each face of `coarse` covers, `coarse` having been simplified from
/// `fine` within `envelopes` (see the module docs). Runs in parallel.
///
/// ```
/// use envelope_mesh::generate;
/// use envelope_offset::{build_envelopes, EnvelopeOptions, EpsilonField};
/// use envelope_simplify::{correspondence, simplify, SimplifyOptions};
/// let fine = generate::icosphere(3, 1.0);
/// let (coarse, _) = simplify(&fine, &SimplifyOptions::new(EpsilonField::Constant(0.05)), &mut ()).unwrap();
/// let env = build_envelopes(&fine, &EnvelopeOptions::new(EpsilonField::Constant(0.05))).unwrap();
/// let c = correspondence(&fine, &env, &coarse);
/// assert!(c.is_onto() && c.by_nearest.is_empty());
/// assert!(c.error.iter().all(|&e| e <= 0.05 * 1.001));
/// ```
#[must_use]
pub fn correspondence(
    fine: &TriangleSoup,
    envelopes: &Envelopes,
    coarse: &TriangleSoup,
) -> Correspondence {
    let prisms = fine_prisms(fine, envelopes);
    let boxes: Vec<Aabb> = prisms
        .iter()
        .map(|p| Aabb::from_points(&p.corners()))
        .collect();
    let prism_tree = Bvh::new(&boxes);
    let coarse_tree = face_tree(coarse);
    let pairs = coarse_tree.pairs_with_where(&prism_tree, |c, f| {
        let t = coarse.triangle(envelope_mesh::FaceId(c));
        prisms[f as usize].intersects_triangle(t)
    });
    // Sorted by coarse face, then fine face: each coarse face's list is a run.
    let mut covers = vec![Vec::new(); coarse.num_faces()];
    let mut hit = vec![false; fine.num_faces()];
    for &(c, f) in &pairs {
        covers[c as usize].push(f);
        hit[f as usize] = true;
    }
    let error: Vec<f64> = covers
        .par_iter()
        .enumerate()
        .map(|(c, fs)| {
            let ct = coarse.triangle(envelope_mesh::FaceId(c as u32));
            let farthest = |points: &[DVec3], t: [DVec3; 3]| {
                points
                    .iter()
                    .map(|&k| point_triangle_distance(k, t))
                    .fold(0.0, f64::max)
            };
            fs.iter()
                .map(|&f| {
                    let t = fine.triangle(envelope_mesh::FaceId(f));
                    farthest(&prisms[f as usize].corners(), t).min(farthest(&ct, t))
                })
                .fold(0.0, f64::max)
        })
        .collect();
    let by_nearest: Vec<u32> = (0..fine.num_faces() as u32)
        .filter(|&f| !hit[f as usize])
        .collect();
    for &f in &by_nearest {
        if let Some(c) = nearest_face(coarse, &coarse_tree, centroid(fine, f)) {
            let list = &mut covers[c as usize];
            if let Err(at) = list.binary_search(&f) {
                list.insert(at, f);
            }
        }
    }
    Correspondence {
        coarse_faces: coarse.num_faces(),
        fine_faces: fine.num_faces(),
        covers,
        by_nearest,
        error,
    }
}

fn centroid(soup: &TriangleSoup, f: u32) -> DVec3 {
    let [a, b, c] = soup.triangle(envelope_mesh::FaceId(f));
    (a + b + c) / 3.0
}

/// The face of `soup` closest to `p` (f64 distances; the lowest id among equals), by a best-
/// first walk of `tree`.
fn nearest_face(soup: &TriangleSoup, tree: &Bvh, p: DVec3) -> Option<u32> {
    use envelope_predicates::bvh::NodeKind;
    use std::cmp::Ordering;
    use std::collections::BinaryHeap;
    #[derive(PartialEq)]
    struct Near(f64, envelope_predicates::bvh::NodeId);
    impl Eq for Near {}
    impl PartialOrd for Near {
        fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
            Some(self.cmp(o))
        }
    }
    impl Ord for Near {
        // The smallest bound first.
        fn cmp(&self, o: &Self) -> Ordering {
            o.0.total_cmp(&self.0)
        }
    }
    let mut heap = BinaryHeap::new();
    heap.push(Near(0.0, tree.root()?));
    let mut best: Option<(f64, u32)> = None;
    while let Some(Near(bound, n)) = heap.pop() {
        if best.is_some_and(|(d, _)| bound > d) {
            break;
        }
        match tree.kind(n) {
            NodeKind::Leaf(items) => {
                for &f in items {
                    let d = point_triangle_distance(p, soup.triangle(envelope_mesh::FaceId(f)));
                    if best.is_none_or(|(bd, bf)| d < bd || (d == bd && f < bf)) {
                        best = Some((d, f));
                    }
                }
            }
            NodeKind::Interior(a, b) => {
                for c in [a, b] {
                    heap.push(Near(tree.bounds(c).distance_lower_bound(p), c));
                }
            }
        }
    }
    best.map(|(_, f)| f)
}
