//! glTF 2.0 scenes (`.gltf`, `.glb`) for the envelope engine: a validating reader that gives
//! every triangle primitive as a [`TriangleSoup`] with its [`Attributes`], and a writer that
//! keeps the whole document and replaces only the primitives it was given.
//!
//! Reading ([`Scene::read_path`], [`Scene::from_slice`]) validates at the boundary; every
//! refusal is a [`GltfError`] naming the byte offset, JSON path, buffer, bufferView or
//! accessor and the mesh and primitive using it:
//! * the GLB container (magic, version, lengths, chunk order and alignment), the JSON, and
//!   every reference in the document and the rules the `gltf` crate's validator checks
//!   (among them: POSITION accessors carry `min` and `max`, as the specification requires);
//!   node transforms finite in f32 with non-zero quaternions, and nodes forming trees;
//! * `extensionsRequired`: only extensions that cannot change the geometry are accepted
//!   ([`KNOWN_EXTENSIONS`]); Draco, meshopt and quantization are refused, named;
//! * buffers: the GLB BIN chunk, base64 `data:` URIs, or files relative to the `.gltf`
//!   (no other scheme, no absolute path); each at least its `byteLength`; every bufferView
//!   inside its buffer and every accessor inside its view *before* anything is allocated, so
//!   memory stays within the input's size;
//! * triangle primitives (`TRIANGLES`, and `TRIANGLE_STRIP` and `TRIANGLE_FAN`, converted to
//!   triangles with the strip's alternate winding, dropping the strip's and fan's triangles
//!   with a repeated corner): POSITION must be `FLOAT` VEC3, not normalized (quantized
//!   positions are refused, naming the accessor, rather than converted); every coordinate
//!   passes [`envelope_mesh::check_coordinate`]; indices are unsigned scalars below the
//!   vertex count; no accessor read is sparse or without a bufferView; NORMAL (`FLOAT` VEC3),
//!   TEXCOORD_0 and COLOR_0 (`FLOAT` or normalized `UNSIGNED_BYTE`/`UNSIGNED_SHORT`) are read
//!   exactly into per-corner [`Wedges`](envelope_mesh::Wedges) (the corners are the primitive's indices, the values
//!   its vertex table);
//! * the soup of a primitive welds vertices at bitwise-equal positions (glTF splits vertices
//!   along texture and normal seams; the simplifier needs the surface connected); the seams
//!   stay in the attributes' corners;
//! * points and lines primitives are kept as they are and written back untouched.
//!
//! Writing ([`Scene::to_glb`], [`Scene::to_gltf`], [`Scene::write_path`]) starts from the
//! JSON as read, so scenes, nodes and their transforms, materials, textures, samplers,
//! images, cameras, animations, extras and extensions are kept. A replaced primitive
//! ([`Scene::replace`]) gets new accessors: POSITION (`FLOAT`, with the `min` and `max` the
//! specification requires), NORMAL/TEXCOORD_0/COLOR_0 from its attributes (a glTF vertex per
//! distinct combination of position and attribute values), or NORMAL recomputed per vertex
//! (area-weighted) when it has none but the input primitive had normals; `indices` (unsigned
//! short or int) and mode `TRIANGLES`; its other attributes, morph targets and extensions
//! (a Draco fallback would shadow the new geometry) are dropped. Then one binary buffer is
//! rebuilt from every bufferView still referenced (geometry, embedded images, animation
//! data), each at a 4-byte-aligned offset, and accessors and bufferViews no longer
//! referenced are dropped and the rest renumbered. When `extensionsUsed` names an extension
//! this crate does not know (which might refer to accessors or bufferViews), nothing is
//! dropped or renumbered. Output is a `.glb` (one BIN chunk) or a `.gltf` with the buffer
//! embedded as a base64 data URI (one file, so the write stays atomic); external image URIs
//! are written as they were (relative to the output's folder).
//!
//! Levels of detail ([`Scene::add_lod`]) are written with `MSFT_lod`: the node showing the
//! mesh gets `extensions.MSFT_lod.ids` (one new node per level, with a new mesh holding the
//! level's primitives) and `extras.MSFT_screencoverage` (one value per level, base first:
//! the smallest screen coverage at which that level is shown). A level node copies the base
//! node's transform; when the base node has children, the mesh moves to a new child node
//! (identity transform) which carries the extension, so the children are never switched
//! off.
//!
//! ```
//! use envelope_gltf::Scene;
//! use envelope_mesh::{Attributes, TriangleSoup};
//! let tri = TriangleSoup::from_raw(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
//! let scene = Scene::from_meshes(&[(tri.clone(), Attributes::default())])?;
//! let back = Scene::from_slice(&scene.to_glb()?, None)?;
//! assert_eq!(back.primitives()[0].soup(), &tri);
//! # Ok::<(), envelope_gltf::GltfError>(())
//! ```
#![forbid(unsafe_code)]

