//! Certified verdicts on a simplifier's output: two-sided Hausdorff distance against a
//! tolerance, self-intersections and topology, each decided by exact predicates.
//!
//! [`certify`] answers, for any two triangle meshes `orig` and `approx` and a tolerance
//! `epsilon`:
//!
//! * whether every point of `approx` is within `epsilon` of `orig` and every point of `orig`
//!   within `epsilon` of `approx` ([`OneSided`] per direction: [`Verdict::Holds`] only when
//!   proved, [`Verdict::Violated`] only with an exact [`Witness`], [`Verdict::Undecided`] when
//!   the bounds meet within `resolution` of `epsilon`), with a certified interval
//!   `[lower, upper]` for the one-sided Hausdorff distance;
//! * the intersecting face pairs of `approx` (exact, adjacency-aware);
//! * genus, components and border loops of both meshes, and whether they match;
//! * on request ([`Options::map`]), an [`ErrorMap`]: certified bounds per face, both ways,
//!   and per vertex of `approx`.
//!
//! How the distance is certified (branch and bound, exact cover of each triangle by rounded
//! sub-triangles with proved error bounds, exact witnesses, exact comparison with `epsilon²`)
//! is written down in the `hausdorff` module source; the short form: a proof needs one
//! triangle of the other mesh within `epsilon - delta` of all three corners of a sub-triangle
//! (distance to a triangle is convex), and a witness is a point exactly on the mesh whose
//! exact distance to every nearby triangle exceeds `epsilon`.
//!
//! ```
//! use envelope_mesh::generate::icosphere;
//! use envelope_verify::{certify, Options, Verdict};
//!
//! let orig = icosphere(2, 1.0);
//! let mut approx = orig.clone();
//! // Push vertex 0 outward by 0.01 along its (unit) position vector.
//! approx.positions[0] *= 1.01;
//! let near = certify(&orig, &approx, &Options::new(0.0101));
//! assert_eq!(near.verdict, Verdict::Holds);
//! let far = certify(&orig, &approx, &Options::new(0.0099));
//! assert_eq!(far.verdict, Verdict::Violated);
//! let w = far.approx_to_orig.witness.as_ref().unwrap();
//! assert!(w.exact_f64 && w.point == approx.positions[0] && w.distance > 0.0099);
//! ```
//!
//! # Error maps
//!
//! With [`Options::map`], [`Certificate::map`] holds the bounds the branch and bound already
//! proved for each face, not a second estimate: a face's upper bound is the largest certified
//! bound of the sub-triangles (or cut pieces) that settled it, its lower bound the certified
//! distance of one exact point of it. A vertex of `approx` gets the largest upper bound of its
//! faces, so it bounds the distance of the whole surface around it, not only of the vertex
//! (the farthest point may lie inside a face). What this guarantees:
//!
//! * every value is a proved upper bound of the distance of its face (or of the faces around
//!   its vertex) to the other mesh;
//! * where a direction holds, every value of that direction is at most `epsilon`;
//! * the largest vertex value is at least the proved lower bound `approx_to_orig.lower`
//!   (the farthest face's bound covers the farthest point).
//!
//! The branch and bound stops refining once a piece is proved within `epsilon`, which leaves
//! a face's bound just below `epsilon` wherever it had to subdivide; for the map, each face
//! within `epsilon` is then decided again at tolerances between its lower and upper bounds
//! (three bisection rounds at most, stopping once they are within a quarter of each other):
//! a proof lowers its upper bound, an exact witness raises its lower bound. Bounds can stay
//! apart (an undecided round, a tie at `epsilon`). Without [`Options::map`] none of this is
//! computed; with it, verification takes a few times longer.
//!
//! ```
//! use envelope_mesh::generate::icosphere;
//! use envelope_verify::{certify, Options};
//!
//! let orig = icosphere(2, 1.0);
//! let mut approx = orig.clone();
//! approx.positions[0] *= 1.01;
//! let c = certify(&orig, &approx, &Options { map: true, ..Options::new(0.02) });
//! let map = c.map.as_ref().unwrap();
//! assert_eq!(map.approx_faces.len(), approx.faces.len());
//! // The moved vertex carries the largest bound, at least the 0.01 it moved.
//! let worst = map.approx_vertices.iter().copied().fold(0.0, f64::max);
//! assert_eq!(map.approx_vertices[0], worst);
//! assert!(worst >= 0.01 * (1.0 - 1e-9) && worst <= 0.02);
//! ```
#![forbid(unsafe_code)]

mod hausdorff;
mod numeric;

use envelope_mesh::{FaceId, Topology, TriangleSoup, analyze};
use std::sync::atomic::{AtomicBool, Ordering};

