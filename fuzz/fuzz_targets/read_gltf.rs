//! The glTF reader on a generated scene with bytes overwritten where the input says (pairs
//! of a little-endian u16 offset and a byte; in the JSON chunk or in the binary one), and on
//! the input itself. Oracle: whatever the reader accepts, the writer writes, and reading that
//! back gives the same primitives (soups, attributes, modes) and the same instances; no
//! panic on anything refused. A failure prints the input as a pasteable Rust byte string.
#![no_main]

use std::sync::OnceLock;

use envelope_gltf::{Scene, sample};

fn check(bytes: &[u8]) -> Result<(), String> {
    let Ok(scene) = Scene::from_slice(bytes, None) else {
        return Ok(());
    };
    let written = scene
        .to_glb()
        .map_err(|e| format!("accepted, not written: {e}"))?;
    let back = Scene::from_slice(&written, None).map_err(|e| format!("written, refused: {e}"))?;
    if back.primitives().len() != scene.primitives().len() {
        return Err("a different number of primitives".into());
    }
    for (a, b) in scene.primitives().iter().zip(back.primitives()) {
        if a.soup() != b.soup() || a.attributes() != b.attributes() || a.mode() != b.mode() {
            return Err(format!("{} changed in the round trip", a.label()));
        }
    }
    if scene.instances() != back.instances() {
        return Err("the instances changed in the round trip".into());
    }
    Ok(())
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    static SAMPLE: OnceLock<Vec<u8>> = OnceLock::new();
    let mut glb = SAMPLE.get_or_init(|| sample::scene(0, 5, 3)).clone();
    for edit in data.chunks_exact(3) {
        let at = usize::from(u16::from_le_bytes([edit[0], edit[1]])) % glb.len();
        glb[at] = edit[2];
    }
    for bytes in [&glb[..], data] {
        if let Err(why) = check(bytes) {
            envelope_fuzz::fail_with_input(&why, data);
        }
    }
});