mod container;
mod error;
mod read;
pub mod sample;
mod transform;
mod write;

use std::path::Path;

use envelope_mesh::{Attributes, TriangleSoup};
use serde_json::Value;

pub use error::{GltfError, Use};
pub use gltf::mesh::Mode;
pub use read::KNOWN_EXTENSIONS;

/// One primitive of one mesh of the document, read.
#[derive(Clone, Debug)]
pub struct Primitive {
    mesh: usize,
    primitive: usize,
    name: Option<String>,
    material: Option<usize>,
    mode: Mode,
    soup: TriangleSoup,
    attributes: Attributes,
    morph_targets: usize,
    skinned: bool,
    /// The file gave NORMAL: a replacement without normals gets them recomputed.
    had_normals: bool,
}

impl Primitive {
    /// The mesh (`meshes[mesh]`).
    #[must_use]
    pub fn mesh(&self) -> usize {
        self.mesh
    }

    /// Its place in the mesh (`meshes[mesh].primitives[index]`).
    #[must_use]
    pub fn index(&self) -> usize {
        self.primitive
    }

    /// The mesh's name, if it has one.
    #[must_use]
    pub fn name(&self) -> Option<&str> {
        self.name.as_deref()
    }

    /// The material (`materials[i]`), if any.
    #[must_use]
    pub fn material(&self) -> Option<usize> {
        self.material
    }

    /// The primitive's mode as written.
    #[must_use]
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// Whether it is made of triangles (triangles, strip or fan): only those have a soup.
    #[must_use]
    pub fn is_triangles(&self) -> bool {
        matches!(
            self.mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        )
    }

    /// Its triangles (vertices welded by position; empty for points and lines).
    #[must_use]
    pub fn soup(&self) -> &TriangleSoup {
        &self.soup
    }

    /// Its NORMAL, TEXCOORD_0 and COLOR_0, per corner of the soup's faces.
    #[must_use]
    pub fn attributes(&self) -> &Attributes {
        &self.attributes
    }

    /// Its morph targets (`targets`).
    #[must_use]
    pub fn morph_targets(&self) -> usize {
        self.morph_targets
    }

    /// Whether a node with a skin shows its mesh.
    #[must_use]
    pub fn skinned(&self) -> bool {
        self.skinned
    }

    /// `meshes[m].primitives[p]`, as messages name it.
    #[must_use]
    pub fn label(&self) -> String {
        match &self.name {
            Some(n) => format!("meshes[{}].primitives[{}] ({n})", self.mesh, self.primitive),
            None => format!("meshes[{}].primitives[{}]", self.mesh, self.primitive),
        }
    }
}

/// A node of a scene that shows a mesh, with its world transform.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// `nodes[node]`.
    pub node: usize,
    /// `meshes[mesh]`.
    pub mesh: usize,
    /// `scenes[scene]` it was reached from.
    pub scene: usize,
    /// Column-major world matrix (the product of the transforms from the scene's root).
    pub world: [[f64; 4]; 4],
    /// Whether the node has a skin.
    pub skinned: bool,
}

/// New triangles for a primitive: a soup and its per-corner attributes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Geometry {
    /// The triangles.
    pub soup: TriangleSoup,
    /// Their attributes (empty: POSITION only, plus recomputed NORMAL if the input had it).
    pub attributes: Attributes,
}

/// Levels of detail of one mesh (see [`Scene::add_lod`]).
#[derive(Clone, Debug)]
pub(crate) struct LodGroup {
    pub(crate) mesh: usize,
    /// Per level, per primitive of the mesh: the new geometry (`None`: kept as it is).
    pub(crate) levels: Vec<Vec<Option<Geometry>>>,
    pub(crate) coverage: Vec<f64>,
}

