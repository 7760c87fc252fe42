"""glTF through the `envelope` program: a .glb made by trimesh goes in, a .glb comes out that
trimesh loads with the printed face counts and that cgltf's validator (gltfpack) accepts.

The program is ENVELOPE_BIN, else target/release/envelope or target/debug/envelope of this
repository. With CI=true a missing program, trimesh or gltfpack fails the test.
"""

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

CI = os.environ.get("CI") == "true"

if CI:
    import trimesh
else:
    trimesh = pytest.importorskip("trimesh")


def program():
    root = Path(__file__).resolve().parents[2]
    candidates = [os.environ.get("ENVELOPE_BIN")] + [
        str(root / "target" / kind / "envelope") for kind in ("release", "debug")
    ]
    for c in candidates:
        if c and Path(c).is_file() and os.access(c, os.X_OK):
            return c
    if CI:
        pytest.fail("the envelope program is not built (cargo build -p envelope-cli)")
    pytest.skip("the envelope program is not built")


def validate(path):
    """cgltf's validator: gltfpack exits non-zero on a file it refuses."""
    gltfpack = shutil.which("gltfpack")
    if gltfpack is None:
        if CI:
            pytest.fail("gltfpack (Debian package gltfpack) is required under CI=true")
        pytest.skip("gltfpack is not installed")
    out = subprocess.run(
        [gltfpack, "-i", str(path), "-o", str(path.with_suffix(".packed.glb"))],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stdout + out.stderr


@pytest.fixture()
def scene_glb(tmp_path):
    scene = trimesh.Scene()
    scene.add_geometry(
        trimesh.creation.icosphere(subdivisions=4),
        node_name="ball",
        geom_name="ball",
        transform=trimesh.transformations.scale_matrix(2.0),
    )
    scene.add_geometry(
        trimesh.creation.torus(1.0, 0.3),
        node_name="ring",
        geom_name="ring",
        transform=trimesh.transformations.translation_matrix([3.0, 0.0, 0.0]),
    )
    path = tmp_path / "in.glb"
    scene.export(str(path))
    return path


def faces_printed(stdout):
    return [(int(a), int(b)) for a, b in re.findall(r": (\d+) -> (\d+) faces", stdout)]


def test_simplify_glb_loads_in_trimesh_and_validates(scene_glb, tmp_path):
    out = tmp_path / "out.glb"
    run = subprocess.run(
        [program(), "simplify", str(scene_glb), str(out), "--epsilon", "1%", "--threads", "1"],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.count("certificate holds after rounding to f32") == 2, run.stdout
    counts = faces_printed(run.stdout)
    assert [a for a, _ in counts] == [5120, 2048]
    loaded = trimesh.load(str(out))
    assert sorted(len(g.faces) for g in loaded.geometry.values()) == sorted(b for _, b in counts)
    original = trimesh.load(str(scene_glb))
    for name in ("ball", "ring"):
        assert (loaded.graph[name][0] == original.graph[name][0]).all()
    validate(out)


def test_lod_glb_has_msft_lod_and_validates(scene_glb, tmp_path):
    out = tmp_path / "lod.glb"
    run = subprocess.run(
        [program(), "lod", str(scene_glb), str(out), "--epsilons", "0.5%,2%", "--threads", "1"],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    loaded = trimesh.load(str(out))
    assert len(loaded.geometry) == 6  # two meshes, two levels each
    validate(out)


def test_refusal_names_the_extension(tmp_path):
    path = tmp_path / "draco.gltf"
    path.write_text(
        '{"asset": {"version": "2.0"}, "extensionsUsed": ["EXT_meshopt_compression"],'
        ' "extensionsRequired": ["EXT_meshopt_compression"]}'
    )
    run = subprocess.run(
        [program(), "simplify", str(path), str(tmp_path / "out.glb"), "--epsilon", "1%"],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 2
    assert "EXT_meshopt_compression" in run.stderr