use envelope_predicates::bvh::{self, Bvh};
use envelope_predicates::faces_intersect;
use glam::DVec3;
use serde_json::{Value, json};

/// What [`certify`] checks, and how finely.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The tolerance (an absolute distance, > 0).
    pub epsilon: f64,
    /// Stop refining where upper and lower bounds are closer than this (absolute); the
    /// answer is then [`Verdict::Undecided`]. [`Options::new`] sets `1e-6 * epsilon`.
    pub resolution: f64,
    /// Look for self-intersections of `approx`.
    pub self_intersections: bool,
    /// Stop at the first intersecting pair found (like CGAL's `does_self_intersect`) instead of
    /// listing them all; the verdict is the same, the certificate names one pair.
    pub first_intersection_only: bool,
    /// Compare genus, components and border loops.
    pub topology: bool,
    /// Check `orig -> approx` too (two-sided). When false only `approx -> orig` is decided:
    /// the envelope question, see [`Certificate::envelope_of`].
    pub orig_to_approx: bool,
    /// Allow the intersections `orig` already had: an intersecting pair of `approx` whose two
    /// faces are both faces of `orig` (the same three corners, bit for bit, in the same
    /// cyclic order) that intersect in `orig` too is listed in
    /// [`Certificate::kept_intersections`] and is no violation; any other pair is. For a simplifier that keeps the faces around an input's
    /// self-intersections unchanged: such a pair meets exactly as it did in `orig`.
    pub allow_input_intersections: bool,
    /// Keep the certified bounds of every face, both ways, and of every vertex of `approx`
    /// ([`Certificate::map`], see [Error maps](crate#error-maps)). Off by default: it
    /// decides each face again at up to three tighter tolerances.
    pub map: bool,
}

impl Options {
    /// All checks, resolution `1e-6 * epsilon`.
    #[must_use]
    pub fn new(epsilon: f64) -> Options {
        Options {
            epsilon,
            resolution: epsilon * 1e-6,
            self_intersections: true,
            first_intersection_only: false,
            topology: true,
            orig_to_approx: true,
            allow_input_intersections: false,
            map: false,
        }
    }

    /// Only whether `approx` lies in the epsilon-envelope of `orig` (every point of `approx`
    /// within epsilon of `orig`), plus self-intersections and topology: no `orig -> approx`.
    #[must_use]
    pub fn envelope_of(epsilon: f64) -> Options {
        Options {
            orig_to_approx: false,
            ..Options::new(epsilon)
        }
    }

    /// Only the two-sided distance.
    #[must_use]
    pub fn distance_only(epsilon: f64) -> Options {
        Options {
            self_intersections: false,
            topology: false,
            ..Options::new(epsilon)
        }
    }
}

/// A decision.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Verdict {
    /// Proved.
    Holds,
    /// Not decided within the resolution (never a wrong `Holds`).
    Undecided,
    /// Disproved, with a witness.
    Violated,
}

impl Verdict {
    /// `"holds"`, `"undecided"`, `"violated"`.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::Undecided => "undecided",
            Verdict::Violated => "violated",
        }
    }
}

/// A point exactly on a face of one mesh, farther than epsilon from the other mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Witness {
    /// The face the point lies on.
    pub face: FaceId,
    /// The point is exactly `(b[0] a + b[1] b + b[2] c) / 2^level` for the face corners `a, b, c`.
    pub barycentric: [u64; 3],
    /// See `barycentric`.
    pub level: u32,
    /// The point in f64 (exactly it when `exact_f64`, else rounded to nearest per coordinate).
    pub point: DVec3,
    /// Whether `point` is the exact witness.
    pub exact_f64: bool,
    /// A proved lower bound of its distance to the other mesh, at least epsilon. The
    /// distance itself is proved strictly greater than epsilon; when it exceeds epsilon by
    /// less than this bound can resolve, the bound is epsilon itself.
    pub distance: f64,
}

/// One direction: is every point of the first mesh within epsilon of the second?
#[derive(Clone, Debug, PartialEq)]
pub struct OneSided {
    /// The decision.
    pub verdict: Verdict,
    /// Proved lower bound of the one-sided Hausdorff distance.
    pub lower: f64,
    /// Proved upper bound of the one-sided Hausdorff distance (refined only as far as the
    /// decision needed: at most epsilon when it holds).
    pub upper: f64,
    /// The farthest witness found, when violated.
    pub witness: Option<Witness>,
    /// Number of sub-triangles left undecided at the resolution.
    pub undecided_regions: usize,
    /// Number of (sub-)triangles examined.
    pub subdivisions: u64,
}

