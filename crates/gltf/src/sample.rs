//! Generated test scenes (meshes made in code, like `envelope_mesh::generate`): a GLB with
//! two meshes, node transforms of every kind, a texture whose PNG is in a bufferView, and a
//! lines primitive.

use envelope_mesh::generate;
use serde_json::{Value, json};

/// A valid 1x1 RGB PNG, the sample scene's texture.
pub const PNG: [u8; 69] = [
    137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 73, 72, 68, 82, 0, 0, 0, 1, 0, 0, 0, 1, 8, 2, 0,
    0, 0, 144, 119, 83, 222, 0, 0, 0, 12, 73, 68, 65, 84, 120, 156, 99, 248, 223, 192, 0, 0, 4, 1,
    1, 128, 197, 42, 24, 93, 0, 0, 0, 0, 73, 69, 78, 68, 174, 66, 96, 130,
];

struct Doc {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Doc {
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        let mut v = json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(t) = target {
            v["target"] = t.into();
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    fn floats<const N: usize>(&mut self, values: &[[f32; N]], kind: &str, bounds: bool) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let view = self.view(&bytes, Some(34962));
        let mut a =
            json!({"bufferView": view, "componentType": 5126, "count": values.len(), "type": kind});
        if bounds {
            let lo: Vec<f32> = (0..N)
                .map(|c| values.iter().map(|v| v[c]).fold(f32::INFINITY, f32::min))
                .collect();
            let hi: Vec<f32> = (0..N)
                .map(|c| {
                    values
                        .iter()
                        .map(|v| v[c])
                        .fold(f32::NEG_INFINITY, f32::max)
                })
                .collect();
            a["min"] = json!(lo);
            a["max"] = json!(hi);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn indices(&mut self, indices: &[u32]) -> usize {
        let bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let view = self.view(&bytes, Some(34963));
        self.accessors.push(json!({"bufferView": view, "componentType": 5125, "count": indices.len(), "type": "SCALAR"}));
        self.accessors.len() - 1
    }
}

/// The f32 positions and flat indices of a generated soup.
fn f32_mesh(soup: &envelope_mesh::TriangleSoup) -> (Vec<[f32; 3]>, Vec<u32>) {
    (
        soup.positions
            .iter()
            .map(|p| p.as_vec3().to_array())
            .collect(),
        soup.faces.iter().flatten().map(|v| v.0).collect(),
    )
}

/// A GLB: mesh 0 `sphere` (an icosphere of `sphere_subdivisions`, radius 1, with NORMAL and
/// TEXCOORD_0, a textured material) shown by node 1 (rotation and scale 2) under node 0
/// (translation); mesh 1 `torus` (`around` x `tube` quads, no normals) with a second, LINES
/// primitive, shown by node 2 (a matrix: scale 0.5 and a translation). Positions are the
/// generators' rounded to f32.
///
/// ```
/// let scene = envelope_gltf::Scene::from_slice(&envelope_gltf::sample::scene(1, 8, 4), None)?;
/// assert_eq!(scene.primitives().len(), 3);
/// assert_eq!(scene.primitives()[0].soup().num_faces(), 80);
/// # Ok::<(), envelope_gltf::GltfError>(())
/// ```
#[must_use]
pub fn scene(sphere_subdivisions: u32, around: u32, tube: u32) -> Vec<u8> {
    let mut d = Doc {
        bin: Vec::new(),
        views: Vec::new(),
        accessors: Vec::new(),
    };
    let (sp, si) = f32_mesh(&generate::icosphere(sphere_subdivisions, 1.0));
    let normals: Vec<[f32; 3]> = sp
        .iter()
        .map(|p| glam::Vec3::from_array(*p).normalize().to_array())
        .collect();
    let uv: Vec<[f32; 2]> = sp
        .iter()
        .map(|p| {
            [
                0.5 + p[1].atan2(p[0]) / std::f32::consts::TAU,
                0.5 - p[2].clamp(-1.0, 1.0).asin() / std::f32::consts::PI,
            ]
        })
        .collect();
    let sphere = json!({
        "name": "sphere",
        "primitives": [{
            "attributes": {
                "POSITION": d.floats(&sp, "VEC3", true),
                "NORMAL": d.floats(&normals, "VEC3", false),
                "TEXCOORD_0": d.floats(&uv, "VEC2", false),
            },
            "indices": d.indices(&si),
            "material": 0,
        }],
    });
    let (tp, ti) = f32_mesh(&generate::torus(1.0, 0.3, around, tube));
    let tpos = d.floats(&tp, "VEC3", true);
    let torus = json!({
        "name": "torus",
        "primitives": [
            {"attributes": {"POSITION": tpos}, "indices": d.indices(&ti)},
            {"attributes": {"POSITION": tpos}, "indices": d.indices(&[0, 1, 1, 2]), "mode": 1},
        ],
    });
    let image = d.view(&PNG, None);
    let json = json!({
        "asset": {"version": "2.0", "generator": "envelope_gltf::sample"},
        "scene": 0,
        "scenes": [{"nodes": [0, 2]}],
        "nodes": [
            {"name": "root", "translation": [1.0, 2.0, 3.0], "children": [1]},
            {"name": "sphere", "mesh": 0, "rotation": [0.0, 0.0, 0.38268343, 0.9238795], "scale": [2.0, 2.0, 2.0]},
            {"name": "torus", "mesh": 1, "matrix": [0.5, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0, -3.0, 0.0, 0.0, 1.0]},
        ],
        "meshes": [sphere, torus],
        "materials": [{"name": "checker", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9729}],
        "images": [{"bufferView": image, "mimeType": "image/png"}],
        "accessors": d.accessors,
        "bufferViews": d.views,
        "buffers": [{"byteLength": d.bin.len()}],
    });
    let text = serde_json::to_vec(&json).unwrap_or_default();
    crate::container::join_glb(&text, &d.bin).unwrap_or_default()
}
