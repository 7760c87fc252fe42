//! Reading: the document validated, buffers loaded, every mesh primitive's accessors read
//! with bounds checked before anything is allocated.

use std::path::Path;

use envelope_mesh::{Attributes, TriangleSoup, VertexId, Wedges, check_coordinate};
use glam::{DMat4, DQuat, DVec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use serde_json::Value;

use crate::container::{data_uri, percent_decode, split_glb};
use crate::error::Use;
use crate::{GltfError, Instance, Primitive, Scene};

/// Extensions that only add to materials, textures, lights or metadata: a file requiring
/// them is read (and written back with them), since none changes the geometry.
pub const KNOWN_EXTENSIONS: &[&str] = &[
    "KHR_materials_clearcoat",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_iridescence",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_unlit",
    "KHR_materials_variants",
    "KHR_materials_volume",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_texture_transform",
    "KHR_texture_basisu",
    "EXT_texture_webp",
    "KHR_lights_punctual",
    "KHR_xmp_json_ld",
    "MSFT_lod",
];

/// A scene from the bytes of a `.glb` or `.gltf`; `base` is the folder external buffers
/// are relative to (`None`: only GLB and data URIs are loaded).
pub(crate) fn read(bytes: &[u8], base: Option<&Path>) -> Result<Scene, GltfError> {
    // A GLB starts with its magic, a .gltf with `{` (after white space or a byte order
    // mark); anything else is named as a bad GLB magic.
    let text = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let (json_bytes, bin) = if crate::container::is_glb(bytes) {
        split_glb(bytes)?
    } else if text.trim_ascii_start().starts_with(b"{") {
        (text, None)
    } else {
        return Err(split_glb(bytes)
            .err()
            .unwrap_or(GltfError::Json("empty file".into())));
    };
    let json: Value =
        serde_json::from_slice(json_bytes).map_err(|e| GltfError::Json(e.to_string()))?;
    if let Some(required) = json.get("extensionsRequired").and_then(Value::as_array) {
        for ext in required {
            let name = ext.as_str().unwrap_or_default();
            if !KNOWN_EXTENSIONS.contains(&name) {
                return Err(GltfError::RequiredExtension(name.to_string()));
            }
        }
    }
    check_position_refs(&json)?;
    // The typed view validates every reference; the required extensions are checked above
    // (the typed model only knows those it was built with).
    let mut typed = json.clone();
    if let Some(o) = typed.as_object_mut() {
        o.remove("extensionsRequired");
    }
    let root: gltf::json::Root =
        serde_json::from_value(typed).map_err(|e| GltfError::Json(e.to_string()))?;
    let doc = gltf::Document::from_json(root).map_err(|e| match e {
        gltf::Error::Validation(list) => {
            let (path, err) = list
                .into_iter()
                .next()
                .map_or((String::new(), String::from("invalid")), |(p, e)| {
                    (p.to_string(), e.to_string())
                });
            GltfError::Invalid { path, reason: err }
        }
        e => GltfError::Json(e.to_string()),
    })?;
    let buffers = load_buffers(&doc, bin, base)?;
    check_views(&doc, &buffers)?;
    let mut primitives = Vec::new();
    for mesh in doc.meshes() {
        for prim in mesh.primitives() {
            primitives.push(read_primitive(&buffers, &mesh, &prim)?);
        }
    }
    let instances = instances(&doc)?;
    for p in &mut primitives {
        p.skinned = instances.iter().any(|i| i.mesh == p.mesh && i.skinned);
    }
    Ok(Scene::from_parts(json, buffers, primitives, instances))
}

/// Every POSITION names an accessor that exists: the typed validator's primitive hook
/// indexes the accessors with it before its own reference check (a panic on such input,
/// found by the fuzz target `read_gltf`).
fn check_position_refs(json: &Value) -> Result<(), GltfError> {
    let accessors = json
        .get("accessors")
        .and_then(Value::as_array)
        .map_or(0, Vec::len);
    let meshes = json.get("meshes").and_then(Value::as_array);
    for (m, mesh) in meshes.into_iter().flatten().enumerate() {
        let prims = mesh.get("primitives").and_then(Value::as_array);
        for (p, prim) in prims.into_iter().flatten().enumerate() {
            let pos = prim.get("attributes").and_then(|a| a.get("POSITION"));
            if let Some(i) = pos.and_then(Value::as_u64)
                && i >= accessors as u64
            {
                return Err(GltfError::Invalid {
                    path: format!("meshes[{m}].primitives[{p}].attributes.POSITION"),
                    reason: format!("accessors[{i}] does not exist ({accessors} accessors)"),
                });
            }
        }
    }
    Ok(())
}

fn load_buffers(
    doc: &gltf::Document,
    mut bin: Option<&[u8]>,
    base: Option<&Path>,
) -> Result<Vec<Vec<u8>>, GltfError> {
    let mut out = Vec::new();
    for buffer in doc.buffers() {
        let i = buffer.index();
        let fail = |reason: String| GltfError::BufferUri { buffer: i, reason };
        let mut bytes = match buffer.source() {
            gltf::buffer::Source::Bin => bin
                .take()
                .ok_or_else(|| fail("no uri, and no (unused) GLB BIN chunk to stand for".into()))?
                .to_vec(),
            gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => {
                data_uri(uri).map_err(fail)?
            }
            gltf::buffer::Source::Uri(uri) => {
                if uri.contains(':') || uri.starts_with('/') || uri.starts_with('\\') {
                    return Err(fail(format!(
                        "uri {uri:?} is not a relative path or a data URI"
                    )));
                }
                let base = base.ok_or_else(|| {
                    fail(format!(
                        "uri {uri:?} is relative, and there is no file to resolve it against"
                    ))
                })?;
                let path = base.join(percent_decode(uri).map_err(fail)?);
                std::fs::read(&path).map_err(|e| GltfError::io(&path, e))?
            }
        };
        let declared = buffer.length() as u64;
        if (bytes.len() as u64) < declared {
            return Err(GltfError::BufferTooShort {
                buffer: i,
                declared,
                actual: bytes.len() as u64,
            });
        }
        // A GLB chunk may carry up to 3 padding bytes; the buffer is its declared length.
        bytes.truncate(declared as usize);
        out.push(bytes);
    }
    Ok(out)
}

fn check_views(doc: &gltf::Document, buffers: &[Vec<u8>]) -> Result<(), GltfError> {
    for view in doc.views() {
        let buffer = view.buffer().index();
        let offset = view.offset() as u64;
        let end = offset.saturating_add(view.length() as u64);
        let length = buffers[buffer].len() as u64;
        if end > length {
            return Err(GltfError::ViewOutOfBuffer {
                view: view.index(),
                buffer,
                offset,
                end,
                length,
            });
        }
    }
    Ok(())
}

/// The bytes of one accessor: the view from its offset, the stride, the element size.
struct Elements<'a> {
    bytes: &'a [u8],
    stride: usize,
    count: usize,
    kind: DataType,
    normalized: bool,
}

