//! Caps over loops with edges longer than the cube (issue 37): points added on the long
//! loop edges, the kept face on each such edge split at them.
//!
//! A groove along a flat face of a CAD part, or a tunnel's mouth on a coarse (simplified)
//! wall, has a rim that runs along single edges many times `alpha` long. A cap whose corners
//! are loop vertices only cannot pass the alpha test there: each cap triangle on a long loop
//! edge has two diagonals to its third corner, each at most `2 alpha` (L-infinity), so the
//! loop edge is at most `4 alpha`. El-Sana and Varshney's alpha-hull closes such a groove;
//! the rim's points between its vertices are points of the surface like any other.
//!
//! **Points (our choice).** Every loop edge longer than `alpha` (L-infinity) is cut into the
//! fewest equal pieces at most `alpha` long; the points are f64 constructions, and each one's
//! distance to the exact point of the edge it stands for is bounded exactly (rationals) by
//! [`POINT_ERROR`] `alpha`, else the loop is left unrefined. The cap is then tested at
//! `alpha (1 - 2 POINT_ERROR)`: the cube of that radius at a point lies in the cube of
//! radius `alpha` at the exact point of the edge, which lies in the alpha-prism of the input
//! face on that edge, so every cap still lies in the union of the input's alpha-prisms.
//!
//! **Pieces.** The kept face on a refined edge is split into a fan from its third corner
//! (its orientation kept). A piece lies within `POINT_ERROR alpha` of the face it comes
//! from. A kept face on two refined edges of one loop is not split (the loop is left
//! unrefined); two loops that would split one face are told apart by the caller.

use std::collections::HashMap;

use envelope_mesh::{FaceId, TriangleSoup, VertexId};
use envelope_predicates::arith::rational;
use envelope_predicates::exact_num::Rational;
use glam::DVec3;

use crate::rim::{Candidate, cap_avoiding};

/// Bound, in `alpha`, on a point's distance to the exact point of its edge (see the module
/// docs): far above the rounding of a point on coordinates within a few diagonals of the
/// origin, far below anything the cube test can see.
pub const POINT_ERROR: f64 = 1.0 / (1u64 << 40) as f64;

/// Pieces per loop edge at most (a longer edge leaves the loop unrefined).
const MAX_PIECES: usize = 64;

/// A cap over a loop refined at points of its long edges. Vertex ids from `base` on (the
/// number of positions of the soup it was built on) are the points: `base + j` is
/// `points[j]`.
#[derive(Clone, Debug)]
pub(crate) struct Refined {
    /// See the struct docs.
    pub(crate) base: usize,
    /// The added points.
    pub(crate) points: Vec<DVec3>,
    /// The cap.
    pub(crate) cap: Vec<[VertexId; 3]>,
    /// Each kept face split, with its pieces (in the face's orientation).
    pub(crate) split: Vec<(FaceId, Vec<[VertexId; 3]>)>,
}

impl Refined {
    /// The same refinement with its points numbered from `base + offset` (several refined
    /// caps in one output).
    pub(crate) fn shifted(&self, offset: usize) -> Refined {
        let base = self.base;
        let shift = |t: &[VertexId; 3]| {
            t.map(|v| {
                if v.index() >= base {
                    VertexId::from_index(v.index() + offset)
                } else {
                    v
                }
            })
        };
        Refined {
            base,
            points: self.points.clone(),
            cap: self.cap.iter().map(shift).collect(),
            split: self
                .split
                .iter()
                .map(|(f, pieces)| (*f, pieces.iter().map(shift).collect()))
                .collect(),
        }
    }
}

/// The f64 point `j / k` of the way from `a` to `b`, if it is within [`POINT_ERROR`] `alpha`
/// (each coordinate, exactly) of the exact point.
fn point_on(a: DVec3, b: DVec3, j: usize, k: usize, alpha: f64) -> Option<DVec3> {
    let t = j as f64 / k as f64;
    let p = a + (b - a) * t;
    let bound = rational(POINT_ERROR * alpha);
    let (j, k) = (u32::try_from(j).ok()?, u32::try_from(k).ok()?);
    (0..3)
        .all(|i| {
            let (ra, rb) = (rational(a[i]), rational(b[i]));
            let exact: Rational = &ra + (rb - &ra) * j / k;
            (rational(p[i]) - exact).abs() <= bound
        })
        .then_some(p)
}