/// Certified bounds of the distance of one face (every point of it) to the other mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceBound {
    /// Proved lower bound (the distance of one exact point of the face; 0 when none was
    /// certified).
    pub lower: f64,
    /// Proved upper bound of the largest distance of a point of the face (infinite only when
    /// no bound could be certified, or for a face whose corners are not vertices).
    pub upper: f64,
}

/// Certified distance bounds per face, both ways, and per vertex of `approx` (see
/// [Error maps](crate#error-maps)).
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorMap {
    /// Per face of `approx`, in face order: the bounds of its distance to `orig`.
    pub approx_faces: Vec<FaceBound>,
    /// Per face of `orig`, in face order: the bounds of its distance to `approx` (`None`
    /// when `orig -> approx` was not checked).
    pub orig_faces: Option<Vec<FaceBound>>,
    /// Per vertex of `approx`: the largest upper bound of the faces around it, which bounds
    /// the distance to `orig` of every point of those faces (0 for a vertex on no face).
    pub approx_vertices: Vec<f64>,
}

impl ErrorMap {
    /// The largest vertex value (0 for a mesh without vertices).
    #[must_use]
    pub fn max_vertex_value(&self) -> f64 {
        self.approx_vertices.iter().copied().fold(0.0, f64::max)
    }

    /// The map's JSON: per-face `upper` and `lower` arrays both ways, per-vertex values
    /// (`null` for an infinite bound).
    #[must_use]
    pub fn to_json(&self) -> Value {
        let num = |x: f64| if x.is_finite() { json!(x) } else { Value::Null };
        let faces = |b: &[FaceBound]| {
            json!({
                "upper": b.iter().map(|f| num(f.upper)).collect::<Vec<_>>(),
                "lower": b.iter().map(|f| num(f.lower)).collect::<Vec<_>>(),
            })
        };
        json!({
            "approx_faces": faces(&self.approx_faces),
            "orig_faces": self.orig_faces.as_deref().map(faces),
            "approx_vertices": self.approx_vertices.iter().map(|&x| num(x)).collect::<Vec<_>>(),
        })
    }
}

/// Topology numbers of one mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TopologySummary {
    /// Sum of the components' genera (`None` when undefined: non-manifold or non-orientable).
    pub genus: Option<u32>,
    /// Face-connected components.
    pub components: usize,
    /// Border loops (and open border chains).
    pub border_loops: usize,
}

impl TopologySummary {
    /// The summary of a mesh.
    #[must_use]
    pub fn of(soup: &TriangleSoup) -> TopologySummary {
        TopologySummary::from(&analyze(soup))
    }
}

impl From<&Topology> for TopologySummary {
    fn from(t: &Topology) -> Self {
        TopologySummary {
            genus: t.genus,
            components: t.components.len(),
            border_loops: t.num_border_loops(),
        }
    }
}

/// Topology of both meshes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TopologyCheck {
    /// Of `orig`.
    pub orig: TopologySummary,
    /// Of `approx`.
    pub approx: TopologySummary,
}

impl TopologyCheck {
    /// Same genus (both defined), components and border loops.
    #[must_use]
    pub fn matches(&self) -> bool {
        self.orig.genus.is_some() && self.orig == self.approx
    }
}

/// Everything [`certify`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct Certificate {
    /// `Violated` if any checked property is violated, else `Undecided` if any is undecided,
    /// else `Holds`.
    pub verdict: Verdict,
    /// The tolerance.
    pub epsilon: f64,
    /// The resolution used.
    pub resolution: f64,
    /// Bounding-box diagonal of `orig` (for relative values).
    pub diagonal: f64,
    /// Every point of `approx` within epsilon of `orig`?
    pub approx_to_orig: OneSided,
    /// Every point of `orig` within epsilon of `approx`? When [`Options::orig_to_approx`] is
    /// off this is [`OneSided::unchecked`] (undecided, interval `[0, inf]`) and does not enter
    /// the verdict.
    pub orig_to_approx: OneSided,
    /// Whether `orig_to_approx` was checked.
    pub two_sided: bool,
    /// Intersecting face pairs of `approx`, when asked: all of them, or one when
    /// [`Options::first_intersection_only`] (empty when there is none, either way).
    pub self_intersections: Option<Vec<(FaceId, FaceId)>>,
    /// Whether `self_intersections` lists every pair (false when it stopped at the first).
    pub self_intersections_complete: bool,
    /// The faces of `approx` overlap in more pairs than [`bvh::pair_budget`] allows and
    /// none of the pairs tested within it intersect: whether any pair does is not decided
    /// (the verdict is then at best [`Verdict::Undecided`]).
    pub self_intersections_undecided: bool,
    /// Intersecting pairs of `approx` made of two unchanged faces of `orig` that met there
    /// too, allowed by
    /// [`Options::allow_input_intersections`] (empty otherwise; never in
    /// `self_intersections`).
    pub kept_intersections: Vec<(FaceId, FaceId)>,
    /// Topology of both, when asked.
    pub topology: Option<TopologyCheck>,
    /// Per-face and per-vertex bounds, when asked ([`Options::map`]).
    pub map: Option<ErrorMap>,
}

