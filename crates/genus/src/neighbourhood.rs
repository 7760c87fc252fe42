//! Alpha-neighbourhoods (El-Sana and Varshney 1997, section 4.2).
//!
//! Two triangles are *alpha-close* when their alpha-prisms intersect. Candidates come from a
//! uniform grid of cell side `2 alpha` (the paper's choice): every face is registered in the
//! cells its prism's bounding box overlaps (f64 cell indices, widened by one cell on each side
//! so that rounding in the index computation can only add candidates, never lose one), and
//! every candidate pair is then decided exactly by [`AlphaPrism::intersects`]. A prism
//! spanning more than 4096 cells (a long triangle, a tiny alpha) is paired with every face
//! instead of being registered, so the grid never blows up.

use std::collections::HashMap;

use envelope_mesh::{FaceId, TriangleSoup};
use rayon::prelude::*;

use crate::{AlphaPrism, GenusError};

/// The alpha-close pairs `(f, g)`, `f < g`, among `faces` of `soup` (all faces when `None`),
/// sorted.
///
/// # Errors
/// [`GenusError::InvalidAlpha`] for a non-positive or non-finite `alpha`;
/// [`GenusError::NonFiniteCoordinate`] for a non-finite vertex.
///
/// ```
/// use envelope_genus::alpha_close_pairs;
/// use envelope_mesh::TriangleSoup;
/// // Two parallel triangles 1.0 apart: close for alpha = 0.5 (cubes touch), not for 0.49.
/// let s = TriangleSoup::from_raw(
///     &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0],
///       [0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]],
///     &[[0, 1, 2], [3, 4, 5]],
/// );
/// assert_eq!(alpha_close_pairs(&s, 0.5, None).unwrap().len(), 1);
/// assert!(alpha_close_pairs(&s, 0.49, None).unwrap().is_empty());
/// ```
pub fn alpha_close_pairs(
    soup: &TriangleSoup,
    alpha: f64,
    faces: Option<&[FaceId]>,
) -> Result<Vec<(FaceId, FaceId)>, GenusError> {
    alpha_close_pairs_where(soup, alpha, faces, |_, _| true)
}

/// [`alpha_close_pairs`] restricted to the candidate pairs `keep` accepts; `keep` is asked
/// before the (costlier) exact prism intersection, so a cheap filter saves most of the time.
pub(crate) fn alpha_close_pairs_where(
    soup: &TriangleSoup,
    alpha: f64,
    faces: Option<&[FaceId]>,
    keep: impl Fn(FaceId, FaceId) -> bool + Sync,
) -> Result<Vec<(FaceId, FaceId)>, GenusError> {
    if !(alpha.is_finite() && alpha > 0.0) {
        return Err(GenusError::InvalidAlpha(alpha));
    }
    let ids: Vec<FaceId> = match faces {
        Some(f) => f.to_vec(),
        None => soup.face_ids().collect(),
    };
    let prisms: Vec<AlphaPrism> = ids
        .par_iter()
        .map(|&f| AlphaPrism::new(soup.triangle(f), alpha))
        .collect::<Result<_, _>>()?;
    let cell = 2.0 * alpha;
    let index = |x: f64| (x / cell).floor() as i64;
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    // Prisms spanning more than MAX_CELLS cells (a long triangle and a tiny alpha) are not
    // registered; they are paired with every prism instead.
    const MAX_CELLS: i128 = 4096;
    let mut big: Vec<usize> = Vec::new();
    let mut is_big = vec![false; prisms.len()];
    let mut ranges: Vec<([i64; 3], [i64; 3])> = Vec::with_capacity(prisms.len());
    for (k, p) in prisms.iter().enumerate() {
        let (lo, hi) = p.bbox;
        let l = [index(lo.x) - 1, index(lo.y) - 1, index(lo.z) - 1];
        let h = [index(hi.x) + 1, index(hi.y) + 1, index(hi.z) + 1];
        ranges.push((l, h));
        let cells: i128 = (0..3)
            .map(|a| i128::from(h[a]) - i128::from(l[a]) + 1)
            .product();
        if !(1..=MAX_CELLS).contains(&cells) {
            big.push(k);
            is_big[k] = true;
            continue;
        }
        for i in l[0]..=h[0] {
            for j in l[1]..=h[1] {
                for m in l[2]..=h[2] {
                    grid.entry([i, j, m]).or_default().push(k);
                }
            }
        }
    }
    // Per face, the later faces sharing a cell (and the big ones): memory stays linear in
    // the output even when cells are crowded (a large alpha).
    let mut pairs: Vec<(FaceId, FaceId)> = (0..prisms.len())
        .into_par_iter()
        .flat_map_iter(|k| {
            let mut cand: Vec<usize> = if is_big[k] {
                (k + 1..prisms.len()).collect()
            } else {
                let (l, h) = ranges[k];
                let mut c = Vec::new();
                for i in l[0]..=h[0] {
                    for j in l[1]..=h[1] {
                        for m in l[2]..=h[2] {
                            if let Some(v) = grid.get(&[i, j, m]) {
                                c.extend(v.iter().copied().filter(|&x| x > k));
                            }
                        }
                    }
                }
                c.extend(big.iter().copied().filter(|&b| b > k));
                c
            };
            cand.sort_unstable();
            cand.dedup();
            let (prisms, ids, keep) = (&prisms, &ids, &keep);
            cand.into_iter()
                .filter(move |&b| keep(ids[k], ids[b]) && prisms[k].intersects(&prisms[b]))
                .map(move |b| {
                    let (f, g) = (ids[k], ids[b]);
                    (f.min(g), f.max(g))
                })
        })
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    Ok(pairs)
}
