//! glTF round trips, replacements, levels of detail and refusals, on scenes made in code.

use envelope_gltf::{Geometry, GltfError, Mode, Scene, sample};
use envelope_mesh::{Attributes, TriangleSoup, generate};
use serde_json::{Value, json};

fn glb(json: &Value, bin: &[u8]) -> Vec<u8> {
    let pad = |n: usize| n.next_multiple_of(4);
    let text = serde_json::to_vec(json).unwrap();
    let (jl, bl) = (pad(text.len()), pad(bin.len()));
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&((12 + 8 + jl + 8 + bl) as u32).to_le_bytes());
    out.extend_from_slice(&(jl as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    out.resize(20 + jl, b' ');
    out.extend_from_slice(&(bl as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    out.resize(28 + jl + bl, 0);
    out
}

/// One triangle: POSITION (accessor 0), indices (accessor 1, u16).
fn triangle_doc() -> (Value, Vec<u8>) {
    let mut bin = Vec::new();
    for x in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        bin.extend_from_slice(&x.to_le_bytes());
    }
    for i in [0u16, 1, 2, 0] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let json = json!({
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 8},
        ],
        "buffers": [{"byteLength": 44}],
    });
    (json, bin)
}

fn f32_soup(soup: &TriangleSoup) -> TriangleSoup {
    let mut s = soup.clone();
    for p in &mut s.positions {
        *p = p.as_vec3().as_dvec3();
    }
    s
}

#[test]
fn sample_reads_with_transforms_attributes_and_image() {
    let scene = Scene::from_slice(&sample::scene(2, 12, 6), None).unwrap();
    let prims = scene.primitives();
    assert_eq!(prims.len(), 3);
    assert_eq!(prims[0].soup(), &f32_soup(&generate::icosphere(2, 1.0)));
    assert_eq!(
        prims[1].soup(),
        &f32_soup(&generate::torus(1.0, 0.3, 12, 6))
    );
    assert_eq!(prims[2].mode(), Mode::Lines);
    assert!(!prims[2].is_triangles());
    let a = prims[0].attributes();
    assert!(a.normals.is_some() && a.texcoords.is_some() && a.colors.is_none());
    assert!(a.is_valid_for(prims[0].soup().num_faces()));
    assert_eq!(prims[0].material(), Some(0));
    // Node 1 (scale 2 under a translation) and node 2 (a matrix with scale 0.5).
    assert!((scene.mesh_scale(0) - 2.0).abs() < 1e-6 && scene.mesh_scale(0) >= 2.0);
    assert!((scene.mesh_scale(1) - 0.5).abs() < 1e-6 && scene.mesh_scale(1) >= 0.5);
    let sphere = scene.instances().iter().find(|i| i.mesh == 0).unwrap();
    assert_eq!(sphere.world[3][..3], [1.0, 2.0, 3.0]);
    let view = scene.json()["images"][0]["bufferView"].as_u64().unwrap() as usize;
    assert_eq!(scene.view_bytes(view).unwrap(), &sample::PNG);
    assert!(scene.world_diagonal() > 4.0);
}

#[test]
fn round_trip_keeps_everything() {
    let scene = Scene::from_slice(&sample::scene(2, 12, 6), None).unwrap();
    for bytes in [scene.to_glb().unwrap(), scene.to_gltf().unwrap()] {
        let back = Scene::from_slice(&bytes, None).unwrap();
        for key in ["nodes", "scenes", "materials", "textures", "samplers"] {
            assert_eq!(back.json()[key], scene.json()[key], "{key}");
        }
        for (a, b) in back.primitives().iter().zip(scene.primitives()) {
            assert_eq!(a.soup(), b.soup());
            assert_eq!(a.attributes(), b.attributes());
            assert_eq!(a.mode(), b.mode());
        }
        let view = back.json()["images"][0]["bufferView"].as_u64().unwrap() as usize;
        assert_eq!(back.view_bytes(view).unwrap(), &sample::PNG);
        assert_eq!(back.instances(), scene.instances());
    }
}

