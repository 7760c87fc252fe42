//! The genus-reducing step (El-Sana and Varshney 1997, sections 3.2-3.4), driven like the
//! paper: [`reduce_genus`] checks the input, finds the tessellation edges and chains
//! ([`crate::tessellation`]), turns the candidate rims into caps ([`crate::triangulate`]),
//! keeps the caps the alpha test accepts, removes the triangles that became interior by
//! breadth-first spreading, and validates the result.
//!
//! **Acceptance of a cap** is the alpha test of [`crate::rim`]: diagonals within the cube,
//! triangles inside the alpha-cubes of their corners
//! ([`crate::details::covered_by_corner_cubes`], exact); since a corner is an input vertex,
//! its cube lies in the alpha-prism of every input face at that vertex, so every added
//! triangle lies inside the union of alpha-prisms. A hole wider than `2 alpha` fails this
//! (its middle is farther than `alpha` from every rim vertex). With
//! [`TessellationSource::Closing`] the closing's regions are filled afterwards
//! ([`crate::fill`]), whose caps may also have corners on points of input edges
//! ([`crate::steiner`]).
//!
//! **Interior triangles (3.4), over tunnel networks (issue 37).** The surface is cut along
//! every candidate rim into cells; [`select`] decides which cells fill: the preferred side
//! of each rim marks its region cells, and a filling cell that meets a staying one across an
//! edge no taken rim covers (a mouth wider than the cube) stays instead, until stable. So a
//! tunnel that opens wide stays open and is plugged where it joins the rest of the network,
//! which still fills. A plug is a rim run the other way where only one side has a candidate.
//! Caps that fold back over their planar kept face are refused first
//! ([`crate::rim::folds_onto_kept`]).
//! The crate README lists the rules; refusing can only keep the input as it was.
//!
//! **Validation.** The output is checked with `envelope-check`; caps involved in a new
//! intersecting, coincident, duplicate or non-manifold finding are refused and the selection
//! is redone (at worst the input comes back unchanged). Of two caps in conflict, one already
//! in conflict with something else (a cap duplicating kept faces, e.g. over the outer loop
//! of a face) is refused first, otherwise the later one.

use std::cell::OnceCell;
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet, VecDeque};
use std::time::Instant;

use envelope_check::{CheckOptions, DegeneracyClass, Element, check};
use envelope_mesh::{FaceId, TriangleSoup, VertexId, analyze};
use envelope_predicates::{Orientation, orient3d};

use crate::GenusError;
use crate::rim::{Candidate, Edge, cap_of, folds_onto_kept, split_simple};
use crate::tessellation::{
    EdgeMap, Patches, face_normals, link_chains, normal_variation, patches, signed_volume,
    tessellation_edges,
};
use crate::union::{TessellationSource, union_rims};
use crate::validation::{Fill, class_counts, new_findings};

/// Options of [`reduce_genus`].
#[derive(Clone, Debug, PartialEq)]
pub struct GenusOptions {
    /// The L-infinity radius: holes and tunnels a cube of side `2 alpha` cannot pass are
    /// filled (absolute length).
    pub alpha: f64,
    /// Sharp-edge threshold in degrees (angle between face normals), default 70.
    pub beta_degrees: f64,
}

impl GenusOptions {
    /// Options with the paper's `beta = 70` degrees.
    #[must_use]
    pub fn new(alpha: f64) -> Self {
        GenusOptions {
            alpha,
            beta_degrees: 70.0,
        }
    }
}

