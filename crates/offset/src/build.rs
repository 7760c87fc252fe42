//! The pipeline of [`build_envelopes`] (steps 1-7 of the crate docs): accept the input,
//! evaluate epsilon, normals, offsets by the chosen method, proof and repair, tubes.
use std::sync::Arc;

use envelope_mesh::{Topology, TriangleSoup, VertexFaces, VertexId, analyze};
use envelope_predicates::bvh::Bvh;
use glam::DVec3;

use crate::analytical::AnalyticalFaces;
use crate::engine::StepPolicy;
use crate::error::EnvelopeError;
use crate::error::TUBE_SEGMENTS;
use crate::numerical::numerical_eps;
use crate::options::{AnalyticalMemo, EnvelopeMethod, EnvelopeOptions, raised};
use crate::proof::Proof;
use crate::repair::{Proved, prove_and_repair};
use crate::tubes::Tube;
use crate::{analytical, normals, tubes};

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
    /// The method whose offsets these are ([`EnvelopeMethod::Analytical`] or [`EnvelopeMethod::Numerical`];
    /// with [`EnvelopeMethod::Auto`], the one it kept).
    pub method: EnvelopeMethod,
    /// The exact non-intersection proof.
    pub proof: Proof,
    /// A tree over the faces of [`Envelopes::outer`] then those of [`Envelopes::inner`]
    /// (item `f`: outer face `f`; item `n + f`, `n` faces: inner face `f`), the one the
    /// proof searched, with both offsets of a face in one leaf: `envelope-simplify`'s
    /// `Barriers::with_tree` takes it instead of building its own.
    pub tree: Bvh,
    /// The analytical method's per-face minima, when [`EnvelopeOptions::analytical_memo`]
    /// asked to keep them and the method ran: for a later build over a subset of these faces.
    pub analytical: Option<Arc<AnalyticalFaces>>,
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
        && !TUBE_SEGMENTS.contains(&k)
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
    let input_free = options.input_free_of_intersections;
    let abandon = options.abandon.as_deref();
    let abandoned = || {
        if raised(abandon) {
            Err(EnvelopeError::Abandoned)
        } else {
            Ok(())
        }
    };
    let memo = match &options.analytical_memo {
        None => (None, false),
        Some(AnalyticalMemo::Keep) => (None, true),
        Some(AnalyticalMemo::Reuse(before)) => (Some(&**before), true),
    };
    let mut kept_minima = None;
    // `input_tree`: one tree over the input faces, for the analytical method and every proof.
    // An abandoned clipping stops early and is not proved.
    let mut analytical = || {
        let (plus, minus, minima) =
            analytical::analytical_eps(soup, &vf, &normals, &targets, input_tree, memo, &|| {
                raised(abandon)
            });
        kept_minima = minima.map(Arc::new);
        abandoned().map(|()| (plus, minus))
    };
    // From zero, or from proved offsets (`start`); an abandoned growth stops at its next
    // pass and is not proved.
    let numerical = |start: Option<(&[f64], &[f64])>| {
        let grown = numerical_eps(
            soup,
            &vf,
            &normals,
            &targets,
            &options.numerical,
            diagonal,
            (start, abandon),
        );
        abandoned().map(|()| grown)
    };
    abandoned()?;
    let prove = |(p, m): (Vec<f64>, Vec<f64>), proved: Option<&Proved>| {
        let base = proved.filter(|b| b.proof.contacts.is_empty());
        prove_and_repair(
            soup,
            &normals,
            &faces,
            (p, m),
            (input_free, base),
            input_tree,
            (options.max_repair_rounds, abandon),
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
        EnvelopeMethod::Analytical => (EnvelopeMethod::Analytical, prove(analytical()?, None)),
        EnvelopeMethod::Numerical => (EnvelopeMethod::Numerical, prove(numerical(None)?, None)),
        EnvelopeMethod::Auto => {
            let short = |e: &[f64]| e.iter().zip(&targets).any(|(x, r)| x < r);
            let a = prove(analytical()?, None);
            abandoned()?;
            if !a.proof.holds() {
                // Repair gave up: numerical from scratch, and the better of the two.
                let n = prove(numerical(None)?, None);
                if n.proof.holds() || n.total() > a.total() {
                    (EnvelopeMethod::Numerical, n)
                } else {
                    (EnvelopeMethod::Analytical, a)
                }
            } else if short(&a.eps_plus) || short(&a.eps_minus) {
                // Clipping or repair cut some offsets: grow those numerically from the
                // proved analytical envelopes (the others stay), and prove the result (the
                // pairs of faces that did not move were proved with the analytical ones).
                let n = prove(numerical(Some((&a.eps_plus, &a.eps_minus)))?, Some(&a));
                if n.proof.holds() && n.total() >= a.total() {
                    (EnvelopeMethod::Numerical, n)
                } else {
                    (EnvelopeMethod::Analytical, a)
                }
            } else {
                (EnvelopeMethod::Analytical, a)
            }
        }
    };
    abandoned()?;
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
        analytical: kept_minima,
    })
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
