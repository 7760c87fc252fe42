"""simplify: arrays in and out, the report, the certificate, the settings, threads."""

import numpy as np
import pytest

import envelope


def test_cup_is_simplified_and_certified(cup, simplified_cup):
    v, f = cup
    out = simplified_cup
    assert out.is_certified
    assert out.certificate is not None and out.certificate.verdict == "holds"
    assert out.violations == []
    assert out.vertices.dtype == np.float64 and out.vertices.shape[1] == 3
    assert out.faces.dtype == np.int64 and out.faces.shape[1] == 3
    assert 0 < len(out.faces) < len(f) // 4
    assert out.faces.min() >= 0 and out.faces.max() < len(out.vertices)


def test_report_is_the_json_report(cup, simplified_cup):
    report = simplified_cup.report
    assert isinstance(report, dict)
    assert report["input_faces"] == len(cup[1])
    assert report["output_faces"] == len(simplified_cup.faces)
    assert report["output_vertices"] == len(simplified_cup.vertices)
    assert report["method"] == "local"
    assert report["verify"]["verdict"] == "holds"
    assert report["epsilon_fraction"] == pytest.approx(0.01)


def test_subset_placement_keeps_input_positions(cup):
    v, f = cup
    out = envelope.simplify(v, f, "1%", placement="subset", threads=1)
    rows = {tuple(p) for p in v.tolist()}
    assert all(tuple(p) in rows for p in out.vertices.tolist())


def test_absolute_and_relative_epsilon_agree(sphere):
    v, f = sphere
    diagonal = float(np.linalg.norm(v.max(axis=0) - v.min(axis=0)))
    relative = envelope.simplify(v, f, "2%", threads=1)
    absolute = envelope.simplify(v, f, 0.02 * diagonal, threads=1)
    assert relative.report["epsilon_abs"] == pytest.approx(absolute.report["epsilon_abs"])
    assert np.array_equal(relative.faces, absolute.faces)


def test_sphere_keeps_its_topology(sphere):
    out = envelope.simplify(*sphere, "2%", threads=1)
    assert out.is_certified
    topology = out.certificate.topology
    assert topology["matches"] and topology["approx"]["genus"] == 0
    assert len(out.faces) < len(sphere[1])


def test_threads_give_identical_arrays(cup):
    one = envelope.simplify(*cup, "1/2%", threads=1)
    two = envelope.simplify(*cup, "1/2%", threads=2)
    assert np.array_equal(one.vertices, two.vertices)
    assert np.array_equal(one.faces, two.faces)


def test_certify_false_has_no_certificate(cup):
    out = envelope.simplify(*cup, "1%", certify=False, threads=1)
    assert out.certificate is None
    assert not out.is_certified
    assert out.report["verify"] is None


def test_target_faces_stops_early(cup):
    full = envelope.simplify(*cup, "1%", placement="subset", threads=1)
    early = envelope.simplify(*cup, "1%", placement="subset", target_faces=2000, threads=1)
    assert len(full.faces) < len(early.faces) <= 2000


@pytest.mark.parametrize("dtype", [np.int32, np.uint16, np.uint64, np.int16])
def test_any_integer_dtype_and_lists(sphere, dtype):
    v, f = sphere
    out = envelope.simplify(v.tolist(), f.astype(dtype), "2%", threads=1)
    reference = envelope.simplify(v, f, "2%", threads=1)
    assert np.array_equal(out.faces, reference.faces)


def test_float32_vertices_are_converted(sphere):
    v, f = sphere
    out = envelope.simplify(v.astype(np.float32), f, "2%", threads=1)
    assert out.vertices.dtype == np.float64 and out.is_certified


@pytest.mark.parametrize(
    "settings",
    [
        {"method": "global"},
        {"method": "hybrid"},
        {"envelope": "analytical"},
        {"envelope": "numerical"},
        {"hole_filling": "exhaustive"},
        {"placement": "collapse"},
        {"tube_segments": None},
        {"tube_segments": 3},
    ],
)
def test_settings(cup, settings):
    out = envelope.simplify(*cup, "1%", threads=1, **settings)
    assert out.is_certified
    if "method" in settings:
        assert out.report["method"] != "local"


def test_signature_defaults_are_the_library_defaults():
    import inspect

    params = inspect.signature(envelope.simplify).parameters
    for name in ["placement", "method", "envelope", "hole_filling", "tube_segments", "certify"]:
        assert params[name].default == envelope.DEFAULTS[name]
    assert envelope.DEFAULTS["tube_segments_range"][0] <= envelope.DEFAULTS["tube_segments"]


def test_gil_is_released(sphere):
    import threading

    v, f = sphere
    done = threading.Event()

    def work():
        envelope.lod(v, f, ["1%", "2%", "4%"], threads=1)
        done.set()

    thread = threading.Thread(target=work)
    thread.start()
    spins = 0
    while not done.is_set():
        spins += 1
    thread.join()
    assert spins > 1000


def test_self_intersecting_input_keeps_its_crossings(sphere):
    """Two spheres through each other: the faces where they meet stay as they are, the rest
    is simplified, and the certificate allows only the input's own intersections."""
    v, f = sphere
    both_v = np.vstack([v, v + np.array([1.2, 0.1, 0.05])])
    both_f = np.vstack([f, f + len(v)])
    out = envelope.simplify(both_v, both_f, "1%", threads=1)
    assert out.is_certified
    assert len(out.faces) < len(both_f)
    kept = out.report["kept"]
    assert kept is not None and kept["intersecting_pairs"] > 0
    assert kept["kept_faces"] >= 2
    assert len(out.certificate.kept_intersections) > 0
    assert out.certificate.self_intersections == []
    # The oracle, which allows the input's own intersections too, finds the same pairs.
    strict = envelope.verify(both_v, both_f, out.vertices, out.faces, "1%")
    assert strict.holds and len(strict.kept_intersections) == len(out.certificate.kept_intersections)
