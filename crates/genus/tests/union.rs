//! The union-of-alpha-prisms tessellation source (sections 3.3, 4): narrow passages through
//! smooth surfaces, which the sharp-edge source cannot see.

use envelope_check::{CheckOptions, DegeneracyClass, check};
use envelope_genus::details::covered_by_corner_cubes;
use envelope_genus::{GenusOptions, TessellationSource, reduce_genus_with};
use envelope_mesh::{TriangleSoup, analyze, generate};

/// A smooth torus: central hole of radius `major - minor = 0.3` (width 0.6), no sharp edge.
fn torus() -> TriangleSoup {
    generate::torus(1.0, 0.7, 32, 16)
}

fn run(soup: &TriangleSoup, alpha: f64, source: TessellationSource) -> TriangleSoup {
    let (out, report) = reduce_genus_with(soup, &GenusOptions::new(alpha), source).unwrap();
    let topo = analyze(&out);
    assert_eq!(report.genus_out, topo.genus);
    assert!(
        topo.manifold && topo.consistently_oriented,
        "{source:?} at {alpha}"
    );
    assert_eq!(topo.num_border_loops(), 0);
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
        assert_eq!(
            c.finding(class).count,
            0,
            "{source:?} at {alpha}: {class:?}"
        );
    }
    for &f in &report.added_faces {
        assert!(covered_by_corner_cubes(out.triangle(f), alpha));
    }
    assert!(topo.genus <= analyze(soup).genus);
    out
}

#[test]
fn union_mode_fills_the_narrow_hole_of_a_smooth_torus() {
    let t = torus();
    assert_eq!(analyze(&t).genus, Some(1));
    // 2 alpha = 1.0 > the hole's width 0.6: filled in union mode only.
    let out = run(&t, 0.5, TessellationSource::PrismUnion);
    assert_eq!(analyze(&out).genus, Some(0));
    assert_eq!(analyze(&out).components.len(), 1);
    assert!(out.num_faces() < t.num_faces());
    let out = run(&t, 0.5, TessellationSource::SharpEdges);
    assert_eq!(analyze(&out).genus, Some(1));
    assert_eq!(out.num_faces(), t.num_faces());
}

#[test]
fn union_mode_keeps_a_hole_wider_than_the_cube() {
    let t = torus();
    // 2 alpha = 0.2 < 0.6: nothing is swallowed, the torus comes back unchanged.
    for source in [
        TessellationSource::PrismUnion,
        TessellationSource::SharpEdges,
    ] {
        let out = run(&t, 0.1, source);
        assert_eq!(analyze(&out).genus, Some(1));
        assert_eq!(out.faces, t.faces);
    }
    let (_, report) =
        reduce_genus_with(&t, &GenusOptions::new(0.1), TessellationSource::PrismUnion).unwrap();
    assert_eq!(report.swallowed_faces, 0);
}

#[test]
fn union_mode_does_not_eat_material() {
    // A thin torus tube (diameter 0.2) with a wide hole (width 1.8): the two sides of the
    // tube are within 2 alpha but face away from each other.
    let t = generate::torus(1.0, 0.1, 48, 12);
    let (out, report) =
        reduce_genus_with(&t, &GenusOptions::new(0.3), TessellationSource::PrismUnion).unwrap();
    assert_eq!(report.swallowed_faces, 0);
    assert_eq!(out.faces, t.faces);
}

#[test]
fn union_mode_fills_a_narrower_hole_at_a_smaller_alpha() {
    // Hole width 0.3, a different tessellation: filled at 2 alpha = 0.6, kept at 0.1.
    let t = generate::torus(1.0, 0.85, 40, 20);
    assert_eq!(
        analyze(&run(&t, 0.3, TessellationSource::PrismUnion)).genus,
        Some(0)
    );
    assert_eq!(
        analyze(&run(&t, 0.3, TessellationSource::SharpEdges)).genus,
        Some(1)
    );
    assert_eq!(
        analyze(&run(&t, 0.05, TessellationSource::PrismUnion)).genus,
        Some(1)
    );
}
