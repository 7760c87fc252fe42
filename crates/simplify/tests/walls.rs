//! Border walls (`walls` module): closed against the envelopes, and the simplifier's output
//! on a mesh with a hole certified two-sided.

use envelope_mesh::{VertexId, analyze, generate};
use envelope_offset::{EnvelopeOptions, EpsilonField, build_envelopes};
use envelope_simplify::policy::{WALL_SEGMENTS, border_walls};
use envelope_simplify::{SimplifyOptions, simplify};
use envelope_verify::Verdict;

#[test]
fn disk_with_a_hole_is_certified_two_sided() {
    let disk = generate::disk_with_holes(1);
    let eps = 0.3;
    let mut options = SimplifyOptions::new(EpsilonField::Constant(eps));
    options.verify = true;
    let (out, report) = simplify(&disk, &options, &mut ()).unwrap();
    assert!(out.num_faces() < disk.num_faces(), "nothing removed");
    let c = envelope_verify::certify(&disk, &out, &envelope_verify::Options::new(eps));
    assert_eq!(c.verdict, Verdict::Holds, "{:?}", c.violations());
    assert_eq!(report.verify.unwrap().verdict, Verdict::Holds);
    assert_eq!(report.border_loops_out, 2);
}

#[test]
fn walls_are_glued_bit_exactly_to_the_envelope_borders() {
    let disk = generate::disk_with_holes(1);
    let topology = analyze(&disk);
    let env = build_envelopes(&disk, &EnvelopeOptions::new(EpsilonField::Constant(0.2))).unwrap();
    let walls = border_walls(&disk, &topology, &env.outer, &env.inner);
    assert_eq!(walls.len(), topology.border_loops.len());
    let m = WALL_SEGMENTS;
    let stride = (m + 1) as u32;
    let bits = |p: glam::DVec3| p.to_array().map(f64::to_bits);
    let mut covered = 0;
    for w in &walls {
        let n = w.vertices.len();
        assert!(w.segments.iter().all(|&s| s), "a segment was skipped");
        for (i, (v, ring)) in w.vertices.iter().zip(&w.rings).enumerate() {
            assert_eq!(ring.len(), m + 1);
            assert_eq!(bits(ring[0]), bits(env.outer.positions[v.index()]));
            assert_eq!(bits(ring[m]), bits(env.inner.positions[v.index()]));
            for (k, p) in ring.iter().enumerate() {
                let id = i as u32 * stride + k as u32;
                assert_eq!(bits(w.mesh.positions[id as usize]), bits(*p));
            }
        }
        // Each segment's strip has the envelopes' boundary edges as triangle edges, and its
        // consecutive quads share their rungs, so the strip has no gap.
        let has_edge = |a: u32, b: u32| {
            w.mesh.faces.iter().any(|f| {
                let f = f.map(|x| x.0);
                (0..3).any(|j| {
                    let (p, q) = (f[j], f[(j + 1) % 3]);
                    (p, q) == (a, b) || (p, q) == (b, a)
                })
            })
        };
        for i in 0..n {
            let (a, b) = (i as u32 * stride, ((i + 1) % n) as u32 * stride);
            for k in 0..=m as u32 {
                assert!(has_edge(a + k, b + k), "rung {k} of segment {i}");
                if k < m as u32 {
                    assert!(has_edge(a + k, a + k + 1) && has_edge(b + k, b + k + 1));
                }
            }
            let (va, vb) = (w.vertices[i], w.vertices[(i + 1) % n]);
            let key = |x: VertexId, y: VertexId| (x.0.min(y.0), x.0.max(y.0));
            assert!(
                topology
                    .border_edges
                    .iter()
                    .any(|e| key(e[0], e[1]) == key(va, vb))
            );
            covered += 1;
        }
    }
    assert_eq!(covered, topology.border_edges.len());
}