fn dims(d: Dimensions) -> usize {
    match d {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 => 4,
        Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

fn kind_name(a: &gltf::Accessor) -> String {
    format!(
        "{:?} {:?}{}{}",
        a.data_type(),
        a.dimensions(),
        if a.normalized() { " normalized" } else { "" },
        if a.sparse().is_some() { " sparse" } else { "" }
    )
}

fn elements<'a>(
    buffers: &'a [Vec<u8>],
    a: &gltf::Accessor,
    used: &Use,
) -> Result<Elements<'a>, GltfError> {
    let fail = |found: String| GltfError::AccessorKind {
        accessor: a.index(),
        used: used.clone(),
        found,
        expected: "a dense accessor in a bufferView",
    };
    if a.sparse().is_some() {
        return Err(fail("sparse storage".into()));
    }
    let view = a.view().ok_or_else(|| fail("no bufferView".into()))?;
    let start = view.offset();
    let bytes = &buffers[view.buffer().index()][start..start + view.length()];
    let size = a.data_type().size() * dims(a.dimensions());
    let stride = view.stride().unwrap_or(size);
    let count = a.count();
    // Saturating: a huge count or offset is refused below, never wrapped.
    let end = if count == 0 {
        a.offset() as u64
    } else {
        (a.offset() as u64)
            .saturating_add((stride as u64).saturating_mul(count as u64 - 1))
            .saturating_add(size as u64)
    };
    if end > bytes.len() as u64 || stride < size {
        return Err(GltfError::AccessorOutOfView {
            accessor: a.index(),
            used: used.clone(),
            view: view.index(),
            count: count as u64,
            end,
            length: bytes.len() as u64,
        });
    }
    Ok(Elements {
        bytes: &bytes[a.offset()..],
        stride,
        count,
        kind: a.data_type(),
        normalized: a.normalized(),
    })
}

