//! Levels of detail of a glTF scene: each triangle primitive's chain (Cohen et al. 7.2),
//! every level rounded to f32 and certified against the input at its bound, written as one
//! file with `MSFT_lod` or as one file per level.
//!
//! Screen-coverage hints (`extras.MSFT_screencoverage` on the node carrying `MSFT_lod`): a
//! level `k` may be shown from the switching distance `d_k` the chain reports (for a mesh of
//! several primitives, the largest over them), where the mesh's bounding-box diagonal `D`
//! covers `D / (2 d_k tan(fov / 2))` of the screen's width; so the base is shown above the
//! coverage of `d_1`, level `k` above that of `d_{k+1}`, and the last level down to 0. Both
//! lengths are in the mesh's units, so the ratio holds under any node transform of uniform
//! scale.

use envelope_gltf::{Geometry, Scene};
use envelope_verify::Certificate;

use crate::scene::{EpsilonScope, local_epsilons, rounded_certified};
use crate::{EnvelopeMethod, Epsilon, Error, HoleFilling, Lod, LodRule, Mesh, Screen, defaults};

/// One level of one primitive.
#[derive(Clone, Debug)]
pub struct LevelReport {
    /// 1, 2, ...
    pub index: usize,
    /// Triangles.
    pub faces: usize,
    /// The bound to the input, both ways (absolute, the primitive's units).
    pub bound: f64,
    /// Viewing distance from which the level may be shown (the primitive's units).
    pub switching_distance: f64,
    /// The certificate of the written (f32) level against the input at `bound`.
    pub certificate: Certificate,
}

/// The chain of one primitive.
#[derive(Clone, Debug)]
pub struct PrimitiveLevels {
    /// `meshes[mesh]`.
    pub mesh: usize,
    /// `meshes[mesh].primitives[primitive]`.
    pub primitive: usize,
    /// How messages name it.
    pub label: String,
    /// Triangles of the input.
    pub faces_in: usize,
    /// Its levels (empty when kept as it is).
    pub levels: Vec<LevelReport>,
    /// Why it was kept as it is (points or lines), if it was.
    pub kept: Option<String>,
    geometries: Vec<Geometry>,
}

/// Level-of-detail chains of every triangle primitive of a scene.
///
/// ```
/// use envelope::{Epsilon, SceneLod};
/// let glb = envelope::advanced::gltf::sample::scene(2, 16, 8);
/// let scene = envelope::advanced::gltf::Scene::from_slice(&glb, None)?;
/// let chains = SceneLod::new(vec![Epsilon::percent(1.0), Epsilon::percent(3.0)])
///     .threads(1)
///     .run(&scene)?;
/// let written = chains.lod_scene()?.to_glb()?; // levels are added when written
/// let lod = envelope::advanced::gltf::Scene::from_slice(&written, None)?;
/// assert!(lod.json()["extensionsUsed"].to_string().contains("MSFT_lod"));
/// assert_eq!(chains.level_scene(2)?.primitives()[0].soup().num_faces(),
///            chains.primitives()[0].levels[1].faces);
/// # Ok::<(), envelope::Error>(())
/// ```
pub struct SceneLod {
    epsilons: Vec<Epsilon>,
    scope: EpsilonScope,
    rule: LodRule,
    envelope_method: EnvelopeMethod,
    hole_filling: HoleFilling,
    screen: Screen,
    threads: Option<usize>,
}

impl SceneLod {
    /// Chains at these epsilons (each relative to each primitive's diagonal by default).
    #[must_use]
    pub fn new(epsilons: Vec<Epsilon>) -> Self {
        SceneLod {
            epsilons,
            scope: defaults::EPSILON_SCOPE,
            rule: LodRule::default(),
            envelope_method: defaults::ENVELOPE_METHOD,
            hole_filling: defaults::hole_filling(),
            screen: Screen::default(),
            threads: None,
        }
    }

    /// What the epsilons are relative to.
    #[must_use]
    pub fn scope(mut self, scope: EpsilonScope) -> Self {
        self.scope = scope;
        self
    }

    /// Whether the epsilons are bounds or steps.
    #[must_use]
    pub fn rule(mut self, rule: LodRule) -> Self {
        self.rule = rule;
        self
    }

    /// How the envelopes find their offsets.
    #[must_use]
    pub fn envelope_method(mut self, method: EnvelopeMethod) -> Self {
        self.envelope_method = method;
        self
    }

    /// How holes are filled.
    #[must_use]
    pub fn hole_filling(mut self, hole_filling: HoleFilling) -> Self {
        self.hole_filling = hole_filling;
        self
    }

    /// The display the switching distances (and coverage hints) are computed for.
    #[must_use]
    pub fn screen(mut self, screen: Screen) -> Self {
        self.screen = screen;
        self
    }

    /// Worker threads (default: one per core).
    #[must_use]
    pub fn threads(mut self, threads: usize) -> Self {
        self.threads = Some(threads);
        self
    }