/// What [`reduce_genus`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct GenusReport {
    /// Input faces.
    pub faces_in: usize,
    /// Output faces.
    pub faces_out: usize,
    /// Genus of the input (`None` if undefined).
    pub genus_in: Option<u32>,
    /// Genus of the output.
    pub genus_out: Option<u32>,
    /// Border loops of the input.
    pub border_loops_in: usize,
    /// Border loops of the output.
    pub border_loops_out: usize,
    /// Tessellation edges (sharp or border).
    pub tessellation_edges: usize,
    /// Faces swallowed by the union of alpha-prisms (0 unless
    /// [`TessellationSource::PrismUnion`]).
    pub swallowed_faces: usize,
    /// Candidate rims from the union of alpha-prisms, all levels (included in `candidates`).
    pub union_candidates: usize,
    /// Open tessellation chains.
    pub open_chains: usize,
    /// Closed tessellation chains.
    pub closed_chains: usize,
    /// Candidate rims (patch loops of patches with two or more loops).
    pub candidates: usize,
    /// Candidates refused before capping: concave rims, rims through a vertex twice, rims
    /// that could not be triangulated.
    pub refused_shape: usize,
    /// Candidates refused because the cube passes: a diagonal longer than `2 alpha` or a cap
    /// triangle outside its corners' cubes.
    pub refused_wide: usize,
    /// Candidates refused because the interior spread was not enclosed.
    pub refused_enclosure: usize,
    /// Candidates refused by the output validation.
    pub refused_validation: usize,
    /// Candidate rims dropped as internal: their kept patch is itself on the region side of
    /// an accepted rim (the junction of two tunnels), so the region spreads across them.
    pub internal_rims: usize,
    /// Rims capped (a through hole has two).
    pub holes_filled: usize,
    /// Triangles added by the caps.
    pub triangles_added: usize,
    /// Input triangles removed: interior ones, and those split into `pieces`.
    pub triangles_removed: usize,
    /// Pieces of input triangles split at points added on a cap's long loop edges (closing
    /// mode); `faces_out = faces_in + triangles_added + pieces - triangles_removed`.
    pub pieces: usize,
    /// Input triangles split into `pieces` (counted in `triangles_removed`).
    pub split_faces: usize,
    /// Points added on input edges (output vertices that are not input vertices).
    pub points_added: usize,
    /// Alpha-close face pairs among the faces at the accepted rims (section 4.2).
    pub alpha_close_pairs: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// The added triangles, as face ids of the output.
    pub added_faces: Vec<FaceId>,
    /// The pieces, as face ids of the output.
    pub piece_faces: Vec<FaceId>,
}

impl GenusReport {
    /// The report as JSON (stable field names, the fields above without `added_faces` and
    /// `piece_faces`).
    #[must_use]
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "faces_in": self.faces_in,
            "faces_out": self.faces_out,
            "genus_in": self.genus_in,
            "genus_out": self.genus_out,
            "border_loops_in": self.border_loops_in,
            "border_loops_out": self.border_loops_out,
            "tessellation_edges": self.tessellation_edges,
            "swallowed_faces": self.swallowed_faces,
            "union_candidates": self.union_candidates,
            "open_chains": self.open_chains,
            "closed_chains": self.closed_chains,
            "candidates": self.candidates,
            "holes_filled": self.holes_filled,
            "refused_shape": self.refused_shape,
            "refused_wide": self.refused_wide,
            "refused_enclosure": self.refused_enclosure,
            "refused_validation": self.refused_validation,
            "internal_rims": self.internal_rims,
            "triangles_added": self.triangles_added,
            "triangles_removed": self.triangles_removed,
            "pieces": self.pieces,
            "split_faces": self.split_faces,
            "points_added": self.points_added,
            "alpha_close_pairs": self.alpha_close_pairs,
            "seconds": self.seconds,
        })
    }
}

/// Classes of the input that the paper cannot handle (section 6) and we refuse.
const REFUSED: [DegeneracyClass; 5] = [
    DegeneracyClass::CoincidentTriangles,
    DegeneracyClass::DuplicateTriangles,
    DegeneracyClass::IntersectingTriangles,
    DegeneracyClass::NonManifoldEdges,
    DegeneracyClass::InconsistentOrientation,
];

/// Reduces the genus of `soup`: fills the holes, tunnels and cavities an axis-aligned cube of
/// side `2 alpha` cannot pass at rims of sharp or border edges (see the module docs). The
/// output has compacted vertex ids (a subset of the input's, in input order); no vertex is
/// created.
///
/// # Errors
/// [`GenusError::InvalidAlpha`], [`GenusError::InvalidBeta`],
/// [`GenusError::NonFiniteCoordinate`], [`GenusError::IndexOutOfRange`] and
/// [`GenusError::Unacceptable`] (coincident, duplicate or intersecting triangles,
/// non-manifold edges, inconsistent orientation) naming an offending element.
///
/// ```
/// use envelope_genus::{reduce_genus, GenusOptions};
/// use envelope_mesh::{analyze, generate};
/// let plate = generate::plate_with_holes(2); // genus 2, unit square holes
/// let (out, report) = reduce_genus(&plate, &GenusOptions::new(0.6)).unwrap();
/// assert_eq!((report.genus_in, report.genus_out), (Some(2), Some(0)));
/// assert_eq!(analyze(&out).genus, Some(0));
/// let (_, kept) = reduce_genus(&plate, &GenusOptions::new(0.4)).unwrap();
/// assert_eq!(kept.genus_out, Some(2));
/// ```
pub fn reduce_genus(
    soup: &TriangleSoup,
    options: &GenusOptions,
) -> Result<(TriangleSoup, GenusReport), GenusError> {
    reduce_genus_with(soup, options, TessellationSource::SharpEdges)
}