impl Elements<'_> {
    /// Component `c` of element `i`, converted exactly to f64 (normalized integers divided as
    /// the specification says).
    fn get(&self, i: usize, c: usize) -> f64 {
        let at = i * self.stride + c * self.kind.size();
        let b = &self.bytes[at..at + self.kind.size()];
        let n = self.normalized;
        match self.kind {
            DataType::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            DataType::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            DataType::U16 => {
                let x = f64::from(u16::from_le_bytes([b[0], b[1]]));
                if n { x / 65535.0 } else { x }
            }
            DataType::I16 => {
                let x = f64::from(i16::from_le_bytes([b[0], b[1]]));
                if n { (x / 32767.0).max(-1.0) } else { x }
            }
            DataType::U8 => {
                let x = f64::from(b[0]);
                if n { x / 255.0 } else { x }
            }
            DataType::I8 => {
                let x = f64::from(b[0] as i8);
                if n { (x / 127.0).max(-1.0) } else { x }
            }
        }
    }

    fn index(&self, i: usize) -> u64 {
        self.get(i, 0) as u64
    }
}

fn read_primitive(
    buffers: &[Vec<u8>],
    mesh: &gltf::Mesh,
    prim: &gltf::Primitive,
) -> Result<Primitive, GltfError> {
    let (m, p) = (mesh.index(), prim.index());
    let used = |semantic: &str| Use {
        mesh: m,
        primitive: p,
        semantic: semantic.to_string(),
    };
    let mode = prim.mode();
    let mut out = Primitive {
        mesh: m,
        primitive: p,
        name: mesh.name().map(str::to_string),
        material: prim.material().index(),
        mode,
        soup: TriangleSoup::default(),
        attributes: Attributes::default(),
        morph_targets: prim.morph_targets().count(),
        skinned: false,
        had_normals: prim.get(&gltf::Semantic::Normals).is_some(),
    };
    if !matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        return Ok(out);
    }
    let pos = prim
        .get(&gltf::Semantic::Positions)
        .ok_or(GltfError::NoPositions {
            mesh: m,
            primitive: p,
        })?;
    let u = used("POSITION");
    if pos.data_type() != DataType::F32 || pos.dimensions() != Dimensions::Vec3 || pos.normalized()
    {
        return Err(GltfError::AccessorKind {
            accessor: pos.index(),
            used: u,
            found: kind_name(&pos),
            expected: "F32 Vec3 (quantized positions, KHR_mesh_quantization, are not read)",
        });
    }
    let e = elements(buffers, &pos, &u)?;
    let n = e.count;
    let mut raw = Vec::with_capacity(n);
    for i in 0..n {
        let mut v = [0.0; 3];
        for (c, x) in v.iter_mut().enumerate() {
            *x = e.get(i, c);
            check_coordinate(*x).map_err(|err| GltfError::BadValue {
                accessor: pos.index(),
                used: u.clone(),
                element: i as u64,
                component: c,
                reason: err.to_string(),
            })?;
        }
        raw.push(v);
    }
    let corners = corner_list(buffers, prim, n, &used("indices"))?;
    let triangles = match mode {
        Mode::Triangles => {
            if corners.len() % 3 != 0 {
                return Err(GltfError::PartialTriangle {
                    mesh: m,
                    primitive: p,
                    corners: corners.len() as u64,
                });
            }
            corners
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]])
                .collect()
        }
        Mode::TriangleStrip => strip(&corners),
        _ => fan(&corners),
    };
    // Corners at bitwise-equal positions (-0 taken as +0) become one vertex: glTF splits
    // vertices along seams, the simplifier needs the surface connected.
    let mut weld = std::collections::HashMap::with_capacity(n);
    let mut positions = Vec::new();
    let mut map = Vec::with_capacity(n);
    for v in &raw {
        let key = v.map(|x| (x + 0.0).to_bits());
        let id = *weld.entry(key).or_insert_with(|| {
            positions.push(DVec3::from_array(*v));
            positions.len() as u32 - 1
        });
        map.push(id);
    }
    out.soup = TriangleSoup::new(
        positions,
        triangles
            .iter()
            .map(|t: &[u32; 3]| t.map(|v| VertexId(map[v as usize])))
            .collect(),
    );
    if let Some(a) = prim.get(&gltf::Semantic::Normals) {
        out.attributes.normals = Some(wedges(
            &triangles,
            values::<3>(buffers, &a, &used("NORMAL"), n, &[DataType::F32], false)?,
        ));
    }
    if let Some(a) = prim.get(&gltf::Semantic::TexCoords(0)) {
        let t = [DataType::F32, DataType::U8, DataType::U16];
        out.attributes.texcoords = Some(wedges(
            &triangles,
            values::<2>(buffers, &a, &used("TEXCOORD_0"), n, &t, true)?,
        ));
    }
    if let Some(a) = prim.get(&gltf::Semantic::Colors(0)) {
        let t = [DataType::F32, DataType::U8, DataType::U16];
        out.attributes.colors = Some(wedges(
            &triangles,
            values::<4>(buffers, &a, &used("COLOR_0"), n, &t, true)?,
        ));
    }
    Ok(out)
}

