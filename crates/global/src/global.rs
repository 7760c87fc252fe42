//! The greedy selection of section 5.3: candidates ranked by decreasing cover; the best one
//! that overlaps no accepted one cuts the hole of the current triangles it overlaps, is
//! placed, and the sub-holes it leaves are filled recursively with valid triangles (the local
//! algorithm's greedy filling); when a sub-hole cannot be filled, everything is rolled back
//! and the next candidate is tried.
//!
//! ```text
//! simplify_global
//!   loop over passes                 until a pass accepts nothing (or max_passes)
//!     seed_candidates                every dirty vertex, in parallel (rayon)
//!     rank                           decreasing cover, then aspect ratio (total order)
//!     for each candidate
//!       overlaps_accepted?           a vertex of its region was touched since: skip
//!       cut_region                   remove the region's faces (mesh checkpoint)
//!       fill_from(candidate)         place it, fill the sub-holes greedily (5.1 filter)
//!       commit, or rollback
//! ```
//!
//! Choices the paper leaves open (Varshney's thesis, its ref. [24], is not available):
//!
//! | question | answer |
//! |---|---|
//! | what a candidate replaces | the faces around the vertices of the region it was generated from (a `k`-ring disk around a seed); its corners are on the region's boundary |
//! | cover | the region's vertices whose prism edge (fiber) the candidate meets (exact); input triangles are not counted separately (a triangle is covered when its vertices are) |
//! | overlap of two candidates | they share a removed vertex, or an accepted candidate changed a face around one of them: detected by a per-vertex stamp of the last accepted change |
//! | ties | seed id (first in id order, as the local algorithm's queue), then aspect ratio, rings, corner ids |
//! | when a patch stands for its region | every triangle valid (5.1), and, for a region of several vertices, the fiber of every removed vertex meets the patch (exact; the generalized projection of the region onto the patch). Without this, a large region filled across its short boundary collapses the surface between the envelopes (seen on the figure 8 bar: a 4-face output) |
//! | sub-holes | the local algorithm's greedy filling ([`Greedy::fill_from`]), every triangle through the same [`EnvelopeFilter`] |
//! | border vertices | removed in open regions ([`Region::open`](crate::Region)) when the barriers have border tubes (as in the local algorithm): the hole is the chain left on the region's boundary, closed by a new border edge that the fill tests against the tubes ([`CandidateProfile::border_edges`](envelope_simplify::policy::CandidateProfile)) and refuses when it already exists; the projection condition below applies to the removed interior vertices, the removed border vertices are taken on the local algorithm's terms (the tube test) |
//! | passes | after the first, only seeds within `max_rings` rings of a change are generated again |
//!
//! Genus and orientation: a region is a disk and the hole a simple polygon filled with
//! triangles on its vertices in its orientation, refused when an edge already exists (link
//! condition), as in the local algorithm.

use crate::candidates::{Candidate, Fibers, Generated, Reach, covers, seed_candidates};
use crate::region::{ball_any, region};
use crate::surface::{FiberIndex, SURFACE_RINGS, SurfaceReach, surface_candidates};
use envelope_mesh::{FaceId, HalfEdgeMesh, VertexId};
use envelope_simplify::Progress;
use envelope_simplify::policy::{
    Approximation, Barriers, EnvelopeFilter, FaceGrid, FillContext, Filter, Greedy, Hole,
};
use glam::DVec3;
use rayon::prelude::*;
use serde_json::{Value, json};
use std::collections::HashSet;
use thiserror::Error;

/// Options of [`simplify_global`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GlobalOptions {
    /// Largest region, in rings around its seed.
    pub max_rings: usize,
    /// Largest hole cycle of a region.
    pub max_cycle: usize,
    /// Candidates kept per region.
    pub per_region: usize,
    /// Passes at most.
    pub max_passes: usize,
    /// Run the mesh's and the grid's sanity checks after every accepted candidate (slow).
    pub check_each_step: bool,
    /// Regions may remove border vertices (open holes closed by a new border edge, tested
    /// against the border tubes). [`simplify_global`] uses it only when the barriers have
    /// tubes, as the local algorithm does.
    pub border: bool,
    /// Stop once at most this many faces remain (checked before every candidate; the
    /// driver sets it from `SimplifyOptions::target_faces`).
    pub target_faces: Option<usize>,
    /// Candidates from the whole surface with their maximal holes too ([`SurfaceReach`],
    /// module `surface`); `None`: the region candidates only.
    pub surface: Option<SurfaceReach>,
}

