//! glTF scenes through the front door: simplified and levels of detail, certified after
//! rounding to f32, transforms and images kept.

use envelope::advanced::gltf::{Scene, sample};
use envelope::{Epsilon, EpsilonScope, Error, SceneLod, SceneSimplifier};
use serde_json::{Value, json};

/// The sample GLB with its JSON changed by `edit`.
fn edited(glb: &[u8], edit: impl Fn(&mut Value)) -> Vec<u8> {
    let len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let mut doc: Value = serde_json::from_slice(&glb[20..20 + len]).unwrap();
    edit(&mut doc);
    let bin = &glb[20 + len + 8..];
    let mut text = serde_json::to_vec(&doc).unwrap();
    text.resize(text.len().next_multiple_of(4), b' ');
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&((28 + text.len() + bin.len()) as u32).to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    out
}

#[test]
fn glb_to_glb_every_primitive_certified_after_rounding() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.glb");
    std::fs::write(&input, sample::scene(3, 32, 12)).unwrap();
    let scene = envelope::load_scene(&input).unwrap();
    let done = SceneSimplifier::new(Epsilon::percent(1.0))
        .threads(1)
        .run(&scene)
        .unwrap();
    assert!(done.is_certified());
    let output = dir.path().join("out.glb");
    envelope::save_scene(&done.scene, &output).unwrap();
    let back = envelope::load_scene(&output).unwrap();
    assert_eq!(back.json()["nodes"], scene.json()["nodes"]);
    assert_eq!(back.instances(), scene.instances());
    let view = back.json()["images"][0]["bufferView"].as_u64().unwrap() as usize;
    assert_eq!(back.view_bytes(view).unwrap(), &sample::PNG);
    for ((orig, out), report) in scene
        .primitives()
        .iter()
        .zip(back.primitives())
        .zip(&done.primitives)
    {
        if !orig.is_triangles() {
            assert!(report.kept.is_some());
            assert_eq!(out.mode(), orig.mode());
            continue;
        }
        assert_eq!(
            report.epsilon,
            Epsilon::percent(1.0).resolve_for_diagonal(orig.soup().diagonal())
        );
        assert!(
            out.soup().num_faces() < orig.soup().num_faces() / 2,
            "{}",
            report.label
        );
        assert_eq!(out.soup().num_faces(), report.faces_out);
        // The file's own f32 triangles, certified again here.
        let a = envelope::Mesh::from_soup(orig.soup().clone());
        let b = envelope::Mesh::from_soup(out.soup().clone());
        let c = envelope::verify(&a, &b, Epsilon::absolute(report.epsilon)).unwrap();
        assert!(c.holds(), "{}: {:?}", report.label, c.violations());
        // The sphere had normals: the output has them too.
        assert_eq!(
            out.attributes().normals.is_some(),
            orig.attributes().normals.is_some()
        );
    }
}

#[test]
fn scene_scope_divides_by_the_node_scale() {
    let scene = Scene::from_slice(&sample::scene(2, 16, 8), None).unwrap();
    let done = SceneSimplifier::new(Epsilon::percent(1.0))
        .scope(EpsilonScope::Scene)
        .threads(1)
        .run(&scene)
        .unwrap();
    let world = 0.01 * scene.world_diagonal();
    // The sphere is shown at scale 2, the torus at 0.5.
    let sphere = done.primitives[0].epsilon;
    let torus = done.primitives[1].epsilon;
    assert!(
        sphere <= world / 2.0 && sphere > world / 2.0 * 0.999,
        "{sphere} {world}"
    );
    assert!(
        torus <= world / 0.5 && torus > world / 0.5 * 0.999,
        "{torus} {world}"
    );
    assert!(done.is_certified());
}

#[test]
fn lod_file_has_msft_lod_and_level_nodes() {
    let scene = Scene::from_slice(&sample::scene(2, 16, 8), None).unwrap();
    let chains = SceneLod::new(vec![Epsilon::percent(1.0), Epsilon::percent(4.0)])
        .threads(1)
        .run(&scene)
        .unwrap();
    assert!(chains.is_certified());
    let lod = chains.lod_scene().unwrap();
    let back = Scene::from_slice(&lod.to_glb().unwrap(), None).unwrap();
    let j = back.json();
    assert!(
        j["extensionsUsed"]
            .as_array()
            .unwrap()
            .contains(&json!("MSFT_lod"))
    );
    for (node, mesh) in [(1usize, 0usize), (2, 1)] {
        let n = &j["nodes"][node];
        let ids = n["extensions"]["MSFT_lod"]["ids"].as_array().unwrap();
        assert_eq!(ids.len(), 2);
        let cov: Vec<f64> = n["extras"]["MSFT_screencoverage"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert_eq!(cov.len(), 3);
        assert!(
            cov[0] > cov[1] && cov[1] > cov[2] && cov[2] == 0.0,
            "{cov:?}"
        );
        let mut faces = Vec::new();
        for id in ids {
            let level = &j["nodes"][id.as_u64().unwrap() as usize];
            for key in ["translation", "rotation", "scale", "matrix"] {
                assert_eq!(level[key], n[key]);
            }
            let m = level["mesh"].as_u64().unwrap() as usize;
            assert_ne!(m, mesh);
            let p = back.primitives().iter().find(|p| p.mesh() == m).unwrap();
            faces.push(p.soup().num_faces());
        }
        let base = back.primitives().iter().find(|p| p.mesh() == mesh).unwrap();
        assert!(
            base.soup().num_faces() >= faces[0] && faces[0] >= faces[1],
            "{faces:?}"
        );
        assert!(base.soup().num_faces() > faces[1], "{faces:?}");
    }
    let level2 = chains.level_scene(2).unwrap();
    assert_eq!(
        level2.primitives()[1].soup().num_faces(),
        chains.primitives()[1].levels[1].faces
    );
    // The sphere's texture coordinates reach every level, one per corner.
    let sphere = &level2.primitives()[0];
    let uv = sphere
        .attributes()
        .texcoords
        .as_ref()
        .expect("level texcoords");
    assert_eq!(uv.corners.len(), sphere.soup().num_faces());
    assert!(chains.level_scene(3).is_err());
}

#[test]
fn morph_targets_and_skins_are_refused_by_name() {
    let glb = edited(&sample::scene(1, 8, 4), |doc| {
        doc["meshes"][1]["primitives"][0]["targets"] = json!([{"POSITION": 4}]);
    });
    let scene = Scene::from_slice(&glb, None).unwrap();
    let err = SceneSimplifier::new(Epsilon::percent(1.0))
        .run(&scene)
        .unwrap_err();
    assert!(matches!(err, Error::Primitive { .. }));
    let msg = err.to_string();
    assert!(
        msg.contains("meshes[1].primitives[0] (torus)") && msg.contains("morph"),
        "{msg}"
    );
}
