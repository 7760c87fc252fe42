//! Small meshes on a coarse grid, where duplicate vertices and faces, zero-area faces,
//! T-junctions, non-manifold edges and flipped faces are common: whenever `repair` accepts
//! one, its output must be a valid soup with no face repeating a vertex, and its surface the
//! input's point set (the certificate's two distance directions at a tiny epsilon never
//! violated).
#![no_main]

use arbitrary::Arbitrary;
use envelope_mesh::{TriangleSoup, VertexId};
use envelope_repair::{RepairOptions, repair};
use envelope_verify::{Options, Verdict, certify};
use glam::DVec3;
use libfuzzer_sys::fuzz_target;

#[derive(Arbitrary, Debug)]
struct Input {
    vertices: Vec<[u8; 3]>,
    faces: Vec<[u8; 3]>,
}

fuzz_target!(|input: Input| {
    let positions: Vec<DVec3> = input
        .vertices
        .iter()
        .take(12)
        .map(|v| {
            DVec3::new(
                f64::from(v[0] % 4),
                f64::from(v[1] % 4),
                f64::from(v[2] % 3),
            )
        })
        .collect();
    if positions.len() < 3 {
        return;
    }
    let n = positions.len() as u32;
    let faces: Vec<[VertexId; 3]> = input
        .faces
        .iter()
        .take(16)
        .map(|f| f.map(|i| VertexId(u32::from(i) % n)))
        .collect();
    if faces.is_empty() {
        return;
    }
    let soup = TriangleSoup::new(positions, faces);
    let Ok((repaired, _report)) = repair(&soup, &RepairOptions::default()) else {
        return;
    };
    for f in &repaired.faces {
        assert!(
            f.iter().all(|v| v.index() < repaired.num_vertices()),
            "{f:?}"
        );
        assert!(
            f[0] != f[1] && f[1] != f[2] && f[0] != f[2],
            "a face repeats a vertex: {f:?}"
        );
    }
    let diagonal = soup.diagonal();
    if diagonal == 0.0 || repaired.num_faces() == 0 {
        return;
    }
    let c = certify(&soup, &repaired, &Options::new(1e-9 * diagonal));
    assert_ne!(
        c.approx_to_orig.verdict,
        Verdict::Violated,
        "repair moved the surface: {soup:?} -> {repaired:?}"
    );
    assert_ne!(
        c.orig_to_approx.verdict,
        Verdict::Violated,
        "repair lost surface: {soup:?} -> {repaired:?}"
    );
});
