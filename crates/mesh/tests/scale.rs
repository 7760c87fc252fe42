//! Scale check (ignored by default; run in release):
//! `cargo test --release -p envelope-mesh --test scale -- --ignored --nocapture`.

use envelope_mesh::{HalfEdgeMesh, analyze, degeneracy, generate};
use std::time::Instant;

#[test]
#[ignore = "10 million faces; run in release"]
fn ten_million_faces() {
    let soup = generate::torus(2.0, 0.5, 2500, 2000);
    assert_eq!(soup.num_faces(), 10_000_000);
    let t0 = Instant::now();
    let t = analyze(&soup);
    eprintln!("analyze: {:?}", t0.elapsed());
    assert_eq!(t.genus, Some(1));
    let t0 = Instant::now();
    assert!(degeneracy::non_manifold_vertices(&soup).is_empty());
    eprintln!("non_manifold_vertices: {:?}", t0.elapsed());
    let t0 = Instant::now();
    assert!(degeneracy::duplicate_faces(&soup).is_empty());
    eprintln!("duplicate_faces: {:?}", t0.elapsed());
    let t0 = Instant::now();
    let m = HalfEdgeMesh::from_soup(&soup).unwrap();
    eprintln!("from_soup: {:?}", t0.elapsed());
    let t0 = Instant::now();
    m.sanity_check().unwrap();
    eprintln!("sanity_check: {:?}", t0.elapsed());
}
