"""lod, genus, load and save."""

import numpy as np
import pytest

import envelope


def test_lod_levels(cup):
    levels = envelope.lod(*cup, ["1/4%", "1/2%", 0.05], threads=1)
    assert [l.index for l in levels] == [1, 2, 3]
    assert all(l.is_certified and l.certificate.holds for l in levels)
    faces = [len(l.faces) for l in levels]
    assert faces == sorted(faces, reverse=True) and faces[0] < len(cup[1])
    bounds = [l.bound for l in levels]
    assert bounds == sorted(bounds) and bounds[2] == 0.05
    distances = [l.switching_distance for l in levels]
    assert distances == sorted(distances) and distances[0] > 0
    assert levels[1].step == pytest.approx(levels[1].bound - levels[0].bound)
    d = levels[0].to_dict()
    assert d["level"] == 1 and d["faces"] == faces[0]
    # Nested vertex sets: each level's positions are among the previous level's.
    previous = {tuple(p) for p in levels[0].vertices.tolist()}
    assert all(tuple(p) in previous for p in levels[1].vertices.tolist())


def test_lod_correspondences_cover_every_finer_face(cup):
    levels = envelope.lod(*cup, "1/2%,1%", certify=False, correspondences=True, threads=1)
    fine = len(cup[1])
    for level in levels:
        c = level.correspondence
        assert c["coarse_faces"] == len(level.faces) == len(c["covers"])
        assert c["fine_faces"] == fine
        covered = {f for faces in c["covers"] for f in faces}
        assert covered == set(range(fine))
        assert all(e <= level.step * (1 + 1e-9) for e in c["error"])
        fine = len(level.faces)
    assert envelope.lod(*cup, "1%", certify=False, threads=1)[0].correspondence is None


def test_lod_sum_rule_and_screen(cup):
    levels = envelope.lod(*cup, "1/4%,1/4%", rule="sum", certify=False, pixels=2.0, threads=1)
    assert levels[1].bound == pytest.approx(2 * levels[0].bound)
    assert levels[0].certificate is None and not levels[0].is_certified
    default = envelope.lod(*cup, "1/4%", certify=False, threads=1)
    assert levels[0].switching_distance == pytest.approx(default[0].switching_distance / 2)


def test_genus_fills_a_torus_hole():
    import math

    # A torus of square section (sharp edges bound the filled regions): hole radius
    # about 0.72, filled when a cube of side 2 alpha cannot pass.
    rings, segments, big, small = 24, 4, 1.0, 0.4
    v = []
    for i in range(rings):
        a = 2 * math.pi * i / rings
        for j in range(segments):
            b = 2 * math.pi * j / segments + math.pi / 4
            r = big + small * math.cos(b)
            v.append((r * math.cos(a), r * math.sin(a), small * math.sin(b)))
    f = []
    for i in range(rings):
        for j in range(segments):
            p, q = i * segments + j, ((i + 1) % rings) * segments + j
            p1, q1 = i * segments + (j + 1) % segments, ((i + 1) % rings) * segments + (j + 1) % segments
            f += [(p, q, q1), (p, q1, p1)]
    v, f = np.array(v), np.array(f)
    assert envelope.check(v, f).genus == 1
    assert envelope.genus(v, f, 0.2).report["genus_out"] == 1
    out = envelope.genus(v, f, 1.0)
    assert out.report["genus_in"] == 1
    assert out.report["genus_out"] == 0
    assert len(out.added_faces) == out.report["triangles_added"] > 0
    assert max(out.added_faces) < len(out.faces)


def test_genus_of_the_cup(cup):
    out = envelope.genus(*cup, "1%", threads=1)
    assert out.report["genus_out"] == 0 and out.faces.dtype == np.int64


@pytest.mark.parametrize("ext", ["obj", "off", "ply", "stl"])
def test_save_load_round_trip(tmp_path, sphere, ext):
    v, f = sphere
    path = tmp_path / f"sphere.{ext}"
    envelope.save(path, v, f)
    v2, f2 = envelope.load(str(path))
    assert v2.dtype == np.float64 and f2.dtype == np.int64
    assert len(f2) == len(f)
    # STL stores float32 triangles (vertices welded on reading); the others keep float64.
    tolerance = 1e-6 if ext == "stl" else 0.0
    assert np.allclose(np.sort(v2, axis=0), np.sort(v, axis=0), atol=tolerance)
    if ext != "stl":
        assert np.array_equal(f2, f) and np.array_equal(v2, v)