impl OneSided {
    /// A direction that was not checked: undecided, with the trivial interval `[0, inf]`.
    #[must_use]
    pub fn unchecked() -> OneSided {
        OneSided {
            verdict: Verdict::Undecided,
            lower: 0.0,
            upper: f64::INFINITY,
            witness: None,
            undecided_regions: 0,
            subdivisions: 0,
        }
    }
}

impl Certificate {
    /// Every checked property is proved ([`Verdict::Holds`]).
    #[must_use]
    pub fn holds(&self) -> bool {
        self.verdict == Verdict::Holds
    }

    /// Whether `approx` lies inside the epsilon-envelope of `orig`, `{p : dist(p, orig) <=
    /// epsilon}` (the Minkowski sum of `orig` with the closed epsilon-ball): exactly the
    /// `approx -> orig` decision. CGAL's `Polyhedral_envelope` (and fast-envelope) test a union
    /// of per-face prisms that is designed to lie inside this set, so their "inside" implies
    /// `Holds` here, but not conversely (they may reject outputs within epsilon).
    #[must_use]
    pub fn envelope_of(&self) -> Verdict {
        self.approx_to_orig.verdict
    }

    /// Names of the violated properties (`approx_to_orig`, `orig_to_approx`,
    /// `self_intersections`, `topology`).
    #[must_use]
    pub fn violations(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        if self.approx_to_orig.verdict == Verdict::Violated {
            v.push("approx_to_orig");
        }
        if self.two_sided && self.orig_to_approx.verdict == Verdict::Violated {
            v.push("orig_to_approx");
        }
        if self
            .self_intersections
            .as_ref()
            .is_some_and(|p| !p.is_empty())
        {
            v.push("self_intersections");
        }
        if self.topology.is_some_and(|t| !t.matches()) {
            v.push("topology");
        }
        v
    }

    /// The certificate as one JSON object (stable keys).
    #[must_use]
    pub fn to_json(&self) -> Value {
        let rel = |x: f64| {
            if self.diagonal > 0.0 {
                json!(x / self.diagonal)
            } else {
                Value::Null
            }
        };
        let num = |x: f64| if x.is_finite() { json!(x) } else { Value::Null };
        let side = |s: &OneSided| {
            json!({
                "verdict": s.verdict.as_str(),
                "lower": num(s.lower),
                "upper": num(s.upper),
                "lower_relative": rel(s.lower),
                "upper_relative": rel(s.upper),
                "undecided_regions": s.undecided_regions,
                "subdivisions": s.subdivisions,
                "witness": s.witness.as_ref().map(|w| json!({
                    "face": w.face.index(),
                    "point": [w.point.x, w.point.y, w.point.z],
                    "exact_f64": w.exact_f64,
                    "barycentric": w.barycentric,
                    "denominator_log2": w.level,
                    "distance_at_least": num(w.distance),
                })),
            })
        };
        let topo = |t: &TopologySummary| json!({ "genus": t.genus, "components": t.components, "border_loops": t.border_loops });
        let mut out = json!({
            "verdict": self.verdict.as_str(),
            "violations": self.violations(),
            "epsilon": self.epsilon,
            "epsilon_relative": rel(self.epsilon),
            "resolution": self.resolution,
            "diagonal": self.diagonal,
            "two_sided": self.two_sided,
            "envelope_of": self.envelope_of().as_str(),
            "approx_to_orig": side(&self.approx_to_orig),
            "orig_to_approx": if self.two_sided { side(&self.orig_to_approx) } else { Value::Null },
            "hausdorff": if self.two_sided {
                json!({
                    "lower": num(self.approx_to_orig.lower.max(self.orig_to_approx.lower)),
                    "upper": num(self.approx_to_orig.upper.max(self.orig_to_approx.upper)),
                })
            } else {
                Value::Null
            },
            "self_intersections": self.self_intersections.as_ref().map(|p| json!({
                "count": p.len(),
                "complete": self.self_intersections_complete,
                "undecided": self.self_intersections_undecided,
                "pairs": p.iter().take(100).map(|(a, b)| [a.index(), b.index()]).collect::<Vec<_>>(),
                "kept_from_input": self.kept_intersections.len(),
            })),
            "topology": self.topology.map(|t| json!({
                "orig": topo(&t.orig),
                "approx": topo(&t.approx),
                "matches": t.matches(),
            })),
        });
        if let Some(map) = &self.map {
            out["map"] = map.to_json();
        }
        out
    }
}

