"""verify and check: a pushed vertex is caught with a witness, a certified output holds."""

import numpy as np
import pytest

import envelope


def test_certified_output_holds(cup, simplified_cup):
    c = envelope.verify(*cup, simplified_cup.vertices, simplified_cup.faces, "1%")
    assert c.verdict == "holds" and c.holds and c.violations == []
    assert c.approx_to_orig.verdict == "holds" and c.orig_to_approx.verdict == "holds"
    assert c.approx_to_orig.upper <= c.epsilon and c.orig_to_approx.upper <= c.epsilon
    lower, upper = c.hausdorff
    assert 0 <= lower <= upper <= c.epsilon
    assert c.self_intersections == [] and c.topology["matches"]
    assert c.approx_to_orig.witness is None
    d = c.to_dict()
    assert d["verdict"] == "holds" and d["epsilon"] == c.epsilon
    assert d["epsilon_relative"] == pytest.approx(0.01)


def test_pushed_vertex_is_violated_with_a_witness(cup, simplified_cup):
    v = simplified_cup.vertices.copy()
    used = int(simplified_cup.faces[0, 0])
    v[used] += [0.0, 0.0, 0.5]
    c = envelope.verify(*cup, v, simplified_cup.faces, "1%")
    assert c.verdict == "violated" and not c.holds
    assert "approx_to_orig" in c.violations
    side = c.approx_to_orig
    assert side.verdict == "violated" and side.lower > c.epsilon
    w = side.witness
    assert w is not None and w.distance_at_least > c.epsilon
    assert len(w.point) == 3 and w.face < len(simplified_cup.faces)
    assert c.to_dict()["approx_to_orig"]["witness"]["face"] == w.face


def test_verify_identical_meshes(sphere):
    c = envelope.verify(*sphere, *sphere, 1e-6)
    assert c.holds and c.hausdorff[1] <= 1e-6


def test_check_report(cup, sphere):
    r = envelope.check(*cup)
    assert r.acceptable and r.problems == {}
    assert (r.vertices, r.faces) == (len(cup[0]), len(cup[1]))
    assert r.border_loops == 1 and r.genus == 0 and r.manifold and r.orientable
    assert set(r.degeneracies) == set(r.to_dict()["degeneracies"])
    s = envelope.check(*sphere)
    assert s.acceptable and s.border_loops == 0 and s.euler == 2


def test_check_finds_a_flipped_face(sphere):
    v, f = sphere
    f = f.copy()
    f[0] = f[0][::-1]
    r = envelope.check(v, f)
    assert not r.acceptable
    assert "inconsistent_orientation" in r.problems
    assert r.degeneracies["inconsistent_orientation"]["severity"] == "error"


def test_verify_error_map(cup, simplified_cup):
    out = simplified_cup
    c = envelope.verify(*cup, out.vertices, out.faces, "1%", map=True)
    assert c.holds
    m = c.error_map
    assert len(m["approx_faces"]["upper"]) == len(out.faces)
    assert len(m["orig_faces"]["upper"]) == len(cup[1])
    assert len(m["approx_vertices"]) == len(out.vertices)
    # Each bound at most epsilon where the certificate holds; the worst vertex at least the
    # certificate's lower bound (a vertex bounds the faces around it).
    assert all(u <= c.epsilon for u in m["approx_faces"]["upper"])
    assert all(u <= c.epsilon for u in m["orig_faces"]["upper"])
    assert max(m["approx_vertices"]) >= c.approx_to_orig.lower
    lower, upper = m["approx_faces"]["lower"], m["approx_faces"]["upper"]
    assert all(lo <= up for lo, up in zip(lower, upper))
    assert envelope.verify(*cup, out.vertices, out.faces, "1%").error_map is None