/// [`reduce_genus`] with a choice of where the rims come from: with
/// [`TessellationSource::PrismUnion`], the rims of the regions swallowed by the union of
/// alpha-prisms ([`crate::union`]) are candidates too, so narrow tunnels and holes through
/// smooth surfaces are filled. (A separate entry point rather than a field of
/// [`GenusOptions`], so that struct literals of the options keep compiling.)
///
/// # Errors
/// As [`reduce_genus`].
///
/// ```
/// use envelope_genus::{reduce_genus_with, GenusOptions, TessellationSource};
/// use envelope_mesh::{analyze, generate};
/// // A smooth torus: central hole of radius 0.3, no sharp edge.
/// let torus = generate::torus(1.0, 0.7, 32, 16);
/// let sharp = reduce_genus_with(&torus, &GenusOptions::new(0.5), TessellationSource::SharpEdges);
/// assert_eq!(sharp.unwrap().1.genus_out, Some(1));
/// let (out, r) =
///     reduce_genus_with(&torus, &GenusOptions::new(0.5), TessellationSource::PrismUnion).unwrap();
/// assert_eq!((r.genus_in, r.genus_out), (Some(1), Some(0)));
/// assert_eq!(analyze(&out).genus, Some(0));
/// ```
pub fn reduce_genus_with(
    soup: &TriangleSoup,
    options: &GenusOptions,
    source: TessellationSource,
) -> Result<(TriangleSoup, GenusReport), GenusError> {
    let start = Instant::now();
    let alpha = options.alpha;
    if !(alpha.is_finite() && alpha > 0.0) {
        return Err(GenusError::InvalidAlpha(alpha));
    }
    let beta = options.beta_degrees;
    if !(beta.is_finite() && beta > 0.0 && beta < 180.0) {
        return Err(GenusError::InvalidBeta(beta));
    }
    check_input(soup)?;
    let topo_in = analyze(soup);

    let edges = EdgeMap::new(soup);
    let normals = face_normals(soup);
    let tess = tessellation_edges(&edges, &normals, beta);
    let chains = link_chains(&tess);
    let tess_set: HashSet<(VertexId, VertexId)> = tess.iter().copied().collect();
    let pat = patches(soup, &edges, &tess_set);

    // Candidates: loops of patches with at least two loops.
    let mut patch_faces: Vec<Vec<FaceId>> = vec![Vec::new(); pat.count];
    for f in soup.face_ids() {
        if let Some(p) = pat.of_face.get(f.index()).filter(|&&p| p != usize::MAX) {
            patch_faces[*p].push(f);
        }
    }
    let variation: Vec<f64> = patch_faces
        .iter()
        .map(|fs| normal_variation(soup, fs.iter().copied()))
        .collect();
    let mut candidates: Vec<Candidate> = Vec::new();
    let outward = signed_volume(soup) >= 0.0;
    let (mut refused_shape, mut refused_wide) = (0, 0);
    for (p, loops) in pat.loops.iter().enumerate() {
        if loops.len() < 2 {
            continue;
        }
        for (vertices, faces) in loops
            .iter()
            .flat_map(|lp| split_simple(&lp.vertices, &lp.faces))
        {
            let lp = crate::tessellation::PatchLoop { vertices, faces };
            if !convex_rim(soup, &edges, &lp.vertices, &lp.faces, outward) {
                refused_shape += 1;
                continue;
            }
            let mut key: Vec<(VertexId, VertexId)> = (0..lp.vertices.len())
                .map(|i| {
                    let (a, b) = (lp.vertices[i], lp.vertices[(i + 1) % lp.vertices.len()]);
                    (a.min(b), a.max(b))
                })
                .collect();
            key.sort_unstable();
            candidates.push(Candidate {
                vertices: lp.vertices.clone(),
                keep: lp.faces.clone(),
                key,
                variation: variation[p],
                plug: false,
                cap: Vec::new(),
            });
        }
    }
    let (mut swallowed_faces, mut union_candidates) = (0, 0);
    if source == TessellationSource::PrismUnion {
        let union = union_rims(soup, &edges, alpha, outward)?;
        swallowed_faces = union.swallowed;
        let known: HashSet<Vec<(VertexId, VertexId)>> =
            candidates.iter().map(|c| c.key.clone()).collect();
        for (vertices, faces) in union.rims.iter().flat_map(|(v, f)| split_simple(v, f)) {
            let mut key: Vec<(VertexId, VertexId)> = (0..vertices.len())
                .map(|i| {
                    let (a, b) = (vertices[i], vertices[(i + 1) % vertices.len()]);
                    (a.min(b), a.max(b))
                })
                .collect();
            key.sort_unstable();
            if known.contains(&key) || candidates.iter().any(|c| c.key == key) {
                continue;
            }
            union_candidates += 1;
            candidates.push(Candidate {
                vertices,
                keep: faces,
                key,
                variation: 0.0,
                plug: false,
                cap: Vec::new(),
            });
        }
    }
    let num_candidates = candidates.len();
    // Caps accepted by the alpha test.
    candidates.retain_mut(|c| match cap_of(soup, c, alpha) {
        Ok(cap) => {
            c.cap = cap;
            true
        }
        Err((cap, shape)) => {
            c.cap = cap;
            refused_shape += usize::from(shape);
            refused_wide += usize::from(!shape);
            false
        }
    });
    // Plugs: each edge cycle with a cap from one side only also runs the other way.
    let mut plugs: Vec<Candidate> = Vec::new();
    let mut sides_of: HashMap<&[Edge], usize> = HashMap::new();
    for c in &candidates {
        *sides_of.entry(c.key.as_slice()).or_default() += 1;
    }
    for c in candidates
        .iter()
        .filter(|c| sides_of[c.key.as_slice()] == 1)
    {
        let n = c.vertices.len();
        let vertices: Vec<VertexId> = (0..n).map(|i| c.vertices[(n - i) % n]).collect();
        let keep: Option<Vec<FaceId>> = (0..n)
            .map(|i| {
                let j = n - 1 - i;
                edges.across(c.keep[j], c.vertices[j], c.vertices[(j + 1) % n])
            })
            .collect();
        let Some(keep) = keep else { continue };
        let plug = Candidate {
            vertices,
            keep,
            key: c.key.clone(),
            variation: f64::INFINITY,
            plug: true,
            cap: c.cap.iter().map(|t| [t[0], t[2], t[1]]).collect(),
        };
        if !folds_onto_kept(soup, &plug, &plug.cap) {
            plugs.push(plug);
        }
    }
    candidates.extend(plugs);
    // Two-sided ambiguity: the kept side is the one with less normal variation; ties keep
    // both orders (the interior test decides).
    candidates.sort_by(|a, b| a.key.cmp(&b.key).then(a.variation.total_cmp(&b.variation)));
    let cells = Cells::new(soup, &edges, &candidates);

    let mut refused: HashSet<usize> = HashSet::new();
    let mut refused_validation: HashSet<usize> = HashSet::new();
    // The input's counts of the validated classes, taken when a first output is validated.
    let baseline: OnceCell<HashMap<DegeneracyClass, usize>> = OnceCell::new();
    let (out, added, active, filled) = loop {
        let (active, filled) = select(&edges, &candidates, &cells, &refused);
        let (out, added, cap_of_face, removed) = assemble(soup, &candidates, &active);
        if cap_of_face.is_empty() {
            break (out, added, active, filled);
        }
        // Material is defined where there is a solid: on inputs without borders.
        let shrinking = if topo_in.num_border_loops() == 0 {
            fills_taking_material(soup, &out, &removed, &cap_of_face, outward)
        } else {
            BTreeSet::new()
        };
        if !shrinking.is_empty() {
            refused_validation.extend(shrinking.iter().copied());
            refused.extend(shrinking);
            continue;
        }
        let base = baseline.get_or_init(|| class_counts(soup));
        let implicated = validate(&out, &cap_of_face, base);
        match implicated {
            None => break (out, added, active, filled),
            Some(bad) if bad.is_empty() => {
                // Nothing to blame precisely: refuse every active cap.
                refused.extend(active.iter().copied());
                refused_validation.extend(active.iter().copied());
            }
            Some(bad) => {
                refused_validation.extend(bad.iter().copied());
                refused.extend(bad);
            }
        }
    };
    // Per edge cycle not capped: refused by the validation, internal (both sides filled: a
    // junction inside a filled network), or not enclosed.
    let (mut refused_enclosure, mut internal_rims, mut refused_by_validation) = (0, 0, 0);
    for group in key_groups(&candidates) {
        if !group.clone().any(|k| active.contains(&k)) {
            if group.clone().any(|k| refused_validation.contains(&k)) {
                refused_by_validation += 1;
            } else if group.clone().all(|k| {
                let (kept, region) = &cells.sides[k];
                kept.iter().chain(region).all(|&q| filled[q])
            }) {
                internal_rims += 1;
            } else {
                refused_enclosure += 1;
            }
        }
    }
    // Alpha-neighbourhoods of the faces at the accepted rims (report only).
    let mut rim_faces: Vec<FaceId> = active
        .iter()
        .flat_map(|&i| candidates[i].keep.iter().copied())
        .collect();
    rim_faces.sort_unstable();
    rim_faces.dedup();
    let alpha_close = if rim_faces.is_empty() {
        0
    } else {
        crate::alpha_close_pairs(soup, alpha, Some(&rim_faces))?.len()
    };
    let (mut out, mut added, mut holes_filled) = (out, added, active.len());
    let (mut pieces, mut split_faces) = (Vec::new(), 0);
    // The closing needs a solid: an input with borders keeps the sharp-edge result. It only
    // fills regions with two loops or more (handles), so a result of genus 0 has none left.
    if source == TessellationSource::Closing
        && topo_in.num_border_loops() == 0
        && analyze(&out).genus != Some(0)
    {
        let mut is_cap = vec![false; out.num_faces()];
        for &f in &added {
            is_cap[f] = true;
        }
        let filled = crate::fill::fill_closing(&out, &is_cap, alpha, &baseline, soup, outward);
        out = filled.soup;
        added = filled.added;
        pieces = filled.pieces;
        split_faces = filled.split_faces;
        holes_filled += filled.caps;
        swallowed_faces = filled.swallowed;
        union_candidates = filled.loops_tried;
        refused_shape += filled.refused_shape;
        refused_wide += filled.refused_wide;
        refused_by_validation += filled.refused_validation;
    }
    // Input faces gone: the faces of the output that are neither caps nor pieces are input
    // faces.
    let removed = soup.num_faces() - (out.num_faces() - added.len() - pieces.len());
    // The output's positions begin with the input's; the points come after them.
    let (out, added_faces, points_added) = compact(&out, added, soup.num_vertices());
    let topo_out = analyze(&out);
    let report = GenusReport {
        faces_in: soup.num_faces(),
        faces_out: out.num_faces(),
        genus_in: topo_in.genus,
        genus_out: topo_out.genus,
        border_loops_in: topo_in.num_border_loops(),
        border_loops_out: topo_out.num_border_loops(),
        tessellation_edges: tess.len(),
        swallowed_faces,
        union_candidates,
        open_chains: chains.iter().filter(|c| !c.closed).count(),
        closed_chains: chains.iter().filter(|c| c.closed).count(),
        candidates: num_candidates,
        refused_shape,
        refused_wide,
        refused_enclosure,
        refused_validation: refused_by_validation,
        internal_rims,
        holes_filled,
        triangles_added: added_faces.len(),
        triangles_removed: removed,
        pieces: pieces.len(),
        split_faces,
        points_added,
        alpha_close_pairs: alpha_close,
        seconds: start.elapsed().as_secs_f64(),
        added_faces,
        piece_faces: pieces.into_iter().map(FaceId::from_index).collect(),
    };
    Ok((out, report))
}

