//! Timing of the local simplifier on an icosphere between its own offsets along the vertex
//! normals (radial, exact for a sphere) at ±1% of the bounding-box diagonal.
//!
//! `cargo run --release -p envelope-simplify --example sphere_timing -- [subdivisions] [percent] [greedy|paper|exhaustive]`

use envelope_mesh::{HalfEdgeMesh, generate};
use envelope_predicates::self_intersections;
use envelope_simplify::HoleFilling;
use envelope_simplify::policy::{Barriers, Options, simplify_local};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let sub: u32 = args.get(1).map_or(6, |s| s.parse().expect("subdivisions"));
    let percent: f64 = args.get(2).map_or(1.0, |s| s.parse().expect("percent"));
    let hole_filling = match args.get(3).map_or("greedy", String::as_str) {
        "paper" => HoleFilling::Greedy {
            forced_lookahead: false,
        },
        "exhaustive" => HoleFilling::Exhaustive { max_vertices: 10 },
        _ => HoleFilling::default(),
    };
    let input = generate::icosphere(sub, 1.0);
    let eps = percent / 100.0 * input.diagonal();
    let offset = |s: f64| {
        let mut t = input.clone();
        t.positions.iter_mut().for_each(|p| *p *= s);
        t
    };
    let t0 = Instant::now();
    let barriers = Barriers::new(vec![offset(1.0 + eps), offset(1.0 - eps)], vec![]).unwrap();
    let t_barriers = t0.elapsed();
    let mut mesh = HalfEdgeMesh::from_soup(&input).unwrap();
    let t1 = Instant::now();
    let stats = simplify_local(
        &mut mesh,
        &barriers,
        &Options {
            hole_filling,
            ..Options::default()
        },
    )
    .unwrap();
    let t_simplify = t1.elapsed();
    let out = mesh.to_soup();
    let faces: Vec<[u32; 3]> = out.faces.iter().map(|f| f.map(|v| v.0)).collect();
    let pairs = self_intersections(&out.positions, &faces);
    println!(
        "icosphere({sub}): {} faces -> {} faces ({} vertices) with eps = {eps:.5} ({percent}% of diagonal), {hole_filling:?}",
        stats.faces_before, stats.faces_after, stats.vertices_after
    );
    println!(
        "barrier BVH {:.3} s, simplify {:.3} s; attempts {}, removed {}, no valid fill {}, candidate tests {}",
        t_barriers.as_secs_f64(),
        t_simplify.as_secs_f64(),
        stats.attempts,
        stats.removed,
        stats.no_valid_fill,
        stats.candidate_tests
    );
    println!(
        "genus {:?}, self-intersecting pairs {}",
        mesh.topology().genus,
        pairs.len()
    );
}
