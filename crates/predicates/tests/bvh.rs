//! BVH queries against brute force, and self-intersection detection on hand-made meshes.

use envelope_predicates::bvh::{Aabb, Bvh, NodeKind};
use envelope_predicates::{faces_intersect, self_intersections};
use glam::DVec3;

struct Lcg(u64);
impl Lcg {
    fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 ^ (self.0 >> 29)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn point(&mut self, s: f64) -> DVec3 {
        DVec3::new(self.unit() * s, self.unit() * s, self.unit() * s)
    }
}

fn random_boxes(g: &mut Lcg, n: usize) -> Vec<Aabb> {
    (0..n)
        .map(|_| {
            let p = g.point(10.0);
            Aabb::from_points(&[p, p + g.point(0.8)])
        })
        .collect()
}

#[test]
fn queries_match_brute_force() {
    let mut g = Lcg(7);
    for n in [0, 1, 3, 5, 17, 300, 9000] {
        let boxes = random_boxes(&mut g, n);
        let bvh = Bvh::new(&boxes);
        assert_eq!(bvh.len(), n);
        let mut brute = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                if boxes[i].overlaps(&boxes[j]) {
                    brute.push((i as u32, j as u32));
                }
            }
        }
        if n <= 300 {
            assert_eq!(bvh.self_pairs(), brute, "n = {n}");
        } else {
            // Large: compare counts and a filtered subset.
            let pairs = bvh.self_pairs();
            assert_eq!(pairs.len(), brute.len());
            assert_eq!(pairs, brute);
        }
        let q = Aabb::from_points(&[DVec3::splat(3.0), DVec3::splat(5.0)]);
        let expect: Vec<u32> = (0..n as u32)
            .filter(|&i| boxes[i as usize].overlaps(&q))
            .collect();
        assert_eq!(bvh.overlapping(&q), expect);
        let other = random_boxes(&mut g, 50);
        let t2 = Bvh::new(&other);
        let mut cross = Vec::new();
        for i in 0..n {
            for j in 0..other.len() {
                if boxes[i].overlaps(&other[j]) {
                    cross.push((i as u32, j as u32));
                }
            }
        }
        assert_eq!(bvh.pairs_with(&t2), cross);
        assert_items_nest(&bvh, &boxes);
    }
}

/// Every node box contains its items' boxes, and every item is in exactly one leaf.
fn assert_items_nest(tree: &Bvh, boxes: &[Aabb]) {
    let mut seen = Vec::new();
    if let Some(root) = tree.root() {
        let mut stack = vec![root];
        while let Some(nd) = stack.pop() {
            let b = tree.bounds(nd);
            match tree.kind(nd) {
                NodeKind::Leaf(items) => {
                    for &i in items {
                        let bi = boxes[i as usize];
                        assert!(b.contains(bi.min) && b.contains(bi.max));
                        seen.push(i);
                    }
                }
                NodeKind::Interior(l, r) => stack.extend([l, r]),
            }
        }
    }
    seen.sort_unstable();
    assert_eq!(seen, (0..boxes.len() as u32).collect::<Vec<_>>());
}

/// `Bvh::join` answers like one tree built over the concatenated boxes (empty sides too).
#[test]
fn joined_trees_match_one_tree() {
    let mut g = Lcg(11);
    for (na, nb) in [(0, 0), (0, 7), (9, 0), (1, 1), (40, 300), (2000, 1500)] {
        let (a, b) = (random_boxes(&mut g, na), random_boxes(&mut g, nb));
        let all: Vec<Aabb> = a.iter().chain(&b).copied().collect();
        let one = Bvh::new(&all);
        let joined = Bvh::join(&Bvh::new(&a), &Bvh::new(&b));
        assert_eq!(joined.len(), na + nb);
        assert_answers_alike(&mut g, &joined, &one, &all, &format!("{na} + {nb}"));
        // The in-place join: the same tree, leaf order and leaf boxes included.
        let grown = Bvh::new(&a).joined(&Bvh::new(&b));
        assert_eq!(grown.leaf_order(), joined.leaf_order(), "{na} + {nb}");
        assert_eq!(grown.leaf_boxes(), joined.leaf_boxes(), "{na} + {nb}");
        assert_answers_alike(&mut g, &grown, &one, &all, &format!("{na} + {nb} in place"));
        // Refitted (children after their parent, as a backward pass needs them).
        let refitted = grown.refit(&all);
        assert_answers_alike(&mut g, &refitted, &one, &all, &format!("{na} + {nb} refit"));
    }
}