/// Whether every loop edge with a face on the other side is a convex edge of the surface
/// (exact orient3d: the other face's far corner is strictly behind the kept face). Holes,
/// tunnels and pockets open at convex rims; a concave rim is the foot of a protrusion, which
/// an alpha-hull never removes.
fn convex_rim(
    soup: &TriangleSoup,
    edges: &EdgeMap,
    vertices: &[VertexId],
    faces: &[FaceId],
    outward: bool,
) -> bool {
    let n = vertices.len();
    (0..n).all(|i| {
        let (a, b) = (vertices[i], vertices[(i + 1) % n]);
        let f = faces[i];
        let Some(g) = edges.across(f, a, b) else {
            return true; // a border edge
        };
        let Some(&c) = soup.faces[g.index()].iter().find(|&&v| v != a && v != b) else {
            return false;
        };
        let t = soup.triangle(f);
        let behind = if outward {
            Orientation::Negative
        } else {
            Orientation::Positive
        };
        orient3d(t[0], t[1], t[2], soup.position(c)) == behind
    })
}

fn check_input(soup: &TriangleSoup) -> Result<(), GenusError> {
    for (i, p) in soup.positions.iter().enumerate() {
        if !p.is_finite() {
            return Err(GenusError::NonFiniteCoordinate {
                vertex: Some(VertexId::from_index(i)),
            });
        }
    }
    for f in soup.face_ids() {
        if soup.faces[f.index()]
            .iter()
            .any(|v| v.index() >= soup.num_vertices())
        {
            return Err(GenusError::IndexOutOfRange { face: f });
        }
    }
    let report = check(
        soup,
        &CheckOptions {
            max_examples: usize::MAX,
            ..CheckOptions::default()
        },
    );
    // T-junctions (Fig. 2) are accepted; the exact intersection test reports the faces
    // touching at a T-junction vertex as intersecting, so pairs explained by a T-junction
    // (one face has the T vertex, the other the edge it lies on) are tolerated.
    let mut t_contacts: HashSet<(VertexId, (VertexId, VertexId))> = HashSet::new();
    for e in &report.finding(DegeneracyClass::TJunctions).examples {
        if let Element::VertexOnEdge { vertex, edge, .. } = e {
            t_contacts.insert((*vertex, (edge[0].min(edge[1]), edge[0].max(edge[1]))));
        }
    }
    let explained = |f: FaceId, g: FaceId| {
        let (tf, tg) = (soup.faces[f.index()], soup.faces[g.index()]);
        let by = |t: [VertexId; 3], u: [VertexId; 3]| {
            t.iter().any(|&v| {
                (0..3).any(|k| {
                    let (a, b) = (u[k], u[(k + 1) % 3]);
                    t_contacts.contains(&(v, (a.min(b), a.max(b))))
                })
            })
        };
        by(tf, tg) || by(tg, tf)
    };
    for class in REFUSED {
        let finding = report.finding(class);
        let offending: Vec<&Element> = finding
            .examples
            .iter()
            .filter(|e| match e {
                Element::FacePair { faces } if class == DegeneracyClass::IntersectingTriangles => {
                    !explained(faces[0], faces[1])
                }
                _ => true,
            })
            .collect();
        if let Some(first) = offending.first() {
            return Err(GenusError::Unacceptable {
                class,
                count: offending.len(),
                example: describe(first),
            });
        }
    }
    Ok(())
}