/// A glTF document with its buffers and its primitives read.
#[derive(Clone, Debug)]
pub struct Scene {
    json: Value,
    buffers: Vec<Vec<u8>>,
    primitives: Vec<Primitive>,
    instances: Vec<Instance>,
    replaced: Vec<Option<Geometry>>,
    lods: Vec<LodGroup>,
}

impl Scene {
    pub(crate) fn from_parts(
        json: Value,
        buffers: Vec<Vec<u8>>,
        primitives: Vec<Primitive>,
        instances: Vec<Instance>,
    ) -> Scene {
        let replaced = vec![None; primitives.len()];
        Scene {
            json,
            buffers,
            primitives,
            instances,
            replaced,
            lods: Vec::new(),
        }
    }

    /// Reads a `.glb` or `.gltf` file (the content decides; external buffers are relative to
    /// the file's folder).
    ///
    /// # Errors
    /// A [`GltfError`] naming the element (see the module docs).
    pub fn read_path(path: impl AsRef<Path>) -> Result<Scene, GltfError> {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|e| GltfError::io(path, e))?;
        let base = path.parent().unwrap_or(Path::new("."));
        read::read(&bytes, Some(base))
    }

    /// Reads a `.glb` or `.gltf` from memory; `base` is the folder external buffers are
    /// relative to (`None`: only the GLB chunk and data URIs).
    ///
    /// # Errors
    /// As [`Scene::read_path`].
    pub fn from_slice(bytes: &[u8], base: Option<&Path>) -> Result<Scene, GltfError> {
        read::read(bytes, base)
    }

    /// A scene of one node per soup (identity transforms), each a mesh of one primitive.
    ///
    /// # Errors
    /// [`GltfError::WriteCoordinate`] or [`GltfError::BadReplacement`] for a soup that
    /// cannot be written.
    pub fn from_meshes(meshes: &[(TriangleSoup, Attributes)]) -> Result<Scene, GltfError> {
        write::from_meshes(meshes)
    }

    /// The primitives of every mesh, mesh by mesh, in order.
    #[must_use]
    pub fn primitives(&self) -> &[Primitive] {
        &self.primitives
    }

    /// Every node (of every scene) that shows a mesh.
    #[must_use]
    pub fn instances(&self) -> &[Instance] {
        &self.instances
    }

    /// The document's JSON as read.
    #[must_use]
    pub fn json(&self) -> &Value {
        &self.json
    }

    /// The bytes of `bufferViews[view]`, `None` when it does not exist.
    #[must_use]
    pub fn view_bytes(&self, view: usize) -> Option<&[u8]> {
        let v = self.json.get("bufferViews")?.get(view)?;
        let buffer = self.buffers.get(v.get("buffer")?.as_u64()? as usize)?;
        let start = v.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize;
        let len = v.get("byteLength")?.as_u64()? as usize;
        buffer.get(start..start.checked_add(len)?)
    }

    /// The largest factor by which a node showing `mesh` stretches a length (the spectral
    /// norm of its world matrix's linear part, rounded up); 1 when no node shows it.
    #[must_use]
    pub fn mesh_scale(&self, mesh: usize) -> f64 {
        self.instances
            .iter()
            .filter(|i| i.mesh == mesh)
            .map(|i| transform::max_stretch(&i.world))
            .fold(None, |a: Option<f64>, s| Some(a.map_or(s, |a| a.max(s))))
            .unwrap_or(1.0)
    }

    /// The bounding-box diagonal of every triangle primitive as the scenes show it (world
    /// space, every instance; a mesh no node shows counts in its own units).
    #[must_use]
    pub fn world_diagonal(&self) -> f64 {
        transform::world_diagonal(self)
    }

    /// Replaces the triangles of `primitives()[index]` (a triangle primitive): from now on
    /// it shows them, and they are written in place of the file's.
    ///
    /// # Errors
    /// [`GltfError::BadReplacement`] when `index` is not a triangle primitive, an index is
    /// out of range or the attributes do not fit; [`GltfError::WriteCoordinate`] for a
    /// coordinate the reader would refuse.
    pub fn replace(&mut self, index: usize, geometry: Geometry) -> Result<(), GltfError> {
        let p = self
            .primitives
            .get(index)
            .ok_or(GltfError::BadReplacement {
                mesh: 0,
                primitive: index,
                reason: format!("there are only {} primitives", self.primitives.len()),
            })?;
        write::check_geometry(p, &geometry)?;
        let p = &mut self.primitives[index];
        p.soup = geometry.soup.clone();
        p.attributes = geometry.attributes.clone();
        self.replaced[index] = Some(geometry);
        Ok(())
    }

    /// Adds levels of detail to `mesh`: `levels[k][i]` is the geometry of the mesh's
    /// primitive `i` at level `k + 1` (`None`: the primitive as it is, e.g. lines), and
    /// `coverage` the `MSFT_screencoverage` hints, one per level with the base first
    /// (`levels.len() + 1` values, decreasing).
    ///
    /// # Errors
    /// [`GltfError::BadReplacement`] for a geometry that does not fit, a mesh that does not
    /// exist, or counts that do not match.
    pub fn add_lod(
        &mut self,
        mesh: usize,
        levels: Vec<Vec<Option<Geometry>>>,
        coverage: Vec<f64>,
    ) -> Result<(), GltfError> {
        let prims: Vec<&Primitive> = self.primitives.iter().filter(|p| p.mesh == mesh).collect();
        let fail = |reason: String| GltfError::BadReplacement {
            mesh,
            primitive: 0,
            reason,
        };
        if prims.is_empty() {
            return Err(fail("no such mesh".into()));
        }
        if coverage.len() != levels.len() + 1 {
            return Err(fail(format!(
                "{} coverage hints for {} levels and the base",
                coverage.len(),
                levels.len()
            )));
        }
        for level in &levels {
            if level.len() != prims.len() {
                return Err(fail(format!(
                    "a level has {} primitives, the mesh {}",
                    level.len(),
                    prims.len()
                )));
            }
            for (p, g) in prims.iter().zip(level) {
                if let Some(g) = g {
                    write::check_geometry(p, g)?;
                }
            }
        }
        self.lods.push(LodGroup {
            mesh,
            levels,
            coverage,
        });
        Ok(())
    }

    /// The document as a `.glb`.
    ///
    /// # Errors
    /// [`GltfError::TooLarge`] past 4 GiB.
    pub fn to_glb(&self) -> Result<Vec<u8>, GltfError> {
        let (json, bin) = write::document(self, false)?;
        container::join_glb(&json, &bin)
    }

    /// The document as a `.gltf` with its buffer embedded as a base64 data URI.
    ///
    /// # Errors
    /// As [`Scene::to_glb`].
    pub fn to_gltf(&self) -> Result<Vec<u8>, GltfError> {
        Ok(write::document(self, true)?.0)
    }

    /// Writes a `.glb` or `.gltf` (by the extension, case-insensitive) atomically: to a
    /// temporary file in the same folder, synced, renamed over `path`.
    ///
    /// # Errors
    /// [`GltfError::UnknownExtension`], [`GltfError::Io`] naming `path`, or as
    /// [`Scene::to_glb`].
    pub fn write_path(&self, path: impl AsRef<Path>) -> Result<(), GltfError> {
        let path = path.as_ref();
        let bytes = match extension(path).as_deref() {
            Some("glb") => self.to_glb()?,
            Some("gltf") => self.to_gltf()?,
            _ => return Err(GltfError::UnknownExtension(path.to_path_buf())),
        };
        write::atomic(path, &bytes)
    }
}

fn extension(path: &Path) -> Option<String> {
    Some(path.extension()?.to_str()?.to_ascii_lowercase())
}

/// Whether `path` names a glTF file by its extension (`.glb`, `.gltf`, any case).
///
/// ```
/// assert!(envelope_gltf::is_gltf_path("a/b.GLB".as_ref()));
/// assert!(!envelope_gltf::is_gltf_path("a/b.obj".as_ref()));
/// ```
#[must_use]
pub fn is_gltf_path(path: &Path) -> bool {
    matches!(extension(path).as_deref(), Some("glb" | "gltf"))
}