/// `tree` answers as `reference` (a tree built over `boxes`): its self pairs, 20 random box
/// queries, its pairs with another random tree both ways; and its items nest in its nodes.
fn assert_answers_alike(g: &mut Lcg, tree: &Bvh, reference: &Bvh, boxes: &[Aabb], label: &str) {
    assert_eq!(tree.self_pairs(), reference.self_pairs(), "{label}");
    for _ in 0..20 {
        let p = g.point(10.0);
        let q = Aabb::from_points(&[p, p + g.point(2.0)]);
        assert_eq!(tree.overlapping(&q), reference.overlapping(&q), "{label}");
    }
    let other = Bvh::new(&random_boxes(g, 60));
    assert_eq!(
        tree.pairs_with(&other),
        reference.pairs_with(&other),
        "{label}"
    );
    assert_eq!(
        other.pairs_with(tree),
        other.pairs_with(reference),
        "{label}"
    );
    assert_items_nest(tree, boxes);
}

/// A tree over `na` random boxes, or (with `nb > 0`) two trees over `na` and `nb` joined, and
/// the boxes of its items in id order.
fn built_or_joined(g: &mut Lcg, na: usize, nb: usize) -> (Bvh, Vec<Aabb>) {
    let (a, b) = (random_boxes(g, na), random_boxes(g, nb));
    let tree = if nb == 0 {
        Bvh::new(&a)
    } else {
        Bvh::join(&Bvh::new(&a), &Bvh::new(&b))
    };
    (tree, a.into_iter().chain(b).collect())
}

/// `Bvh::refit` answers like a tree built over the new boxes, whether they moved a little
/// or were replaced by unrelated ones, on built and joined trees (sizes above the parallel
/// threshold too); `self_pairs_emit` pushes exactly what it is asked to for those pairs.
#[test]
fn refit_trees_match_new_trees_and_emit_matches_pairs() {
    let mut g = Lcg(23);
    for (na, nb) in [(1, 0), (2, 3), (300, 0), (9000, 0), (40, 700), (5000, 3000)] {
        let (tree, old) = built_or_joined(&mut g, na, nb);
        let nudged: Vec<Aabb> = old
            .iter()
            .map(|x| {
                let d = g.point(0.6) - DVec3::splat(0.3);
                Aabb::from_points(&[x.min + d, x.max + d + g.point(0.2)])
            })
            .collect();
        let unrelated = random_boxes(&mut g, old.len());
        // Three copies of every item: the boxes, nudged and unrelated ones.
        let tripled: Vec<Aabb> = old
            .iter()
            .chain(&nudged)
            .chain(&unrelated)
            .copied()
            .collect();
        let tree3 = tree.interleaved(3);
        // The fused form is the same tree.
        assert_eq!(
            format!("{:?}", tree.interleaved_refit(3, &tripled)),
            format!("{:?}", tree3.refit(&tripled))
        );
        for (boxes, tree) in [(&nudged, &tree), (&unrelated, &tree), (&tripled, &tree3)] {
            let refit = tree.refit(boxes);
            let built = Bvh::new(boxes);
            assert_eq!(refit.len(), boxes.len());
            assert_answers_alike(&mut g, &refit, &built, boxes, &format!("{na} + {nb}"));
            let mut twice: Vec<(u32, u32)> = built
                .self_pairs()
                .into_iter()
                .flat_map(|(i, j)| [(i, j), (j, i + 1_000_000)])
                .filter(|&(i, j)| (i + j) % 3 != 0)
                .collect();
            twice.sort_unstable();
            let emitted = refit.self_pairs_emit(|i, j, out| {
                out.extend(
                    [(i, j), (j, i + 1_000_000)]
                        .into_iter()
                        .filter(|&(i, j)| (i + j) % 3 != 0),
                )
            });
            assert_eq!(emitted, twice);
        }
    }
}

#[test]
fn distance_lower_bound_is_a_lower_bound() {
    let mut g = Lcg(9);
    for _ in 0..1000 {
        let b = Aabb::from_points(&[g.point(1.0), g.point(1.0)]);
        let p = g.point(3.0) - DVec3::splat(1.0);
        let lb = b.sq_distance_lower_bound(p);
        let c = p.clamp(b.min, b.max);
        assert!(lb <= (p - c).length_squared() * (1.0 + 1e-15));
        assert!(b.distance_lower_bound(p) <= (p - c).length());
        assert!(
            b.inflated(0.1)
                .contains(c + (p - c).normalize_or_zero() * 0.1)
        );
    }
}

