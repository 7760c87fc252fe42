//! Unit tests of the proof and repair rounds and of the numerical growth on part of the mesh,
//! and the crate's test helpers.
use std::sync::atomic::AtomicBool;

use envelope_mesh::{TriangleSoup, VertexFaces, VertexId, generate};
use envelope_predicates::bvh::{Aabb, Bvh};
use glam::DVec3;

use crate::normals;
use crate::numerical::{Near, numerical_eps_ordered, numerical_eps_sorted};
use crate::options::NumericalParams;
use crate::proof::Surface;
use crate::repair::prove_and_repair;

/// Marsaglia's xorshift64 from `seed` (the randomized unit tests of this crate).
pub(crate) fn xorshift(mut state: u64) -> impl FnMut() -> u64 {
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    }
}

fn prepared(soup: &TriangleSoup) -> (Vec<DVec3>, Vec<[u32; 3]>, Bvh) {
    let vf = VertexFaces::new(soup.num_vertices(), &soup.faces);
    let normals = normals::vertex_normals_with(soup, &vf).normals;
    let faces: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
    let tree = Bvh::from_triangles(&soup.positions, &faces);
    (normals, faces, tree)
}

/// The proof against a proved configuration tests the pairs with a changed face: it
/// finds an envelope vertex pushed through the input, and finds nothing when nothing
/// changed (the same answer as the full proof in both cases).
#[test]
fn proof_against_a_proved_configuration_finds_what_changed() {
    let sphere = generate::icosphere(2, 1.0);
    let (normals, faces, tree) = prepared(&sphere);
    let n = sphere.num_vertices();
    let eps = vec![0.02; n];
    let base = prove_and_repair(
        &sphere,
        &normals,
        &faces,
        (eps.clone(), eps.clone()),
        (false, None),
        &tree,
        (0, None),
    );
    assert!(base.proof.contacts.is_empty());
    let same = prove_and_repair(
        &sphere,
        &normals,
        &faces,
        (eps.clone(), eps.clone()),
        (true, Some(&base)),
        &tree,
        (0, None),
    );
    assert!(same.proof.contacts.is_empty());
    // Vertex 7's outer offset negative: its outer vertex goes through the input.
    let mut pushed = eps.clone();
    pushed[7] = -0.05;
    for known in [(false, None), (true, Some(&base))] {
        let p = prove_and_repair(
            &sphere,
            &normals,
            &faces,
            (pushed.clone(), eps.clone()),
            known,
            &tree,
            (0, None),
        );
        assert!(
            p.proof
                .contacts
                .iter()
                .any(|c| c.a.0 == Surface::Input && c.b.0 == Surface::Outer),
            "{:?}",
            p.proof.contacts
        );
    }
}

/// One soup of two unit icospheres (`subdivisions`), the second moved by `shift`.
fn two_spheres(subdivisions: u32, shift: DVec3) -> TriangleSoup {
    let a = generate::icosphere(subdivisions, 1.0);
    let mut positions = a.positions.clone();
    let n = positions.len() as u32;
    positions.extend(a.positions.iter().map(|&p| p + shift));
    let mut faces = a.faces.clone();
    faces.extend(a.faces.iter().map(|f| f.map(|v| VertexId(v.0 + n))));
    TriangleSoup::new(positions, faces)
}

/// Two interpenetrating spheres in one soup (manifold, oriented, self-intersecting):
/// input-input contacts are reported unless the caller says the input was checked.
#[test]
fn input_pairs_are_tested_unless_known_free() {
    let soup = two_spheres(1, DVec3::new(0.9, 0.1, 0.05));
    let (normals, faces, tree) = prepared(&soup);
    let eps = vec![0.01; soup.num_vertices()];
    let input_pairs = |input_free: bool| {
        prove_and_repair(
            &soup,
            &normals,
            &faces,
            (eps.clone(), eps.clone()),
            (input_free, None),
            &tree,
            (0, None),
        )
        .proof
        .contacts
        .iter()
        .filter(|c| c.a.0 == Surface::Input && c.b.0 == Surface::Input)
        .count()
    };
    assert!(input_pairs(false) > 0);
    assert_eq!(input_pairs(true), 0);
}