fn raw_faces(soup: &TriangleSoup) -> Vec<[u32; 3]> {
    let n = soup.positions.len();
    soup.faces
        .iter()
        .map(|f| f.map(|v| v.0))
        .filter(|f| f.iter().all(|&v| (v as usize) < n))
        .collect()
}

/// Bounds per face of `soup` from bounds per face of [`raw_faces`] (a face naming a missing
/// vertex was not measured: `[0, inf]`).
fn per_soup_face(soup: &TriangleSoup, raw: Vec<FaceBound>) -> Vec<FaceBound> {
    let n = soup.positions.len();
    if raw.len() == soup.faces.len() {
        return raw;
    }
    let mut raw = raw.into_iter();
    soup.faces
        .iter()
        .map(|f| {
            let measured = f.iter().all(|v| v.index() < n);
            measured.then(|| raw.next()).flatten().unwrap_or(FaceBound {
                lower: 0.0,
                upper: f64::INFINITY,
            })
        })
        .collect()
}

/// Per vertex, the largest upper bound of the faces around it (0 on no face).
fn vertex_values(soup: &TriangleSoup, faces: &[FaceBound]) -> Vec<f64> {
    let mut out = vec![0.0f64; soup.positions.len()];
    for (f, b) in soup.faces.iter().zip(faces) {
        for v in f {
            if let Some(x) = out.get_mut(v.index()) {
                *x = x.max(b.upper);
            }
        }
    }
    out
}

/// One intersecting pair of faces `(i, j)`, `i < j`, or `None` when the faces do not intersect
/// (same exact, adjacency-aware test and candidate pairs as
/// [`envelope_predicates::self_intersections`], which lists them all). Once a pair is found
/// the remaining candidates are skipped without running the exact test, so the cost of a mesh
/// that does intersect is mostly the box traversal. With several threads, which pair is named
/// may vary between runs; whether there is one does not.
///
/// ```
/// use envelope_verify::first_self_intersection;
/// use glam::DVec3;
/// let pos = [DVec3::ZERO, DVec3::X, DVec3::Y,
///            DVec3::new(0.2, 0.2, -1.0), DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.4, 0.4, 0.0)];
/// assert_eq!(first_self_intersection(&pos, &[[0, 1, 2], [3, 4, 5]]), Some((0, 1)));
/// assert_eq!(first_self_intersection(&pos, &[[0, 1, 2]]), None);
/// ```
#[must_use]
pub fn first_self_intersection(positions: &[DVec3], faces: &[[u32; 3]]) -> Option<(u32, u32)> {
    first_pair(&Bvh::from_triangles(positions, faces), positions, faces)
}

/// Two faces of a soup.
type FacePair = (FaceId, FaceId);

/// Splits intersecting pairs of `approx` into those whose two faces are faces of `orig` (the
/// same corners bit for bit, in the same cyclic order) that intersect in `orig` too, exactly,
/// and the others.
fn split_kept_pairs(
    orig: &TriangleSoup,
    approx: &TriangleSoup,
    pairs: Vec<FacePair>,
) -> (Vec<FacePair>, Vec<FacePair>) {
    // A face as its corners' bits, rotated to start at the smallest: equal for the same
    // oriented triangle whatever corner it starts at.
    let key = |s: &TriangleSoup, f: FaceId| {
        let c = s.triangle(f).map(|p| p.to_array().map(f64::to_bits));
        let k = (0..3).min_by_key(|&k| c[k]).unwrap_or(0);
        [c[k], c[(k + 1) % 3], c[(k + 2) % 3]]
    };
    let faces: std::collections::HashMap<_, FaceId> =
        orig.face_ids().map(|f| (key(orig, f), f)).collect();
    let of = raw_faces(orig);
    let met_in_orig =
        |&(a, b): &FacePair| match (faces.get(&key(approx, a)), faces.get(&key(approx, b))) {
            (Some(&x), Some(&y)) => faces_intersect(&orig.positions, of[x.index()], of[y.index()]),
            _ => false,
        };
    pairs.into_iter().partition(met_in_orig)
}

/// [`first_self_intersection`] with the faces' BVH given.
fn first_pair(tree: &Bvh, positions: &[DVec3], faces: &[[u32; 3]]) -> Option<(u32, u32)> {
    let found = AtomicBool::new(false);
    let pairs = tree.self_pairs_where(|i, j| {
        if found.load(Ordering::Relaxed) {
            return false;
        }
        let hit = faces_intersect(positions, faces[i as usize], faces[j as usize]);
        if hit {
            found.store(true, Ordering::Relaxed);
        }
        hit
    });
    pairs.first().copied()
}

