"""Every kind of bad input: its exception class and its message (the library's Display)."""

import numpy as np
import pytest

import envelope


def replace_row(a, row, value):
    a = a.copy()
    a[row] = value
    return a


def test_hierarchy():
    assert issubclass(envelope.InputError, envelope.EnvelopeError)
    for cls in [envelope.ReadError, envelope.InvalidMeshError, envelope.NotAcceptableError]:
        assert issubclass(cls, envelope.InputError)
    for cls in [envelope.InvalidMeshError, envelope.InvalidArgumentError, envelope.InvalidEpsilonError]:
        assert issubclass(cls, ValueError)
    assert issubclass(envelope.InvalidEpsilonError, envelope.InvalidArgumentError)
    for cls in [envelope.CertificateViolated, envelope.Cancelled, envelope.SimplifyError, envelope.WriteError]:
        assert issubclass(cls, envelope.EnvelopeError)
        assert not issubclass(cls, ValueError)
    assert envelope.Cancelled.__module__ == "envelope"
    assert envelope.CertificateViolated.__doc__


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda v, f: (v[:, :2], f), "invalid mesh: vertices must have shape (n, 3), got (266, 2)"),
        (lambda v, f: (v.ravel(), f), "invalid mesh: vertices must have shape (n, 3), got (798,)"),
        (lambda v, f: (v, f[:, :2]), "invalid mesh: faces must have shape (m, 3), got (528, 2)"),
        (lambda v, f: (v, f.astype(float)), "invalid mesh: faces must be integers, got dtype float64"),
        (lambda v, f: (v, f.astype(bool)), "invalid mesh: faces must be integers, got dtype bool"),
        (
            lambda v, f: (v, replace_row(f, 5, [0, -1, 2])),
            "invalid mesh: triangle 5 [0, -1, 2] names a negative vertex index",
        ),
        (
            lambda v, f: (v, replace_row(f, 7, [0, 1, 266])),
            "invalid mesh: triangle 7 [0, 1, 266] names a vertex beyond the last one (266 vertices)",
        ),
        (
            lambda v, f: (v, replace_row(f, 9, [0, 1, 2**40])),
            "invalid mesh: triangle 9 [0, 1, 1099511627776] names a vertex beyond the last one (266 vertices)",
        ),
        (
            lambda v, f: (replace_row(v, 3, [0.0, np.inf, 0.0]), f),
            "invalid mesh: vertex 3 has a coordinate that is not finite: [0.0, inf, 0.0]",
        ),
        (
            lambda v, f: (replace_row(v, 4, [np.nan, 0.0, 0.0]), f),
            "invalid mesh: vertex 4 has a coordinate that is not finite: [NaN, 0.0, 0.0]",
        ),
        (
            lambda v, f: ([["a", "b", "c"]], f),
            "invalid mesh: vertices cannot be read as float64 numbers: could not convert string to float: 'a'",
        ),
    ],
)
def test_invalid_arrays(sphere, make, message):
    v, f = make(*sphere)
    for call in [
        lambda: envelope.simplify(v, f, "1%"),
        lambda: envelope.check(v, f),
        lambda: envelope.lod(v, f, "1%"),
        lambda: envelope.genus(v, f, "1%"),
    ]:
        with pytest.raises(envelope.InvalidMeshError) as err:
            call()
        assert str(err.value) == message


def test_verify_names_the_mesh(sphere):
    v, f = sphere
    with pytest.raises(envelope.InvalidMeshError, match=r"^v1, f1: invalid mesh: triangle 0 \[0, -1, 2\]"):
        envelope.verify(v, f, v, replace_row(f, 0, [0, -1, 2]), "1%")
    with pytest.raises(envelope.InvalidMeshError, match=r"^v0, f0: invalid mesh: vertices must"):
        envelope.verify(v[:, :2], f, v, f, "1%")


SYNTAX = (
    "expected a positive length: absolute (0.01) or a percentage of the bounding-box "
    "diagonal (2%, 1/64%)"
)


