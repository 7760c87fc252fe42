"""simplify_trimesh: trimesh in, trimesh out. With CI=true a missing trimesh fails."""

import os

import numpy as np
import pytest

import envelope

if os.environ.get("CI") == "true":
    import trimesh
else:
    trimesh = pytest.importorskip("trimesh")


def test_simplify_trimesh(cup):
    mesh = trimesh.Trimesh(*cup, process=False)
    out = envelope.simplify_trimesh(mesh, "1%", threads=1)
    assert isinstance(out, trimesh.Trimesh)
    reference = envelope.simplify(*cup, "1%", threads=1)
    assert np.array_equal(out.faces, reference.faces)
    assert np.array_equal(out.vertices, reference.vertices)


def test_simplify_trimesh_passes_settings_and_errors(cup):
    mesh = trimesh.Trimesh(*cup, process=False)
    with pytest.raises(envelope.InvalidArgumentError):
        envelope.simplify_trimesh(mesh, "1%", placement="nowhere")
    early = envelope.simplify_trimesh(mesh, "1%", target_faces=3000, threads=1)
    assert len(early.faces) <= 3000
