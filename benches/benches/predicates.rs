//! Predicate throughput: orient3d and triangle–triangle tests per second on random and on
//! near-degenerate inputs (filtered vs exact kernel), and `self_intersections` on a ~1M-face
//! torus, and the build of a BVH over the faces of a ~140k-face torus (the size of bunny00's
//! barriers). Run: `cargo bench -p envelope-benches --bench predicates`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use envelope_benches::Rng;
use envelope_predicates::bvh::Bvh;
use envelope_predicates::generic::triangles_intersect;
use envelope_predicates::{Exact, Filtered, Kernel, self_intersections};
use glam::DVec3;

const N: usize = 1024;

fn random_quads(r: &mut Rng) -> Vec<[DVec3; 4]> {
    (0..N)
        .map(|_| [r.point(), r.point(), r.point(), r.point()])
        .collect()
}

/// d on the plane abc up to rounding: the adaptive stages are needed.
fn degenerate_quads(r: &mut Rng) -> Vec<[DVec3; 4]> {
    (0..N)
        .map(|_| {
            let (a, b, c) = (r.point(), r.point(), r.point());
            [a, b, c, a + (b - a) * r.unit() + (c - a) * r.unit()]
        })
        .collect()
}

fn random_tri_pairs(r: &mut Rng, degenerate: bool) -> Vec<([DVec3; 3], [DVec3; 3])> {
    (0..N)
        .map(|_| {
            let t1 = [r.point(), r.point(), r.point()];
            let t2 = if degenerate {
                // Vertices snapped onto t1's plane: coplanar up to rounding.
                let mut on = || t1[0] + (t1[1] - t1[0]) * r.unit() + (t1[2] - t1[0]) * r.unit();
                [on(), on(), on()]
            } else {
                let o = r.point();
                [o, o + (r.point() - 0.5) * 0.5, o + (r.point() - 0.5) * 0.5]
            };
            (t1, t2)
        })
        .collect()
}

fn orient3d(c: &mut Criterion) {
    let mut r = Rng(0x9e37_79b9_7f4a_7c15);
    let (rand, degen) = (random_quads(&mut r), degenerate_quads(&mut r));
    let mut g = c.benchmark_group("orient3d");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    g.throughput(Throughput::Elements(N as u64));
    for (name, set) in [("random", &rand), ("near_degenerate", &degen)] {
        g.bench_function(format!("filtered/{name}"), |b| {
            b.iter(|| {
                set.iter()
                    .map(|q| Filtered::orient3d(q[0], q[1], q[2], q[3]) as u8 as u32)
                    .sum::<u32>()
            })
        });
        g.bench_function(format!("exact/{name}"), |b| {
            b.iter(|| {
                set.iter()
                    .map(|q| Exact::orient3d(q[0], q[1], q[2], q[3]) as u8 as u32)
                    .sum::<u32>()
            })
        });
    }
    g.finish();
}

fn tri_tri(c: &mut Criterion) {
    let mut r = Rng(0x1234_5678_9abc_def1);
    let (rand, degen) = (
        random_tri_pairs(&mut r, false),
        random_tri_pairs(&mut r, true),
    );
    let mut g = c.benchmark_group("triangles_intersect");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    g.throughput(Throughput::Elements(N as u64));
    for (name, set) in [("random", &rand), ("near_coplanar", &degen)] {
        g.bench_function(format!("filtered/{name}"), |b| {
            b.iter(|| {
                set.iter()
                    .filter(|(t1, t2)| triangles_intersect::<Filtered>(black_box(*t1), *t2))
                    .count()
            })
        });
        g.bench_function(format!("exact/{name}"), |b| {
            b.iter(|| {
                set.iter()
                    .filter(|(t1, t2)| triangles_intersect::<Exact>(black_box(*t1), *t2))
                    .count()
            })
        });
    }
    g.finish();
}

/// A closed torus of `n x m` quads, two triangles each.
fn torus(n: u32, m: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut pos = Vec::with_capacity((n * m) as usize);
    for i in 0..n {
        let u = f64::from(i) / f64::from(n) * std::f64::consts::TAU;
        for j in 0..m {
            let v = f64::from(j) / f64::from(m) * std::f64::consts::TAU;
            let rr = 2.0 + 0.7 * v.cos();
            pos.push(DVec3::new(rr * u.cos(), rr * u.sin(), 0.7 * v.sin()));
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let mut faces = Vec::with_capacity((2 * n * m) as usize);
    for i in 0..n {
        for j in 0..m {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (pos, faces)
}

fn self_intersect(c: &mut Criterion) {
    let (pos, faces) = torus(1000, 500);
    let mut g = c.benchmark_group("self_intersections");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500));
    g.throughput(Throughput::Elements(faces.len() as u64));
    g.bench_function("torus_1M_faces", |b| {
        b.iter(|| {
            let found = self_intersections(black_box(&pos), &faces);
            assert!(found.is_empty());
            found.len()
        })
    });
    g.finish();
}

fn bvh_build(c: &mut Criterion) {
    let (pos, faces) = torus(350, 200);
    let mut g = c.benchmark_group("bvh_build");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500));
    g.throughput(Throughput::Elements(faces.len() as u64));
    g.bench_function("torus_140k_faces", |b| {
        b.iter(|| {
            let tree = Bvh::from_triangles(black_box(&pos), &faces);
            assert_eq!(tree.len(), faces.len());
            tree.len()
        })
    });
    g.finish();
}

criterion_group!(benches, orient3d, tri_tri, self_intersect, bvh_build);
criterion_main!(benches);
