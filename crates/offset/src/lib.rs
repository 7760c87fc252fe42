//! Simplification envelopes: vertex normals, analytical and numerical epsilon, per-vertex
//! epsilon fields and border tubes (Cohen et al., "Simplification Envelopes", 1996, sections
//! 3, 4, 6.2, 6.3).
//!
//! [`build_envelopes`] reads like the paper:
//!
//! 1. accept the input (manifold, consistently oriented: section 3's "well-behaved" model),
//! 2. evaluate the [`EpsilonField`] per vertex (6.3),
//! 3. compute [`vertex_normals`] within 90 degrees of every adjacent face (3); a vertex with
//!    none (a folded fan) is *pinned*: offsets zero there ([`Envelopes::pinned`]),
//! 4. compute per-vertex `eps_plus` / `eps_minus` by the [`Method::Analytical`] prism
//!    clipping (4.1) or the [`Method::Numerical`] iterative growth (4.2) (or the growth
//!    from the proved clipping where it fell short: [`Method::Auto`]),
//! 5. place the envelope vertices `v ± eps_v n_v` (f64 constructions, same connectivity),
//! 6. **prove** exactly that input, outer and inner envelope are pairwise and individually
//!    free of intersections ([`Proof`]); when the proof fails (the analytical distances are
//!    f64 constructions and approximate the bilinear-patch prism; the numerical steps check
//!    end positions, not the swept volume) every vertex of an offending envelope face has its
//!    epsilon halved and the proof is re-run, at most [`EnvelopeOptions::max_repair_rounds`]
//!    times. A proof that still fails is reported, never hidden,
//! 7. grow border [`Tube`]s (6.2) and prove them.
//!
//! Exactness: predicates are exact (`envelope-predicates`), normals, offset vertices and
//! distances are f64 constructions. The guarantee is the exact proof on the constructed
//! vertices, nothing else.
//!
//! Choices the paper leaves open, made here: the normal combination (angle-weighted average,
//! maximin fallback; [`normals`](vertex_normals)), pinning where there is no valid normal,
//! the prism's conservative "closest point" set and the repair by halving (analytical),
//! `K = 4`, global step `min(1 % of the diagonal, eps/K)`, local step half the shortest incident edge within 90 degrees of the
//! offset direction, the step tripled after every accepted step (not in the paper: an
//! unobstructed vertex reaches its target in about 2 checks instead of `K`), at most 10
//! halvings per step (numerical; [`NumericalParams`]), the order of moves (Z-order
//! renumbering, then coloured parallel batches, deterministic; [`engine`](self) docs), outer
//! and inner grown together and checked against each other, and the tube rules in
//! [`tubes`](Tube).
#![forbid(unsafe_code)]

mod analytical;
mod engine;
mod field;
mod normals;
mod proof;
mod tubes;

/// Marsaglia's xorshift64 from `seed` (the randomized unit tests of this crate).
#[cfg(test)]
fn xorshift(mut state: u64) -> impl FnMut() -> u64 {
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    }
}

use envelope_mesh::{Topology, TriangleSoup, VertexFaces, VertexId, analyze};
use envelope_predicates::bvh::{Aabb, Bvh};
use glam::DVec3;

pub use field::{
    EpsilonField, EpsilonFileError, EpsilonParseError, EpsilonSpec, parse_epsilon,
    parse_epsilon_values, read_epsilon_file,
};
pub use normals::{VertexNormals, vertex_normals};
pub use proof::{Contact, Proof, Surface};
pub use tubes::Tube;

use engine::{Mover, Scene, StepPolicy};

/// How the per-vertex epsilon is found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Method {
    /// Prism clipping (section 4.1), then the exact proof and repair.
    Analytical,
    /// Iterative growth with exact checks (section 4.2).
    #[default]
    Numerical,
    /// The analytical clipping first, proved and repaired. When every offset reaches the
    /// requested epsilon, that is the result. When clipping or repair cut some, the numerical
    /// growth starts from the proved analytical envelopes and moves only the short vertices
    /// (the others are part of its scene, where they are); its result is proved again and
    /// kept when the proof holds (every offset is then at least the analytical one).
    /// When the analytical repair gives up, the numerical method from zero offsets, and the
    /// better of the two. Not in the paper: the analytical method is several times faster
    /// and reaches the full epsilon when it is small against the features; the growth gets
    /// closer to it where epsilon is large against them, and seeding it with the analytical
    /// offsets reaches further than growing from zero (`envelope simplify --no-verify
    /// --report R` on `armadillo.off` at 1 % of the diagonal: 942 faces, 3.6 s of envelopes,
    /// against 1,128 faces and 4.5 s from zero; `bunny00.off`: 442 against 450; analytical
    /// alone: 648).
    Auto,
}

/// Parameters of the numerical method (section 4.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NumericalParams {
    /// `K`: a vertex that has taken fewer than `K` steps halves its step when rejected.
    pub k: u32,
    /// Global step cap as a fraction of the bounding-box diagonal (also capped by `eps/K`).
    pub global_fraction: f64,
    /// Local step as a fraction of the shortest incident edge within 90 degrees of the
    /// offset direction.
    pub local_fraction: f64,
    /// Maximum halvings of one step.
    pub max_halvings: u32,
    /// Factor applied to a mover's step after each accepted step (`1.0`: the paper's fixed
    /// step; `2.0`: doubling, so an unobstructed vertex reaches its target in about
    /// `log2(target / step)` checks instead of `target / step`).
    pub step_growth: f64,
}

impl Default for NumericalParams {
    fn default() -> Self {
        NumericalParams {
            k: 4,
            global_fraction: 0.01,
            local_fraction: 0.5,
            max_halvings: 10,
            step_growth: 3.0,
        }
    }
}

