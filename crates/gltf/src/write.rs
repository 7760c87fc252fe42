//! Writing: replaced primitives' accessors emitted, level-of-detail nodes added, then one
//! binary buffer rebuilt from what is still referenced (module docs of the crate).

use std::fs;
use std::io::Write as _;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use envelope_mesh::{Attributes, TriangleSoup, check_coordinate};
use glam::DVec3;
use serde_json::{Map, Value, json};

use crate::container::base64_encode;
use crate::read::KNOWN_EXTENSIONS;
use crate::{Geometry, GltfError, Mode, Primitive, Scene};

const FLOAT: u32 = 5126;
const UNSIGNED_SHORT: u32 = 5123;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Refuses a geometry the reader would refuse back, for a primitive that has triangles.
pub(crate) fn check_geometry(p: &Primitive, g: &Geometry) -> Result<(), GltfError> {
    let fail = |reason: String| GltfError::BadReplacement {
        mesh: p.mesh,
        primitive: p.primitive,
        reason,
    };
    if !p.is_triangles() {
        return Err(fail(format!(
            "a {:?} primitive, not triangles: it is kept as it is",
            p.mode
        )));
    }
    if !g.soup.indices_in_range() {
        return Err(fail("a face names a vertex that does not exist".into()));
    }
    if !g.attributes.is_valid_for(g.soup.num_faces()) {
        return Err(fail(
            "the attributes need one corner triple per face, indices in range and finite values"
                .into(),
        ));
    }
    for (v, p3) in g.soup.positions.iter().enumerate() {
        for x in p3.to_array() {
            // Written as f32: the rounded value must pass too.
            check_coordinate(x)
                .and_then(|()| check_coordinate(f64::from(x as f32)))
                .map_err(|error| GltfError::WriteCoordinate {
                    mesh: p.mesh,
                    primitive: p.primitive,
                    vertex: v,
                    error,
                })?;
        }
    }
    Ok(())
}

pub(crate) fn from_meshes(meshes: &[(TriangleSoup, Attributes)]) -> Result<Scene, GltfError> {
    let n = meshes.len();
    let json = json!({
        "asset": {"version": "2.0", "generator": "envelope"},
        "scene": 0,
        "scenes": [{"nodes": (0..n).collect::<Vec<_>>()}],
        "nodes": (0..n).map(|i| json!({"mesh": i})).collect::<Vec<_>>(),
        "meshes": (0..n).map(|_| json!({"primitives": [{"attributes": {}}]})).collect::<Vec<_>>(),
    });
    let primitives = (0..n)
        .map(|i| Primitive {
            mesh: i,
            primitive: 0,
            name: None,
            material: None,
            mode: Mode::Triangles,
            soup: TriangleSoup::default(),
            attributes: Attributes::default(),
            morph_targets: 0,
            skinned: false,
            had_normals: false,
        })
        .collect();
    let instances = (0..n)
        .map(|i| crate::Instance {
            node: i,
            mesh: i,
            scene: 0,
            world: glam::DMat4::IDENTITY.to_cols_array_2d(),
            skinned: false,
        })
        .collect();
    let mut scene = Scene::from_parts(json, Vec::new(), primitives, instances);
    for (i, (soup, attributes)) in meshes.iter().enumerate() {
        let g = Geometry {
            soup: soup.clone(),
            attributes: attributes.clone(),
        };
        scene.replace(i, g)?;
    }
    Ok(scene)
}

/// glTF vertices of a geometry: one per distinct (position, normal, uv, colour) corner.
struct Vertices {
    positions: Vec<[f32; 3]>,
    normals: Option<Vec<[f32; 3]>>,
    texcoords: Option<Vec<[f32; 2]>>,
    colors: Option<Vec<[f32; 4]>>,
    indices: Vec<u32>,
}

fn unit(v: DVec3) -> [f32; 3] {
    let u = v.normalize_or_zero();
    if u == DVec3::ZERO {
        [0.0, 0.0, 1.0]
    } else {
        u.as_vec3().to_array()
    }
}