    /// Builds every chain.
    ///
    /// # Errors
    /// As [`SceneSimplifier::run`](crate::SceneSimplifier::run); a level whose f32 positions
    /// are not certified is an [`Error::Primitive`] naming it.
    pub fn run(&self, scene: &Scene) -> Result<SceneLevels, Error> {
        let per_epsilon = self
            .epsilons
            .iter()
            .map(|&e| local_epsilons(scene, e, self.scope))
            .collect::<Result<Vec<_>, Error>>()?;
        let mut out = Vec::new();
        for (i, p) in scene.primitives().iter().enumerate() {
            let mut chain = PrimitiveLevels {
                mesh: p.mesh(),
                primitive: p.index(),
                label: p.label(),
                faces_in: p.soup().num_faces(),
                levels: Vec::new(),
                kept: None,
                geometries: Vec::new(),
            };
            let eps: Option<Vec<f64>> = per_epsilon.iter().map(|e| e[i]).collect();
            let Some(eps) = eps.filter(|e| !e.is_empty()) else {
                chain.kept = Some(format!("a {:?} primitive", p.mode()));
                out.push(chain);
                continue;
            };
            let name = |e: Error| Error::Primitive {
                label: p.label(),
                source: Box::new(e),
            };
            let input = Mesh::from_soup(p.soup().clone())
                .with_attributes(p.attributes().clone())
                .map_err(|e| name(e.into()))?;
            let mut lod = Lod::new(eps.into_iter().map(Epsilon::absolute).collect())
                .rule(self.rule)
                .envelope_method(self.envelope_method)
                .hole_filling(self.hole_filling)
                .screen(self.screen)
                .certify(true);
            if let Some(n) = self.threads {
                lod = lod.threads(n);
            }
            for level in lod.run(&input).map_err(name)? {
                // The level with the attributes carried from the input (`Lod::level_mesh`).
                let approx = Lod::level_mesh(&input, &level);
                let certified = level.certified.map(|v| v.certificate);
                let rounded =
                    rounded_certified(&input, &approx, certified.as_ref(), level.cumulative)
                        .map_err(name)?
                        .ok_or_else(|| {
                            name(Error::InvalidArgument(format!(
                                "level {}: not certified within {} after rounding to f32",
                                level.index, level.cumulative
                            )))
                        })?;
                let (mesh, certificate) = rounded.into_parts();
                chain.levels.push(LevelReport {
                    index: level.index,
                    faces: mesh.num_faces(),
                    bound: level.cumulative,
                    switching_distance: level.switching_distance,
                    certificate,
                });
                let (soup, attributes) = mesh.into_parts();
                chain.geometries.push(Geometry { soup, attributes });
            }
            out.push(chain);
        }
        Ok(SceneLevels {
            base: scene.clone(),
            primitives: out,
            screen: self.screen,
            count: self.epsilons.len(),
        })
    }
}

/// Every primitive's chain, and the scene they came from.
#[derive(Clone, Debug)]
pub struct SceneLevels {
    base: Scene,
    primitives: Vec<PrimitiveLevels>,
    screen: Screen,
    count: usize,
}

impl SceneLevels {
    /// One chain per primitive, in [`Scene::primitives`] order.
    #[must_use]
    pub fn primitives(&self) -> &[PrimitiveLevels] {
        &self.primitives
    }

    /// Levels per chain (the input, level 0, not counted).
    #[must_use]
    pub fn count(&self) -> usize {
        self.count
    }

    /// Whether every level of every chain is certified.
    #[must_use]
    pub fn is_certified(&self) -> bool {
        self.primitives
            .iter()
            .flat_map(|p| &p.levels)
            .all(|l| l.certificate.holds())
    }

    /// The scene at level `k` (0: the input), every triangle primitive replaced.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] past the last level.
    pub fn level_scene(&self, k: usize) -> Result<Scene, Error> {
        if k > self.count {
            return Err(Error::InvalidArgument(format!(
                "level {k} of a chain of {}",
                self.count
            )));
        }
        let mut scene = self.base.clone();
        if k == 0 {
            return Ok(scene);
        }
        for (i, p) in self.primitives.iter().enumerate() {
            if let Some(g) = p.geometries.get(k - 1) {
                scene.replace(i, g.clone()).map_err(gltf_error)?;
            }
        }
        Ok(scene)
    }

    /// The input with every level added as `MSFT_lod` nodes (module docs for the hints).
    ///
    /// # Errors
    /// [`Error::Gltf`] when a level does not fit its primitive.
    pub fn lod_scene(&self) -> Result<Scene, Error> {
        let mut scene = self.base.clone();
        let mut meshes: Vec<usize> = self.primitives.iter().map(|p| p.mesh).collect();
        meshes.dedup();
        let tan = (self.screen.fov_degrees.to_radians() / 2.0).tan();
        for m in meshes {
            let chains: Vec<&PrimitiveLevels> =
                self.primitives.iter().filter(|p| p.mesh == m).collect();
            if chains.iter().all(|c| c.levels.is_empty()) {
                continue;
            }
            let levels = (0..self.count)
                .map(|k| {
                    chains
                        .iter()
                        .map(|c| c.geometries.get(k).cloned())
                        .collect()
                })
                .collect();
            let diagonal = self
                .base
                .primitives()
                .iter()
                .filter(|p| p.mesh() == m && p.is_triangles())
                .filter_map(|p| p.soup().bounding_box())
                .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
                .map_or(0.0, |(lo, hi)| (hi - lo).length());
            let mut coverage: Vec<f64> = (0..self.count)
                .map(|k| {
                    let d = chains
                        .iter()
                        .filter_map(|c| c.levels.get(k))
                        .map(|l| l.switching_distance)
                        .fold(0.0f64, f64::max);
                    if d > 0.0 {
                        diagonal / (2.0 * d * tan)
                    } else {
                        0.0
                    }
                })
                .collect();
            coverage.push(0.0);
            scene.add_lod(m, levels, coverage).map_err(gltf_error)?;
        }
        Ok(scene)
    }
}

fn gltf_error(e: envelope_gltf::GltfError) -> Error {
    Error::Gltf {
        path: Default::default(),
        source: e,
    }
}