fn wedges<const N: usize>(triangles: &[[u32; 3]], values: Vec<[f64; N]>) -> Wedges<N> {
    Wedges {
        values,
        corners: triangles.to_vec(),
    }
}

/// The corner list: the indices, or `0..n` for a primitive without them.
fn corner_list(
    buffers: &[Vec<u8>],
    prim: &gltf::Primitive,
    n: usize,
    used: &Use,
) -> Result<Vec<u32>, GltfError> {
    let Some(a) = prim.indices() else {
        return Ok((0..n as u32).collect());
    };
    if !matches!(a.data_type(), DataType::U8 | DataType::U16 | DataType::U32)
        || a.dimensions() != Dimensions::Scalar
        || a.normalized()
    {
        return Err(GltfError::AccessorKind {
            accessor: a.index(),
            used: used.clone(),
            found: kind_name(&a),
            expected: "an unsigned U8, U16 or U32 Scalar",
        });
    }
    let e = elements(buffers, &a, used)?;
    let mut out = Vec::with_capacity(e.count);
    for i in 0..e.count {
        let index = e.index(i);
        if index >= n as u64 {
            return Err(GltfError::IndexOutOfRange {
                accessor: a.index(),
                used: used.clone(),
                element: i as u64,
                index,
                vertices: n as u64,
            });
        }
        out.push(index as u32);
    }
    Ok(out)
}

/// A triangle strip as triangles, every other one turned to keep the winding; triangles with
/// a repeated corner (the strip's joins) are left out.
fn strip(c: &[u32]) -> Vec<[u32; 3]> {
    (2..c.len())
        .map(|i| {
            if i % 2 == 0 {
                [c[i - 2], c[i - 1], c[i]]
            } else {
                [c[i - 1], c[i - 2], c[i]]
            }
        })
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect()
}

/// A triangle fan as triangles around its first corner (repeated corners left out).
fn fan(c: &[u32]) -> Vec<[u32; 3]> {
    (2..c.len())
        .map(|i| [c[0], c[i - 1], c[i]])
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect()
}

