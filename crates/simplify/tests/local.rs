//! The local algorithm on meshes whose answer is known by hand, and its guarantees checked by
//! brute force with the exact predicates.

use envelope_mesh::{FaceId, HalfEdgeMesh, TriangleSoup, VertexId, analyze, generate};
use envelope_predicates::{self_intersections, triangles_intersect};
use envelope_simplify::HoleFilling;
use envelope_simplify::policy::{
    BarrierKind, Barriers, CandidateProfile, EnvelopeFilter, Exhaust, Exhaustive, Fifo, Filter,
    Greedy, LocalSimplifier, Options, Policies, Rejection, Stats, simplify_local,
    simplify_local_with,
};
use proptest::prelude::*;

fn mesh(s: &TriangleSoup) -> HalfEdgeMesh {
    HalfEdgeMesh::from_soup(s).unwrap()
}

fn checked() -> Options {
    Options {
        check_each_step: true,
        ..Options::default()
    }
}

/// Raw faces of a soup, for the predicates crate.
fn raw(s: &TriangleSoup) -> Vec<[u32; 3]> {
    s.faces.iter().map(|f| f.map(|v| v.0)).collect()
}

/// Every guarantee of the output, by brute force: the mesh is consistent, has the input's
/// topology, no self-intersection, only input vertices, and no face touches an envelope.
fn assert_guarantees(input: &TriangleSoup, out: &HalfEdgeMesh, barriers: &Barriers) {
    out.sanity_check().unwrap();
    let s = out.to_soup();
    let (t0, t1) = (analyze(input), analyze(&s));
    assert_eq!(
        (t1.genus, t1.components.len(), t1.num_border_loops()),
        (t0.genus, t0.components.len(), t0.num_border_loops()),
        "topology changed"
    );
    assert!(
        self_intersections(&s.positions, &raw(&s)).is_empty(),
        "self-intersection"
    );
    for p in &s.positions {
        assert!(
            input.positions.contains(p),
            "vertex {p} is not an input vertex"
        );
    }
    for f in s.face_ids() {
        let t = s.triangle(f);
        for i in 0..barriers.num_triangles() {
            let (b, kind) = barriers.triangle(i);
            if kind == BarrierKind::Envelope {
                assert!(
                    !triangles_intersect(t, b),
                    "face {f} touches envelope triangle {i}"
                );
            }
        }
    }
}

fn input_clear_of(input: &TriangleSoup, barriers: &Barriers) {
    for f in input.face_ids() {
        assert!(
            !barriers.blocks(input.triangle(f), [false; 3]),
            "input face {f} touches a barrier"
        );
    }
}

// ----------------------------------------------------------------- tetrahedron

#[test]
fn a_tetrahedron_cannot_be_simplified() {
    let s = generate::tetrahedron();
    let mut m = mesh(&s);
    let before = m.clone();
    let stats = simplify_local(&mut m, &Barriers::none(), &checked()).unwrap();
    assert_eq!(stats.removed, 0);
    assert_eq!(stats.attempts, 4);
    assert_eq!(m, before);
}

// ----------------------------------------------------------------- flat plate in a slab

/// An `n x n` grid of the unit square at `z(i, j)`, faces up.
fn plate(n: u32, z: impl Fn(u32, u32) -> f64) -> TriangleSoup {
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            pos.push([
                f64::from(i) / f64::from(n),
                f64::from(j) / f64::from(n),
                z(i, j),
            ]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            faces.push([a, b, c]);
            faces.push([a, c, d]);
        }
    }
    TriangleSoup::from_raw(&pos, &faces)
}

/// A square of two triangles at height `z`, much larger than the unit square.
fn big_square(z: f64) -> TriangleSoup {
    TriangleSoup::from_raw(
        &[
            [-5.0, -5.0, z],
            [6.0, -5.0, z],
            [6.0, 6.0, z],
            [-5.0, 6.0, z],
        ],
        &[[0, 1, 2], [0, 2, 3]],
    )
}

/// A closed square tube (a picture frame) around the border of the unit square: walls at
/// distance `r` in the plane and at height `±r`.
fn frame_tube(r: f64) -> TriangleSoup {
    let square = |lo: f64, hi: f64, z: f64| [[lo, lo, z], [hi, lo, z], [hi, hi, z], [lo, hi, z]];
    let rings = [
        square(-r, 1.0 + r, r),
        square(r, 1.0 - r, r),
        square(r, 1.0 - r, -r),
        square(-r, 1.0 + r, -r),
    ];
    let pos: Vec<[f64; 3]> = rings.iter().flatten().copied().collect();
    let mut faces = Vec::new();
    for k in 0..4u32 {
        for c in 0..4u32 {
            let (a, b) = (4 * k + c, 4 * k + (c + 1) % 4);
            let (d, e) = (4 * ((k + 1) % 4) + c, 4 * ((k + 1) % 4) + (c + 1) % 4);
            faces.push([a, b, e]);
            faces.push([a, e, d]);
        }
    }
    TriangleSoup::from_raw(&pos, &faces)
}