fn describe(e: &Element) -> String {
    match e {
        Element::Vertex { vertex, position } => format!("vertex {} at {position}", vertex.0),
        Element::VertexGroup { vertices, .. } => format!("vertices {vertices:?}"),
        Element::Face { face, .. } => format!("face {}", face.0),
        Element::FacePair { faces } => format!("faces {} and {}", faces[0].0, faces[1].0),
        Element::Edge { edge, .. } => format!("edge {}-{}", edge[0].0, edge[1].0),
        Element::VertexOnEdge { vertex, edge, .. } => {
            format!("vertex {} on edge {}-{}", vertex.0, edge[0].0, edge[1].0)
        }
    }
}

/// The index ranges of the candidates with the same edge cycle (`cands` sorted by key).
fn key_groups(cands: &[Candidate]) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
    let mut i = 0;
    std::iter::from_fn(move || {
        let start = i;
        while i < cands.len() && cands[i].key == cands[start].key {
            i += 1;
        }
        (start < cands.len()).then_some(start..i)
    })
}

/// The cells of the surface cut along every candidate rim, and for each candidate the cells
/// on its kept side and on its region side.
struct Cells {
    /// Cell of each face (`usize::MAX` for a face with a repeated index).
    of_face: Vec<usize>,
    count: usize,
    /// Per candidate: kept-side cells, region-side cells (sorted, deduplicated).
    sides: Vec<(Vec<usize>, Vec<usize>)>,
}