@pytest.mark.parametrize(
    "epsilon, message",
    [
        ("-1%", f'invalid epsilon: "-1%": zero or negative; {SYNTAX}'),
        ("abc", f'invalid epsilon: "abc": not a number; {SYNTAX}'),
        (-0.5, "invalid epsilon: -0.5 is not a positive finite length"),
        (0, "invalid epsilon: 0 is not a positive finite length"),
        (float("nan"), "invalid epsilon: NaN is not a positive finite length"),
        ([1], 'invalid epsilon: expected a number or a string such as "1%", got list'),
        (True, 'invalid epsilon: expected a number or a string such as "1%", got bool'),
    ],
)
def test_invalid_epsilon(sphere, epsilon, message):
    with pytest.raises(envelope.InvalidEpsilonError) as err:
        envelope.simplify(*sphere, epsilon)
    assert str(err.value) == message
    with pytest.raises(envelope.InvalidEpsilonError):
        envelope.verify(*sphere, *sphere, epsilon)


@pytest.mark.parametrize(
    "settings, message",
    [
        ({"placement": "fast"}, 'placement must be one of subset, slide, collapse, auto; got "fast"'),
        ({"method": "quick"}, 'method must be one of local, global, hybrid; got "quick"'),
        ({"envelope": "x"}, 'envelope must be one of analytical, numerical, auto; got "x"'),
        ({"hole_filling": "x"}, 'hole_filling must be one of greedy, exhaustive; got "x"'),
        ({"tube_segments": 2}, "tube segments must be in 3..=64, got 2"),
        ({"tube_segments": -2}, "tube segments must be in 3..=64, got -2"),
        ({"threads": 0}, "threads must be at least 1"),
        ({"threads": -4}, "threads must be at least 1"),
        ({"target_faces": -1}, "target_faces must not be negative, got -1"),
        (
            {"method": "global", "placement": "slide"},
            "placement slide and collapse move vertices in the local algorithm's phase, which "
            "the global method does not run (use the local or hybrid method)",
        ),
    ],
)
def test_invalid_arguments(sphere, settings, message):
    with pytest.raises(envelope.InvalidArgumentError) as err:
        envelope.simplify(*sphere, "1%", **settings)
    assert str(err.value) == f"invalid argument: {message}"


def test_not_acceptable(sphere):
    v, f = sphere
    doubled = np.vstack([f, f[:1]])
    with pytest.raises(envelope.NotAcceptableError) as err:
        envelope.simplify(v, doubled, "1%")
    assert str(err.value).startswith("the input is not acceptable: ")
    assert "duplicate_triangles" in str(err.value)
    report = envelope.check(v, doubled)
    assert not report.acceptable
    assert report.problems["duplicate_triangles"] == 1


def test_lod_and_genus_arguments(sphere):
    with pytest.raises(envelope.InvalidEpsilonError, match="must increase"):
        envelope.lod(*sphere, "2%,1%")
    with pytest.raises(envelope.InvalidArgumentError, match=r"^invalid argument: fov_degrees must be in \(0, 180\), got 200"):
        envelope.lod(*sphere, "1%", fov_degrees=200)
    with pytest.raises(envelope.InvalidArgumentError, match='rule must be one of cumulative, sum; got "x"'):
        envelope.lod(*sphere, "1%", rule="x")
    with pytest.raises(envelope.InvalidArgumentError, match="^beta must be strictly between 0 and 180 degrees, got 190"):
        envelope.genus(*sphere, "1%", beta_degrees=190)
    with pytest.raises(envelope.InvalidArgumentError, match='source must be one of sharp_edges, prism_union, closing; got "x"'):
        envelope.genus(*sphere, "1%", source="x")
    with pytest.raises(envelope.InvalidEpsilonError):
        envelope.genus(*sphere, -1.0)


def test_files(tmp_path, sphere):
    missing = tmp_path / "missing.off"
    with pytest.raises(envelope.ReadError) as err:
        envelope.load(missing)
    assert str(err.value) == f"{missing}: file not found"
    broken = tmp_path / "broken.off"
    broken.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n")
    with pytest.raises(envelope.ReadError, match="broken.off"):
        envelope.load(broken)
    with pytest.raises(envelope.InvalidArgumentError) as err:
        envelope.save(tmp_path / "mesh.xyz", *sphere)
    assert str(err.value) == f"{tmp_path / 'mesh.xyz'}: unknown mesh format (expected .obj, .off, .ply or .stl)"
    with pytest.raises(envelope.WriteError):
        envelope.save(tmp_path / "no" / "such" / "dir.off", *sphere)