/// The first intersecting pair in the tree's sequential pair order among the first `budget`
/// pairs with overlapping boxes, or `None` (deterministic, whatever the thread count).
fn bounded_first_pair(
    tree: &Bvh,
    positions: &[DVec3],
    faces: &[[u32; 3]],
    budget: usize,
) -> Option<(u32, u32)> {
    let (mut found, mut tested) = (None, 0usize);
    tree.self_pairs_while(|i, j| {
        tested += 1;
        if faces_intersect(positions, faces[i as usize], faces[j as usize]) {
            found = Some((i, j));
        }
        found.is_none() && tested < budget
    });
    found
}

/// [`envelope_predicates::self_intersections`] with the faces' BVH given (the same pairs).
fn all_pairs(tree: &Bvh, positions: &[DVec3], faces: &[[u32; 3]]) -> Vec<(u32, u32)> {
    tree.self_pairs_where(|i, j| faces_intersect(positions, faces[i as usize], faces[j as usize]))
}

/// Decides whether every point of `from` lies within `epsilon` of `to` (one direction only),
/// with a certified interval for the one-sided Hausdorff distance.
///
/// ```
/// use envelope_mesh::TriangleSoup;
/// use envelope_verify::{one_sided, Verdict};
/// let big = TriangleSoup::from_raw(&[[0., 0., 0.], [4., 0., 0.], [0., 4., 0.]], &[[0, 1, 2]]);
/// let small = TriangleSoup::from_raw(&[[0., 0., 1.], [1., 0., 1.], [0., 1., 1.]], &[[0, 1, 2]]);
/// // The small triangle floats 1 above the big one ...
/// let s = one_sided(&small, &big, 1.0, 1e-9);
/// assert_eq!(s.verdict, Verdict::Holds);
/// assert!(s.lower <= 1.0 && 1.0 <= s.upper);
/// // ... but the big one reaches far from the small one.
/// assert_eq!(one_sided(&big, &small, 1.0, 1e-9).verdict, Verdict::Violated);
/// ```
#[must_use]
pub fn one_sided(
    from: &TriangleSoup,
    to: &TriangleSoup,
    epsilon: f64,
    resolution: f64,
) -> OneSided {
    assert!(
        epsilon > 0.0 && epsilon.is_finite(),
        "epsilon must be positive and finite"
    );
    let target = hausdorff::Target::new(&to.positions, &raw_faces(to));
    let tol = hausdorff::Tolerance::new(epsilon, resolution.max(0.0));
    hausdorff::one_sided(&from.positions, &raw_faces(from), &target, &tol, false).0
}

/// Repeated one-sided questions against one surface: "is every point of these triangles
/// within `epsilon` of it?", decided by the certificate's exact branch and bound, with the
/// surface's tree built once. A simplifier's tolerance test asks it of each candidate
/// triangle. An answer is `true` only when proved; a triangle the search leaves undecided
/// within its budget answers `false`, like a witness (conservative: it may only refuse).
///
/// ```
/// use envelope_mesh::TriangleSoup;
/// use envelope_verify::Within;
/// use glam::DVec3;
/// let floor = TriangleSoup::from_raw(&[[0., 0., 0.], [4., 0., 0.], [0., 4., 0.]], &[[0, 1, 2]]);
/// let within = Within::new(&floor, 1.0);
/// let at = |z: f64| [DVec3::new(0., 0., z), DVec3::new(1., 0., z), DVec3::new(0., 1., z)];
/// assert!(within.holds(&[at(1.0)]));
/// assert!(!within.holds(&[at(0.5), at(1.25)]));
/// ```
pub struct Within {
    target: hausdorff::Target,
    tol: hausdorff::Tolerance,
}

impl Within {
    /// The questions against `to` at `epsilon` (resolution `1e-6 * epsilon`, as
    /// [`Options::new`]).
    ///
    /// # Panics
    /// When `epsilon` is not positive and finite.
    #[must_use]
    pub fn new(to: &TriangleSoup, epsilon: f64) -> Within {
        Within::with_target(
            hausdorff::Target::new(&to.positions, &raw_faces(to)),
            epsilon,
        )
    }

    /// [`Within::new`] against the triangles `to` (repeated ones count once): for
    /// questions against a few triangles that change between calls.
    ///
    /// # Panics
    /// When `epsilon` is not positive and finite.
    #[must_use]
    pub fn from_triangles(to: Vec<[DVec3; 3]>, epsilon: f64) -> Within {
        Within::with_target(hausdorff::Target::from_triangles(to), epsilon)
    }

