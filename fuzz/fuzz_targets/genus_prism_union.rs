//! Genus reduction on random small parts (voxel blocks from a random 4x4x3 occupancy, flat
//! grids with random holes, coarse plates with a slot) at random alphas, from the sharp rims
//! or with the closing's regions (`TessellationSource::Closing`). Checks: inputs the reduction accepts give an
//! output whose half-edge structure passes `sanity_check()` (when the input's builds), with no new intersecting,
//! coincident or non-manifold element (exact `envelope-check`), and every added triangle lies
//! in the union of alpha-prisms: it is covered by its corners' alpha-cubes (exact) and each
//! corner's cube lies in the alpha-prism of an input face at that corner (exact containment;
//! a corner on an input edge with the cube of the closing mode's smaller radius), and every
//! piece of a split input face lies in that face's alpha-prism (`tests/support/prisms.rs` of
//! the genus crate).
#![no_main]

use envelope_check::{CheckOptions, DegeneracyClass, check};
use envelope_genus::testmeshes::{disk_with_square_holes, plate_with_slot};
use envelope_genus::{GenusOptions, TessellationSource, reduce_genus_with};
use envelope_mesh::{HalfEdgeMesh, analyze, generate};
use glam::DVec3;

#[path = "../../crates/genus/tests/support/prisms.rs"]
mod prisms;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if data.len() < 6 {
        return;
    }
    let alpha = f64::from(data[0] % 64 + 1) / 16.0; // 1/16 .. 4
    let beta = 30.0 + f64::from(data[1] % 120);
    let cell = [1.0, 0.5, 0.75, 1.25][usize::from(data[2] % 4)];
    let soup = if data[3] % 4 == 0 {
        let widths: Vec<u32> = data[4..]
            .iter()
            .take(4)
            .map(|b| u32::from(b % 4) + 1)
            .collect();
        disk_with_square_holes(&widths, cell)
    } else if data[3] % 4 == 1 {
        // A coarse plate with a long slot: the closing's caps need points on its rims.
        let length = f64::from(data[4] % 32 + 1) * cell / 2.0;
        let width = f64::from(data[5] % 8 + 1) * cell / 4.0;
        plate_with_slot(length, width, cell)
    } else {
        let bits: Vec<bool> = (0..48)
            .map(|i| data.get(4 + i / 8).is_none_or(|b| b >> (i % 8) & 1 == 1))
            .collect();
        generate::voxel_surface(
            4,
            4,
            3,
            |i, j, k| bits[(i + 4 * (j + 4 * k)) as usize],
            DVec3::splat(cell),
        )
    };
    if soup.num_faces() == 0 {
        return;
    }
    let options = GenusOptions {
        alpha,
        beta_degrees: beta,
    };
    let source = if data[3] & 4 == 0 {
        TessellationSource::SharpEdges
    } else {
        TessellationSource::Closing
    };
    let Ok((out, report)) = reduce_genus_with(&soup, &options, source) else {
        return;
    };
    // Nothing is left open that was closed, and the genus never grows.
    let (topo_in, topo_out) = (analyze(&soup), analyze(&out));
    assert!(
        topo_out.num_border_loops() <= topo_in.num_border_loops(),
        "a loop left open"
    );
    if let (Some(a), Some(b)) = (topo_in.genus, topo_out.genus) {
        assert!(b <= a, "genus grew: {a} -> {b}");
    }
    // Filling only adds material: on a closed input the enclosed volume never shrinks (f64,
    // with room for its rounding).
    if topo_in.num_border_loops() == 0 {
        let volume = |s: &envelope_mesh::TriangleSoup| -> (f64, f64) {
            s.face_ids().fold((0.0, 0.0), |(v, size), f| {
                let [a, b, c] = s.triangle(f);
                let t = a.dot(b.cross(c));
                (v + t, size + t.abs())
            })
        };
        let ((v_in, s_in), (v_out, s_out)) = (volume(&soup), volume(&out));
        let sign = if v_in >= 0.0 { 1.0 } else { -1.0 };
        assert!(
            sign * v_out >= sign * v_in - 1e-9 * (s_in + s_out),
            "material taken away: {v_in} -> {v_out}"
        );
    }
    // Inputs with a non-manifold vertex are accepted (and kept as they are); when the input
    // builds a half-edge mesh, the output must too.
    if out.num_faces() > 0 && HalfEdgeMesh::from_soup(&soup).is_ok() {
        let mesh = HalfEdgeMesh::from_soup(&out).expect("output builds a half-edge mesh");
        mesh.sanity_check().expect("sanity_check");
    }
    let before = check(&soup, &CheckOptions::default());
    let after = check(&out, &CheckOptions::default());
    for class in [
        DegeneracyClass::IntersectingTriangles,
        DegeneracyClass::CoincidentTriangles,
        DegeneracyClass::DuplicateTriangles,
        DegeneracyClass::NonManifoldEdges,
        DegeneracyClass::InconsistentOrientation,
        DegeneracyClass::ZeroAreaTriangles,
    ] {
        assert!(
            after.finding(class).count <= before.finding(class).count,
            "{class:?} added"
        );
    }
    prisms::assert_inside_prisms(&soup, &out, &report, alpha);
});
