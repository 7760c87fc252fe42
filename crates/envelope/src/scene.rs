//! glTF scenes (`.gltf`, `.glb`, read and written by `envelope-gltf`): every triangle
//! primitive simplified and certified after its positions are rounded to f32.
//!
//! Epsilon per primitive ([`EpsilonScope::Primitive`], the default): a relative epsilon is
//! a part of the primitive's own bounding-box diagonal, an absolute one a length in the
//! primitive's own units. For the whole scene ([`EpsilonScope::Scene`]): a relative epsilon
//! is a part of the scene's world-space diagonal (every instance of every triangle primitive
//! through its node transforms), an absolute one a world length; it becomes each
//! primitive's local epsilon by dividing by the largest stretch of the node transforms that
//! show its mesh (an upper bound of their spectral norms), so a local deviation of at most
//! that length is at most the world epsilon in every instance.
//!
//! glTF stores positions as f32. The simplified positions are rounded to f32 and the
//! rounded mesh is certified against the input; if rounding breaks the certificate (or
//! leaves it undecided), the primitive is simplified again with [`Placement::Subset`], whose
//! vertices are input vertices and so exact in f32, and certified again. Points and lines
//! primitives are kept as they are; a primitive with morph targets, or whose mesh a skinned
//! node shows, is refused by name (its targets and weights would no longer fit).

use std::path::Path;

use envelope_gltf::{Geometry, Scene};
use envelope_mesh::TriangleSoup;
use envelope_verify::Certificate;

use crate::{EnvelopeMethod, Epsilon, Error, HoleFilling, Mesh, Method, Placement, Simplifier};
use crate::{defaults, oracle};

/// What an epsilon given for a scene is relative to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum EpsilonScope {
    /// Each primitive's own diagonal and units (the default).
    #[default]
    Primitive,
    /// The whole scene's world-space diagonal and units.
    Scene,
}

/// Reads a `.glb` or `.gltf` scene (see `envelope::advanced::gltf` for what is validated).
///
/// # Errors
/// [`Error::Gltf`], naming the file's element.
pub fn load_scene(path: impl AsRef<Path>) -> Result<Scene, Error> {
    let path = path.as_ref();
    Scene::read_path(path).map_err(|e| Error::Gltf {
        path: path.to_path_buf(),
        source: e,
    })
}

/// Writes a scene as `.glb` or `.gltf` (by the extension; the `.gltf` embeds its buffer),
/// through a temporary file renamed into place.
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("scene.glb");
/// std::fs::write(&path, envelope::advanced::gltf::sample::scene(1, 8, 4)).unwrap();
/// let scene = envelope::load_scene(&path)?;
/// envelope::save_scene(&scene, dir.path().join("copy.gltf"))?;
/// let copy = envelope::load_scene(dir.path().join("copy.gltf"))?;
/// assert_eq!(copy.primitives()[0].soup(), scene.primitives()[0].soup());
/// let err = envelope::load_scene(dir.path().join("missing.glb")).unwrap_err();
/// assert!(err.to_string().contains("missing.glb"));
/// # Ok::<(), envelope::Error>(())
/// ```
///
/// # Errors
/// [`Error::Gltf`].
pub fn save_scene(scene: &Scene, path: impl AsRef<Path>) -> Result<(), Error> {
    let path = path.as_ref();
    scene.write_path(path).map_err(|e| Error::Gltf {
        path: path.to_path_buf(),
        source: e,
    })
}

/// What happened to one primitive.
#[derive(Clone, Debug)]
pub struct PrimitiveReport {
    /// `meshes[mesh]`.
    pub mesh: usize,
    /// `meshes[mesh].primitives[primitive]`.
    pub primitive: usize,
    /// How messages name it.
    pub label: String,
    /// Triangles in.
    pub faces_in: usize,
    /// Triangles out (as in for a primitive kept as it is).
    pub faces_out: usize,
    /// The absolute epsilon, in the primitive's units (0 when kept).
    pub epsilon: f64,
    /// The certificate of the written (f32) triangles against the input (`None` when kept).
    pub certificate: Option<Certificate>,
    /// Whether rounding to f32 broke the first certificate and the subset run was used.
    pub subset_fallback: bool,
    /// Why it was kept as it is (points or lines), if it was.
    pub kept: Option<String>,
}