#[test]
fn flat_plate_with_fixed_border_keeps_only_border_vertices() {
    let s = plate(10, |_, _| 0.0);
    let barriers = Barriers::new(vec![big_square(0.01), big_square(-0.01)], vec![]).unwrap();
    input_clear_of(&s, &barriers);
    let mut m = mesh(&s);
    let stats = simplify_local(&mut m, &barriers, &checked()).unwrap();
    // 40 border vertices stay (no tube), every interior one goes: a 40-gon, 38 triangles.
    assert_eq!((m.num_vertices(), m.num_faces()), (40, 38), "{stats:?}");
    assert!(m.vertices().all(|v| m.is_border_vertex(v)));
    assert_guarantees(&s, &m, &barriers);
}

#[test]
fn flat_plate_with_border_tube_reduces_to_two_triangles() {
    let s = plate(10, |_, _| 0.0);
    let barriers = Barriers::new(
        vec![big_square(0.01), big_square(-0.01)],
        vec![frame_tube(0.02)],
    )
    .unwrap();
    input_clear_of(&s, &barriers);
    let mut m = mesh(&s);
    let stats = simplify_local(&mut m, &barriers, &checked()).unwrap();
    // The corners cannot be cut (the grid step 0.1 is more than twice the tube radius).
    assert_eq!((m.num_vertices(), m.num_faces()), (4, 2), "{stats:?}");
    assert_guarantees(&s, &m, &barriers);
}

#[test]
fn barriers_through_the_vertices_freeze_the_plate() {
    // Epsilon 0: the envelopes pass through every vertex; every candidate touches them.
    let s = plate(6, |_, _| 0.0);
    let barriers = Barriers::new(vec![big_square(0.0)], vec![frame_tube(0.02)]).unwrap();
    let mut m = mesh(&s);
    let before = m.clone();
    let stats = simplify_local(&mut m, &barriers, &checked()).unwrap();
    assert_eq!(stats.removed, 0);
    assert_eq!(m, before);
}

#[test]
fn tight_envelopes_around_a_curved_plate_change_nothing() {
    // A paraboloid: removing any vertex moves the surface by at least 0.1 h² = 0.0016 there;
    // the envelopes are the plate moved 0.0002 up and down. (Its grid quads are planar, so
    // only the tube, too thin to cut a corner, keeps the corners.)
    let s = plate(8, |i, j| {
        let (x, y) = (f64::from(i) / 8.0 - 0.5, f64::from(j) / 8.0 - 0.5);
        0.1 * (x * x + y * y)
    });
    let shifted = |dz: f64| {
        let mut t = s.clone();
        t.positions.iter_mut().for_each(|p| p.z += dz);
        t
    };
    let barriers = Barriers::new(
        vec![shifted(0.0002), shifted(-0.0002)],
        vec![frame_tube(0.06)],
    )
    .unwrap();
    input_clear_of(&s, &barriers);
    let mut m = mesh(&s);
    let before = m.clone();
    let stats = simplify_local(&mut m, &barriers, &checked()).unwrap();
    assert_eq!(stats.removed, 0, "{stats:?}");
    assert_eq!(m, before);
    // With room (0.01) it simplifies.
    let barriers =
        Barriers::new(vec![shifted(0.01), shifted(-0.01)], vec![frame_tube(0.1)]).unwrap();
    let stats = simplify_local(&mut m, &barriers, &checked()).unwrap();
    assert!(stats.removed > 40, "{stats:?}");
    assert_guarantees(&s, &m, &barriers);
}

// ----------------------------------------------------------------- spheres

fn sphere_barriers(eps: f64) -> Barriers {
    Barriers::new(
        vec![
            generate::icosphere(4, 1.0 + eps),
            generate::icosphere(4, 1.0 - eps),
        ],
        vec![],
    )
    .unwrap()
}