impl Cells {
    fn new(soup: &TriangleSoup, edges: &EdgeMap, cands: &[Candidate]) -> Self {
        let barrier: HashSet<Edge> = cands.iter().flat_map(|c| c.key.iter().copied()).collect();
        // The cells are the patches of the surface cut along the rims.
        let Patches { of_face, count, .. } = patches(soup, edges, &barrier);
        let sides = cands
            .iter()
            .map(|c| {
                let n = c.vertices.len();
                let mut kept: Vec<usize> = c.keep.iter().map(|f| of_face[f.index()]).collect();
                let mut region: Vec<usize> = (0..n)
                    .filter_map(|i| {
                        let (a, b) = (c.vertices[i], c.vertices[(i + 1) % n]);
                        edges.across(c.keep[i], a, b).map(|g| of_face[g.index()])
                    })
                    .collect();
                kept.sort_unstable();
                kept.dedup();
                region.sort_unstable();
                region.dedup();
                (kept, region)
            })
            .collect();
        Cells {
            of_face,
            count,
            sides,
        }
    }

    /// Whether candidate `i` separates: no cell on both of its sides (a border loop has no
    /// region side).
    fn separates(&self, i: usize) -> bool {
        let (kept, region) = &self.sides[i];
        kept.iter().all(|k| region.binary_search(k).is_err())
    }
}