fn vertices(g: &Geometry, recompute_normals: bool) -> Vertices {
    let a = &g.attributes;
    let soup = &g.soup;
    let idx = |w: Option<&envelope_mesh::Wedges<2>>, f: usize, k: usize| {
        w.map_or(u32::MAX, |w| w.corners[f][k])
    };
    let mut corners = Vec::with_capacity(soup.num_faces() * 3);
    for (f, face) in soup.faces.iter().enumerate() {
        for k in 0..3 {
            corners.push([
                face[k].0,
                a.normals.as_ref().map_or(u32::MAX, |w| w.corners[f][k]),
                idx(a.texcoords.as_ref(), f, k),
                a.colors.as_ref().map_or(u32::MAX, |w| w.corners[f][k]),
            ]);
        }
    }
    // Vertices in the soup's order (then by attribute), so a soup without attributes and
    // without unreferenced vertices reads back as it was.
    let mut keys = corners.clone();
    keys.sort_unstable();
    keys.dedup();
    let indices = corners
        .iter()
        .map(|c| keys.binary_search(c).unwrap_or(0) as u32)
        .collect();
    let positions = keys
        .iter()
        .map(|k| soup.positions[k[0] as usize].as_vec3().to_array())
        .collect();
    let normals = match &a.normals {
        Some(w) => Some(
            keys.iter()
                .map(|k| unit(DVec3::from_array(w.values[k[1] as usize])))
                .collect(),
        ),
        None if recompute_normals => {
            let mut sum = vec![DVec3::ZERO; soup.num_vertices()];
            for f in soup.face_ids() {
                let [p, q, r] = soup.triangle(f);
                let n = (q - p).cross(r - p);
                for v in soup.faces[f.index()] {
                    sum[v.index()] += n;
                }
            }
            Some(keys.iter().map(|k| unit(sum[k[0] as usize])).collect())
        }
        None => None,
    };
    let texcoords = a.texcoords.as_ref().map(|w| {
        keys.iter()
            .map(|k| w.values[k[2] as usize].map(|x| x as f32))
            .collect()
    });
    let colors = a.colors.as_ref().map(|w| {
        keys.iter()
            .map(|k| w.values[k[3] as usize].map(|x| x.clamp(0.0, 1.0) as f32))
            .collect()
    });
    Vertices {
        positions,
        normals,
        texcoords,
        colors,
        indices,
    }
}

/// New accessors and bufferViews, their bytes in a buffer of their own (`buffer`, the index
/// past the document's buffers).
struct Emitter<'a> {
    accessors: &'a mut Vec<Value>,
    views: &'a mut Vec<Value>,
    bin: &'a mut Vec<u8>,
    buffer: usize,
}