#[test]
fn icosphere_between_concentric_spheres() {
    let s = generate::icosphere(3, 1.0);
    let mut removed = Vec::new();
    for eps in [0.1, 0.03, 0.01] {
        let barriers = sphere_barriers(eps);
        input_clear_of(&s, &barriers);
        let mut m = mesh(&s);
        let stats = simplify_local(&mut m, &barriers, &Options::default()).unwrap();
        assert_guarantees(&s, &m, &barriers);
        removed.push(stats.removed);
    }
    assert!(
        removed[0] > removed[1] && removed[1] > removed[2],
        "{removed:?}"
    );
    assert!(removed[0] > 500, "{removed:?} of 642 vertices");
}

#[test]
fn sanity_checks_hold_after_every_step() {
    let s = generate::icosphere(2, 1.0);
    let mut m = mesh(&s);
    let barriers = sphere_barriers(0.05);
    let stats = simplify_local(&mut m, &barriers, &checked()).unwrap();
    assert!(stats.removed > 0);
    assert_guarantees(&s, &m, &barriers);
}

// ----------------------------------------------------------------- topology

#[test]
fn torus_stays_genus_one() {
    let s = generate::torus(2.0, 0.5, 24, 12);
    let barriers = Barriers::new(
        vec![
            generate::torus(2.0, 0.62, 48, 24),
            generate::torus(2.0, 0.38, 48, 24),
        ],
        vec![],
    )
    .unwrap();
    input_clear_of(&s, &barriers);
    let mut m = mesh(&s);
    let stats = simplify_local(&mut m, &barriers, &checked()).unwrap();
    assert!(stats.removed > 100, "{stats:?}");
    assert_eq!(m.topology().genus, Some(1));
    assert_guarantees(&s, &m, &barriers);
    // Without any envelope only the topology guard and self-intersection test act.
    let mut m = mesh(&s);
    simplify_local(&mut m, &Barriers::none(), &checked()).unwrap();
    assert_guarantees(&s, &m, &Barriers::none());
}

#[test]
fn plate_with_two_holes_stays_genus_two() {
    let s = generate::plate_with_holes(2);
    let mut m = mesh(&s);
    let stats = simplify_local(&mut m, &Barriers::none(), &checked()).unwrap();
    assert!(stats.removed > 0, "{stats:?}");
    assert_eq!(m.topology().genus, Some(2));
    assert_guarantees(&s, &m, &Barriers::none());
}

#[test]
fn open_cylinder_without_tubes_keeps_its_borders() {
    let s = generate::open_cylinder(1.0, 2.0, 12, 8);
    let mut m = mesh(&s);
    simplify_local(&mut m, &Barriers::none(), &checked()).unwrap();
    assert_guarantees(&s, &m, &Barriers::none());
    assert_eq!(m.num_vertices(), 24, "only the 2 x 12 border vertices stay");
}

// ----------------------------------------------------------------- greedy vs exhaustive

fn octahedron() -> TriangleSoup {
    TriangleSoup::from_raw(
        &[
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ],
        &[
            [4, 0, 1],
            [4, 1, 2],
            [4, 2, 3],
            [4, 3, 0],
            [5, 1, 0],
            [5, 2, 1],
            [5, 3, 2],
            [5, 0, 3],
        ],
    )
}

#[test]
fn exhaustive_fills_where_the_single_pass_gets_stuck() {
    // The square hole of the octahedron's apex: all four candidates have the same aspect
    // ratio, so greedy takes hole positions (0, 1, 2) first and must then place (2, 3, 0),
    // which a base filter forbids. The other triangulation, (0, 1, 3) + (1, 2, 3), is fine.
    let s = octahedron();
    let apex = VertexId(4);
    let hole = mesh(&s).remove_vertex_fan(apex).unwrap();
    let banned = {
        let mut b = [hole[2], hole[3], hole[0]];
        b.sort();
        b
    };
    let ban = move |p: &CandidateProfile<'_>| {
        let mut t = p.triangle;
        t.sort();
        t != banned
    };
    let barriers = Barriers::none();
    let filter = EnvelopeFilter::with_base(&barriers, ban);

    let mut m = mesh(&s);
    let mut m2 = m.clone();
    let before = m.clone();
    let mut local = LocalSimplifier::new(&mut m, false);
    assert_eq!(
        local.try_remove_vertex(apex, &filter, &Greedy::PAPER),
        Err(Rejection::NoValidFill)
    );
    local.sanity_check().unwrap();
    assert_eq!(m, before, "a failed attempt restores the fan exactly");

    let mut local = LocalSimplifier::new(&mut m, false);
    let removal = local
        .try_remove_vertex(apex, &filter, &Exhaustive::default())
        .unwrap();
    assert_eq!(removal.faces.len(), 2);
    local.sanity_check().unwrap();
    assert_eq!((m.num_vertices(), m.num_faces()), (5, 6));
    let got: Vec<[VertexId; 3]> = removal
        .faces
        .iter()
        .map(|&f: &FaceId| {
            let mut t = m.face_vertices(f);
            t.sort();
            t
        })
        .collect();
    assert!(!got.contains(&banned));
    assert_guarantees(&s, &m, &barriers);

    // Whole runs: exhaustive ends with no more faces than greedy on this case.
    let run = |filler: &dyn envelope_simplify::policy::HoleFiller| -> usize {
        let mut m = mesh(&s);
        let policies = Policies {
            filter: &filter,
            order: &Fifo,
            filler,
            stop: &Exhaust,
            keep_border: false,
            keep: &[],
            check_each_step: true,
            fibers: None,
            fiber_test: None,
            collapse: false,
            auto_moving: false,
        };
        simplify_local_with(&mut m, &policies, &mut ()).unwrap();
        assert_guarantees(&s, &m, &barriers);
        m.num_faces()
    };
    assert!(run(&Exhaustive::default()) <= run(&Greedy::PAPER));
    // The forced-triangle look-ahead sees this one coming.
    let mut local = LocalSimplifier::new(&mut m2, false);
    assert!(
        local
            .try_remove_vertex(apex, &filter, &Greedy::default())
            .is_ok()
    );
}