/// Repair rounds test only the faces the halving moved and keep the other answers: the
/// contacts after each round are those of a full proof of that round's offsets. On the
/// interpenetrating spheres the envelope contacts shrink round by round while the
/// input-input ones (never moved) must be kept.
#[test]
fn repair_rounds_find_what_a_full_proof_finds() {
    let soup = two_spheres(2, DVec3::new(1.7, 0.1, 0.05));
    let (normals, faces, tree) = prepared(&soup);
    let eps = vec![0.2; soup.num_vertices()];
    let mut rounds_with_envelope_contacts = 0;
    for rounds in 0..4 {
        let repaired = prove_and_repair(
            &soup,
            &normals,
            &faces,
            (eps.clone(), eps.clone()),
            (false, None),
            &tree,
            (rounds, None),
        );
        let full = prove_and_repair(
            &soup,
            &normals,
            &faces,
            (repaired.eps_plus.clone(), repaired.eps_minus.clone()),
            (false, None),
            &tree,
            (0, None),
        );
        assert_eq!(
            repaired.proof.contacts, full.proof.contacts,
            "after {rounds} rounds"
        );
        assert!(
            full.proof
                .contacts
                .iter()
                .any(|c| c.a.0 == Surface::Input && c.b.0 == Surface::Input)
        );
        if full.proof.contacts.iter().any(|c| c.b.0 != Surface::Input) {
            rounds_with_envelope_contacts += 1;
        }
    }
    assert!(
        rounds_with_envelope_contacts >= 2,
        "{rounds_with_envelope_contacts}"
    );
}

/// Two spheres of radius 1, 0.2 apart along x, with their vertex faces and normals.
fn spheres_apart() -> (TriangleSoup, VertexFaces, Vec<DVec3>) {
    let soup = two_spheres(3, DVec3::new(2.2, 0.0, 0.0));
    let vf = VertexFaces::new(soup.num_vertices(), &soup.faces);
    let normals = normals::vertex_normals_with(&soup, &vf).normals;
    (soup, vf, normals)
}

/// The growth on the part of the mesh its few movers reach gives the offsets of the
/// growth on the whole mesh, on two spheres 0.2 apart: the first's outer envelope grown
/// from zero where it faces the second, whose outer envelope does not move and stops it
/// (the faces that stop a mover are there); then both outer envelopes grown where they
/// face each other (they compete for the gap: the order of the moves shows). A few inner
/// offsets of the second grow from half their target in both.
#[test]
fn near_growth_is_the_whole_mesh_growth() {
    let (soup, vf, normals) = spheres_apart();
    let n = soup.num_vertices();
    let target = vec![0.15; n];
    let x = |v: usize| soup.positions[v].x;
    let minus: Vec<f64> = (0..n)
        .map(|v| {
            if v >= n / 2 && v % 97 == 0 {
                0.075
            } else {
                0.15
            }
        })
        .collect();
    let bounds = Aabb::from_points(&soup.positions);
    let params = NumericalParams::default();
    for both in [false, true] {
        let facing = |v: usize| {
            if v < n / 2 {
                x(v) > 0.85
            } else {
                both && x(v) < 1.35
            }
        };
        let plus: Vec<f64> = (0..n).map(|v| if facing(v) { 0.0 } else { 0.15 }).collect();
        let near = Near {
            soup: &soup,
            vf: &vf,
            normals: &normals,
            requested: &target,
            start: (&plus, &minus),
            bounds: &bounds,
            stop: None,
        };
        let part = near.grow(&params, soup.diagonal()).expect("few movers");
        let whole = numerical_eps_sorted(
            &soup,
            &normals,
            &target,
            &params,
            soup.diagonal(),
            (Some((&plus, &minus)), None),
            &bounds,
        );
        assert_eq!(part, whole, "both fronts: {both}");
        // The growth did something: the fronts were stopped (0.2 apart, 0.15 each),
        // and grew.
        let front = |v: usize| facing(v) && (x(v) - 1.1).abs() < 0.11;
        assert!((0..n).filter(|&v| front(v)).count() > 1);
        assert!(
            (0..n).any(|v| front(v) && whole.0[v] < 0.15),
            "{:?}",
            whole.0
        );
        assert!((0..n).any(|v| facing(v) && whole.0[v] > 0.0));
        assert!((n / 2..n).any(|v| v % 97 == 0 && whole.1[v] > 0.075));
        // Many movers: the whole mesh's growth.
        let zeros = vec![0.0; n];
        let many = Near {
            start: (&zeros, &zeros),
            ..near
        };
        assert!(many.grow(&params, soup.diagonal()).is_none());
    }
}