/// The stable selection (section 3.4 over whole networks of tunnels). The surface is cut
/// along every candidate rim into cells. The cells on the region side of the preferred
/// candidate of each edge cycle (the first not refused; ties give both) are tentatively
/// filled. A candidate is usable when all its kept cells stay and all its region cells are
/// filled; usable candidates are taken in order unless they share an edge with one already
/// taken. Every edge between a filled cell and a kept one must lie on a taken rim; where one
/// does not (a mouth wider than the cube, a rim refused), the filled cell is kept instead,
/// and this repeats until stable. So a tunnel that opens wide at one end stays open and is
/// plugged at its junction with the rest of the network, which still fills; refusing can
/// only keep more of the input. Returns the taken candidates and the filled cells.
fn select(
    edges: &EdgeMap,
    cands: &[Candidate],
    cells: &Cells,
    refused: &HashSet<usize>,
) -> (Vec<usize>, Vec<bool>) {
    let mut preferred: Vec<usize> = Vec::new();
    for group in key_groups(cands) {
        let group: Vec<usize> = group
            .filter(|&k| !refused.contains(&k) && !cands[k].plug && cells.separates(k))
            .collect();
        if let Some(&first) = group.first() {
            preferred.extend(group.iter().copied().filter(|&k| {
                cands[k]
                    .variation
                    .total_cmp(&cands[first].variation)
                    .is_eq()
            }));
        }
    }
    // Flattest kept patches first: their kept cells are anchored (a mouth on a planar face
    // anchors the face) before a junction rim could put them on its region side.
    preferred.sort_by(|&a, &b| cands[a].variation.total_cmp(&cands[b].variation));
    let mut filled = vec![false; cells.count];
    let mut anchored = vec![false; cells.count];
    for &k in &preferred {
        let (kept, region) = &cells.sides[k];
        if region.iter().any(|&q| anchored[q]) {
            continue;
        }
        for &q in region {
            filled[q] = true;
        }
        for &q in kept {
            if !filled[q] {
                anchored[q] = true;
            }
        }
    }
    loop {
        let mut taken: Vec<usize> = Vec::new();
        let mut covered: HashSet<Edge> = HashSet::new();
        for (k, c) in cands.iter().enumerate() {
            if refused.contains(&k) || !cells.separates(k) {
                continue;
            }
            let (kept, region) = &cells.sides[k];
            if kept.iter().any(|&q| filled[q]) || region.iter().any(|&q| !filled[q]) {
                continue;
            }
            if c.key.iter().any(|e| covered.contains(e)) {
                continue;
            }
            covered.extend(c.key.iter().copied());
            taken.push(k);
        }
        let mut changed = false;
        for (e, fs) in &edges.faces {
            if let [(f, _), (g, _)] = fs.as_slice() {
                let (p, q) = (cells.of_face[f.index()], cells.of_face[g.index()]);
                if p == usize::MAX || q == usize::MAX || filled[p] == filled[q] {
                    continue;
                }
                if !covered.contains(e) {
                    let inner = if filled[p] { p } else { q };
                    filled[inner] = false;
                    changed = true;
                }
            }
        }
        if !changed {
            return (taken, filled);
        }
    }
}

/// Faces spread over from the non-kept side of `c`'s rim, not crossing `barrier`; `None`
/// when the spread reaches a kept face.
fn interior_region(
    soup: &TriangleSoup,
    edges: &EdgeMap,
    c: &Candidate,
    barrier: &HashSet<(VertexId, VertexId)>,
    kept: &HashSet<FaceId>,
) -> Option<HashSet<FaceId>> {
    let n = c.vertices.len();
    let mut region: HashSet<FaceId> = HashSet::new();
    let mut queue = VecDeque::new();
    for i in 0..n {
        let (a, b) = (c.vertices[i], c.vertices[(i + 1) % n]);
        if let Some(g) = edges.across(c.keep[i], a, b) {
            if region.insert(g) {
                queue.push_back(g);
            }
        }
    }
    while let Some(f) = queue.pop_front() {
        if kept.contains(&f) {
            return None;
        }
        let t = soup.faces[f.index()];
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if barrier.contains(&(a.min(b), a.max(b))) {
                continue;
            }
            if let Some(g) = edges.across(f, a, b) {
                if region.insert(g) {
                    queue.push_back(g);
                }
            }
        }
    }
    Some(region)
}

/// The rim edges and the kept faces of the active candidates: the walls the interior spread
/// may not cross, and the faces it may not enter.
fn rim_sets(
    cands: &[Candidate],
    active: &[usize],
) -> (HashSet<(VertexId, VertexId)>, HashSet<FaceId>) {
    let barrier = active
        .iter()
        .flat_map(|&i| cands[i].key.iter().copied())
        .collect();
    let kept = active
        .iter()
        .flat_map(|&i| cands[i].keep.iter().copied())
        .collect();
    (barrier, kept)
}

/// Output faces (input ids), the indices of the added faces in it, the candidate of each
/// added face, and the removed input faces.
fn assemble(
    soup: &TriangleSoup,
    cands: &[Candidate],
    active: &[usize],
) -> (
    TriangleSoup,
    Vec<usize>,
    HashMap<usize, usize>,
    HashSet<FaceId>,
) {
    let edges = EdgeMap::new(soup);
    let (barrier, kept) = rim_sets(cands, active);
    let mut removed: HashSet<FaceId> = HashSet::new();
    for &i in active {
        if let Some(r) = interior_region(soup, &edges, &cands[i], &barrier, &kept) {
            removed.extend(r);
        }
    }
    let mut faces: Vec<[VertexId; 3]> = soup
        .face_ids()
        .filter(|f| !removed.contains(f))
        .map(|f| soup.faces[f.index()])
        .collect();
    let mut added = Vec::new();
    let mut cap_of_face = HashMap::new();
    for &i in active {
        for t in &cands[i].cap {
            added.push(faces.len());
            cap_of_face.insert(faces.len(), i);
            faces.push(*t);
        }
    }
    (
        TriangleSoup::new(soup.positions.clone(), faces),
        added,
        cap_of_face,
        removed,
    )
}

