//! The genus after reduction against an independent voxel closing (issue 37): on generated
//! parts with known tunnel sizes (plates with holes of several widths, blocks with tunnels, a
//! cheese-like block of crossing tunnels), the output genus is at most the closing's genus
//! plus `max(1, genus_in / 10)`, and the output is closed, manifold, free of intersections
//! (`envelope-check`) with every added triangle inside the alpha-prisms.

mod support;

use envelope_check::{CheckOptions, DegeneracyClass, check};
use envelope_genus::testmeshes::{plate_with_slot, plate_with_square_holes};
use envelope_genus::{GenusOptions, GenusReport, TessellationSource, reduce_genus_with};
use envelope_mesh::{TriangleSoup, analyze, generate};
use glam::DVec3;
use proptest::prelude::*;
use support::prisms::assert_inside_prisms;
use support::voxel_closing::{closing_genus, voxel_genus};

/// Runs the reduction (both sources) and asserts what must always hold; returns the output
/// genus of each source.
fn certified(
    soup: &TriangleSoup,
    alpha: f64,
    source: TessellationSource,
) -> (TriangleSoup, GenusReport) {
    let (out, report) = reduce_genus_with(soup, &GenusOptions::new(alpha), source).unwrap();
    let c = check(&out, &CheckOptions::default());
    for class in [
        DegeneracyClass::IntersectingTriangles,
        DegeneracyClass::CoincidentTriangles,
        DegeneracyClass::DuplicateTriangles,
        DegeneracyClass::NonManifoldEdges,
        DegeneracyClass::NonManifoldVertices,
        DegeneracyClass::InconsistentOrientation,
        DegeneracyClass::ZeroAreaTriangles,
    ] {
        assert_eq!(c.finding(class).count, 0, "{class:?} in the output");
    }
    assert!(c.manifold, "output not manifold");
    let topo = analyze(&out);
    assert_eq!(topo.num_border_loops(), 0, "output not closed");
    // Filling only adds material (the closing contains the solid).
    let volume = |s: &TriangleSoup| -> f64 {
        s.face_ids()
            .map(|f| {
                let [a, b, c] = s.triangle(f);
                a.dot(b.cross(c))
            })
            .sum()
    };
    let (v_in, v_out) = (volume(soup), volume(&out));
    assert!(
        v_out >= v_in - 1e-9 * v_in.abs(),
        "volume {v_in} -> {v_out}: material taken away"
    );
    assert_eq!(report.genus_out, topo.genus);
    assert_inside_prisms(soup, &out, &report, alpha);
    (out, report)
}

/// The target of issue 37: at most the closing's genus plus `max(1, genus_in / 10)`.
fn assert_near_closing(soup: &TriangleSoup, alpha: f64, h: f64, source: TessellationSource) {
    let g_in = i64::from(analyze(soup).genus.unwrap());
    assert_eq!(
        voxel_genus(soup, h),
        g_in,
        "the voxelization sees the input genus"
    );
    let closed = closing_genus(soup, alpha, h);
    let (_, r) = certified(soup, alpha, source);
    let g_out = i64::from(r.genus_out.unwrap());
    assert!(g_out <= g_in, "genus grew: {g_in} -> {g_out}");
    let slack = (g_in / 10).max(1);
    assert!(
        g_out <= closed + slack,
        "{source:?} alpha {alpha}: genus {g_in} -> {g_out}, closing {closed} (+{slack} allowed); {r:?}"
    );
}

/// A `nx x ny x nz` block of unit cells with straight square tunnels: `(axis, a, b, w)` runs
/// along `axis` through the cells whose other two coordinates are in `[a, a + w) x [b, b + w)`.
fn block_with_tunnels(n: [u32; 3], tunnels: &[(usize, u32, u32, u32)]) -> TriangleSoup {
    let tunnels = tunnels.to_vec();
    generate::voxel_surface(
        n[0],
        n[1],
        n[2],
        move |i, j, k| {
            let c = [i, j, k];
            !tunnels.iter().any(|&(axis, a, b, w)| {
                let (u, v) = (c[(axis + 1) % 3], c[(axis + 2) % 3]);
                u >= a && u < a + w && v >= b && v < b + w
            })
        },
        DVec3::ONE,
    )
}

/// A cheese-like block: 1-cell tunnels along z on every other column and along x on every
/// other row, crossing each other (a network of many close tunnels sharing walls).
fn cheese_block(m: u32) -> TriangleSoup {
    let n = 2 * m + 1;
    generate::voxel_surface(
        n,
        n,
        n,
        |i, j, k| {
            let z_tunnel = i % 2 == 1 && j % 2 == 1;
            let x_tunnel = j % 2 == 1 && k % 2 == 1 && k > 1 && k + 2 < n;
            !(z_tunnel || x_tunnel)
        },
        DVec3::ONE,
    )
}