/// Options of [`build_envelopes`].
#[derive(Debug)]
pub struct EnvelopeOptions {
    /// Requested epsilon per vertex.
    pub epsilon: EpsilonField,
    /// Analytical or numerical.
    pub method: Method,
    /// Numerical-method parameters (also used to grow tubes).
    pub numerical: NumericalParams,
    /// Vertices per tube ring; `None` builds no tubes.
    pub tube_segments: Option<u32>,
    /// Maximum rounds of "halve offending vertices, re-prove".
    pub max_repair_rounds: u32,
    /// The caller has proved the input free of self-intersections (as `envelope-check`'s
    /// exact pairwise test does, and `envelope simplify` refuses an input that fails it):
    /// the proof then skips input-input pairs. With `false` (the default) it tests them, and
    /// an intersecting input shows as input-input contacts.
    pub input_free_of_intersections: bool,
}

impl EnvelopeOptions {
    /// Defaults (numerical, 8-gon tubes, 30 repair rounds) for a field.
    #[must_use]
    pub fn new(epsilon: EpsilonField) -> Self {
        EnvelopeOptions {
            epsilon,
            method: Method::default(),
            numerical: NumericalParams::default(),
            tube_segments: Some(8),
            max_repair_rounds: 30,
            input_free_of_intersections: false,
        }
    }
}

/// Why the envelopes could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EnvelopeError {
    /// No faces.
    #[error("the mesh has no faces")]
    Empty,
    /// A face names a vertex that does not exist.
    #[error("a face index is out of range")]
    IndexOutOfRange,
    /// Non-manifold edges or vertices.
    #[error("the mesh is not manifold")]
    NotManifold,
    /// Faces are not consistently oriented.
    #[error("the mesh is not consistently oriented")]
    NotOriented,
    /// Per-vertex epsilon count differs from the vertex count.
    #[error("{got} epsilon values for {expected} vertices")]
    EpsilonCount {
        /// Vertices.
        expected: usize,
        /// Values.
        got: usize,
    },
    /// A non-finite or non-positive epsilon.
    #[error("epsilon of vertex {} is not finite and positive", .vertex.0)]
    BadEpsilon {
        /// The first such vertex.
        vertex: VertexId,
    },
    /// An epsilon too small to be represented as an offset beside the mesh's coordinates
    /// (below [`EPSILON_FLOOR`] times the largest coordinate magnitude).
    #[error(
        "epsilon {epsilon:e}{} is below 2^-40 times the largest coordinate magnitude \
         {magnitude:e} (at least {floor:e} is needed): offsets that small are lost in the \
         rounding of the coordinates; use a larger epsilon or move the mesh toward the origin",
        .vertex.map(|v| format!(" (vertex {})", v.0)).unwrap_or_default()
    )]
    EpsilonTooSmall {
        /// The first such vertex (`None` for a constant epsilon).
        vertex: Option<VertexId>,
        /// Its epsilon.
        epsilon: f64,
        /// The smallest accepted epsilon.
        floor: f64,
        /// The largest coordinate magnitude of the mesh.
        magnitude: f64,
    },
    /// Coordinates so large that envelopes around them leave the exact predicates' range.
    #[error(
        "coordinates up to {magnitude:e} with epsilon {epsilon:e} would put envelope points \
         beyond 2^119, outside the exact predicates' range; scale the mesh down"
    )]
    CoordinatesTooLarge {
        /// The largest coordinate magnitude of the mesh.
        magnitude: f64,
        /// The largest epsilon (after clamping to the diagonal).
        epsilon: f64,
    },
    /// A tube ring with too few or too many vertices.
    #[error("{0} tube segments: a tube ring needs 3 to {MAX_TUBE_SEGMENTS} vertices")]
    TubeSegments(u32),
}

/// The smallest epsilon, as a fraction of the largest coordinate magnitude, that
/// [`EpsilonField::evaluate`] accepts: 2^-40 leaves an offset about 4,000 units in the last
/// place of the coordinates it is added to.
pub const EPSILON_FLOOR: f64 = 9.094_947_017_729_282e-13;

/// The most vertices a tube ring may have.
pub const MAX_TUBE_SEGMENTS: u32 = 64;

/// Inner and outer envelopes, tubes and the exact proof.
#[derive(Clone, Debug)]
pub struct Envelopes {
    /// `v + eps_plus_v n_v` for every vertex, input connectivity.
    pub outer: TriangleSoup,
    /// `v - eps_minus_v n_v` for every vertex, input connectivity.
    pub inner: TriangleSoup,
    /// Vertex normals (zero at [`Envelopes::pinned`] vertices).
    pub normals: Vec<DVec3>,
    /// Vertices with no valid normal (no direction strictly within 90 degrees of all their
    /// faces, decided exactly: a folded fan). Both offsets are zero there: the envelopes
    /// pass through the input vertex, which pinches the space between them to that point.
    /// Not in the paper, which assumes every vertex has a normal. A simplifier must keep
    /// these vertices, and a candidate triangle may touch an envelope there only at a
    /// corner it shares with it (`envelope-simplify`'s `Barriers::with_pins`).
    pub pinned: Vec<VertexId>,
    /// Requested epsilon per vertex.
    pub requested: Vec<f64>,
    /// Achieved outer offset per vertex (`<= requested`).
    pub eps_plus: Vec<f64>,
    /// Achieved inner offset per vertex (`<= requested`).
    pub eps_minus: Vec<f64>,
    /// Border tubes (empty for closed meshes).
    pub tubes: Vec<Tube>,
    /// The method whose offsets these are ([`Method::Analytical`] or [`Method::Numerical`];
    /// with [`Method::Auto`], the one it kept).
    pub method: Method,
    /// The exact non-intersection proof.
    pub proof: Proof,
    /// A tree over the faces of [`Envelopes::outer`] then those of [`Envelopes::inner`]
    /// (item `f`: outer face `f`; item `n + f`, `n` faces: inner face `f`), the one the
    /// proof searched, with both offsets of a face in one leaf: `envelope-simplify`'s
    /// `Barriers::with_tree` takes it instead of building its own.
    pub tree: Bvh,
}