/// The growth's tree over the faces its few movers can reach gives the offsets of the
/// tree over all faces: two spheres 0.2 apart, the second's envelopes proved at 0.15,
/// the first's outer envelope grown from zero where it faces the second, towards a
/// target of 0.15 (it stops at the second's outer envelope, about 0.05 away).
#[test]
fn few_movers_grow_as_with_the_whole_scene() {
    let (soup, vf, normals) = spheres_apart();
    let n = soup.num_vertices();
    let target = vec![0.15; n];
    let facing = |v: usize| v < n / 2 && soup.positions[v].x > 0.8;
    let plus: Vec<f64> = (0..n).map(|v| if facing(v) { 0.0 } else { 0.15 }).collect();
    let movers = (0..n).filter(|&v| facing(v)).count();
    assert!(movers > 4, "{movers}");
    let grow = |few: usize, stop: Option<&AtomicBool>| {
        numerical_eps_ordered(
            &soup,
            &vf,
            &normals,
            &target,
            &NumericalParams::default(),
            soup.diagonal(),
            [&plus, &target],
            (few, stop),
        )
    };
    // One mover per `few` scene faces or more: the whole scene's tree; 0: never.
    let (whole, around) = (grow(usize::MAX, None), grow(0, None));
    assert_eq!(whole, around);
    // A stop raised before the growth: no pass, every offset at its start; a lowered one
    // changes nothing.
    let (raised, lowered) = (AtomicBool::new(true), AtomicBool::new(false));
    assert_eq!(
        grow(usize::MAX, Some(&raised)),
        (plus.clone(), target.clone())
    );
    assert_eq!(grow(usize::MAX, Some(&lowered)), whole);
    let front = (0..n).filter(|&v| facing(v) && soup.positions[v].x > 0.98);
    assert!(front.clone().count() > 0);
    assert!(front.clone().all(|v| whole.0[v] < 0.1), "{:?}", whole.0);
}

/// The full proof's two pair searches (over prisms, over each pair of surfaces) find the
/// same contacts and return the same tree, on interpenetrating spheres at offsets from
/// small (a prism about its face) to larger than the faces (outer meets outer and inner,
/// envelopes cross the other sphere), with and without the input-input pairs, and with
/// random per-vertex offsets (some negative: envelope vertices through the input).
#[test]
fn both_pair_searches_find_the_same_contacts() {
    use crate::proof::{Known, PairSearch, prove_envelopes_searching};
    let soup = two_spheres(2, DVec3::new(1.6, 0.2, 0.1));
    let (normals, faces, tree) = prepared(&soup);
    let mut next = xorshift(0x5eed_cafe);
    for scale in [0.002, 0.05, 0.3, 0.8] {
        let mut eps = || -> Vec<f64> {
            (0..soup.num_vertices())
                .map(|_| scale * ((next() % 1000) as f64 / 800.0 - 0.1))
                .collect()
        };
        let (plus, minus) = (eps(), eps());
        let at = |sign: f64, e: &[f64]| -> Vec<DVec3> {
            (0..soup.num_vertices())
                .map(|v| soup.positions[v] + normals[v] * (sign * e[v]))
                .collect()
        };
        let (outer, inner) = (at(1.0, &plus), at(-1.0, &minus));
        for input_free in [false, true] {
            let known = Known {
                input_free,
                ..Known::default()
            };
            let run = |search| {
                prove_envelopes_searching(
                    &soup.positions,
                    [(&outer, &plus), (&inner, &minus)],
                    &faces,
                    &tree,
                    &known,
                    Some(search),
                )
            };
            let (a, ta) = run(PairSearch::Prisms);
            let (b, tb) = run(PairSearch::Faces);
            assert_eq!(a, b, "scale {scale}, input free {input_free}");
            assert_eq!(ta.leaf_boxes(), tb.leaf_boxes());
            assert_eq!(ta.leaf_order(), tb.leaf_order());
            if scale >= 0.3 {
                let kinds: std::collections::BTreeSet<_> =
                    a.iter().map(|c| (c.a.0, c.b.0)).collect();
                assert!(kinds.len() >= 4, "scale {scale}: only {kinds:?}");
            }
        }
    }
}