    fn with_target(target: hausdorff::Target, epsilon: f64) -> Within {
        assert!(
            epsilon > 0.0 && epsilon.is_finite(),
            "epsilon must be positive and finite"
        );
        Within {
            target,
            tol: hausdorff::Tolerance::new(epsilon, epsilon * 1e-6),
        }
    }

    /// The epsilon the questions are asked at.
    #[must_use]
    pub fn epsilon(&self) -> f64 {
        self.tol.eps()
    }

    /// Whether every point of every triangle of `triangles` is proved within epsilon of
    /// the surface (exact; `false` also when undecided).
    #[must_use]
    pub fn holds(&self, triangles: &[[DVec3; 3]]) -> bool {
        // An empty surface covers nothing.
        triangles.is_empty()
            || (!self.target.is_empty()
                && hausdorff::all_within(triangles, &self.target, &self.tol))
    }

    /// The largest side of the bounding box of any of the surface's triangles (0 when
    /// there is none).
    #[must_use]
    pub fn largest_extent(&self) -> f64 {
        self.target.largest_extent()
    }

    /// A shortcut that may only refuse: whether some point of `points` is estimated (in
    /// f64) farther than epsilon from the surface. Not a proof either way.
    #[must_use]
    pub fn some_point_beyond(&self, points: &[DVec3]) -> bool {
        self.target.some_point_beyond(points, self.tol.eps())
    }

    /// The surface's triangles (each distinct one once) whose bounding boxes overlap one of
    /// `regions`.
    #[must_use]
    pub fn triangles_overlapping(&self, regions: &[bvh::Aabb]) -> Vec<[DVec3; 3]> {
        let mut ids = Vec::new();
        for region in regions {
            self.target.for_each_overlapping(region, |t| ids.push(t));
        }
        ids.sort_unstable();
        ids.dedup();
        ids.into_iter().map(|t| self.target.triangle(t)).collect()
    }
}

/// Certifies `approx` against `orig`: two-sided Hausdorff distance at most `epsilon`,
/// self-intersections of `approx`, topology of both (see [`Options`]).
///
/// ```
/// use envelope_mesh::generate::torus;
/// use envelope_verify::{certify, Options, Verdict};
/// let t = torus(2.0, 0.5, 24, 12);
/// let c = certify(&t, &t, &Options::new(1e-3));
/// assert_eq!(c.verdict, Verdict::Holds);
/// assert_eq!(c.topology.unwrap().approx.genus, Some(1));
/// assert!(c.violations().is_empty() && c.approx_to_orig.upper <= 1e-3);
/// ```
///
/// # Panics
/// When `epsilon` is not positive and finite.
#[must_use]
pub fn certify(orig: &TriangleSoup, approx: &TriangleSoup, options: &Options) -> Certificate {
    let eps = options.epsilon;
    assert!(
        eps > 0.0 && eps.is_finite(),
        "epsilon must be positive and finite"
    );
    let (of, af) = (raw_faces(orig), raw_faces(approx));
    let tol = hausdorff::Tolerance::new(eps, options.resolution.max(0.0));
    // The BVH of `approx`'s target is also the candidate source of the self-intersection test.
    let (to_orig, to_approx) = rayon::join(
        || hausdorff::Target::new(&orig.positions, &of),
        || {
            (options.orig_to_approx || options.self_intersections)
                .then(|| hausdorff::Target::new(&approx.positions, &af))
        },
    );
    let (
        ((approx_to_orig, approx_faces), (orig_to_approx, orig_faces)),
        (self_intersections, topology),
    ) = rayon::join(
        || {
            let forward =
                || hausdorff::one_sided(&approx.positions, &af, &to_orig, &tol, options.map);
            match to_approx.as_ref().filter(|_| options.orig_to_approx) {
                Some(back) => rayon::join(forward, || {
                    hausdorff::one_sided(&orig.positions, &of, back, &tol, options.map)
                }),
                None => (forward(), (OneSided::unchecked(), None)),
            }
        },
        || {
            let si = to_approx
                .as_ref()
                .filter(|_| options.self_intersections)
                .map(|t| {
                    let built;
                    let tree = match t.bvh() {
                        Some(tree) => tree,
                        None => {
                            built = Bvh::from_triangles(&approx.positions, &af);
                            &built
                        }
                    };
                    // A dense stack: pairs tested one at a time up to the budget, stopping
                    // at the first that intersects.
                    let budget = bvh::pair_budget(af.len());
                    if tree.self_pair_count_up_to(budget) >= budget {
                        let pair = bounded_first_pair(tree, &approx.positions, &af, budget);
                        let pairs: Vec<(FaceId, FaceId)> =
                            pair.iter().map(|&(a, b)| (FaceId(a), FaceId(b))).collect();
                        return (pairs, false, pair.is_none());
                    }
                    let pairs = if options.first_intersection_only {
                        first_pair(tree, &approx.positions, &af)
                            .into_iter()
                            .collect()
                    } else {
                        all_pairs(tree, &approx.positions, &af)
                    };
                    let pairs = pairs
                        .into_iter()
                        .map(|(a, b)| (FaceId(a), FaceId(b)))
                        .collect::<Vec<_>>();
                    (pairs, !options.first_intersection_only, false)
                });
            let topo = options.topology.then(|| TopologyCheck {
                orig: TopologySummary::of(orig),
                approx: TopologySummary::of(approx),
            });
            (si, topo)
        },
    );
    let (self_intersections, complete, mut undecided) = match self_intersections {
        Some((pairs, complete, undecided)) => (Some(pairs), complete, undecided),
        None => (None, !options.first_intersection_only, false),
    };
    let (self_intersections, kept_intersections) = match self_intersections {
        Some(pairs) if options.allow_input_intersections && !pairs.is_empty() => {
            let (kept, new) = split_kept_pairs(orig, approx, pairs);
            // Stopped at its first pair, which was kept: whether a new one follows is open.
            if new.is_empty() && !complete {
                undecided = true;
            }
            (Some(new), kept)
        }
        other => (other, Vec::new()),
    };
    let map = approx_faces.map(|faces| {
        let approx_faces = per_soup_face(approx, faces);
        ErrorMap {
            approx_vertices: vertex_values(approx, &approx_faces),
            approx_faces,
            orig_faces: orig_faces.map(|faces| per_soup_face(orig, faces)),
        }
    });
    let mut c = Certificate {
        verdict: Verdict::Holds,
        epsilon: eps,
        resolution: options.resolution,
        diagonal: orig.diagonal(),
        approx_to_orig,
        orig_to_approx,
        two_sided: options.orig_to_approx,
        self_intersections,
        self_intersections_complete: complete,
        self_intersections_undecided: undecided,
        kept_intersections,
        topology,
        map,
    };
    c.verdict = if !c.violations().is_empty() {
        Verdict::Violated
    } else if c.self_intersections_undecided {
        Verdict::Undecided
    } else if c.two_sided {
        c.approx_to_orig.verdict.max(c.orig_to_approx.verdict)
    } else {
        c.approx_to_orig.verdict
    };
    c
}