/// The candidates of the fills that would take material away (see
/// [`Fill::takes_material`]): the removed faces and the caps of `out` are
/// grouped by shared edges into fills (a region with its caps), each weighed on its own.
fn fills_taking_material(
    soup: &TriangleSoup,
    out: &TriangleSoup,
    removed: &HashSet<FaceId>,
    cap_of_face: &HashMap<usize, usize>,
    outward: bool,
) -> BTreeSet<usize> {
    let mut removed: Vec<FaceId> = removed.iter().copied().collect();
    removed.sort_unstable();
    let mut caps: Vec<usize> = cap_of_face.keys().copied().collect();
    caps.sort_unstable();
    // Nodes: the removed faces, then the cap faces; joined where they share an edge.
    let tri = |i: usize| {
        if i < removed.len() {
            soup.faces[removed[i].index()]
        } else {
            out.faces[caps[i - removed.len()]]
        }
    };
    let n = removed.len() + caps.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut first_at: HashMap<Edge, usize> = HashMap::new();
    for i in 0..n {
        let t = tri(i);
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let j = *first_at.entry((a.min(b), a.max(b))).or_insert(i);
            let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
            parent[ri] = rj;
        }
    }
    let mut fills: BTreeMap<usize, Fill> = BTreeMap::new();
    for i in 0..n {
        let r = root(&mut parent, i);
        let t = tri(i).map(|v| soup.position(v));
        let fill = fills.entry(r).or_default();
        if i < removed.len() {
            fill.removed.push(t);
        } else {
            fill.caps.push(t);
        }
    }
    let sign = if outward { 1.0 } else { -1.0 };
    let mut bad = BTreeSet::new();
    for (r, fill) in &fills {
        if fill.takes_material(sign) {
            for i in (removed.len()..n).filter(|&i| root(&mut parent, i) == *r) {
                bad.insert(cap_of_face[&caps[i - removed.len()]]);
            }
        }
    }
    bad
}

/// `None` when the output is clean; otherwise the candidates implicated (possibly none).
fn validate(
    out: &TriangleSoup,
    cap_of_face: &HashMap<usize, usize>,
    baseline: &HashMap<DegeneracyClass, usize>,
) -> Option<Vec<usize>> {
    let found = new_findings(out, baseline)?;
    let mut bad: BTreeSet<usize> = BTreeSet::new();
    let mut cap_vertices: HashMap<VertexId, Vec<usize>> = HashMap::new();
    for (&f, &c) in cap_of_face {
        for v in out.faces[f] {
            cap_vertices.entry(v).or_default().push(c);
        }
    }
    // Two conflicting caps: refuse one already in conflict with something else if any (a cap
    // duplicating kept faces, e.g. over the outer loop of a face), else the later one.
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for e in &found {
        if let Some(v) = e.vertex {
            bad.extend(cap_vertices.get(&v).into_iter().flatten());
        }
        let caps: Vec<usize> = e
            .faces
            .iter()
            .filter_map(|f| cap_of_face.get(&f.index()).copied())
            .collect();
        // Two caps in conflict: refusing the later one is enough.
        if let (true, [c1, c2]) = (e.pair, caps.as_slice()) {
            if c1 != c2 {
                pairs.push((*c1, *c2));
                continue;
            }
        }
        bad.extend(caps);
    }
    for (c1, c2) in pairs {
        if !bad.contains(&c1) && !bad.contains(&c2) {
            bad.insert(c1.max(c2));
        }
    }
    Some(bad.into_iter().collect())
}

/// Drops unreferenced vertices; maps the added face indices (face order is kept); counts the
/// vertices kept from `first_new` on.
fn compact(
    s: &TriangleSoup,
    added: Vec<usize>,
    first_new: usize,
) -> (TriangleSoup, Vec<FaceId>, usize) {
    let mut map = vec![u32::MAX; s.num_vertices()];
    let mut used = vec![false; s.num_vertices()];
    for t in &s.faces {
        for v in t {
            used[v.index()] = true;
        }
    }
    let mut positions = Vec::new();
    for (i, u) in used.iter().enumerate() {
        if *u {
            map[i] = positions.len() as u32;
            positions.push(s.positions[i]);
        }
    }
    let faces = s
        .faces
        .iter()
        .map(|t| t.map(|v| VertexId(map[v.index()])))
        .collect();
    let new = used
        .get(first_new..)
        .map_or(0, |u| u.iter().filter(|&&u| u).count());
    (
        TriangleSoup::new(positions, faces),
        added.into_iter().map(FaceId::from_index).collect(),
        new,
    )
}