impl Envelopes {
    /// `eps_plus / requested` and `eps_minus / requested` of every referenced vertex, sorted.
    #[must_use]
    pub fn achieved_fractions(&self) -> Vec<f64> {
        let mut used = vec![false; self.requested.len()];
        for f in &self.outer.faces {
            for v in f {
                used[v.0 as usize] = true;
            }
        }
        let mut out: Vec<f64> = (0..self.requested.len())
            .filter(|&v| used[v])
            .flat_map(|v| {
                [
                    self.eps_plus[v] / self.requested[v],
                    self.eps_minus[v] / self.requested[v],
                ]
            })
            .collect();
        out.sort_by(f64::total_cmp);
        out
    }
}

/// Builds and proves the envelopes (see the crate docs for the steps).
///
/// ```
/// use envelope_mesh::generate;
/// use envelope_offset::{build_envelopes, EnvelopeOptions, EpsilonField};
/// let sphere = generate::icosphere(2, 1.0);
/// let env = build_envelopes(&sphere, &EnvelopeOptions::new(EpsilonField::Constant(0.05))).unwrap();
/// assert!(env.proof.holds());
/// assert!(env.eps_plus.iter().all(|&e| e > 0.0 && e <= 0.05));
/// ```
pub fn build_envelopes(
    soup: &TriangleSoup,
    options: &EnvelopeOptions,
) -> Result<Envelopes, EnvelopeError> {
    accept_indices(soup)?;
    let (topology, input_tree) = rayon::join(|| analyze(soup), || face_tree(soup));
    build_envelopes_with(soup, options, &topology, &input_tree)
}

/// The tree [`build_envelopes_with`] wants: `Bvh::from_triangles` over the soup's faces in
/// order (for a soup whose indices are in range).
///
/// ```
/// use envelope_mesh::generate;
/// let soup = generate::icosphere(1, 1.0);
/// assert_eq!(envelope_offset::face_tree(&soup).len(), soup.num_faces());
/// ```
#[must_use]
pub fn face_tree(soup: &TriangleSoup) -> Bvh {
    let faces: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
    Bvh::from_triangles(&soup.positions, &faces)
}

/// [`build_envelopes`] with the input's topology and face tree computed already (the
/// simplify driver shares them with its input check): `topology` must be
/// `envelope_mesh::analyze(soup)` and `input_tree` [`face_tree`]`(soup)`. A tree of another
/// length than the soup's face count is not used (one is built).
///
/// ```
/// use envelope_mesh::{analyze, generate};
/// use envelope_offset::{build_envelopes, build_envelopes_with, face_tree, EnvelopeOptions, EpsilonField};
/// let sphere = generate::icosphere(2, 1.0);
/// let options = EnvelopeOptions::new(EpsilonField::Constant(0.05));
/// let shared = build_envelopes_with(&sphere, &options, &analyze(&sphere), &face_tree(&sphere)).unwrap();
/// assert_eq!(shared.eps_plus, build_envelopes(&sphere, &options).unwrap().eps_plus);
/// ```
pub fn build_envelopes_with(
    soup: &TriangleSoup,
    options: &EnvelopeOptions,
    topology: &Topology,
    input_tree: &Bvh,
) -> Result<Envelopes, EnvelopeError> {
    let topo = accept_input(soup, topology)?;
    if let Some(k) = options.tube_segments
        && !(3..=MAX_TUBE_SEGMENTS).contains(&k)
    {
        return Err(EnvelopeError::TubeSegments(k));
    }
    let built;
    let input_tree = if input_tree.len() == soup.num_faces() {
        input_tree
    } else {
        built = face_tree(soup);
        &built
    };
    let requested = options.epsilon.evaluate(&soup.positions)?;
    let vf = VertexFaces::new(soup.num_vertices(), &soup.faces);
    let vn = normals::vertex_normals_with(soup, &vf);
    let normals = vn.normals;
    let pinned = vn.invalid;
    // What the methods aim for: the requested epsilon, except zero at pinned vertices.
    let mut targets = requested.clone();
    for v in &pinned {
        targets[v.index()] = 0.0;
    }
    let faces: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
    let diagonal = soup.diagonal();
    // `input_tree`: one tree over the input faces, for the analytical method and every proof.
    let analytical = || analytical::analytical_eps(soup, &vf, &normals, &targets, input_tree);
    // From zero, or from proved offsets (`start`).
    let numerical = |start: Option<(&[f64], &[f64])>| {
        numerical_eps(
            soup,
            &vf,
            &normals,
            &targets,
            &options.numerical,
            diagonal,
            start,
        )
    };
    let input_free = options.input_free_of_intersections;
    let prove = |(p, m): (Vec<f64>, Vec<f64>), proved: Option<&Proved>| {
        let base = proved.filter(|b| b.proof.contacts.is_empty());
        prove_and_repair(
            soup,
            &normals,
            &faces,
            (p, m),
            (input_free, base),
            input_tree,
            options.max_repair_rounds,
        )
    };
    let (
        method,
        Proved {
            eps_plus,
            eps_minus,
            outer,
            inner,
            mut proof,
            tree,
        },
    ) = match options.method {
        Method::Analytical => (Method::Analytical, prove(analytical(), None)),
        Method::Numerical => (Method::Numerical, prove(numerical(None), None)),
        Method::Auto => {
            let short = |e: &[f64]| e.iter().zip(&targets).any(|(x, r)| x < r);
            let a = prove(analytical(), None);
            if !a.proof.holds() {
                // Repair gave up: numerical from scratch, and the better of the two.
                let n = prove(numerical(None), None);
                if n.proof.holds() || n.total() > a.total() {
                    (Method::Numerical, n)
                } else {
                    (Method::Analytical, a)
                }
            } else if short(&a.eps_plus) || short(&a.eps_minus) {
                // Clipping or repair cut some offsets: grow those numerically from the
                // proved analytical envelopes (the others stay), and prove the result (the
                // pairs of faces that did not move were proved with the analytical ones).
                let n = prove(numerical(Some((&a.eps_plus, &a.eps_minus))), Some(&a));
                if n.proof.holds() && n.total() >= a.total() {
                    (Method::Numerical, n)
                } else {
                    (Method::Analytical, a)
                }
            } else {
                (Method::Analytical, a)
            }
        }
    };
    let tubes = match options.tube_segments {
        Some(k) if !topo.is_empty() => {
            // The input's tree and the envelopes' (item = face of the outer, then of the
            // inner surface), in the numbering of the tube proofs: input, outer, inner.
            let surfaces = [(input_tree, 0), (&tree, faces.len() as u32)];
            let input = tubes::TubeInput {
                soup,
                faces: &faces,
                outer: &outer,
                inner: &inner,
                requested: &requested,
                diagonal,
                surfaces: Some(&surfaces[..]),
            };
            let policy = StepPolicy {
                k: options.numerical.k,
                max_halvings: options.numerical.max_halvings,
                growth: options.numerical.step_growth,
            };
            let (t, c) =
                tubes::build_tubes(&input, &topo, k, policy, options.numerical.global_fraction);
            proof.tube_contacts = c;
            t
        }
        _ => Vec::new(),
    };
    Ok(Envelopes {
        outer: TriangleSoup::new(outer, soup.faces.clone()),
        inner: TriangleSoup::new(inner, soup.faces.clone()),
        normals,
        requested,
        pinned,
        eps_plus,
        eps_minus,
        tubes,
        method,
        proof,
        tree,
    })
}

