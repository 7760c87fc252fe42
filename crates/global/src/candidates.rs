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
//! interior vertices within `k - 1` edges of a seed (`k <= max_rings` rings of faces), an
//! edge, or a chain of three vertices through the seed ([`seed_candidates`]), whose faces
//! form a disk with a cycle of at most `max_cycle` vertices; every triple on that cycle is
//! enumerated, and kept only when it covers the seed (the seed's fiber crosses it). Of those,
//! the best `per_region` by cover then aspect ratio are kept. A region none of whose triples
//! covers its seed (the seed's fiber crosses the approximation outside the region, as near
//! creases where fibers lean) and which removes the seed alone keeps its best-shaped triples with cover 0, ranked after every
//! covering candidate: they remove one vertex like the local algorithm.
//!
//! With border tubes, open regions (removing border vertices, [`Region::open`]) come too:
//! balls through all vertices that reach the border, chains of 2 and 3 consecutive border
//! vertices, a border vertex with one interior neighbour. Their cover counts every removed
//! vertex whose fiber the triple meets (a border vertex's fiber often leaves the chain's
//! polygon), and they keep their best triples even with cover 0, ranked last.
//!
//! What the pruning can miss: valid triangles whose corners are not all on one such cycle
//! (corners more than `max_rings` rings apart, regions of other shapes, or around a region
//! that is not a disk), and triangles that do not pass through the prism of the seed of a
//! region they bound. What it cannot do: accept anything. Pruning only removes candidates;
//! every candidate that is placed passes the exact validity filter of 5.1 against the
//! barriers and the current approximation, so the guarantee never rests on the pruning.
//! The fiber test ranks; it does not decide validity.

use crate::region::{Region, ball, ball_any, border_next, region};
use envelope_mesh::{HalfEdgeMesh, VertexId};
use envelope_simplify::policy::{Barriers, aspect_ratio};
use glam::DVec3;

/// The per-vertex prism edges: inner and outer envelope points of every input vertex,
/// indexed by vertex id (f64 constructions of `envelope-offset`); the same fibers the local
/// simplifier slides vertices along.
pub use envelope_simplify::policy::VertexFibers as Fibers;

/// Whether the triangle with corners `t` meets the fiber of `v` (exact on the f64 points; a
/// vertex without a fiber is never covered).
///
/// ```
/// use envelope_global::{covers, Fibers};
/// use envelope_mesh::VertexId;
/// use glam::DVec3;
/// let (inner, outer) = ([DVec3::new(0.2, 0.2, -1.0)], [DVec3::new(0.2, 0.2, 1.0)]);
/// let fibers = Fibers { inner: &inner, outer: &outer };
/// let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// assert!(covers(&fibers, VertexId(0), t));
/// assert!(!covers(&fibers, VertexId(0), t.map(|p| p + DVec3::X)));
/// assert!(!covers(&fibers, VertexId(1), t)); // no fiber
/// ```
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
    /// Faces of the region whose fundamental prism it crosses: each of the face's vertices
    /// is a corner of the candidate or a removed vertex whose fiber it meets (the prism's
    /// three edges all meet the candidate).
    pub faces_covered: u32,
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
    /// The ranking: larger vertex cover first, then seed, then more faces covered, better
    /// aspect ratio, rings and corners (a total order, so the run is deterministic).
    #[must_use]
    pub fn rank(&self, o: &Self) -> std::cmp::Ordering {
        o.cover
            .cmp(&self.cover)
            .then(self.seed.cmp(&o.seed))
            .then(o.faces_covered.cmp(&self.faces_covered))
            .then(o.aspect.total_cmp(&self.aspect))
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
    /// Regions may remove border vertices (open regions; only when the barriers have border
    /// tubes to test the new border edges against).
    pub border: bool,
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
    /// Candidates dropped before ranking because they touch an envelope or wall (see
    /// [`seed_candidates`]'s `screen`).
    pub blocked: u64,
}

impl std::ops::AddAssign for Generated {
    fn add_assign(&mut self, o: Self) {
        self.regions += o.regions;
        self.triples += o.triples;
        self.covering += o.covering;
        self.kept += o.kept;
        self.blocked += o.blocked;
    }
}