impl PrimitiveReport {
    /// Stable JSON keys.
    #[must_use]
    pub fn to_json(&self) -> serde_json::Value {
        let c = self.certificate.as_ref();
        serde_json::json!({
            "primitive": self.label,
            "faces_in": self.faces_in,
            "faces_out": self.faces_out,
            "epsilon": self.epsilon,
            "verdict": c.map(|c| c.verdict.as_str()),
            "approx_to_orig_upper": c.map(|c| c.approx_to_orig.upper),
            "orig_to_approx_upper": c.map(|c| c.orig_to_approx.upper),
            "subset_fallback": self.subset_fallback,
            "kept": self.kept,
        })
    }
}

/// A simplified scene and a report per primitive.
#[derive(Clone, Debug)]
pub struct SimplifiedScene {
    /// The scene with every triangle primitive replaced.
    pub scene: Scene,
    /// One per primitive, in [`Scene::primitives`] order.
    pub primitives: Vec<PrimitiveReport>,
}

impl SimplifiedScene {
    /// Whether every simplified primitive is certified.
    #[must_use]
    pub fn is_certified(&self) -> bool {
        self.primitives
            .iter()
            .all(|p| p.certificate.as_ref().is_none_or(Certificate::holds))
    }
}

/// The absolute epsilons of every primitive (in its own units; `None` for points and lines),
/// refusing what cannot be simplified.
pub(crate) fn local_epsilons(
    scene: &Scene,
    epsilon: Epsilon,
    scope: EpsilonScope,
) -> Result<Vec<Option<f64>>, Error> {
    let epsilon = epsilon.validate()?;
    let world = scene.world_diagonal();
    let mut out = Vec::new();
    for p in scene.primitives() {
        if !p.is_triangles() {
            out.push(None);
            continue;
        }
        let refuse = |reason: String| Error::Primitive {
            label: p.label(),
            source: Box::new(Error::InvalidArgument(reason)),
        };
        if p.morph_targets() > 0 {
            return Err(refuse(format!(
                "{} morph targets would no longer fit the simplified triangles",
                p.morph_targets()
            )));
        }
        if p.skinned() {
            return Err(refuse(
                "a skinned node shows this mesh; joints and weights would no longer fit".into(),
            ));
        }
        let e = match scope {
            EpsilonScope::Primitive => epsilon.resolve_for_diagonal(p.soup().diagonal()),
            EpsilonScope::Scene => epsilon.resolve_for_diagonal(world) / scene.mesh_scale(p.mesh()),
        };
        if !(e.is_finite() && e > 0.0) {
            return Err(refuse(format!(
                "epsilon {epsilon} is {e} here (diagonal {})",
                p.soup().diagonal()
            )));
        }
        out.push(Some(e));
    }
    Ok(out)
}

/// `soup` with every coordinate rounded to the nearest f32, and whether any changed.
pub(crate) fn round_to_f32(soup: &TriangleSoup) -> (TriangleSoup, bool) {
    let mut out = soup.clone();
    let mut changed = false;
    for p in &mut out.positions {
        let r = p.as_vec3().as_dvec3();
        changed |= r != *p;
        *p = r;
    }
    (out, changed)
}

/// Simplifies every triangle primitive of a scene.
///
/// ```
/// use envelope::{Epsilon, SceneSimplifier};
/// let glb = envelope::advanced::gltf::sample::scene(2, 16, 8);
/// let scene = envelope::advanced::gltf::Scene::from_slice(&glb, None)?;
/// let done = SceneSimplifier::new(Epsilon::percent(2.0)).threads(1).run(&scene)?;
/// assert!(done.is_certified());
/// assert!(done.primitives[0].faces_out < done.primitives[0].faces_in);
/// assert!(done.primitives[2].kept.is_some()); // the lines
/// # Ok::<(), envelope::Error>(())
/// ```
pub struct SceneSimplifier {
    epsilon: Epsilon,
    scope: EpsilonScope,
    method: Method,
    envelope_method: EnvelopeMethod,
    placement: Placement,
    hole_filling: HoleFilling,
    threads: Option<usize>,
}