/// Offsets after the exact proof and repair, with the envelope vertices.
struct Proved {
    eps_plus: Vec<f64>,
    eps_minus: Vec<f64>,
    outer: Vec<DVec3>,
    inner: Vec<DVec3>,
    proof: Proof,
    /// The proof's tree over the outer then the inner faces at these positions.
    tree: Bvh,
}

impl Proved {
    /// Sum of the offsets over vertices and both sides.
    fn total(&self) -> f64 {
        self.eps_plus.iter().chain(&self.eps_minus).sum()
    }
}

/// Step 6: places the envelope vertices, proves them exactly, and halves the offsets of
/// every vertex of an offending face until the proof holds (at most `max_rounds` rounds).
///
/// `known`: whether the input is known free of self-intersections, and a configuration over
/// the same input that was proved without any contact; the first proof then tests only the
/// pairs with a face that differs from it (see [`proof::Known`]). Each repair round tests
/// only the pairs with a face it moved, and keeps the other answers of the round before.
fn prove_and_repair(
    soup: &TriangleSoup,
    normals: &[DVec3],
    faces: &[[u32; 3]],
    (mut eps_plus, mut eps_minus): (Vec<f64>, Vec<f64>),
    (input_free, base): (bool, Option<&Proved>),
    input_tree: &Bvh,
    max_rounds: u32,
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
    while !proof.contacts.is_empty() && proof.repair_rounds < max_rounds {
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

/// Faces there are, and each names a vertex there is.
fn accept_indices(soup: &TriangleSoup) -> Result<(), EnvelopeError> {
    if soup.num_faces() == 0 {
        return Err(EnvelopeError::Empty);
    }
    if !soup.indices_in_range() {
        return Err(EnvelopeError::IndexOutOfRange);
    }
    Ok(())
}

/// Checks section 3's assumptions on the soup and its topology `topo` (`analyze(soup)`);
/// returns the border loops (closed) and chains (open).
fn accept_input(
    soup: &TriangleSoup,
    topo: &Topology,
) -> Result<Vec<(Vec<VertexId>, bool)>, EnvelopeError> {
    accept_indices(soup)?;
    if !topo.manifold {
        return Err(EnvelopeError::NotManifold);
    }
    if !topo.consistently_oriented {
        return Err(EnvelopeError::NotOriented);
    }
    let mut out: Vec<(Vec<VertexId>, bool)> = topo
        .border_loops
        .iter()
        .map(|l| (l.clone(), true))
        .collect();
    out.extend(topo.border_chains.iter().map(|l| (l.clone(), false)));
    Ok(out)
}

/// Morton (Z-order) key of `p` in the box `b`, 21 bits per axis.
fn morton(p: DVec3, b: &Aabb) -> u64 {
    let spread = |x: u64| {
        let mut x = x & 0x1f_ffff;
        x = (x | x << 32) & 0x1f_0000_0000_ffff;
        x = (x | x << 16) & 0x1f_0000_ff00_00ff;
        x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
        x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
        (x | x << 2) & 0x1249_2492_4924_9249
    };
    let ext = (b.max - b.min).max(DVec3::splat(f64::MIN_POSITIVE));
    let q = ((p - b.min) / ext * 2_097_151.0).clamp(DVec3::ZERO, DVec3::splat(2_097_151.0));
    spread(q.x as u64) | spread(q.y as u64) << 1 | spread(q.z as u64) << 2
}

/// Per-vertex `(eps_plus, eps_minus)` by the numerical method (section 4.2).
///
/// The mesh is first renumbered in Z-order (vertices by position, faces by centroid) so that
/// the movers of one batch and the faces each check touches are close in memory; a scanned
/// mesh's own order makes every check a string of cache misses. The renumbering changes
/// only the order of moves (the result depends on it, as the paper's sequential order
/// does), not what is checked.
///
/// With `start`, the growth begins at those proved offsets (`(plus, minus)`, an envelope
/// pair whose proof holds): only the vertices short of `requested` move, the others stay
/// where they are as part of the scene. Every offset ends at least at its start.
fn numerical_eps(
    soup: &TriangleSoup,
    vf: &VertexFaces,
    normals: &[DVec3],
    requested: &[f64],
    params: &NumericalParams,
    diagonal: f64,
    start: Option<(&[f64], &[f64])>,
) -> (Vec<f64>, Vec<f64>) {
    let bounds = Aabb::from_points(&soup.positions);
    if let Some(start) = start {
        let near = Near {
            soup,
            vf,
            normals,
            requested,
            start,
            bounds: &bounds,
        };
        if let Some(grown) = near.grow(params, diagonal) {
            return grown;
        }
    }
    numerical_eps_sorted(soup, normals, requested, params, diagonal, start, &bounds)
}

/// [`numerical_eps`] on the whole mesh, renumbered in Z-order in `bounds` (the box of its
/// vertices).
fn numerical_eps_sorted(
    soup: &TriangleSoup,
    normals: &[DVec3],
    requested: &[f64],
    params: &NumericalParams,
    diagonal: f64,
    start: Option<(&[f64], &[f64])>,
    bounds: &Aabb,
) -> (Vec<f64>, Vec<f64>) {
    use rayon::slice::ParallelSliceMut;
    let bounds = *bounds;
    let n = soup.num_vertices();
    let mut order: Vec<u32> = (0..n as u32).collect();
    // Keys are distinct (the ids break ties): the parallel sorts give the one order.
    order.par_sort_by_cached_key(|&v| (morton(soup.positions[v as usize], &bounds), v));
    let mut rank = vec![0u32; n];
    for (new, &old) in order.iter().enumerate() {
        rank[old as usize] = new as u32;
    }
    let mut faces: Vec<[VertexId; 3]> = soup
        .faces
        .iter()
        .map(|f| f.map(|v| VertexId(rank[v.0 as usize])))
        .collect();
    let key = |f: &[VertexId; 3]| {
        let c = order_pos(soup, &order, f[0]) + order_pos(soup, &order, f[1]);
        morton((c + order_pos(soup, &order, f[2])) / 3.0, &bounds)
    };
    faces.par_sort_by_cached_key(|f| (key(f), f.map(|v| v.0)));
    let sorted = TriangleSoup::new(
        order.iter().map(|&v| soup.positions[v as usize]).collect(),
        faces,
    );
    let pick = |a: &[f64]| -> Vec<f64> { order.iter().map(|&v| a[v as usize]).collect() };
    let sorted_normals: Vec<DVec3> = order.iter().map(|&v| normals[v as usize]).collect();
    let vf = VertexFaces::new(n, &sorted.faces);
    let zeros = vec![0.0; n];
    let (start_plus, start_minus) =
        start.map_or((pick(&zeros), pick(&zeros)), |(p, m)| (pick(p), pick(m)));
    let (p, m) = numerical_eps_ordered(
        &sorted,
        &vf,
        &sorted_normals,
        &pick(requested),
        params,
        diagonal,
        [&start_plus, &start_minus],
        FEW_MOVERS,
    );
    let back = |a: &[f64]| -> Vec<f64> { rank.iter().map(|&r| a[r as usize]).collect() };
    (back(&p), back(&m))
}

/// The growth from proved offsets where a few vertices fell short (the automatic method
/// after the analytical one: mech-holes-shark at 1/64 %, 3 movers among 10,192 faces), on
/// the part of the mesh they can reach: the faces around every mover and every face with a
/// copy (input, outer or inner, at the start) whose box overlaps a mover's reach, renumbered
/// in the whole mesh's Z-order. The same growth as on the whole mesh:
///
/// - the movers are the same, in the same order (Z-order in the whole mesh's box, ties by
///   vertex id), with the same stars (a mover's fan is all there) and the same steps (from
///   its fan's edges);
/// - every face a mover's check can meet has a swept box overlapping its reach: a face
///   around a mover, or one that never moves (its swept box is its box at the start);
///   both are there, so every check tests the same pairs, exactly, and the colouring sees
///   the same movers sharing the same vertices;
/// - what is left out never moves and meets no reach. More faces than needed change only
///   the work (every face of an input face's three copies is taken).
///
/// mech-holes-shark at 1/64 %, two threads (instrumented run): the growth 2.7 -> 0.5 ms
/// (the renumbering and the scene's arrays for 5,246 vertices and 30,576 faces were
/// nearly all of it, for three movers).
struct Near<'a> {
    soup: &'a TriangleSoup,
    vf: &'a VertexFaces,
    normals: &'a [DVec3],
    requested: &'a [f64],
    start: (&'a [f64], &'a [f64]),
    /// The box of the whole mesh's vertices (the Z-order's).
    bounds: &'a Aabb,
}

impl Near<'_> {
    /// Offsets grown on the part of the mesh the movers reach, or `None` when the movers
    /// are not few (one per [`FEW_MOVERS`] scene faces or more).
    fn grow(&self, params: &NumericalParams, diagonal: f64) -> Option<(Vec<f64>, Vec<f64>)> {
        use rayon::prelude::*;
        let (soup, (plus, minus)) = (self.soup, self.start);
        let n = soup.num_vertices();
        // Side 1 (outer) and 2 (inner) of vertex `v` moves: its start falls short.
        let moves = |v: usize, side: u32| {
            let s0 = if side == 1 { plus[v] } else { minus[v] };
            // As `numerical_eps_ordered` skips a side: unless `s0 >= target`.
            let reached = matches!(
                s0.partial_cmp(&self.requested[v]),
                Some(std::cmp::Ordering::Greater | std::cmp::Ordering::Equal)
            );
            !self.vf.of(v).is_empty() && !reached
        };
        let movers: Vec<(usize, u32)> = (0..n)
            .flat_map(|v| [(v, 1), (v, 2)])
            .filter(|&(v, side)| moves(v, side))
            .collect();
        if movers.len().saturating_mul(FEW_MOVERS) >= 3 * soup.num_faces() {
            return None;
        }
        // Where copy `side` of vertex `v` can be: its start position, or for a mover the
        // sweep to its target (as `numerical_eps_ordered` places and sweeps them).
        let reach_of = |v: usize, side: u32| {
            let p = soup.positions[v];
            if side == 0 {
                return Aabb::from_points(&[p]);
            }
            let dir = self.normals[v] * if side == 1 { 1.0 } else { -1.0 };
            let s0 = if side == 1 { plus[v] } else { minus[v] };
            if moves(v, side) {
                engine::sweep_box(p, dir, self.requested[v])
            } else if s0 > 0.0 {
                Aabb::from_points(&[p + dir * s0])
            } else {
                Aabb::from_points(&[p])
            }
        };
        let reaches: Vec<Aabb> = movers
            .iter()
            .map(|&(v, side)| {
                self.vf.of(v).iter().fold(Aabb::EMPTY, |b, &f| {
                    soup.faces[f as usize]
                        .iter()
                        .fold(b, |b, u| b.union(&reach_of(u.index(), side)))
                })
            })
            .collect();
        let mut kept = vec![false; soup.num_faces()];
        for &(v, _) in &movers {
            for &f in self.vf.of(v) {
                kept[f as usize] = true;
            }
        }
        let prism = |f: usize| {
            soup.faces[f].iter().fold(Aabb::EMPTY, |b, u| {
                let v = u.index();
                b.union(&reach_of(v, 0))
                    .union(&reach_of(v, 1))
                    .union(&reach_of(v, 2))
            })
        };
        let faces: Vec<usize> = (0..soup.num_faces())
            .into_par_iter()
            .filter(|&f| {
                kept[f] || {
                    let b = prism(f);
                    reaches.iter().any(|r| r.overlaps(&b))
                }
            })
            .collect();
        // The part's vertices in the whole mesh's Z-order (ties by id).
        let mut verts: Vec<u32> = faces
            .iter()
            .flat_map(|&f| soup.faces[f].map(|u| u.0))
            .collect();
        verts.sort_unstable();
        verts.dedup();
        verts.sort_by_cached_key(|&v| (morton(soup.positions[v as usize], self.bounds), v));
        let mut local = vec![u32::MAX; n];
        for (l, &v) in (0u32..).zip(&verts) {
            local[v as usize] = l;
        }
        let part = TriangleSoup::new(
            verts.iter().map(|&v| soup.positions[v as usize]).collect(),
            faces
                .iter()
                .map(|&f| soup.faces[f].map(|u| VertexId(local[u.index()])))
                .collect(),
        );
        let pick = |a: &[f64]| -> Vec<f64> { verts.iter().map(|&v| a[v as usize]).collect() };
        let part_normals: Vec<DVec3> = verts.iter().map(|&v| self.normals[v as usize]).collect();
        let part_vf = VertexFaces::new(part.num_vertices(), &part.faces);
        let (p, m) = numerical_eps_ordered(
            &part,
            &part_vf,
            &part_normals,
            &pick(self.requested),
            params,
            diagonal,
            [&pick(plus), &pick(minus)],
            FEW_MOVERS,
        );
        let (mut out_plus, mut out_minus) = (plus.to_vec(), minus.to_vec());
        for (l, &v) in verts.iter().enumerate() {
            out_plus[v as usize] = p[l];
            out_minus[v as usize] = m[l];
        }
        Some((out_plus, out_minus))
    }
}