/// The candidates of every region seeded at `seed`:
///
/// * balls: the interior vertices within `k - 1` edges of the seed, `k` from 1 to
///   `max_rings` (1: the seed alone, its fan), while the cycle has at most `max_cycle`
///   vertices;
/// * edges (with `max_rings >= 2`): the seed and one interior neighbour of larger id;
/// * paths (with `max_rings >= 2`): the seed and two of its interior neighbours `u`, `w`,
///   `w` the neighbour farthest from `u` in angle around the seed (a short chain through the
///   seed, as along a ridge: figure 8).
///
/// `rings` of a candidate is `k` for a ball and 0 for an edge or a path.
///
/// With a `screen` (the barriers of the validity filter), each region keeps its best
/// `per_region` candidates that do not touch an envelope or wall triangle (nor have
/// collinear corners): the part of the 5.1 test that does not depend on the mesh, so a
/// candidate it drops would be rejected when tried anyway. Without, the best `per_region`.
#[must_use]
pub fn seed_candidates(
    mesh: &HalfEdgeMesh,
    fibers: &Fibers<'_>,
    seed: VertexId,
    reach: &Reach,
    screen: Option<&Barriers>,
) -> (Generated, Vec<Candidate>) {
    let mut counts = Generated::default();
    let mut out = Vec::new();
    let mut add = |inside: &[VertexId], rings: u8, counts: &mut Generated| -> bool {
        let Some(r) = region(mesh, inside, reach.border) else {
            return true;
        };
        if r.cycle.len() > reach.max_cycle {
            return false;
        }
        counts.regions += 1;
        let mut kept = region_candidates(mesh, fibers, &r, rings, counts);
        kept.sort_by(Candidate::rank);
        if let Some(barriers) = screen {
            let mut taken = 0;
            kept.retain(|c| {
                if taken >= reach.per_region {
                    return false;
                }
                // Border edges are not flagged: envelope and wall contact is tested
                // whatever they are, tube contact is left to the filter.
                let ok = !barriers.refuses(c.triangle.map(|v| mesh.position(v)), [false; 3]);
                if ok {
                    taken += 1;
                } else {
                    counts.blocked += 1;
                }
                ok
            });
        }
        kept.truncate(reach.per_region);
        for k in &mut kept {
            k.inside.clone_from(&r.inside);
        }
        counts.kept += kept.len() as u64;
        out.extend(kept);
        true
    };
    let mut last_len = 0;
    for rings in 1..=reach.max_rings {
        let inside = ball(mesh, seed, rings - 1);
        if inside.len() == last_len {
            break; // the ball stopped growing
        }
        last_len = inside.len();
        if !add(&inside, rings as u8, &mut counts) {
            break;
        }
    }
    if reach.max_rings >= 2 && !inside_is_empty(mesh, seed) {
        let edges: Vec<VertexId> = mesh
            .vertex_neighbors(seed)
            .filter(|&u| u > seed && !mesh.is_border_vertex(u))
            .collect();
        for u in edges {
            add(&[seed, u], 0, &mut counts);
        }
        for [u, w] in opposite_pairs(mesh, seed) {
            add(&[seed, u, w], 0, &mut counts);
        }
    }
    if reach.border {
        border_regions(
            mesh,
            seed,
            reach,
            &mut |inside, rings, counts| add(inside, rings, counts),
            &mut counts,
        );
    }
    (counts, out)
}

/// The open regions of `seed` (see [`seed_candidates`]): the balls through all vertices that
/// reach the border, and at a border seed the chains of 2 and 3 consecutive border vertices
/// starting there, and the seed with each neighbour.
fn border_regions(
    mesh: &HalfEdgeMesh,
    seed: VertexId,
    reach: &Reach,
    add: &mut dyn FnMut(&[VertexId], u8, &mut Generated) -> bool,
    counts: &mut Generated,
) {
    let mut last_len = 0;
    for rings in 1..=reach.max_rings {
        let inside = ball_any(mesh, seed, rings - 1);
        if inside.is_empty() || inside.len() == last_len {
            break;
        }
        last_len = inside.len();
        if !inside.iter().any(|&v| mesh.is_border_vertex(v)) {
            continue; // a closed ball, generated above
        }
        if !add(&inside, rings as u8, counts) {
            break;
        }
    }
    if !mesh.is_border_vertex(seed) || reach.max_rings < 2 {
        return;
    }
    let mut chain = vec![seed];
    while chain.len() < 3 {
        match border_next(mesh, chain[chain.len() - 1]) {
            Some(w) if !chain.contains(&w) => chain.push(w),
            _ => break,
        }
        add(&chain, 0, counts);
    }
    let ring: Vec<VertexId> = mesh
        .vertex_neighbors(seed)
        .filter(|&u| !mesh.is_border_vertex(u))
        .collect();
    for u in ring {
        add(&[seed, u], 0, counts);
    }
}

fn inside_is_empty(mesh: &HalfEdgeMesh, seed: VertexId) -> bool {
    ball(mesh, seed, 0).is_empty()
}