impl Default for GlobalOptions {
    /// The global method: regions up to 3 rings and 18 boundary vertices, 8 candidates per
    /// region, up to 32 passes.
    fn default() -> Self {
        GlobalOptions {
            max_rings: 3,
            max_cycle: 18,
            per_region: 8,
            max_passes: 32,
            check_each_step: false,
            border: true,
            target_faces: None,
            surface: None,
        }
    }
}

impl GlobalOptions {
    /// The global method of section 5.3: whole-surface candidates ([`SurfaceReach::default`])
    /// with their maximal holes, ranked together with the region candidates of
    /// [`GlobalOptions::default`].
    #[must_use]
    pub fn surface() -> Self {
        GlobalOptions {
            surface: Some(SurfaceReach::default()),
            ..GlobalOptions::default()
        }
    }

    /// The hybrid's global stage: regions up to 2 rings and 10 boundary vertices, 3
    /// candidates per region, 4 passes. (Larger regions gave the same faces on the
    /// `global_vs_local` benchmark for more time.)
    #[must_use]
    pub fn bounded() -> Self {
        GlobalOptions {
            max_rings: 2,
            max_cycle: 10,
            per_region: 3,
            max_passes: 4,
            check_each_step: false,
            border: true,
            target_faces: None,
            surface: None,
        }
    }
}

/// Why [`simplify_global`] stopped with an error.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum GlobalError {
    /// The input has a vertex whose faces form several fans.
    #[error("vertex {0} is not manifold")]
    NonManifoldVertex(VertexId),
    /// A structure failed its sanity check (only with [`GlobalOptions::check_each_step`]).
    #[error("sanity check failed: {0}")]
    SanityCheck(String),
}

/// Counts of one run of [`simplify_global`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GlobalStats {
    /// Live vertices before.
    pub vertices_before: usize,
    /// Live faces before.
    pub faces_before: usize,
    /// Live vertices after.
    pub vertices_after: usize,
    /// Live faces after.
    pub faces_after: usize,
    /// Passes run.
    pub passes: usize,
    /// Candidate generation counts, summed over passes.
    pub generated: Generated,
    /// Candidates tried (not overlapping an accepted one).
    pub attempts: usize,
    /// Candidates accepted.
    pub accepted: usize,
    /// Candidates skipped because they overlap an accepted one.
    pub overlapping: usize,
    /// Candidates rejected because the candidate or a sub-hole had no valid filling.
    pub no_valid_fill: usize,
    /// Vertices removed.
    pub removed: usize,
    /// Candidate triangles given to the validity filter.
    pub filter_tests: u64,
    /// Whole-surface candidates accepted (with [`GlobalOptions::surface`]).
    pub surface_accepted: usize,
    /// Vertices they removed.
    pub surface_removed: usize,
}

impl GlobalStats {
    /// Stable JSON keys (the report's `method_details`).
    #[must_use]
    pub fn to_json(&self) -> Value {
        json!({
            "faces_before": self.faces_before,
            "faces_after": self.faces_after,
            "passes": self.passes,
            "regions": self.generated.regions,
            "candidate_triples": self.generated.triples,
            "candidates_covering": self.generated.covering,
            "candidates_ranked": self.generated.kept,
            "candidates_blocked": self.generated.blocked,
            "attempts": self.attempts,
            "accepted": self.accepted,
            "overlapping": self.overlapping,
            "no_valid_fill": self.no_valid_fill,
            "removed_vertices": self.removed,
            "filter_tests": self.filter_tests,
            "surface_accepted": self.surface_accepted,
            "surface_removed_vertices": self.surface_removed,
        })
    }
}