impl SceneSimplifier {
    /// Every primitive within `epsilon` (relative to each primitive's diagonal by default).
    #[must_use]
    pub fn new(epsilon: Epsilon) -> Self {
        SceneSimplifier {
            epsilon,
            scope: defaults::EPSILON_SCOPE,
            method: defaults::METHOD,
            envelope_method: defaults::ENVELOPE_METHOD,
            placement: defaults::PLACEMENT,
            hole_filling: defaults::hole_filling(),
            threads: None,
        }
    }

    /// What epsilon is relative to.
    #[must_use]
    pub fn scope(mut self, scope: EpsilonScope) -> Self {
        self.scope = scope;
        self
    }

    /// The simplification algorithm.
    #[must_use]
    pub fn method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// How the envelopes find their offsets.
    #[must_use]
    pub fn envelope_method(mut self, method: EnvelopeMethod) -> Self {
        self.envelope_method = method;
        self
    }

    /// Where output vertices may lie (the f32 fallback always uses the subset).
    #[must_use]
    pub fn placement(mut self, placement: Placement) -> Self {
        self.placement = placement;
        self
    }

    /// How holes are filled.
    #[must_use]
    pub fn hole_filling(mut self, hole_filling: HoleFilling) -> Self {
        self.hole_filling = hole_filling;
        self
    }

    /// Worker threads (default: one per core).
    #[must_use]
    pub fn threads(mut self, threads: usize) -> Self {
        self.threads = Some(threads);
        self
    }

    fn simplifier(&self, eps: f64, placement: Placement) -> Simplifier<'static> {
        let s = Simplifier::new(Epsilon::absolute(eps))
            .method(self.method)
            .envelope_method(self.envelope_method)
            .placement(placement)
            .hole_filling(self.hole_filling)
            .certify(true);
        match self.threads {
            Some(n) => s.threads(n),
            None => s,
        }
    }

    /// Simplifies every triangle primitive (mesh by mesh, in order).
    ///
    /// # Errors
    /// [`Error::Primitive`] naming the primitive that could not be simplified (not
    /// acceptable input, envelopes not proved, morph targets, skins, or no certificate even
    /// for the subset run), or [`Error::InvalidEpsilon`].
    pub fn run(&self, scene: &Scene) -> Result<SimplifiedScene, Error> {
        let epsilons = local_epsilons(scene, self.epsilon, self.scope)?;
        let mut out = scene.clone();
        let mut reports = Vec::new();
        for (i, (p, eps)) in scene.primitives().iter().zip(epsilons).enumerate() {
            let mut report = PrimitiveReport {
                mesh: p.mesh(),
                primitive: p.index(),
                label: p.label(),
                faces_in: p.soup().num_faces(),
                faces_out: p.soup().num_faces(),
                epsilon: 0.0,
                certificate: None,
                subset_fallback: false,
                kept: None,
            };
            let Some(eps) = eps else {
                report.kept = Some(format!("a {:?} primitive", p.mode()));
                reports.push(report);
                continue;
            };
            let name = |e: Error| Error::Primitive {
                label: p.label(),
                source: Box::new(e),
            };
            let input = Mesh::from_soup(p.soup().clone())
                .with_attributes(p.attributes().clone())
                .map_err(|e| name(e.into()))?;
            let (mesh, certificate, fallback) = self.one(&input, eps).map_err(name)?;
            report.epsilon = eps;
            report.faces_out = mesh.num_faces();
            report.certificate = Some(certificate);
            report.subset_fallback = fallback;
            let (soup, attributes) = mesh.into_parts();
            out.replace(i, Geometry { soup, attributes }).map_err(|e| {
                name(Error::Gltf {
                    path: Default::default(),
                    source: e,
                })
            })?;
            reports.push(report);
        }
        Ok(SimplifiedScene {
            scene: out,
            primitives: reports,
        })
    }

    /// One primitive: simplified, rounded to f32, certified; the subset run when rounding
    /// breaks the certificate.
    fn one(&self, input: &Mesh, eps: f64) -> Result<(Mesh, Certificate, bool), Error> {
        let done = self.simplifier(eps, self.placement).run(input)?;
        if let Some(c) = rounded_certified(input, done.mesh(), done.certificate(), eps)? {
            return Ok(c.with(false));
        }
        let subset = self.simplifier(eps, Placement::Subset).run(input)?;
        match rounded_certified(input, subset.mesh(), subset.certificate(), eps)? {
            Some(c) => Ok(c.with(true)),
            None => Err(Error::CertificateViolated(Box::new(subset))),
        }
    }
}