#[test]
fn voxel_closing_counts_known_parts() {
    // The helper itself: a plate with holes 1, 2 and 4 wide keeps the holes at least 2 alpha
    // wide (closing radius alpha).
    let plate = plate_with_square_holes(&[1, 2, 4], 1, 1.0);
    assert_eq!(voxel_genus(&plate, 0.25), 3);
    assert_eq!(closing_genus(&plate, 0.75, 0.25), 2);
    assert_eq!(closing_genus(&plate, 1.25, 0.25), 1);
    assert_eq!(closing_genus(&plate, 2.5, 0.25), 0);
    assert_eq!(closing_genus(&plate, 0.25, 0.25), 3);
    let torus = generate::torus(1.0, 0.4, 48, 24);
    assert_eq!(voxel_genus(&torus, 0.05), 1);
    assert_eq!(closing_genus(&torus, 0.1, 0.05), 1);
    assert_eq!(closing_genus(&torus, 0.5, 0.05), 0);
}

#[test]
fn plate_with_holes_of_several_widths() {
    let plate = plate_with_square_holes(&[1, 1, 2, 3, 5], 1, 1.0);
    for alpha in [0.75, 1.25, 1.75, 3.0] {
        for source in [TessellationSource::SharpEdges, TessellationSource::Closing] {
            assert_near_closing(&plate, alpha, 0.25, source);
        }
    }
}

#[test]
fn block_with_tunnels_along_three_axes() {
    let block = block_with_tunnels(
        [9, 9, 6],
        &[
            (2, 1, 1, 1),
            (2, 4, 1, 2),
            (2, 1, 5, 3),
            (0, 6, 2, 1),
            (1, 1, 7, 1),
        ],
    );
    assert!(analyze(&block).genus.unwrap() >= 5);
    for alpha in [0.75, 1.25] {
        for source in [TessellationSource::SharpEdges, TessellationSource::Closing] {
            assert_near_closing(&block, alpha, 0.25, source);
        }
    }
}

#[test]
fn cheese_block_of_crossing_tunnels() {
    let cheese = cheese_block(3);
    let g = analyze(&cheese).genus.unwrap();
    assert!(g >= 10, "genus {g}");
    for alpha in [0.75] {
        for source in [
            TessellationSource::SharpEdges,
            TessellationSource::PrismUnion,
            TessellationSource::Closing,
        ] {
            assert_near_closing(&cheese, alpha, 0.25, source);
        }
    }
}

#[test]
fn the_closing_fills_a_smooth_torus_that_has_no_sharp_rim() {
    // Central hole of radius 0.6 (width 1.2 against the cube's 2 alpha).
    let torus = generate::torus(1.0, 0.4, 48, 24);
    for (alpha, closed) in [(0.75, 0), (0.1, 1)] {
        assert_eq!(closing_genus(&torus, alpha, 0.05), closed);
        let (_, sharp) = certified(&torus, alpha, TessellationSource::SharpEdges);
        assert_eq!(sharp.genus_out, Some(1), "no sharp rim to cap");
        let (_, r) = certified(&torus, alpha, TessellationSource::Closing);
        assert_eq!(r.genus_out, Some(u32::try_from(closed).unwrap()), "{r:?}");
        assert_eq!(r.holes_filled > 0, closed == 0, "{r:?}");
    }
}

#[test]
fn the_closing_never_leaves_more_genus_than_the_sharp_rims() {
    // The closing step runs on the sharp-edge step's output and only fills: on every part
    // here it ends at or below the sharp-edge genus.
    let parts = [
        cheese_block(2),
        plate_with_square_holes(&[1, 2, 3], 1, 1.0),
        block_with_tunnels([9, 9, 6], &[(2, 1, 1, 1), (0, 6, 2, 1), (1, 1, 7, 1)]),
    ];
    for part in &parts {
        for alpha in [0.625, 1.125, 1.875] {
            let (_, sharp) = certified(part, alpha, TessellationSource::SharpEdges);
            let (_, closing) = certified(part, alpha, TessellationSource::Closing);
            assert!(
                closing.genus_out <= sharp.genus_out,
                "alpha {alpha}: closing {:?}, sharp {:?}",
                closing.genus_out,
                sharp.genus_out
            );
        }
    }
}