/// Simplifies `mesh` in place by the global algorithm (see the module docs), every placed
/// triangle checked by the [`EnvelopeFilter`] against `barriers`. Border vertices are removed
/// only when `barriers` has border tubes and [`GlobalOptions::border`] is set.
///
/// ```
/// use envelope_global::{Fibers, GlobalOptions, simplify_global};
/// use envelope_mesh::{generate, HalfEdgeMesh};
/// use envelope_simplify::policy::Barriers;
/// let soup = generate::icosphere(1, 1.0);
/// let mut m = HalfEdgeMesh::from_soup(&soup).unwrap();
/// // Fibers along the radius (a sphere's normals), 0.3 each way, no barrier at all.
/// let inner: Vec<_> = soup.positions.iter().map(|p| *p * 0.7).collect();
/// let outer: Vec<_> = soup.positions.iter().map(|p| *p * 1.3).collect();
/// let fibers = Fibers { inner: &inner, outer: &outer };
/// let s = simplify_global(&mut m, &Barriers::none(), &fibers, &GlobalOptions::default(), &mut ())
///     .unwrap();
/// assert!(s.removed > 0 && m.num_faces() < 80);
/// ```
pub fn simplify_global(
    mesh: &mut HalfEdgeMesh,
    barriers: &Barriers,
    fibers: &Fibers<'_>,
    options: &GlobalOptions,
    progress: &mut dyn Progress,
) -> Result<GlobalStats, GlobalError> {
    let filter = EnvelopeFilter::new(barriers);
    let options = GlobalOptions {
        border: options.border && barriers.has_tubes(),
        ..*options
    };
    run(mesh, &filter, Some(barriers), fibers, &options, progress)
}

/// [`simplify_global`] with any validity filter (which must test
/// [`CandidateProfile::border_edges`](envelope_simplify::policy::CandidateProfile) when
/// [`GlobalOptions::border`] is set).
pub fn simplify_global_with(
    mesh: &mut HalfEdgeMesh,
    filter: &dyn Filter,
    fibers: &Fibers<'_>,
    options: &GlobalOptions,
    progress: &mut dyn Progress,
) -> Result<GlobalStats, GlobalError> {
    run(mesh, filter, None, fibers, options, progress)
}

/// The driver; `screen`: barriers that `filter` tests every candidate against (see
/// [`seed_candidates`]).
fn run(
    mesh: &mut HalfEdgeMesh,
    filter: &dyn Filter,
    screen: Option<&Barriers>,
    fibers: &Fibers<'_>,
    options: &GlobalOptions,
    progress: &mut dyn Progress,
) -> Result<GlobalStats, GlobalError> {
    if let Some(v) = mesh.vertices().find(|&v| !mesh.is_manifold_vertex(v)) {
        return Err(GlobalError::NonManifoldVertex(v));
    }
    let mut stats = GlobalStats {
        vertices_before: mesh.num_vertices(),
        faces_before: mesh.num_faces(),
        ..GlobalStats::default()
    };
    let reach = Reach {
        max_rings: options.max_rings,
        max_cycle: options.max_cycle,
        per_region: options.per_region,
        border: options.border,
    };
    let mut g = Global {
        grid: FaceGrid::from_mesh(mesh),
        mesh,
        keep: screen.map_or(&[][..], Barriers::kept),
        touched: Vec::new(),
        epoch: 0,
        border: options.border,
    };
    let mut seeds: Vec<VertexId> = g.mesh.vertices().collect();
    let reached = |mesh: &HalfEdgeMesh| options.target_faces.is_some_and(|t| mesh.num_faces() <= t);
    'passes: for _ in 0..options.max_passes {
        if seeds.is_empty() || reached(g.mesh) {
            break;
        }
        stats.passes += 1;
        let start = g.epoch;
        let mut candidates = g.rank(
            fibers,
            &seeds,
            &reach,
            options.surface.as_ref(),
            screen,
            &mut stats.generated,
        );
        let before = stats.accepted;
        for c in candidates.drain(..) {
            if reached(g.mesh) {
                break 'passes;
            }
            if g.overlaps_accepted(&c, start) {
                stats.overlapping += 1;
                continue;
            }
            stats.attempts += 1;
            if stats.attempts % 64 == 0 {
                progress.step(stats.attempts, stats.removed);
            }
            let (tests, placed) = g.try_candidate(&c, filter, fibers);
            stats.filter_tests += tests;
            if placed {
                stats.accepted += 1;
                stats.removed += c.inside.len();
                if c.rings == SURFACE_RINGS {
                    stats.surface_accepted += 1;
                    stats.surface_removed += c.inside.len();
                }
                if options.check_each_step {
                    g.mesh.sanity_check().map_err(GlobalError::SanityCheck)?;
                    g.grid
                        .sanity_check(g.mesh)
                        .map_err(GlobalError::SanityCheck)?;
                }
            } else {
                stats.no_valid_fill += 1;
            }
        }
        if stats.accepted == before {
            break;
        }
        seeds = g.dirty_seeds(start, options.max_rings);
    }
    stats.vertices_after = g.mesh.num_vertices();
    stats.faces_after = g.mesh.num_faces();
    Ok(stats)
}