/// A mesh rounded to f32 and its certificate.
pub(crate) struct Rounded(Mesh, Certificate);

impl Rounded {
    pub(crate) fn into_parts(self) -> (Mesh, Certificate) {
        (self.0, self.1)
    }

    fn with(self, fallback: bool) -> (Mesh, Certificate, bool) {
        (self.0, self.1, fallback)
    }
}

/// `approx` rounded to f32 with its certificate against `input` at `eps`, when that holds
/// (the engine's certificate is reused when rounding changed nothing).
pub(crate) fn rounded_certified(
    input: &Mesh,
    approx: &Mesh,
    certificate: Option<&Certificate>,
    eps: f64,
) -> Result<Option<Rounded>, Error> {
    let (soup, changed) = round_to_f32(approx.soup());
    let certificate = match certificate {
        Some(c) if !changed => c.clone(),
        _ => {
            let rounded = Mesh::from_soup(soup.clone());
            oracle::verify(input, &rounded, Epsilon::absolute(eps))?
        }
    };
    if !certificate.holds() {
        return Ok(None);
    }
    let mesh = Mesh::from_soup(soup)
        .with_attributes(approx.attributes().clone())
        .map_err(Error::from)?;
    Ok(Some(Rounded(mesh, certificate)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3x3 grid in z = 0 (f32-exact), its centre raised to `z`.
    fn grid(z: f64) -> Mesh {
        let mut positions = Vec::new();
        for j in 0..3 {
            for i in 0..3 {
                positions.push([f64::from(i), f64::from(j), 0.0]);
            }
        }
        positions[4][2] = z;
        let mut triangles = Vec::new();
        for j in 0..2 {
            for i in 0..2 {
                let v = j * 3 + i;
                triangles.push([v, v + 1, v + 4]);
                triangles.push([v, v + 4, v + 3]);
            }
        }
        Mesh::new(positions, triangles).unwrap()
    }

    #[test]
    fn rounding_that_breaks_the_certificate_is_caught() {
        let eps = 0.1;
        let input = grid(0.0);
        // Within 0.1 in f64; its f32 rounding (0.100000001...) is not.
        let z = 0.1 - 1e-12;
        assert!(f64::from(z as f32) > eps);
        let approx = grid(z);
        let c = oracle::verify(&input, &approx, Epsilon::absolute(eps)).unwrap();
        assert!(c.holds());
        assert!(
            rounded_certified(&input, &approx, Some(&c), eps)
                .unwrap()
                .is_none()
        );
        // A position that is already f32 keeps the engine's certificate.
        let exact = grid(0.0625);
        let c = oracle::verify(&input, &exact, Epsilon::absolute(eps)).unwrap();
        let r = rounded_certified(&input, &exact, Some(&c), eps)
            .unwrap()
            .unwrap();
        assert_eq!(r.into_parts().0, exact);
        assert!(round_to_f32(approx.soup()).1);
    }
}