/// A torus of `n x m` quads split into triangles (closed, no self-intersections).
fn torus(n: u32, m: u32, r_major: f64, r_minor: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut pos = Vec::new();
    for i in 0..n {
        let u = i as f64 / n as f64 * std::f64::consts::TAU;
        for j in 0..m {
            let v = j as f64 / m as f64 * std::f64::consts::TAU;
            let r = r_major + r_minor * v.cos();
            pos.push(DVec3::new(r * u.cos(), r * u.sin(), r_minor * v.sin()));
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..m {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (pos, faces)
}

fn brute_self_intersections(pos: &[DVec3], faces: &[[u32; 3]]) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for i in 0..faces.len() {
        for j in i + 1..faces.len() {
            if faces_intersect(pos, faces[i], faces[j]) {
                out.push((i as u32, j as u32));
            }
        }
    }
    out
}

#[test]
fn torus_is_clean_and_a_dent_is_found() {
    let (mut pos, faces) = torus(24, 12, 2.0, 0.7);
    assert!(self_intersections(&pos, &faces).is_empty());
    assert!(brute_self_intersections(&pos, &faces).is_empty());
    // Push one vertex through the opposite side of the tube.
    pos[0] = DVec3::new(1.0, 0.0, 0.0);
    let found = self_intersections(&pos, &faces);
    assert!(!found.is_empty());
    assert_eq!(found, brute_self_intersections(&pos, &faces));
}

#[test]
fn flat_grid_fold_and_duplicate_faces() {
    // A 3x3 vertex grid in z = 0, 8 faces.
    let mut pos: Vec<DVec3> = (0..9)
        .map(|k| DVec3::new((k % 3) as f64, (k / 3) as f64, 0.0))
        .collect();
    let mut faces = Vec::new();
    for y in 0..2u32 {
        for x in 0..2u32 {
            let v = y * 3 + x;
            faces.push([v, v + 1, v + 4]);
            faces.push([v, v + 4, v + 3]);
        }
    }
    assert!(self_intersections(&pos, &faces).is_empty());
    // Fold: move the centre vertex across the diagonal so neighbours overlap in the plane.
    pos[4] = DVec3::new(-0.5, -0.4, 0.0);
    let found = self_intersections(&pos, &faces);
    assert!(!found.is_empty());
    assert_eq!(found, brute_self_intersections(&pos, &faces));
    // A duplicated face always counts.
    pos[4] = DVec3::new(1.0, 1.0, 0.0);
    faces.push(faces[0]);
    assert_eq!(self_intersections(&pos, &faces), vec![(0, 8)]);
}

#[test]
fn random_soups_match_brute_force() {
    let mut g = Lcg(11);
    for _ in 0..5 {
        let pos: Vec<DVec3> = (0..120).map(|_| g.point(4.0)).collect();
        let faces: Vec<[u32; 3]> = (0..100)
            .map(|_| {
                let mut f = [0u32; 3];
                for v in &mut f {
                    *v = (g.unit() * 120.0) as u32;
                }
                f
            })
            .collect();
        assert_eq!(
            self_intersections(&pos, &faces),
            brute_self_intersections(&pos, &faces)
        );
    }
}

/// `Bvh::refit_items` is the refit to every item's box with a few of them moved: the same
/// tree to the last node bound, on built and joined trees, with no item, one, a few and
/// half of them moved a little or far. Fails when a leaf holding a moved item keeps its
/// old bound or an interior node is not refitted.
#[test]
fn refit_items_is_a_refit_to_every_box() {
    let mut g = Lcg(41);
    for (na, nb) in [(1, 0), (5, 4), (300, 0), (9000, 0), (40, 700), (2000, 1500)] {
        let (tree, old) = built_or_joined(&mut g, na, nb);
        let n = old.len();
        for share in [0, 1, 3, n / 2] {
            let mut new = old.clone();
            let mut moved = Vec::new();
            for k in 0..share.min(n) {
                // Distinct items: a stride through the ids.
                let i = ((k * 7919) % n) as u32;
                if moved.iter().any(|&(j, _)| j == i) {
                    continue;
                }
                let far = k % 2 == 1;
                let d = if far {
                    g.point(10.0)
                } else {
                    g.point(0.6) - DVec3::splat(0.3)
                };
                let x = old[i as usize];
                new[i as usize] = Aabb::from_points(&[x.min + d, x.max + d]);
                moved.push((i, new[i as usize]));
            }
            assert_eq!(
                format!("{:?}", tree.refit_items(&moved)),
                format!("{:?}", tree.refit(&new)),
                "{na} + {nb}, {} moved",
                moved.len()
            );
        }
    }
}