#[test]
fn greedy_and_exhaustive_are_both_valid() {
    let s = generate::icosphere(2, 1.0);
    let barriers = sphere_barriers(0.08);
    let mut out: Vec<Stats> = Vec::new();
    for hole_filling in [
        HoleFilling::default(),
        HoleFilling::Greedy {
            forced_lookahead: false,
        },
        HoleFilling::Exhaustive { max_vertices: 9 },
    ] {
        let mut m = mesh(&s);
        let options = Options {
            hole_filling,
            ..checked()
        };
        out.push(simplify_local(&mut m, &barriers, &options).unwrap());
        assert_guarantees(&s, &m, &barriers);
    }
    assert!(out.iter().all(|st| st.removed > 50), "{out:?}");
}

#[test]
fn deterministic() {
    let s = generate::icosphere(3, 1.0);
    let barriers = sphere_barriers(0.03);
    let run = || {
        let mut m = mesh(&s);
        simplify_local(&mut m, &barriers, &Options::default()).unwrap();
        m.to_soup()
    };
    assert_eq!(run(), run());
}

#[test]
fn stop_rule_and_visitor() {
    #[derive(Default)]
    struct Count {
        attempts: usize,
        removed: usize,
        rejected: usize,
    }
    impl envelope_simplify::policy::Visitor for Count {
        fn on_attempt(&mut self, _: VertexId) {
            self.attempts += 1;
        }
        fn on_removed(&mut self, _: VertexId, _: &[FaceId]) {
            self.removed += 1;
        }
        fn on_rejected(&mut self, _: VertexId, _: Rejection) {
            self.rejected += 1;
        }
    }
    let s = generate::icosphere(3, 1.0);
    let barriers = sphere_barriers(0.05);
    let filter = EnvelopeFilter::new(&barriers);
    let mut m = mesh(&s);
    let mut count = Count::default();
    let policies = Policies {
        filter: &filter,
        order: &Fifo,
        filler: &Greedy::default(),
        stop: &envelope_simplify::policy::TargetFaces(1000),
        keep_border: true,
        keep: &[],
        check_each_step: false,
        fibers: None,
        fiber_test: None,
        collapse: false,
        auto_moving: false,
    };
    let stats = simplify_local_with(&mut m, &policies, &mut count).unwrap();
    assert!(
        m.num_faces() <= 1000 && m.num_faces() >= 998,
        "{}",
        m.num_faces()
    );
    assert_eq!(
        (count.attempts, count.removed, count.rejected),
        (
            stats.attempts,
            stats.removed,
            stats.attempts - stats.removed
        )
    );
}

// ----------------------------------------------------------------- property test