/// [`numerical_eps_ordered`] builds its tree over the faces its movers can reach only when
/// there are fewer movers than one per this many scene faces (the growth from proved
/// offsets where a few fell short: mech-holes-shark at 1/64 %, 3 movers among 30,576 scene
/// faces, 0.010 -> 0.003 s).
const FEW_MOVERS: usize = 64;

fn order_pos(soup: &TriangleSoup, order: &[u32], v: VertexId) -> DVec3 {
    soup.positions[order[v.0 as usize] as usize]
}

/// [`numerical_eps`] on a renumbered mesh: outer and inner vertices are movers of one scene
/// (input + outer + inner, interleaved: copy `s` of vertex `v` is `3 v + s`, of face `f` is
/// `3 f + s`, with `s` 0 input, 1 outer, 2 inner), see [`engine`].
fn numerical_eps_ordered(
    soup: &TriangleSoup,
    vf: &VertexFaces,
    normals: &[DVec3],
    requested: &[f64],
    params: &NumericalParams,
    diagonal: f64,
    start: [&[f64]; 2],
    few_movers: usize,
) -> (Vec<f64>, Vec<f64>) {
    let n = soup.num_vertices();
    let mut positions = Vec::with_capacity(3 * n);
    for &p in &soup.positions {
        positions.extend_from_slice(&[p, p, p]);
    }
    let mut alias: Vec<u32> = (0..3 * n as u32).map(|i| i - i % 3).collect();
    let mut plus = start[0].to_vec();
    let mut minus = start[1].to_vec();
    let mut faces: Vec<[u32; 3]> = Vec::with_capacity(3 * soup.num_faces());
    for f in &soup.faces {
        for s in 0..3 {
            faces.push(f.map(|v| 3 * v.0 + s));
        }
    }
    let mut sweep: Vec<Aabb> = positions.iter().map(|&p| Aabb::from_points(&[p])).collect();
    let mut movers = Vec::with_capacity(2 * n);
    for v in 0..n {
        let fan = vf.of(v);
        if fan.is_empty() {
            continue;
        }
        let p = soup.positions[v];
        for (side, sign) in [(1u32, 1.0), (2u32, -1.0)] {
            let dir = normals[v] * sign;
            let target = requested[v];
            let gv = 3 * v as u32 + side;
            let s0 = start[side as usize - 1][v];
            if s0 > 0.0 {
                // Proved start offset: the vertex sits there (its own index, not the input's).
                positions[gv as usize] = p + dir * s0;
                alias[gv as usize] = gv;
                sweep[gv as usize] = Aabb::from_points(&[positions[gv as usize]]);
            }
            if s0 >= target {
                continue;
            }
            // Local step: shortest incident edge within 90 degrees of the offset direction.
            let mut shortest = f64::INFINITY;
            let mut shortest_any = f64::INFINITY;
            for &f in fan {
                for u in soup.faces[f as usize] {
                    let e = soup.positions[u.0 as usize] - p;
                    let len = e.length();
                    if len > 0.0 {
                        shortest_any = shortest_any.min(len);
                        if e.dot(dir) > 0.0 {
                            shortest = shortest.min(len);
                        }
                    }
                }
            }
            if !shortest.is_finite() {
                shortest = shortest_any;
            }
            let step = (params.global_fraction * diagonal)
                .min(target / params.k as f64)
                .min(params.local_fraction * shortest);
            sweep[gv as usize] = engine::sweep_box(p, dir, target);
            movers.push(Mover {
                verts: vec![gv],
                base: vec![p],
                dirs: vec![dir],
                star: fan.iter().map(|&f| 3 * f + side).collect(),
                group: side,
                target,
                t: s0,
                step,
                steps: 0,
                halvings: 0,
                done: false,
                cands: Vec::new(),
            });
        }
    }
    let boxes = engine::swept_face_boxes(&faces, &sweep);
    let never = |_: u32, _: u32| false;
    // A few movers (the growth from proved offsets where a few fell short): a tree over
    // the faces they can reach only.
    let mut scene = if movers.len().saturating_mul(few_movers) < faces.len() {
        let reaches: Vec<Aabb> = movers.iter().map(|m| engine::reach(&boxes, m)).collect();
        Scene::around(positions, alias, faces, boxes, &never, &reaches)
    } else {
        Scene::new(positions, alias, faces, boxes, &never)
    };
    let policy = StepPolicy {
        k: params.k,
        max_halvings: params.max_halvings,
        growth: params.step_growth,
    };
    engine::grow(&mut scene, &mut movers, policy);
    for m in &movers {
        let v = (m.verts[0] / 3) as usize;
        if m.group == 1 {
            plus[v] = m.t;
        } else {
            minus[v] = m.t;
        }
    }
    (plus, minus)
}