impl Emitter<'_> {
    fn view(&mut self, bytes: &[u8], target: u32) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.views.push(json!({
            "buffer": self.buffer,
            "byteOffset": offset,
            "byteLength": bytes.len(),
            "target": target,
        }));
        self.views.len() - 1
    }

    fn floats<const N: usize>(&mut self, values: &[[f32; N]], kind: &str, bounds: bool) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let view = self.view(&bytes, ARRAY_BUFFER);
        let mut a = json!({
            "bufferView": view,
            "componentType": FLOAT,
            "count": values.len(),
            "type": kind,
        });
        if bounds && !values.is_empty() {
            let mut lo = [f32::INFINITY; N];
            let mut hi = [f32::NEG_INFINITY; N];
            for v in values {
                for c in 0..N {
                    lo[c] = lo[c].min(v[c]);
                    hi[c] = hi[c].max(v[c]);
                }
            }
            a["min"] = json!(lo.to_vec());
            a["max"] = json!(hi.to_vec());
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn indices(&mut self, indices: &[u32], vertices: usize) -> usize {
        let (bytes, kind): (Vec<u8>, u32) = if vertices <= usize::from(u16::MAX) {
            (
                indices
                    .iter()
                    .flat_map(|&i| (i as u16).to_le_bytes())
                    .collect(),
                UNSIGNED_SHORT,
            )
        } else {
            (
                indices.iter().flat_map(|i| i.to_le_bytes()).collect(),
                UNSIGNED_INT,
            )
        };
        let view = self.view(&bytes, ELEMENT_ARRAY_BUFFER);
        self.accessors.push(json!({
            "bufferView": view,
            "componentType": kind,
            "count": indices.len(),
            "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    /// `prim` (a primitive's JSON) with `g`'s triangles.
    fn primitive(&mut self, prim: &mut Value, g: &Geometry, had_normals: bool) {
        let v = vertices(g, had_normals);
        let mut attributes = Map::new();
        attributes.insert(
            "POSITION".into(),
            self.floats(&v.positions, "VEC3", true).into(),
        );
        if let Some(n) = &v.normals {
            attributes.insert("NORMAL".into(), self.floats(n, "VEC3", false).into());
        }
        if let Some(t) = &v.texcoords {
            attributes.insert("TEXCOORD_0".into(), self.floats(t, "VEC2", false).into());
        }
        if let Some(c) = &v.colors {
            attributes.insert("COLOR_0".into(), self.floats(c, "VEC4", false).into());
        }
        let indices = self.indices(&v.indices, v.positions.len());
        if !prim.is_object() {
            *prim = json!({});
        }
        if let Some(o) = prim.as_object_mut() {
            o.insert("attributes".into(), Value::Object(attributes));
            o.insert("indices".into(), indices.into());
            o.remove("mode");
            o.remove("targets");
            o.remove("extensions");
        }
    }
}

fn array<'a>(doc: &'a mut Value, key: &str) -> &'a mut Vec<Value> {
    if !doc.get(key).is_some_and(Value::is_array) {
        doc[key] = json!([]);
    }
    match doc.get_mut(key) {
        Some(Value::Array(a)) => a,
        _ => unreachable!("just made an array"),
    }
}

/// The JSON (with the buffer embedded when `embed`) and the binary buffer of `scene`.
pub(crate) fn document(scene: &Scene, embed: bool) -> Result<(Vec<u8>, Vec<u8>), GltfError> {
    let mut doc = scene.json.clone();
    let mut accessors = std::mem::take(array(&mut doc, "accessors"));
    let mut views = std::mem::take(array(&mut doc, "bufferViews"));
    let mut meshes = std::mem::take(array(&mut doc, "meshes"));
    let mut new_bin = Vec::new();
    let mut em = Emitter {
        accessors: &mut accessors,
        views: &mut views,
        bin: &mut new_bin,
        buffer: scene.buffers.len(),
    };
    let had_normals = |p: &Primitive| p.had_normals;
    let mut lod_nodes = Vec::new();
    for group in &scene.lods {
        let prims: Vec<&Primitive> = scene
            .primitives
            .iter()
            .filter(|p| p.mesh == group.mesh)
            .collect();
        let mut ids = Vec::new();
        for (k, level) in group.levels.iter().enumerate() {
            let mut mesh = meshes[group.mesh].clone();
            if let Some(name) = mesh.get("name").and_then(Value::as_str) {
                mesh["name"] = format!("{name} LOD {}", k + 1).into();
            }
            for (p, g) in prims.iter().zip(level) {
                if let Some(g) = g {
                    em.primitive(&mut mesh["primitives"][p.primitive], g, had_normals(p));
                }
            }
            meshes.push(mesh);
            ids.push(meshes.len() - 1);
        }
        lod_nodes.push((group.mesh, ids, group.coverage.clone()));
    }
    for (i, g) in scene.replaced.iter().enumerate() {
        if let Some(g) = g {
            let p = &scene.primitives[i];
            em.primitive(
                &mut meshes[p.mesh]["primitives"][p.primitive],
                g,
                had_normals(p),
            );
        }
    }
    doc["meshes"] = Value::Array(meshes);
    for (mesh, level_meshes, coverage) in lod_nodes {
        add_lod_nodes(&mut doc, mesh, &level_meshes, &coverage);
    }
    doc["accessors"] = Value::Array(accessors);
    doc["bufferViews"] = Value::Array(views);
    let mut sources: Vec<&[u8]> = scene.buffers.iter().map(Vec::as_slice).collect();
    sources.push(&new_bin);
    let bin = compact(&mut doc, &sources)?;
    if let Some(o) = doc.as_object_mut() {
        for key in ["accessors", "bufferViews", "meshes"] {
            if o.get(key)
                .and_then(Value::as_array)
                .is_some_and(Vec::is_empty)
            {
                o.remove(key);
            }
        }
        if bin.is_empty() {
            o.remove("buffers");
        } else {
            let mut buffer = json!({"byteLength": bin.len()});
            if embed {
                buffer["uri"] = format!(
                    "data:application/octet-stream;base64,{}",
                    base64_encode(&bin)
                )
                .into();
            }
            o.insert("buffers".into(), json!([buffer]));
        }
    }
    let json = serde_json::to_vec(&doc).map_err(|e| GltfError::Json(e.to_string()))?;
    Ok((json, bin))
}

/// `MSFT_lod` on every node showing `mesh` (module docs of the crate).
fn add_lod_nodes(doc: &mut Value, mesh: usize, levels: &[usize], coverage: &[f64]) {
    let count = doc
        .get("nodes")
        .and_then(Value::as_array)
        .map_or(0, Vec::len);
    for n in 0..count {
        if doc["nodes"][n].get("mesh").and_then(Value::as_u64) != Some(mesh as u64) {
            continue;
        }
        let has_children = doc["nodes"][n]
            .get("children")
            .and_then(Value::as_array)
            .is_some_and(|c| !c.is_empty());
        let nodes = array(doc, "nodes");
        let base = if has_children {
            let mut child = json!({"mesh": mesh});
            if let Some(name) = nodes[n].get("name") {
                child["name"] = name.clone();
            }
            if let Some(o) = nodes[n].as_object_mut() {
                o.remove("mesh");
            }
            nodes.push(child);
            let c = nodes.len() - 1;
            array(&mut nodes[n], "children").push(c.into());
            c
        } else {
            n
        };
        let mut ids = Vec::new();
        for (k, &m) in levels.iter().enumerate() {
            let mut node = json!({"mesh": m});
            if let Some(name) = nodes[base].get("name").and_then(Value::as_str) {
                node["name"] = format!("{name} LOD {}", k + 1).into();
            }
            if !has_children {
                for key in ["matrix", "translation", "rotation", "scale"] {
                    if let Some(v) = nodes[base].get(key) {
                        node[key] = v.clone();
                    }
                }
            }
            nodes.push(node);
            ids.push(nodes.len() - 1);
        }
        let node = &mut nodes[base];
        if !node.get("extensions").is_some_and(Value::is_object) {
            node["extensions"] = json!({});
        }
        node["extensions"]["MSFT_lod"] = json!({ "ids": ids });
        if !node.get("extras").is_some_and(Value::is_object) {
            node["extras"] = json!({});
        }
        node["extras"]["MSFT_screencoverage"] = json!(coverage);
    }
    let used = array(doc, "extensionsUsed");
    if !used.iter().any(|e| e == "MSFT_lod") {
        used.push("MSFT_lod".into());
    }
}

/// Calls `f` on every accessor reference the specification (and EXT_mesh_gpu_instancing)
/// defines.
fn accessor_refs(doc: &mut Value, f: &mut dyn FnMut(&mut Value)) {
    let each = |v: Option<&mut Value>, f: &mut dyn FnMut(&mut Value)| {
        if let Some(Value::Object(o)) = v {
            o.values_mut().for_each(f);
        }
    };
    if let Some(Value::Array(meshes)) = doc.get_mut("meshes") {
        for mesh in meshes {
            if let Some(Value::Array(prims)) = mesh.get_mut("primitives") {
                for prim in prims {
                    each(prim.get_mut("attributes"), f);
                    if let Some(i) = prim.get_mut("indices") {
                        f(i);
                    }
                    if let Some(Value::Array(targets)) = prim.get_mut("targets") {
                        for t in targets {
                            each(Some(t), f);
                        }
                    }
                }
            }
        }
    }
    if let Some(Value::Array(skins)) = doc.get_mut("skins") {
        for s in skins {
            if let Some(i) = s.get_mut("inverseBindMatrices") {
                f(i);
            }
        }
    }
    if let Some(Value::Array(anims)) = doc.get_mut("animations") {
        for a in anims {
            if let Some(Value::Array(samplers)) = a.get_mut("samplers") {
                for s in samplers {
                    for key in ["input", "output"] {
                        if let Some(i) = s.get_mut(key) {
                            f(i);
                        }
                    }
                }
            }
        }
    }
    if let Some(Value::Array(nodes)) = doc.get_mut("nodes") {
        for n in nodes {
            let inst = n
                .get_mut("extensions")
                .and_then(|e| e.get_mut("EXT_mesh_gpu_instancing"))
                .and_then(|e| e.get_mut("attributes"));
            each(inst, f);
        }
    }
}

/// Calls `f` on every bufferView reference (accessors, sparse accessors, images).
fn view_refs(doc: &mut Value, f: &mut dyn FnMut(&mut Value)) {
    if let Some(Value::Array(accessors)) = doc.get_mut("accessors") {
        for a in accessors {
            if let Some(v) = a.get_mut("bufferView") {
                f(v);
            }
            if let Some(sparse) = a.get_mut("sparse") {
                for key in ["indices", "values"] {
                    if let Some(v) = sparse.get_mut(key).and_then(|s| s.get_mut("bufferView")) {
                        f(v);
                    }
                }
            }
        }
    }
    if let Some(Value::Array(images)) = doc.get_mut("images") {
        for i in images {
            if let Some(v) = i.get_mut("bufferView") {
                f(v);
            }
        }
    }
}

/// A walker over the references of one kind (accessors or bufferViews).
type Refs = fn(&mut Value, &mut dyn FnMut(&mut Value));

/// Keeps the referenced entries of `doc[key]` (all of them unless `safe`), renumbering the
/// references through `refs`.
fn keep_referenced(doc: &mut Value, key: &str, safe: bool, refs: Refs) {
    let n = doc.get(key).and_then(Value::as_array).map_or(0, Vec::len);
    let mut used = vec![!safe; n];
    refs(doc, &mut |v| {
        if let Some(i) = v.as_u64().and_then(|i| used.get_mut(i as usize)) {
            *i = true;
        }
    });
    let mut map = vec![None; n];
    let mut kept = Vec::new();
    let old = std::mem::take(array(doc, key));
    for (i, item) in old.into_iter().enumerate() {
        if used[i] {
            map[i] = Some(kept.len());
            kept.push(item);
        }
    }
    doc[key] = Value::Array(kept);
    refs(doc, &mut |v| {
        if let Some(Some(j)) = v.as_u64().and_then(|i| map.get(i as usize)) {
            *v = (*j).into();
        }
    });
}

/// Drops unreferenced accessors and bufferViews (unless an unknown extension might refer to
/// them) and copies every kept view into one buffer, 4-byte aligned.
fn compact(doc: &mut Value, sources: &[&[u8]]) -> Result<Vec<u8>, GltfError> {
    let safe = doc
        .get("extensionsUsed")
        .and_then(Value::as_array)
        .is_none_or(|used| {
            used.iter().all(|e| {
                e.as_str().is_some_and(|e| {
                    KNOWN_EXTENSIONS.contains(&e) || e == "EXT_mesh_gpu_instancing"
                })
            })
        });
    keep_referenced(doc, "accessors", safe, accessor_refs);
    keep_referenced(doc, "bufferViews", safe, view_refs);
    let mut bin = Vec::new();
    for view in array(doc, "bufferViews").iter_mut() {
        let get = |k: &str| view.get(k).and_then(Value::as_u64).unwrap_or(0) as usize;
        let (buffer, offset, length) = (get("buffer"), get("byteOffset"), get("byteLength"));
        let bytes = sources
            .get(buffer)
            .and_then(|b| b.get(offset..offset.checked_add(length)?))
            .ok_or_else(|| GltfError::Invalid {
                path: "bufferViews".into(),
                reason: format!("a view of buffers[{buffer}] at {offset}+{length} is outside it"),
            })?;
        bin.resize(bin.len().next_multiple_of(4), 0);
        view["buffer"] = 0.into();
        view["byteOffset"] = bin.len().into();
        bin.extend_from_slice(bytes);
    }
    if bin.len() as u64 > u64::from(u32::MAX) - 64 {
        return Err(GltfError::TooLarge(bin.len() as u64));
    }
    Ok(bin)
}

static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// `bytes` to `path` through a temporary file in the same folder, synced, then renamed.
pub(crate) fn atomic(path: &Path, bytes: &[u8]) -> Result<(), GltfError> {
    let name = path
        .file_name()
        .ok_or_else(|| GltfError::io(path, std::io::ErrorKind::InvalidInput.into()))?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let n = TEMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".{}.{n}.tmp", std::process::id()));
    let tmp = dir.join(tmp_name);
    let result = (|| {
        let mut f = fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result.map_err(|e| GltfError::io(path, e))
}
