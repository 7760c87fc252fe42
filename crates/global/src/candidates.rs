//! Candidate triangles and their cover (section 5.3): triples of input vertices, ranked by
//! how many vertices they cover through the fundamental prisms.
//!
//! *Generalized projection.* The fundamental prism of a vertex `v` is bounded below and
//! above by the inner and outer envelope points `v - eps_minus n_v` and `v + eps_plus n_v`
//! (section 4); the segment between them is the prism edge through `v`, its *fiber*. The
//! generalized projection maps every point of the space between the envelopes along such
//! fibers onto the input surface. A candidate triangle `T` *covers* vertex `v` when `T`
//! meets `v`'s fiber: exactly [`envelope_predicates::segment_triangle`] on the closed
//! segment and the closed triangle ([`covers`]). A vertex covered by `T` projects into `T`,
//! so `T` can stand for the surface around it.
//!
//! *Where candidates come from (the pruning).* All triples of input vertices is cubic. A
//! candidate is generated only on the boundary cycle of a [`Region`](crate::Region): the
//! interior vertices within `k - 1` edges of a seed (`k <= max_rings` rings of faces) whose faces
//! form a disk with a cycle of at most `max_cycle` vertices; every triple on that cycle is
//! enumerated, and kept only when it covers the seed (the seed's fiber crosses it). Of those,
//! the best `per_region` by cover then aspect ratio are kept.
//!
//! What the pruning can miss: valid triangles whose corners are not all on one such cycle
//! (corners more than `max_rings` rings apart, around border vertices, or around a region
//! that is not a disk), and triangles that do not pass through the prism of the seed of a
//! region they bound. What it cannot do: accept anything. Pruning only removes candidates;
//! every candidate that is placed passes the exact validity filter of 5.1 against the
//! barriers and the current approximation, so the guarantee never rests on the pruning.
//! The fiber test ranks; it does not decide validity.

use crate::region::{Region, ball, region};
use envelope_mesh::{HalfEdgeMesh, VertexId};
use envelope_simplify::aspect_ratio;
use glam::DVec3;

/// The per-vertex prism edges: inner and outer envelope points of every input vertex,
/// indexed by vertex id (f64 constructions of `envelope-offset`).
#[derive(Clone, Copy, Debug)]
pub struct Fibers<'a> {
    /// `v - eps_minus n_v`.
    pub inner: &'a [DVec3],
    /// `v + eps_plus n_v`.
    pub outer: &'a [DVec3],
}

/// Whether the triangle with corners `t` meets the fiber of `v` (exact on the f64 points; a
/// vertex without a fiber is never covered).
#[must_use]
pub fn covers(fibers: &Fibers<'_>, v: VertexId, t: [DVec3; 3]) -> bool {
    let i = v.index();
    match (fibers.inner.get(i), fibers.outer.get(i)) {
        (Some(&p), Some(&q)) => envelope_predicates::segment_triangle(p, q, t).intersects(),
        _ => false,
    }
}

/// One candidate triangle with the region it replaces.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// The corners, oriented as the region's faces.
    pub triangle: [VertexId; 3],
    /// Vertices whose fibers it meets, among those the region removes.
    pub cover: u32,
    /// Its aspect ratio (f64, a priority only).
    pub aspect: f64,
    /// The region's seed.
    pub seed: VertexId,
    /// The region's rings.
    pub rings: u8,
    /// The vertices the region removes (seed first).
    pub inside: Vec<VertexId>,
}

impl Candidate {
    /// The ranking: larger cover first, then better aspect ratio, then seed, rings and
    /// corners (a total order, so the run is deterministic).
    #[must_use]
    pub fn rank(&self, o: &Self) -> std::cmp::Ordering {
        o.cover
            .cmp(&self.cover)
            .then(o.aspect.total_cmp(&self.aspect))
            .then(self.seed.cmp(&o.seed))
            .then(self.rings.cmp(&o.rings))
            .then(self.triangle.cmp(&o.triangle))
    }
}

/// Bounds of the candidate generation (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reach {
    /// Largest ball radius, in rings.
    pub max_rings: usize,
    /// Largest hole cycle.
    pub max_cycle: usize,
    /// Candidates kept per region.
    pub per_region: usize,
}

/// Counts of a candidate generation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Generated {
    /// Usable regions.
    pub regions: u64,
    /// Triples enumerated on their cycles.
    pub triples: u64,
    /// Triples that cover their seed.
    pub covering: u64,
    /// Candidates kept.
    pub kept: u64,
}

impl std::ops::AddAssign for Generated {
    fn add_assign(&mut self, o: Self) {
        self.regions += o.regions;
        self.triples += o.triples;
        self.covering += o.covering;
        self.kept += o.kept;
    }
}

/// The candidates of every region seeded at `seed`: the region of `k` rings removes the
/// interior vertices within `k - 1` edges of the seed (1 ring: the seed alone, its fan),
/// for `k` from 1 to `max_rings`.
#[must_use]
pub fn seed_candidates(
    mesh: &HalfEdgeMesh,
    fibers: &Fibers<'_>,
    seed: VertexId,
    reach: &Reach,
) -> (Generated, Vec<Candidate>) {
    let mut counts = Generated::default();
    let mut out = Vec::new();
    let mut last_len = 0;
    for rings in 1..=reach.max_rings {
        let inside = ball(mesh, seed, rings - 1);
        if inside.len() == last_len {
            break; // the ball stopped growing
        }
        last_len = inside.len();
        let Some(r) = region(mesh, &inside) else {
            continue;
        };
        if r.cycle.len() > reach.max_cycle {
            break;
        }
        counts.regions += 1;
        let mut kept = region_candidates(mesh, fibers, &r, rings as u8, &mut counts);
        kept.sort_by(Candidate::rank);
        kept.truncate(reach.per_region);
        for k in &mut kept {
            k.inside.clone_from(&r.inside);
        }
        counts.kept += kept.len() as u64;
        out.extend(kept);
    }
    (counts, out)
}

fn region_candidates(
    mesh: &HalfEdgeMesh,
    fibers: &Fibers<'_>,
    r: &Region,
    rings: u8,
    counts: &mut Generated,
) -> Vec<Candidate> {
    let c = &r.cycle;
    let n = c.len();
    let seed = r.inside[0];
    let mut out = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            for d in b + 1..n {
                counts.triples += 1;
                let triangle = [c[a], c[b], c[d]];
                let p = triangle.map(|v| mesh.position(v));
                if !covers(fibers, seed, p) {
                    continue;
                }
                counts.covering += 1;
                let cover = r.inside.iter().filter(|&&v| covers(fibers, v, p)).count() as u32;
                out.push(Candidate {
                    triangle,
                    cover,
                    aspect: aspect_ratio(p),
                    seed,
                    rings,
                    inside: Vec::new(),
                });
            }
        }
    }
    out
}