#[cfg(test)]
mod proof_tests {
    use super::*;
    use envelope_mesh::generate;

    fn prepared(soup: &TriangleSoup) -> (Vec<DVec3>, Vec<[u32; 3]>, Bvh) {
        let vf = VertexFaces::new(soup.num_vertices(), &soup.faces);
        let normals = normals::vertex_normals_with(soup, &vf).normals;
        let faces: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
        let tree = Bvh::from_triangles(&soup.positions, &faces);
        (normals, faces, tree)
    }

    /// The proof against a proved configuration tests the pairs with a changed face: it
    /// finds an envelope vertex pushed through the input, and finds nothing when nothing
    /// changed (the same answer as the full proof in both cases).
    #[test]
    fn proof_against_a_proved_configuration_finds_what_changed() {
        let sphere = generate::icosphere(2, 1.0);
        let (normals, faces, tree) = prepared(&sphere);
        let n = sphere.num_vertices();
        let eps = vec![0.02; n];
        let base = prove_and_repair(
            &sphere,
            &normals,
            &faces,
            (eps.clone(), eps.clone()),
            (false, None),
            &tree,
            0,
        );
        assert!(base.proof.contacts.is_empty());
        let same = prove_and_repair(
            &sphere,
            &normals,
            &faces,
            (eps.clone(), eps.clone()),
            (true, Some(&base)),
            &tree,
            0,
        );
        assert!(same.proof.contacts.is_empty());
        // Vertex 7's outer offset negative: its outer vertex goes through the input.
        let mut pushed = eps.clone();
        pushed[7] = -0.05;
        for known in [(false, None), (true, Some(&base))] {
            let p = prove_and_repair(
                &sphere,
                &normals,
                &faces,
                (pushed.clone(), eps.clone()),
                known,
                &tree,
                0,
            );
            assert!(
                p.proof
                    .contacts
                    .iter()
                    .any(|c| c.a.0 == Surface::Input && c.b.0 == Surface::Outer),
                "{:?}",
                p.proof.contacts
            );
        }
    }