/// A per-vertex attribute: `n` values of `N` components (a VEC3 colour gets alpha 1).
fn values<const N: usize>(
    buffers: &[Vec<u8>],
    a: &gltf::Accessor,
    used: &Use,
    n: usize,
    types: &[DataType],
    integers_normalized: bool,
) -> Result<Vec<[f64; N]>, GltfError> {
    let d = dims(a.dimensions());
    let dims_ok = d == N || (N == 4 && d == 3);
    let type_ok = types.contains(&a.data_type())
        && (a.data_type() == DataType::F32) != (integers_normalized && a.normalized())
        && !(a.data_type() == DataType::F32 && a.normalized());
    if !dims_ok || !type_ok {
        return Err(GltfError::AccessorKind {
            accessor: a.index(),
            used: used.clone(),
            found: kind_name(a),
            expected: match N {
                3 => "F32 Vec3",
                2 => "F32, or normalized U8 or U16, Vec2",
                _ => "F32, or normalized U8 or U16, Vec3 or Vec4",
            },
        });
    }
    let e = elements(buffers, a, used)?;
    if e.count != n {
        return Err(GltfError::CountMismatch {
            accessor: a.index(),
            used: used.clone(),
            count: e.count as u64,
            positions: n as u64,
        });
    }
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut v = [1.0; N];
        for c in 0..d {
            v[c] = e.get(i, c);
            if !v[c].is_finite() {
                return Err(GltfError::BadValue {
                    accessor: a.index(),
                    used: used.clone(),
                    element: i as u64,
                    component: c,
                    reason: "not finite".into(),
                });
            }
        }
        out.push(v);
    }
    Ok(out)
}

/// Every node that shows a mesh, with its world transform, through every scene.
fn instances(doc: &gltf::Document) -> Result<Vec<Instance>, GltfError> {
    let mut out = Vec::new();
    for scene in doc.scenes() {
        let mut seen = vec![false; doc.nodes().len()];
        let mut stack: Vec<(gltf::Node, DMat4)> =
            scene.nodes().map(|n| (n, DMat4::IDENTITY)).collect();
        while let Some((node, parent)) = stack.pop() {
            if std::mem::replace(&mut seen[node.index()], true) {
                return Err(GltfError::Invalid {
                    path: format!("nodes[{}]", node.index()),
                    reason: format!(
                        "reached twice from scenes[{}]: nodes must form disjoint trees",
                        scene.index()
                    ),
                });
            }
            let world = parent * local(&node)?;
            if !world.is_finite() {
                return Err(GltfError::Invalid {
                    path: format!("nodes[{}]", node.index()),
                    reason: "its world transform overflows f64".into(),
                });
            }
            if let Some(mesh) = node.mesh() {
                out.push(Instance {
                    node: node.index(),
                    mesh: mesh.index(),
                    scene: scene.index(),
                    world: world.to_cols_array_2d(),
                    skinned: node.skin().is_some(),
                });
            }
            stack.extend(node.children().map(|c| (c, world)));
        }
    }
    Ok(out)
}

/// A node's own transform in f64 (the matrix as written, or T * R * S), refused when a
/// value is not finite in f32 or the rotation has length 0.
fn local(node: &gltf::Node) -> Result<DMat4, GltfError> {
    let fail = |what: &str, reason: &str| GltfError::Invalid {
        path: format!("nodes[{}].{what}", node.index()),
        reason: reason.into(),
    };
    let finite = |what: &str, v: &[f32]| {
        if v.iter().all(|x| x.is_finite()) {
            Ok(())
        } else {
            Err(fail(what, "a value is not finite as f32"))
        }
    };
    Ok(match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            finite("matrix", matrix.as_flattened())?;
            DMat4::from_cols_array_2d(&matrix.map(|c| c.map(f64::from)))
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            finite("translation", &translation)?;
            finite("rotation", &rotation)?;
            finite("scale", &scale)?;
            let f = |a: [f32; 3]| DVec3::from_array(a.map(f64::from));
            let r = rotation.map(f64::from);
            let q = DQuat::from_xyzw(r[0], r[1], r[2], r[3]);
            let length = q.length();
            if length == 0.0 || !length.is_finite() {
                return Err(fail("rotation", "the quaternion has length 0"));
            }
            DMat4::from_scale_rotation_translation(f(scale), q.normalize(), f(translation))
        }
    })
}