/// The mesh being simplified, the index of its live faces, and the change stamps.
struct Global<'m> {
    mesh: &'m mut HalfEdgeMesh,
    grid: FaceGrid,
    /// Epoch of the last accepted change around each vertex (0: never).
    touched: Vec<u64>,
    epoch: u64,
    /// Regions may remove border vertices ([`GlobalOptions::border`]).
    border: bool,
    /// Vertices no region may remove ([`Barriers::with_kept`]).
    keep: &'m [bool],
}

impl Global<'_> {
    /// Candidates of every seed, ranked (rayon; the result does not depend on the threads).
    fn rank(
        &self,
        fibers: &Fibers<'_>,
        seeds: &[VertexId],
        reach: &Reach,
        surface: Option<&SurfaceReach>,
        screen: Option<&Barriers>,
        counts: &mut Generated,
    ) -> Vec<Candidate> {
        let mesh: &HalfEdgeMesh = self.mesh;
        let index = surface.map(|_| FiberIndex::new(mesh, fibers));
        let per_seed: Vec<(Generated, Vec<Candidate>)> = seeds
            .par_iter()
            .map(|&s| {
                let (mut c, mut v) = seed_candidates(mesh, fibers, s, reach, screen);
                if let (Some(sr), Some(index)) = (surface, &index) {
                    let (c2, v2) = surface_candidates(mesh, fibers, index, s, sr, screen);
                    c += c2;
                    v.extend(v2);
                }
                (c, v)
            })
            .collect();
        let mut all = Vec::new();
        for (c, v) in per_seed {
            *counts += c;
            all.extend(v);
        }
        all.sort_by(Candidate::rank);
        // A whole-surface triangle comes from each of its corners' seeds: keep its first.
        let mut seen: HashSet<[VertexId; 3]> = HashSet::new();
        all.retain(|c| {
            if c.rings != SURFACE_RINGS {
                return true;
            }
            let mut t = c.triangle;
            t.sort_unstable();
            seen.insert(t)
        });
        all
    }

    fn stamp(&self, v: VertexId) -> u64 {
        self.touched.get(v.index()).copied().unwrap_or(0)
    }

    /// A vertex of the candidate's region is gone or changed since `start`.
    fn overlaps_accepted(&self, c: &Candidate, start: u64) -> bool {
        c.inside
            .iter()
            .any(|&v| !self.mesh.contains_vertex(v) || self.stamp(v) > start)
            || c.triangle.iter().any(|&v| !self.mesh.contains_vertex(v))
    }

    /// Live vertices within `rings` rings (plus one) of a vertex changed since `start`.
    fn dirty_seeds(&self, start: u64, rings: usize) -> Vec<VertexId> {
        let n = self
            .mesh
            .vertices()
            .map(|v| v.index() + 1)
            .max()
            .unwrap_or(0);
        let mut dirty = vec![false; n];
        for v in self.mesh.vertices() {
            if self.stamp(v) > start {
                let b = ball_any(self.mesh, v, rings);
                for w in b {
                    if w.index() < dirty.len() {
                        dirty[w.index()] = true;
                    }
                    for x in self.mesh.vertex_neighbors(w) {
                        if x.index() < dirty.len() {
                            dirty[x.index()] = true;
                        }
                    }
                }
            }
        }
        self.mesh.vertices().filter(|v| dirty[v.index()]).collect()
    }

    /// Cuts the candidate's region, places it, fills the sub-holes; keeps the result or
    /// restores the region exactly. Returns the filter calls and whether it was placed.
    fn try_candidate(
        &mut self,
        c: &Candidate,
        filter: &dyn Filter,
        fibers: &Fibers<'_>,
    ) -> (u64, bool) {
        if c.inside
            .iter()
            .any(|v| self.keep.get(v.index()).copied().unwrap_or(false))
        {
            return (0, false);
        }
        let Some(r) = region(self.mesh, &c.inside, self.border) else {
            return (0, false);
        };
        let mut at = [0usize; 3];
        for (k, v) in c.triangle.iter().enumerate() {
            match r.cycle.iter().position(|x| x == v) {
                Some(i) => at[k] = i,
                None => return (0, false),
            }
        }
        if !(at[0] < at[1] && at[1] < at[2]) {
            return (0, false);
        }
        // Removed interior vertices (the projection condition applies to them; removed
        // border vertices are taken on the local algorithm's terms: the tube test of the
        // new border edge, and its passing through the rings of the input border vertices
        // it stands for, `Filter::refuses_border_edge`).
        let (interior, border): (Vec<VertexId>, Vec<VertexId>) = r
            .inside
            .iter()
            .partition(|&&v| !self.mesh.is_border_vertex(v));
        if let (true, Some(&first), Some(&last)) = (r.open, r.cycle.first(), r.cycle.last()) {
            let ends = [last, first].map(|u| (u, self.mesh.position(u)));
            if border.iter().any(|&v| filter.refuses_border_edge(v, ends)) {
                return (0, false);
            }
        }
        // The region's triangles, for the test against the filling below.
        let old: Vec<[DVec3; 3]> = r
            .faces
            .iter()
            .map(|&f| self.mesh.face_vertices(f).map(|x| self.mesh.position(x)))
            .collect();
        let cp = self.mesh.begin();
        if self.mesh.remove_faces(&r.faces).is_err() {
            self.mesh.rollback(cp);
            return (0, false);
        }
        for &f in &r.faces {
            self.grid.remove(f);
        }
        let hole = Hole {
            vertices: r.cycle.clone(),
            open: r.open,
        };
        let (ok, tests, placed) = {
            let mut ctx = FillContext::new(self.mesh, &self.grid, filter, &hole);
            let ok = Greedy::default().fill_from(&mut ctx, at);
            (ok, ctx.tests, ctx.placed().to_vec())
        };
        let cov =
            ok && (r.inside.len() == 1 || covers_removed(self.mesh, fibers, &interior, &placed));
        // No barrier component carried across by the filling.
        let cov = cov && {
            let new: Vec<[DVec3; 3]> = placed
                .iter()
                .map(|t| t.map(|x| self.mesh.position(x)))
                .collect();
            !filter.refuses_replacement(
                &old,
                &new,
                &Approximation::of_mesh(self.mesh, &self.grid),
                r.open,
            )
        };
        let added = if cov {
            self.mesh.add_faces(&placed).ok()
        } else {
            None
        };
        let Some(faces) = added else {
            self.mesh.rollback(cp);
            self.reinsert(&r.faces);
            return (tests, false);
        };
        for &v in &r.inside {
            self.mesh
                .remove_vertex(v)
                .expect("a region's inside vertices are isolated once its faces are gone");
        }
        self.mesh.commit(cp);
        self.reinsert(&faces);
        self.grid.rebalance();
        self.epoch += 1;
        for &v in r.inside.iter().chain(&r.cycle) {
            if self.touched.len() <= v.index() {
                self.touched.resize(v.index() + 1, 0);
            }
            self.touched[v.index()] = self.epoch;
        }
        (tests, true)
    }

    fn reinsert(&mut self, faces: &[FaceId]) {
        for &f in faces {
            let t = self.mesh.face_vertices(f);
            self.grid.insert(f, t, t.map(|x| self.mesh.position(x)));
        }
    }
}

/// The projection condition of a multi-vertex removal: the fiber of every removed vertex
/// meets a triangle of the new patch (exact). Without it, a patch can stay between the
/// envelopes and still not stand for the region it replaces (a large region filled across
/// its short boundary collapses the surface; every triangle valid, the input far from the
/// output). A single-vertex region is the local algorithm's removal and is accepted on the
/// same terms as there.
fn covers_removed(
    mesh: &HalfEdgeMesh,
    fibers: &Fibers<'_>,
    inside: &[VertexId],
    placed: &[[VertexId; 3]],
) -> bool {
    inside.iter().all(|&v| {
        placed
            .iter()
            .any(|t| covers(fibers, v, t.map(|x| mesh.position(x))))
    })
}