#[test]
fn replaced_primitive_is_written_f32_exact_and_the_rest_kept() {
    let mut scene = Scene::from_slice(&sample::scene(2, 12, 6), None).unwrap();
    let accessors_before = scene.json()["accessors"].as_array().unwrap().len();
    let tet = f32_soup(&generate::tetrahedron());
    scene
        .replace(
            0,
            Geometry {
                soup: tet.clone(),
                attributes: Attributes::default(),
            },
        )
        .unwrap();
    assert!(matches!(
        scene.replace(
            2,
            Geometry {
                soup: tet.clone(),
                attributes: Attributes::default()
            }
        ),
        Err(GltfError::BadReplacement {
            mesh: 1,
            primitive: 1,
            ..
        })
    ));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.glb");
    scene.write_path(&path).unwrap();
    let back = Scene::read_path(&path).unwrap();
    assert_eq!(back.primitives()[0].soup(), &tet);
    // The input had normals: recomputed, unit; texture coordinates are not invented.
    let normals = back.primitives()[0].attributes().normals.as_ref().unwrap();
    assert!(
        normals
            .values
            .iter()
            .all(|n| (n.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-6)
    );
    assert!(back.primitives()[0].attributes().texcoords.is_none());
    assert_eq!(back.primitives()[1].soup(), scene.primitives()[1].soup());
    assert_eq!(back.json()["nodes"], scene.json()["nodes"]);
    let view = back.json()["images"][0]["bufferView"].as_u64().unwrap() as usize;
    assert_eq!(back.view_bytes(view).unwrap(), &sample::PNG);
    // Old sphere accessors (POSITION, NORMAL, TEXCOORD_0, indices) gone, three new ones.
    let accessors = back.json()["accessors"].as_array().unwrap();
    assert_eq!(accessors.len(), accessors_before - 4 + 3);
    let pos = &accessors[back.json()["meshes"][0]["primitives"][0]["attributes"]["POSITION"]
        .as_u64()
        .unwrap() as usize];
    assert!(pos["min"].is_array() && pos["max"].is_array());
    // Every bufferView is referenced, and the buffer is one.
    assert_eq!(back.json()["buffers"].as_array().unwrap().len(), 1);
    let views = back.json()["bufferViews"].as_array().unwrap().len();
    assert_eq!(views, accessors.len() + 1);
    // The .gltf form reads the same.
    let gltf = dir.path().join("out.gltf");
    scene.write_path(&gltf).unwrap();
    assert_eq!(
        Scene::read_path(&gltf).unwrap().primitives()[0].soup(),
        &tet
    );
    assert!(matches!(
        scene.write_path(dir.path().join("out.obj")),
        Err(GltfError::UnknownExtension(_))
    ));
}

#[test]
fn lod_nodes_and_extension() {
    let mut scene = Scene::from_slice(&sample::scene(1, 8, 4), None).unwrap();
    let tet = f32_soup(&generate::tetrahedron());
    let g = || {
        Some(Geometry {
            soup: tet.clone(),
            attributes: Attributes::default(),
        })
    };
    scene
        .add_lod(
            1,
            vec![vec![g(), None], vec![g(), None]],
            vec![0.5, 0.25, 0.0],
        )
        .unwrap();
    assert!(scene.add_lod(1, vec![vec![g()]], vec![0.5, 0.0]).is_err());
    let back = Scene::from_slice(&scene.to_glb().unwrap(), None).unwrap();
    let j = back.json();
    assert!(
        j["extensionsUsed"]
            .as_array()
            .unwrap()
            .contains(&json!("MSFT_lod"))
    );
    let ids: Vec<usize> = j["nodes"][2]["extensions"]["MSFT_lod"]["ids"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap() as usize)
        .collect();
    assert_eq!(ids.len(), 2);
    assert_eq!(
        j["nodes"][2]["extras"]["MSFT_screencoverage"],
        json!([0.5, 0.25, 0.0])
    );
    for &id in &ids {
        assert_eq!(j["nodes"][id]["matrix"], j["nodes"][2]["matrix"]);
        let m = j["nodes"][id]["mesh"].as_u64().unwrap() as usize;
        let p = back.primitives().iter().find(|p| p.mesh() == m).unwrap();
        assert_eq!(p.soup(), &tet);
        assert_eq!(j["meshes"][m]["primitives"][1]["mode"], 1);
    }
}

#[test]
fn strips_and_fans_become_triangles() {
    let (mut json, mut bin) = triangle_doc();
    bin.truncate(36);
    for x in [1.0f32, 1.0, 0.0] {
        bin.extend_from_slice(&x.to_le_bytes());
    }
    json["accessors"][0]["count"] = 4.into();
    json["bufferViews"][0]["byteLength"] = 48.into();
    json["bufferViews"].as_array_mut().unwrap().pop();
    json["accessors"].as_array_mut().unwrap().pop();
    json["buffers"][0]["byteLength"] = 48.into();
    let prim = &mut json["meshes"][0]["primitives"][0];
    prim.as_object_mut().unwrap().remove("indices");
    prim["mode"] = 5.into();
    let s = Scene::from_slice(&glb(&json, &bin), None).unwrap();
    let faces: Vec<[u32; 3]> = s.primitives()[0]
        .soup()
        .faces
        .iter()
        .map(|f| f.map(|v| v.0))
        .collect();
    assert_eq!(faces, vec![[0, 1, 2], [2, 1, 3]]);
    json["meshes"][0]["primitives"][0]["mode"] = 6.into();
    let s = Scene::from_slice(&glb(&json, &bin), None).unwrap();
    let faces: Vec<[u32; 3]> = s.primitives()[0]
        .soup()
        .faces
        .iter()
        .map(|f| f.map(|v| v.0))
        .collect();
    assert_eq!(faces, vec![[0, 1, 2], [0, 2, 3]]);
}

fn refusal(json: &Value, bin: &[u8]) -> String {
    let err = Scene::from_slice(&glb(json, bin), None).unwrap_err();
    err.to_string()
}

#[test]
fn refusals_name_the_element() {
    let (json, bin) = triangle_doc();
    assert!(Scene::from_slice(&glb(&json, &bin), None).is_ok());

    let mut draco = json.clone();
    draco["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    draco["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    assert!(refusal(&draco, &bin).contains("\"KHR_draco_mesh_compression\""));

    let mut bad_index = bin.clone();
    bad_index[36 + 2..36 + 4].copy_from_slice(&7u16.to_le_bytes());
    let msg = refusal(&json, &bad_index);
    assert!(
        msg.contains("accessors[1]") && msg.contains("indices") && msg.contains("element 1 is 7"),
        "{msg}"
    );

    let good = glb(&json, &bin);
    let err = Scene::from_slice(&good[..good.len() - 8], None).unwrap_err();
    assert!(
        matches!(err, GltfError::Truncated { offset: 0, .. }),
        "{err}"
    );
    let mut cut = good.clone();
    let n = cut.len() - 8;
    cut.truncate(n);
    cut[8..12].copy_from_slice(&(n as u32).to_le_bytes());
    let msg = Scene::from_slice(&cut, None).unwrap_err().to_string();
    assert!(msg.contains("truncated GLB: byte"), "{msg}");

    let mut magic = good.clone();
    magic[..4].copy_from_slice(b"gLTF");
    let err = Scene::from_slice(&magic, None).unwrap_err();
    assert!(
        matches!(err, GltfError::BadMagic { found } if &found == b"gLTF"),
        "{err}"
    );
    assert!(err.to_string().contains("bytes 0..4"), "{err}");
    let err = Scene::from_slice(b"  [1, 2]", None).unwrap_err();
    assert!(matches!(err, GltfError::BadMagic { .. }), "{err}");
    let err = Scene::from_slice(b" {\"asset\": 1}", None).unwrap_err();
    assert!(matches!(err, GltfError::Json(_)), "{err}");

    let mut quantized = json.clone();
    quantized["accessors"][0]["componentType"] = 5122.into();
    quantized["accessors"][0]["normalized"] = true.into();
    let msg = refusal(&quantized, &bin);
    assert!(
        msg.contains("accessors[0]") && msg.contains("POSITION"),
        "{msg}"
    );

    let mut outside = json.clone();
    outside["accessors"][0]["byteOffset"] = 4.into();
    let msg = refusal(&outside, &bin);
    assert!(
        msg.contains("accessors[0]") && msg.contains("bufferViews[0]"),
        "{msg}"
    );

    let mut sparse = json.clone();
    sparse["accessors"][0]["sparse"] = json!({"count": 1,
        "indices": {"bufferView": 1, "componentType": 5123},
        "values": {"bufferView": 0}});
    let msg = refusal(&sparse, &bin);
    assert!(
        msg.contains("accessors[0]") && msg.contains("sparse"),
        "{msg}"
    );

    let mut nan = bin.clone();
    nan[4..8].copy_from_slice(&f32::NAN.to_le_bytes());
    let msg = refusal(&json, &nan);
    assert!(
        msg.contains("element 0 component 1") && msg.contains("NaN"),
        "{msg}"
    );

    let mut dangling = json.clone();
    dangling["meshes"][0]["primitives"][0]["indices"] = 9.into();
    let msg = refusal(&dangling, &bin);
    assert!(msg.contains("meshes[0].primitives[0].indices"), "{msg}");

    let mut short = json.clone();
    short["buffers"][0]["byteLength"] = 400.into();
    assert!(refusal(&short, &bin).contains("buffers[0]"));
}

#[test]
fn bad_magic_glb_is_refused() {
    // A GLB header is recognised by its magic; a wrong version is named.
    let (json, bin) = triangle_doc();
    let mut v = glb(&json, &bin);
    v[4] = 3;
    assert!(matches!(
        Scene::from_slice(&v, None),
        Err(GltfError::BadVersion(3))
    ));
}

#[test]
fn gltf_with_side_and_data_uri_buffers() {
    let (mut json, bin) = triangle_doc();
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tri data.bin"), &bin).unwrap();
    json["buffers"][0]["uri"] = "tri%20data.bin".into();
    let path = dir.path().join("tri.gltf");
    std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    let side = Scene::read_path(&path).unwrap();
    assert_eq!(side.primitives()[0].soup().num_faces(), 1);
    // Without a folder to resolve it against, the side file is refused by name.
    let err = Scene::from_slice(&serde_json::to_vec(&json).unwrap(), None).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("buffers[0]: uri \"tri%20data.bin\""),
        "{err}"
    );
    for uri in ["http://example.com/a.bin", "/etc/passwd"] {
        json["buffers"][0]["uri"] = uri.into();
        let err =
            Scene::from_slice(&serde_json::to_vec(&json).unwrap(), Some(dir.path())).unwrap_err();
        assert!(err.to_string().contains("not a relative path"), "{err}");
    }
    // The .gltf writer embeds the buffer as a data URI, which reads back the same.
    let embedded = side.to_gltf().unwrap();
    assert!(String::from_utf8_lossy(&embedded).contains("data:application/octet-stream;base64,"));
    let back = Scene::from_slice(&embedded, None).unwrap();
    assert_eq!(back.primitives()[0].soup(), side.primitives()[0].soup());
    json["buffers"][0]["uri"] = "data:application/octet-stream;base64,@@@@".into();
    let err = Scene::from_slice(&serde_json::to_vec(&json).unwrap(), None).unwrap_err();
    assert!(
        err.to_string()
            .contains("buffers[0]: the data URI's base64 is malformed"),
        "{err}"
    );
}

/// Fuzz finding (read_gltf): a POSITION naming a missing accessor made the typed validator
/// index out of bounds; it is refused, named.
#[test]
fn fuzz_position_of_a_missing_accessor() {
    let (mut json, bin) = triangle_doc();
    json["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7.into();
    let msg = refusal(&json, &bin);
    assert!(
        msg.contains("meshes[0].primitives[0].attributes.POSITION: accessors[7] does not exist"),
        "{msg}"
    );
    json.as_object_mut().unwrap().remove("accessors");
    json["meshes"][0]["primitives"][0]
        .as_object_mut()
        .unwrap()
        .remove("indices");
    json["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 0.into();
    let msg = refusal(&json, &bin);
    assert!(
        msg.contains("accessors[0] does not exist (0 accessors)"),
        "{msg}"
    );
}

/// Fuzz finding (read_gltf): a rotation of 3.8e42 is infinite in f32, and made the world
/// transform NaN; non-finite transforms and zero quaternions are refused, named.
#[test]
fn fuzz_non_finite_node_transform() {
    let (mut json, bin) = triangle_doc();
    json["nodes"][0]["rotation"] = json!([0.0, 0.0, 3.8268e42, 0.92]);
    let msg = refusal(&json, &bin);
    assert!(
        msg.contains("nodes[0].rotation: a value is not finite as f32"),
        "{msg}"
    );
    json["nodes"][0]["rotation"] = json!([0.0, 0.0, 0.0, 0.0]);
    assert!(refusal(&json, &bin).contains("nodes[0].rotation: the quaternion has length 0"));
    // Nine nested scales of 1e38 overflow f64 (each is finite in f32).
    json["nodes"][0].as_object_mut().unwrap().remove("rotation");
    let mut nodes: Vec<Value> = (0..9)
        .map(|i| json!({"children": [i + 1], "scale": [1e38, 1.0, 1.0]}))
        .collect();
    nodes.push(json!({"mesh": 0}));
    json["nodes"] = Value::Array(nodes);
    let msg = refusal(&json, &bin);
    assert!(msg.contains("its world transform overflows"), "{msg}");
}

#[test]
fn replacement_attributes_are_written_per_corner() {
    use envelope_mesh::Wedges;
    let mut scene = Scene::from_slice(&sample::scene(1, 8, 4), None).unwrap();
    let tet = f32_soup(&generate::tetrahedron());
    // A texture seam: face 0 gives vertex 0 another uv than the other faces do.
    let texcoords = Wedges {
        values: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.5], [0.25, 0.75]],
        corners: vec![[4, 1, 2], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    };
    let colors = Wedges {
        values: vec![[1.0, 0.0, 0.0, 1.0], [0.0, 0.5, 1.0, 0.25]],
        corners: vec![[0, 0, 0], [1, 1, 1], [0, 1, 0], [1, 0, 1]],
    };
    let normals = Wedges {
        values: vec![[0.0, 0.0, 2.0]],
        corners: vec![[0, 0, 0]; 4],
    };
    let attributes = Attributes {
        texcoords: Some(texcoords.clone()),
        normals: Some(normals),
        colors: Some(colors.clone()),
        quality: None,
    };
    scene
        .replace(
            0,
            Geometry {
                soup: tet.clone(),
                attributes,
            },
        )
        .unwrap();
    let back = Scene::from_slice(&scene.to_glb().unwrap(), None).unwrap();
    let p = &back.primitives()[0];
    assert_eq!(p.soup(), &tet);
    let a = p.attributes();
    for f in 0..4 {
        for k in 0..3 {
            assert_eq!(
                a.texcoords.as_ref().unwrap().value(f, k),
                texcoords.value(f, k)
            );
            assert_eq!(a.colors.as_ref().unwrap().value(f, k), colors.value(f, k));
            // Written normalized, as glTF requires unit normals.
            assert_eq!(a.normals.as_ref().unwrap().value(f, k), [0.0, 0.0, 1.0]);
        }
    }
    // The seams split vertices: more glTF vertices than positions.
    assert!(a.texcoords.as_ref().unwrap().values.len() > tet.num_vertices());
}