#[cfg(test)]
mod kept_intersection_tests {
    use super::*;

    /// Two crossing triangles and a third apart: kept as they are, the crossing is allowed
    /// only with `allow_input_intersections`; a moved copy of one of them is not.
    #[test]
    fn input_intersections_are_allowed_only_unchanged() {
        let orig = TriangleSoup::from_raw(
            &[
                [0., 0., 0.],
                [2., 0., 0.],
                [0., 2., 0.],
                [0.5, 0.5, -1.],
                [0.5, 0.5, 1.],
                [1.5, 1.5, 0.],
            ],
            &[[0, 1, 2], [3, 4, 5]],
        );
        let strict = certify(&orig, &orig, &Options::new(0.1));
        assert_eq!(strict.violations(), vec!["self_intersections"]);
        let allow = Options {
            allow_input_intersections: true,
            ..Options::new(0.1)
        };
        let c = certify(&orig, &orig, &allow);
        assert!(c.holds(), "{:?}", c.violations());
        assert_eq!(c.kept_intersections, vec![(FaceId(0), FaceId(1))]);
        // The same crossing, one face rotated in its corner order: still unchanged.
        let mut rotated = orig.clone();
        rotated.faces[1].rotate_left(1);
        assert!(certify(&orig, &rotated, &allow).holds());
        // One face moved a little: a new intersection, refused.
        let mut moved = orig.clone();
        moved.positions[4].z += 1e-3;
        let c = certify(&orig, &moved, &allow);
        assert_eq!(c.violations(), vec!["self_intersections"]);
        assert!(c.kept_intersections.is_empty());
        // Two faces sharing a vertex in `orig` meet nowhere else; with the vertex split in
        // two copies they touch there: unchanged faces, but not an intersection of `orig`.
        let fan = TriangleSoup::from_raw(
            &[
                [0., 0., 0.],
                [1., 0., 0.],
                [0., 1., 0.],
                [-1., 0., 0.],
                [0., -1., 0.],
            ],
            &[[0, 1, 2], [0, 3, 4]],
        );
        let mut split = fan.clone();
        split.positions.push(split.positions[0]);
        split.faces[1][0] = envelope_mesh::VertexId(5);
        let c = certify(&fan, &split, &allow);
        assert!(c.violations().contains(&"self_intersections"));
        assert!(c.kept_intersections.is_empty());
    }
}