    /// One soup of two unit icospheres (`subdivisions`), the second moved by `shift`.
    fn two_spheres(subdivisions: u32, shift: DVec3) -> TriangleSoup {
        let a = generate::icosphere(subdivisions, 1.0);
        let mut positions = a.positions.clone();
        let n = positions.len() as u32;
        positions.extend(a.positions.iter().map(|&p| p + shift));
        let mut faces = a.faces.clone();
        faces.extend(a.faces.iter().map(|f| f.map(|v| VertexId(v.0 + n))));
        TriangleSoup::new(positions, faces)
    }

    /// Two interpenetrating spheres in one soup (manifold, oriented, self-intersecting):
    /// input-input contacts are reported unless the caller says the input was checked.
    #[test]
    fn input_pairs_are_tested_unless_known_free() {
        let soup = two_spheres(1, DVec3::new(0.9, 0.1, 0.05));
        let (normals, faces, tree) = prepared(&soup);
        let eps = vec![0.01; soup.num_vertices()];
        let input_pairs = |input_free: bool| {
            prove_and_repair(
                &soup,
                &normals,
                &faces,
                (eps.clone(), eps.clone()),
                (input_free, None),
                &tree,
                0,
            )
            .proof
            .contacts
            .iter()
            .filter(|c| c.a.0 == Surface::Input && c.b.0 == Surface::Input)
            .count()
        };
        assert!(input_pairs(false) > 0);
        assert_eq!(input_pairs(true), 0);
    }

