//! The exact path's speed: the exact kernel (pure-Rust binary fractions, the default) and,
//! built with `--features gmp`, the GMP kernel in the same run, on inputs that are degenerate
//! up to rounding (where the filters give up and the exact path decides).
//!
//! Run: `cargo run --release -p envelope-benches --features gmp --bin exact_path`.
//! Prints nanoseconds per call (the best of alternating rounds) and the ratio to the first
//! kernel.

use std::hint::black_box;
use std::time::Instant;

use envelope_benches::Rng;
use envelope_predicates::generic::triangles_intersect;
use envelope_predicates::{Exact, Kernel};
use glam::DVec3;

const N: usize = 2000;

struct Inputs {
    quads: Vec<[DVec3; 4]>,
    pairs: Vec<([DVec3; 3], [DVec3; 3])>,
    spheres: Vec<[DVec3; 5]>,
}

fn inputs() -> Inputs {
    let mut r = Rng(0x9e37_79b9_7f4a_7c15);
    let mut quads = Vec::with_capacity(N);
    let mut pairs = Vec::with_capacity(N);
    let mut spheres = Vec::with_capacity(N);
    for _ in 0..N {
        let (a, b, c) = (r.point(), r.point(), r.point());
        let on = |r: &mut Rng| a + (b - a) * r.unit() + (c - a) * r.unit();
        quads.push([a, b, c, on(&mut r)]);
        pairs.push(([a, b, c], [on(&mut r), on(&mut r), on(&mut r)]));
        // Four points on the unit sphere (up to rounding) and a fifth near it.
        let s = |r: &mut Rng| (r.point() - 0.5).normalize_or(DVec3::X);
        spheres.push([s(&mut r), s(&mut r), s(&mut r), s(&mut r), s(&mut r)]);
    }
    Inputs {
        quads,
        pairs,
        spheres,
    }
}

/// Nanoseconds per call of each test on kernel `K`.
fn time<K: Kernel>(x: &Inputs) -> [f64; 3] {
    let per = |start: Instant| start.elapsed().as_nanos() as f64 / N as f64;
    let t = Instant::now();
    let o: u32 = x
        .quads
        .iter()
        .map(|q| K::orient3d(q[0], q[1], q[2], black_box(q[3])) as u8 as u32)
        .sum();
    let orient = per(t);
    let t = Instant::now();
    let i = x
        .pairs
        .iter()
        .filter(|(p, q)| triangles_intersect::<K>(black_box(*p), *q))
        .count();
    let tri = per(t);
    let t = Instant::now();
    let s: u32 = x
        .spheres
        .iter()
        .map(|p| K::insphere(p[0], p[1], p[2], p[3], black_box(p[4])) as u8 as u32)
        .sum();
    let sphere = per(t);
    black_box((o, i, s));
    [orient, tri, sphere]
}

/// A kernel's name and its timing.
type Timed = (&'static str, fn(&Inputs) -> [f64; 3]);

/// The GMP kernel, when built in.
#[cfg(feature = "gmp")]
fn gmp() -> Option<Timed> {
    Some(("ExactGmp (rug)", time::<envelope_predicates::ExactGmp>))
}

#[cfg(not(feature = "gmp"))]
fn gmp() -> Option<Timed> {
    None
}

fn main() {
    let x = inputs();
    let mut kernels: Vec<Timed> = vec![("Exact (pure Rust)", time::<Exact>)];
    kernels.extend(gmp());
    let mut best = vec![[f64::INFINITY; 3]; kernels.len()];
    for _round in 0..7 {
        for (k, (_, f)) in kernels.iter().enumerate() {
            let t = f(&x);
            for j in 0..3 {
                best[k][j] = best[k][j].min(t[j]);
            }
        }
    }
    println!(
        "exact path, {N} inputs degenerate up to rounding, ns per call (best of 7 alternating rounds)"
    );
    println!(
        "{:<20} {:>12} {:>12} {:>12}",
        "kernel", "orient3d", "tri-tri", "insphere"
    );
    for (k, (name, _)) in kernels.iter().enumerate() {
        println!(
            "{:<20} {:>12.0} {:>12.0} {:>12.0}",
            name, best[k][0], best[k][1], best[k][2]
        );
    }
    for (k, (name, _)) in kernels.iter().enumerate().skip(1) {
        println!(
            "{name} / {}: orient3d {:.2}, tri-tri {:.2}, insphere {:.2}",
            kernels[0].0,
            best[k][0] / best[0][0],
            best[k][1] / best[0][1],
            best[k][2] / best[0][2]
        );
    }
    if kernels.len() == 1 {
        println!("(build with --features gmp for the GMP kernel in the same run)");
    }
}