/// For each interior neighbour `u` of `seed`, the interior neighbour `w` with the largest
/// angle `u seed w` (f64, a choice of regions only); each pair once.
fn opposite_pairs(mesh: &HalfEdgeMesh, seed: VertexId) -> Vec<[VertexId; 2]> {
    let p = mesh.position(seed);
    let ring: Vec<VertexId> = mesh
        .vertex_neighbors(seed)
        .filter(|&v| !mesh.is_border_vertex(v))
        .collect();
    let mut pairs = Vec::new();
    for &u in &ring {
        let du = (mesh.position(u) - p).normalize_or_zero();
        let far = ring.iter().filter(|&&w| w != u).min_by(|&&a, &&b| {
            let ca = du.dot((mesh.position(a) - p).normalize_or_zero());
            let cb = du.dot((mesh.position(b) - p).normalize_or_zero());
            ca.total_cmp(&cb).then(a.cmp(&b))
        });
        if let Some(&w) = far {
            let pair = if u < w { [u, w] } else { [w, u] };
            if !pairs.contains(&pair) {
                pairs.push(pair);
            }
        }
    }
    pairs
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
    let mut covered: Vec<VertexId> = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            for d in b + 1..n {
                counts.triples += 1;
                let triangle = [c[a], c[b], c[d]];
                let p = triangle.map(|v| mesh.position(v));
                // Closed regions count only triples that cover their seed.
                let counted = r.open || covers(fibers, seed, p);
                counts.covering += u64::from(counted && !r.open);
                covered.clear();
                if counted {
                    covered.extend(r.inside.iter().copied().filter(|&v| covers(fibers, v, p)));
                }
                let cover = covered.len() as u32;
                let faces_covered = if cover == 0 {
                    0
                } else {
                    r.faces
                        .iter()
                        .filter(|&&f| {
                            mesh.face_vertices(f)
                                .iter()
                                .all(|v| triangle.contains(v) || covered.contains(v))
                        })
                        .count() as u32
                };
                out.push(Candidate {
                    triangle,
                    cover,
                    faces_covered,
                    aspect: aspect_ratio(p),
                    seed,
                    rings,
                    inside: Vec::new(),
                });
            }
        }
    }
    // Only where no triple covers the seed (its fiber leaves through a face outside the
    // region), the region keeps its best-shaped triples with cover 0, ranked last.
    // Open regions keep their triples either way: their border vertices are removed on the
    // local algorithm's terms (the new border edge through the tubes).
    if !r.open && (r.inside.len() > 1 || out.iter().any(|c| c.cover > 0)) {
        out.retain(|c| c.cover > 0);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::generate;

    /// The screen drops exactly the candidates that touch a barrier: with the mesh itself as
    /// the barrier every candidate touches it (at its corners) and none is kept; with a
    /// barrier far away, the screened and unscreened runs keep the same candidates.
    #[test]
    fn the_screen_drops_blocked_candidates_only() {
        let soup = generate::icosphere(2, 1.0);
        let mesh = HalfEdgeMesh::from_soup(&soup).unwrap();
        let inner: Vec<DVec3> = soup.positions.iter().map(|p| *p * 0.9).collect();
        let outer: Vec<DVec3> = soup.positions.iter().map(|p| *p * 1.1).collect();
        let fibers = Fibers {
            inner: &inner,
            outer: &outer,
        };
        let reach = Reach {
            max_rings: 2,
            max_cycle: 12,
            per_region: 3,
            border: false,
        };
        let seed = VertexId(0);
        let (plain_counts, plain) = seed_candidates(&mesh, &fibers, seed, &reach, None);
        assert!(!plain.is_empty());
        assert_eq!(plain_counts.blocked, 0);
        let touching = Barriers::new(vec![soup.clone()], vec![]).unwrap();
        let (counts, kept) = seed_candidates(&mesh, &fibers, seed, &reach, Some(&touching));
        assert!(kept.is_empty(), "{kept:?}");
        assert!(counts.blocked >= plain.len() as u64, "{counts:?}");
        let far = generate::icosphere(1, 10.0);
        let apart = Barriers::new(vec![far], vec![]).unwrap();
        let (counts, kept) = seed_candidates(&mesh, &fibers, seed, &reach, Some(&apart));
        assert_eq!((counts.blocked, kept.clone()), (0, plain));
        // The seed's fan (1 ring): a candidate covering the seed crosses the prism of each
        // fan face whose two cycle vertices are both its corners.
        let fan: Vec<_> = kept
            .iter()
            .filter(|c| c.rings == 1 && c.cover == 1)
            .collect();
        assert!(!fan.is_empty());
        for c in fan {
            let expect = mesh
                .vertex_faces(seed)
                .filter(|&f| {
                    mesh.face_vertices(f)
                        .iter()
                        .all(|v| *v == seed || c.triangle.contains(v))
                })
                .count() as u32;
            assert_eq!(c.faces_covered, expect, "{c:?}");
        }
    }
}