#[test]
fn a_slot_longer_than_the_cube_is_capped_through_points_on_its_rims() {
    // A slot 1 wide and 8 long; the cube (2 alpha = 1.5) cannot enter it, and its rims are
    // single edges 8 long: a cap on the rim's corners alone has diagonals of 8.
    let plate = plate_with_slot(8.0, 1.0, 1.0);
    let alpha = 0.75;
    assert_eq!(closing_genus(&plate, alpha, 0.05), 0);
    let (_, sharp) = certified(&plate, alpha, TessellationSource::SharpEdges);
    assert_eq!(sharp.genus_out, Some(1), "no cap on the corners alone");
    let (out, r) = certified(&plate, alpha, TessellationSource::Closing);
    assert_eq!(r.genus_out, Some(0), "{r:?}");
    // Points every at most alpha on both long rims and the short ones, top and bottom; the
    // frame triangle on each refined rim edge split into pieces.
    assert!(r.points_added >= 4 * 10, "{r:?}");
    assert_eq!(r.split_faces, 8, "{r:?}");
    assert_eq!(out.num_vertices(), plate.num_vertices() + r.points_added);
    // A wider slot (2 alpha = 0.9 < 1) stays.
    let (_, r) = certified(&plate, 0.45, TessellationSource::Closing);
    assert_eq!((r.genus_out, r.pieces), (Some(1), 0), "{r:?}");
}

/// `cheese.off` of the corpus (`scripts/corpus.sh`): a block with 133 crossing tunnels, cut
/// open by notches and grooves, whose closing at 5 % leaves about genus 1. Face-by-face
/// peeling stopped at genus 80 (the voxels keep strips of tunnel wall near wide openings, and
/// each refused loop gave back one layer of long wall triangles, merging neighbouring
/// mouths); the cells' peeling reaches the target. Missing corpus: skipped, except under CI.
#[test]
fn the_corpus_cheese_at_five_percent_is_near_its_closing() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../.corpus/data/meshes/cheese.off");
    let Ok((cheese, _)) = envelope_io::read_path(&path) else {
        assert!(
            std::env::var_os("CI").is_none(),
            "{} is missing: run scripts/corpus.sh",
            path.display()
        );
        eprintln!("skipped: {} is missing (scripts/corpus.sh)", path.display());
        return;
    };
    let d = cheese.diagonal();
    let alpha = 0.05 * d;
    let g_in = i64::from(analyze(&cheese).genus.unwrap());
    let closed = closing_genus(&cheese, alpha, d / 200.0);
    let (_, r) = certified(&cheese, alpha, TessellationSource::Closing);
    let g_out = i64::from(r.genus_out.unwrap());
    assert!(
        g_out <= closed + g_in / 10,
        "genus {g_in} -> {g_out}, closing {closed}; {r:?}"
    );
    // Caps that avoid the kept edges as diagonals and refine long rim edges fill what
    // capping on rim corners left (genus 11).
    assert!(g_out <= 8, "genus {g_in} -> {g_out}; {r:?}");
    assert!(r.points_added > 0, "{r:?}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, .. ProptestConfig::default() })]

    /// Plates with random hole widths and random alpha: near the closing, always certified.
    #[test]
    fn random_plates_reach_the_closing(
        widths in prop::collection::vec(1u32..5, 1..5),
        thickness in 1u32..3,
        alpha_quarters in 2u32..12,
    ) {
        // alpha in odd multiples of 1/8 keeps 2 alpha off the integer hole widths.
        let alpha = f64::from(alpha_quarters) * 0.25 + 0.125;
        let plate = plate_with_square_holes(&widths, thickness, 1.0);
        assert_near_closing(&plate, alpha, 0.125, TessellationSource::SharpEdges);
    }

    /// Blocks with random straight tunnels along z: near the closing, always certified.
    #[test]
    fn random_tunnel_blocks_reach_the_closing(
        spots in prop::collection::vec((0u32..3, 0u32..3, 1u32..3), 1..5),
        alpha_quarters in 2u32..8,
    ) {
        let alpha = f64::from(alpha_quarters) * 0.25 + 0.125;
        // Tunnels on a 4-cell lattice (one-cell walls at least), widths 1 or 2.
        let tunnels: Vec<(usize, u32, u32, u32)> = {
            let mut t: Vec<_> = spots.iter().map(|&(a, b, w)| (2, 1 + 4 * a, 1 + 4 * b, w)).collect();
            t.sort_unstable();
            t.dedup_by_key(|x| (x.1, x.2));
            t
        };
        let block = block_with_tunnels([13, 13, 3], &tunnels);
        assert_near_closing(&block, alpha, 0.125, TessellationSource::SharpEdges);
        assert_near_closing(&block, alpha, 0.125, TessellationSource::Closing);
    }
}