/// The cap of `c` (a loop of `soup`) with points on its loop edges longer than `alpha`, if
/// it has such edges, their kept faces are `splittable` (input faces, so that the points
/// lie on input edges) and the alpha test accepts a cap (see the module docs) with no
/// diagonal on an edge `kept` names.
pub(crate) fn refine(
    soup: &TriangleSoup,
    c: &Candidate,
    alpha: f64,
    splittable: impl Fn(FaceId) -> bool,
    kept: &dyn Fn(VertexId, VertexId) -> bool,
) -> Option<Refined> {
    let n = c.vertices.len();
    let base = soup.positions.len();
    // The loop and its kept faces on a small soup of their own (local ids), so that the cap
    // search sees the pieces as the kept faces of the new loop edges.
    let mut local_pos: Vec<DVec3> = Vec::new();
    let mut global: Vec<VertexId> = Vec::new();
    let mut local_of: HashMap<VertexId, usize> = HashMap::new();
    let mut local = |v: VertexId, p: DVec3| -> VertexId {
        let id = *local_of.entry(v).or_insert_with(|| {
            local_pos.push(p);
            global.push(v);
            local_pos.len() - 1
        });
        VertexId::from_index(id)
    };
    let mut points: Vec<DVec3> = Vec::new();
    let mut loop_local: Vec<VertexId> = Vec::new();
    let mut keep_local: Vec<[VertexId; 3]> = Vec::new();
    let mut keep_of_edge: Vec<FaceId> = Vec::new();
    let mut split: Vec<(FaceId, Vec<[VertexId; 3]>)> = Vec::new();
    for i in 0..n {
        let (a, b, keep) = (c.vertices[i], c.vertices[(i + 1) % n], c.keep[i]);
        let face = soup.faces[keep.index()];
        let w = *face.iter().find(|&&v| v != a && v != b)?;
        let (pa, pb) = (soup.position(a), soup.position(b));
        let pieces = ((pb - pa).abs().max_element() / alpha).ceil();
        loop_local.push(local(a, pa));
        if pieces <= 1.0 {
            keep_of_edge.push(FaceId::from_index(keep_local.len()));
            keep_local.push(face.map(|v| local(v, soup.position(v))));
            continue;
        }
        if pieces > MAX_PIECES as f64 || !splittable(keep) || split.iter().any(|(f, _)| *f == keep)
        {
            return None;
        }
        let k = pieces as usize;
        // The face runs a -> b, or b -> a.
        let at = face.iter().position(|&v| v == a)?;
        let forward = face[(at + 1) % 3] == b;
        let mut chain = vec![a];
        for j in 1..k {
            chain.push(VertexId::from_index(base + points.len()));
            points.push(point_on(pa, pb, j, k, alpha)?);
        }
        chain.push(b);
        let mut fan = Vec::with_capacity(k);
        for s in chain.windows(2) {
            fan.push(if forward {
                [s[0], s[1], w]
            } else {
                [s[1], s[0], w]
            });
        }
        let pos = |v: VertexId| {
            if v.index() >= base {
                points[v.index() - base]
            } else {
                soup.position(v)
            }
        };
        for (j, t) in fan.iter().enumerate() {
            if j > 0 {
                loop_local.push(local(chain[j], pos(chain[j])));
            }
            keep_of_edge.push(FaceId::from_index(keep_local.len()));
            keep_local.push(t.map(|v| local(v, pos(v))));
        }
        split.push((keep, fan));
    }
    if split.is_empty() {
        return None;
    }
    let small = TriangleSoup::new(local_pos, keep_local);
    let lc = Candidate::rim(loop_local, keep_of_edge);
    // Diagonals between input vertices joined by an edge the output keeps are refused.
    let kept_global = |a: VertexId, b: VertexId| {
        let (a, b) = (global[a.index()], global[b.index()]);
        a.index() < base && b.index() < base && kept(a, b)
    };
    let cap = cap_avoiding(&small, &lc, alpha * (1.0 - 2.0 * POINT_ERROR), &kept_global).ok()?;
    Some(Refined {
        base,
        points,
        cap: cap.iter().map(|t| t.map(|v| global[v.index()])).collect(),
        split,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_on_an_edge_are_within_their_bound_and_refused_far_from_the_origin() {
        let (a, b) = (DVec3::new(0.1, 0.2, 0.3), DVec3::new(1.7, -0.9, 0.35));
        for j in 1..7 {
            let p = point_on(a, b, j, 7, 0.05).expect("near the origin");
            assert!((p - (a + (b - a) * (j as f64 / 7.0))).length() < 1e-15);
        }
        // A part a billion units from the origin: rounding is larger than the bound.
        let far = DVec3::splat(1e9);
        assert!(point_on(a + far, b + far, 1, 3, 0.05).is_none());
    }
}