fn perturbed_icosphere(seed: u64, amp: f64) -> TriangleSoup {
    let mut s = generate::icosphere(2, 1.0);
    let mut x = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    for p in &mut s.positions {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let u = (x >> 11) as f64 / (1u64 << 53) as f64; // [0, 1)
        *p *= 1.0 + amp * (2.0 * u - 1.0);
    }
    s
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]
    #[test]
    fn random_spheres_keep_every_guarantee(seed in any::<u64>(), amp in 0.0f64..0.03, e_out in 0.06f64..0.2, e_in in 0.06f64..0.2) {
        let s = perturbed_icosphere(seed, amp);
        let barriers = Barriers::new(
            vec![generate::icosphere(3, 1.0 + e_out), generate::icosphere(3, 1.0 - e_in)],
            vec![],
        ).unwrap();
        input_clear_of(&s, &barriers);
        let mut m = mesh(&s);
        let stats = simplify_local(&mut m, &barriers, &Options::default()).unwrap();
        prop_assert!(stats.removed > 0);
        assert_guarantees(&s, &m, &barriers);
    }
}

// Filters compose: a closure is a filter.
#[test]
fn closures_are_filters() {
    let no = |_: &CandidateProfile<'_>| false;
    let s = generate::icosphere(1, 1.0);
    let mut m = mesh(&s);
    let mut local = LocalSimplifier::new(&mut m, false);
    assert_eq!(
        local.try_remove_vertex(VertexId(0), &no, &Greedy::default()),
        Err(Rejection::NoValidFill)
    );
    let _: &dyn Filter = &no;
}

// ----------------------------------------------------------------- batches and threads

/// The batched FIFO run (default options: removals planned in parallel, carried out in
/// queue order) gives the same mesh for 1 and 3 threads, and keeps every guarantee.
#[test]
fn batched_runs_do_not_depend_on_the_thread_count() {
    use envelope_offset::{EnvelopeMethod, EnvelopeOptions, EpsilonField, build_envelopes};
    // A bumpy sphere: curvature everywhere, so many removals fail and the queue churns.
    let mut s = generate::icosphere(3, 1.0);
    for p in &mut s.positions {
        let bump = 1.0 + 0.05 * (7.0 * p.x).sin() * (5.0 * p.y).cos();
        *p *= bump;
    }
    let mut eo = EnvelopeOptions::new(EpsilonField::Constant(0.02));
    eo.method = EnvelopeMethod::Analytical;
    let env = build_envelopes(&s, &eo).unwrap();
    assert!(env.proof.holds());
    let barriers = Barriers::new(vec![env.outer, env.inner], vec![]).unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut m = mesh(&s);
        let stats = pool.install(|| simplify_local(&mut m, &barriers, &Options::default()));
        (m.to_soup(), stats.unwrap())
    };
    let (one, stats1) = run(1);
    let (three, stats3) = run(3);
    assert!(stats1.removed > 100, "{stats1:?}");
    assert_eq!(one.faces, three.faces);
    assert_eq!(one.positions, three.positions);
    assert_eq!(
        (stats1.attempts, stats1.removed, stats1.candidate_tests),
        (stats3.attempts, stats3.removed, stats3.candidate_tests)
    );
    assert_guarantees(&s, &mesh(&three), &barriers);
}

/// `simplify_local_from`: no seeds, no attempt; every vertex in id order, the same run as
/// `simplify_local`; a few seeds, only those and the vertices re-queued around removals.
#[test]
fn a_seeded_queue_starts_from_its_seeds() {
    let soup = generate::icosphere(2, 1.0);
    let barriers = Barriers::none();
    let options = Options::default();
    let mut none = mesh(&soup);
    let s = envelope_simplify::policy::simplify_local_from(
        &mut none,
        &barriers,
        &options,
        Some(&[]),
        None,
        None,
        &mut (),
    )
    .unwrap();
    assert_eq!((s.attempts, none.num_faces()), (0, soup.num_faces()));
    let all: Vec<VertexId> = mesh(&soup).vertices().collect();
    let (mut a, mut b) = (mesh(&soup), mesh(&soup));
    let sa = envelope_simplify::policy::simplify_local_from(
        &mut a,
        &barriers,
        &options,
        Some(&all),
        None,
        None,
        &mut (),
    )
    .unwrap();
    let sb = simplify_local(&mut b, &barriers, &options).unwrap();
    assert_eq!(sa, sb);
    assert_eq!(a.to_soup(), b.to_soup());
    // One seed without barriers: it goes, and the re-queued ring lets the removals spread,
    // but never to more attempts than a full run.
    let mut one = mesh(&soup);
    let s1 = envelope_simplify::policy::simplify_local_from(
        &mut one,
        &barriers,
        &options,
        Some(&[VertexId(0)]),
        None,
        None,
        &mut (),
    )
    .unwrap();
    assert!(!one.contains_vertex(VertexId(0)));
    assert!(s1.attempts >= 1 && s1.attempts <= sb.attempts + soup.num_vertices());
    one.sanity_check().unwrap();
}