/// The analytical clipping of a subset of the faces, taking the minima that still hold from
/// the whole soup's clipping, gives the offsets of a clipping from scratch: on two spheres
/// 0.2 apart with the second's cap facing the first removed, the first's outer offsets
/// there grow (their closest triangles are gone and are clipped again), the second's border
/// vertices have new normals, and the faces far from the change keep their minima.
#[test]
fn clipping_a_subset_from_the_minima_before_is_clipping_it_afresh() {
    use crate::analytical::analytical_eps;
    let (soup, vf, normals) = spheres_apart();
    let targets = vec![0.3; soup.num_vertices()];
    let whole_tree = Bvh::from_triangles(
        &soup.positions,
        &soup
            .faces
            .iter()
            .map(|f| f.map(|v| v.0))
            .collect::<Vec<_>>(),
    );
    let (plus, _, minima) = analytical_eps(
        &soup,
        &vf,
        &normals,
        &targets,
        &whole_tree,
        (None, true),
        &|| false,
    );
    let minima = minima.expect("kept");
    let n = soup.num_vertices() / 2;
    let subset = TriangleSoup::new(
        soup.positions.clone(),
        soup.faces
            .iter()
            .filter(|f| {
                f.iter()
                    .all(|v| v.index() < n || soup.positions[v.index()].x > 1.6)
            })
            .copied()
            .collect(),
    );
    assert!(subset.num_faces() < soup.num_faces());
    let (sub_normals, sub_faces, sub_tree) = prepared(&subset);
    let sub_vf = VertexFaces::new(subset.num_vertices(), &subset.faces);
    let afresh = analytical_eps(
        &subset,
        &sub_vf,
        &sub_normals,
        &targets,
        &sub_tree,
        (None, false),
        &|| false,
    );
    let reused = analytical_eps(
        &subset,
        &sub_vf,
        &sub_normals,
        &targets,
        &sub_tree,
        (Some(&minima), false),
        &|| false,
    );
    let bits = |e: &[f64]| e.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&reused.0), bits(&afresh.0));
    assert_eq!(bits(&reused.1), bits(&afresh.1));
    // The first sphere's offsets facing the removed cap were cut by it and are not now.
    assert!((0..n).any(|v| afresh.0[v] > plus[v]));
    // Minima were taken, and some were not (changed normals, closest triangles removed).
    let known = minima
        .reusable(&sub_faces, &subset.positions, &sub_normals, &targets)
        .expect("a subset on the same positions");
    assert!(known.iter().any(|k| k[0].is_some() && k[1].is_some()));
    assert!(known.iter().any(|k| k[0].is_none()));
    assert!(known.iter().any(|k| k[1].is_some() && k[0].is_none()));
    // Not a subset, or moved positions: nothing is taken.
    let mut moved = subset.positions.clone();
    moved[0].x += 1e-9;
    assert!(
        minima
            .reusable(&sub_faces, &moved, &sub_normals, &targets)
            .is_none()
    );
    let mut other = sub_faces.clone();
    other[0].swap(0, 1);
    assert!(
        minima
            .reusable(&other, &subset.positions, &sub_normals, &targets)
            .is_none()
    );
}