    /// Repair rounds test only the faces the halving moved and keep the other answers: the
    /// contacts after each round are those of a full proof of that round's offsets. On the
    /// interpenetrating spheres the envelope contacts shrink round by round while the
    /// input-input ones (never moved) must be kept.
    #[test]
    fn repair_rounds_find_what_a_full_proof_finds() {
        let soup = two_spheres(2, DVec3::new(1.7, 0.1, 0.05));
        let (normals, faces, tree) = prepared(&soup);
        let eps = vec![0.2; soup.num_vertices()];
        let mut rounds_with_envelope_contacts = 0;
        for rounds in 0..4 {
            let repaired = prove_and_repair(
                &soup,
                &normals,
                &faces,
                (eps.clone(), eps.clone()),
                (false, None),
                &tree,
                rounds,
            );
            let full = prove_and_repair(
                &soup,
                &normals,
                &faces,
                (repaired.eps_plus.clone(), repaired.eps_minus.clone()),
                (false, None),
                &tree,
                0,
            );
            assert_eq!(
                repaired.proof.contacts, full.proof.contacts,
                "after {rounds} rounds"
            );
            assert!(
                full.proof
                    .contacts
                    .iter()
                    .any(|c| c.a.0 == Surface::Input && c.b.0 == Surface::Input)
            );
            if full.proof.contacts.iter().any(|c| c.b.0 != Surface::Input) {
                rounds_with_envelope_contacts += 1;
            }
        }
        assert!(
            rounds_with_envelope_contacts >= 2,
            "{rounds_with_envelope_contacts}"
        );
    }

    /// Two spheres of radius 1, 0.2 apart along x, with their vertex faces and normals.
    fn spheres_apart() -> (TriangleSoup, VertexFaces, Vec<DVec3>) {
        let soup = two_spheres(3, DVec3::new(2.2, 0.0, 0.0));
        let vf = VertexFaces::new(soup.num_vertices(), &soup.faces);
        let normals = normals::vertex_normals_with(&soup, &vf).normals;
        (soup, vf, normals)
    }

    /// The growth on the part of the mesh its few movers reach gives the offsets of the
    /// growth on the whole mesh, on two spheres 0.2 apart: the first's outer envelope grown
    /// from zero where it faces the second, whose outer envelope does not move and stops it
    /// (the faces that stop a mover are there); then both outer envelopes grown where they
    /// face each other (they compete for the gap: the order of the moves shows). A few inner
    /// offsets of the second grow from half their target in both.
    #[test]
    fn near_growth_is_the_whole_mesh_growth() {
        let (soup, vf, normals) = spheres_apart();
        let n = soup.num_vertices();
        let target = vec![0.15; n];
        let x = |v: usize| soup.positions[v].x;
        let minus: Vec<f64> = (0..n)
            .map(|v| {
                if v >= n / 2 && v % 97 == 0 {
                    0.075
                } else {
                    0.15
                }
            })
            .collect();
        let bounds = Aabb::from_points(&soup.positions);
        let params = NumericalParams::default();
        for both in [false, true] {
            let facing = |v: usize| {
                if v < n / 2 {
                    x(v) > 0.85
                } else {
                    both && x(v) < 1.35
                }
            };
            let plus: Vec<f64> = (0..n).map(|v| if facing(v) { 0.0 } else { 0.15 }).collect();
            let near = Near {
                soup: &soup,
                vf: &vf,
                normals: &normals,
                requested: &target,
                start: (&plus, &minus),
                bounds: &bounds,
            };
            let part = near.grow(&params, soup.diagonal()).expect("few movers");
            let whole = numerical_eps_sorted(
                &soup,
                &normals,
                &target,
                &params,
                soup.diagonal(),
                Some((&plus, &minus)),
                &bounds,
            );
            assert_eq!(part, whole, "both fronts: {both}");
            // The growth did something: the fronts were stopped (0.2 apart, 0.15 each),
            // and grew.
            let front = |v: usize| facing(v) && (x(v) - 1.1).abs() < 0.11;
            assert!((0..n).filter(|&v| front(v)).count() > 1);
            assert!(
                (0..n).any(|v| front(v) && whole.0[v] < 0.15),
                "{:?}",
                whole.0
            );
            assert!((0..n).any(|v| facing(v) && whole.0[v] > 0.0));
            assert!((n / 2..n).any(|v| v % 97 == 0 && whole.1[v] > 0.075));
            // Many movers: the whole mesh's growth.
            let zeros = vec![0.0; n];
            let many = Near {
                start: (&zeros, &zeros),
                ..near
            };
            assert!(many.grow(&params, soup.diagonal()).is_none());
        }
    }

    /// The growth's tree over the faces its few movers can reach gives the offsets of the
    /// tree over all faces: two spheres 0.2 apart, the second's envelopes proved at 0.15,
    /// the first's outer envelope grown from zero where it faces the second, towards a
    /// target of 0.15 (it stops at the second's outer envelope, about 0.05 away).
    #[test]
    fn few_movers_grow_as_with_the_whole_scene() {
        let (soup, vf, normals) = spheres_apart();
        let n = soup.num_vertices();
        let target = vec![0.15; n];
        let facing = |v: usize| v < n / 2 && soup.positions[v].x > 0.8;
        let plus: Vec<f64> = (0..n).map(|v| if facing(v) { 0.0 } else { 0.15 }).collect();
        let movers = (0..n).filter(|&v| facing(v)).count();
        assert!(movers > 4, "{movers}");
        let grow = |few: usize| {
            numerical_eps_ordered(
                &soup,
                &vf,
                &normals,
                &target,
                &NumericalParams::default(),
                soup.diagonal(),
                [&plus, &target],
                few,
            )
        };
        // One mover per `few` scene faces or more: the whole scene's tree; 0: never.
        let (whole, around) = (grow(usize::MAX), grow(0));
        assert_eq!(whole, around);
        let front = (0..n).filter(|&v| facing(v) && soup.positions[v].x > 0.98);
        assert!(front.clone().count() > 0);
        assert!(front.clone().all(|v| whole.0[v] < 0.1), "{:?}", whole.0);
    }
}
