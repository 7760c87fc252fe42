"""envelope.batch: statuses, reruns that do no work, cancellation, shards, and Ray equal to
the local engine (a local Ray cluster of 2 CPUs)."""

import json
import os
import pathlib

import numpy as np
import pytest

import envelope
import envelope.batch


def sphere(n_around=16, n_rings=8):
    """A closed UV sphere of radius 1."""
    verts = [(0.0, 0.0, 1.0)]
    for i in range(1, n_rings):
        t = np.pi * i / n_rings
        for j in range(n_around):
            p = 2 * np.pi * j / n_around
            verts.append((np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)))
    verts.append((0.0, 0.0, -1.0))
    faces = []
    ring = lambda i, j: 1 + (i - 1) * n_around + j % n_around
    for j in range(n_around):
        faces.append((0, ring(1, j), ring(1, j + 1)))
    for i in range(1, n_rings - 1):
        for j in range(n_around):
            a, b = ring(i, j), ring(i, j + 1)
            c, d = ring(i + 1, j), ring(i + 1, j + 1)
            faces += [(a, c, d), (a, d, b)]
    last = len(verts) - 1
    for j in range(n_around):
        faces.append((last, ring(n_rings - 1, j + 1), ring(n_rings - 1, j)))
    return np.array(verts), np.array(faces)


@pytest.fixture
def manifest(tmp_path):
    """Two good meshes, a broken file and a missing one."""
    v, f = sphere()
    envelope.save(tmp_path / "sphere.off", v, f)
    envelope.save(tmp_path / "cup.ply", *envelope.demo())
    (tmp_path / "broken.off").write_text("OFF\n3 1 0\n0 0 0\n")
    items = [
        {"id": "sphere", "input": "sphere.off", "epsilon": "2%"},
        {"id": "broken", "input": "broken.off", "epsilon": "1%"},
        {"id": "cup", "input": "cup.ply", "lod": ["1/2%", "2%"], "placement": "subset"},
        {"id": "missing", "input": "missing.off"},
        {"id": "plain", "input": "sphere.off", "format": "obj"},
    ]
    path = tmp_path / "manifest.jsonl"
    path.write_text("\n".join(json.dumps(i) for i in items) + "\n")
    return path


STATUSES = ["ok", "bad_input", "ok", "bad_input", "ok"]


def meshes(outdir):
    """Every mesh file of a batch's output folder, by relative path, with its bytes."""
    out = pathlib.Path(outdir)
    return {
        str(p.relative_to(out)): p.read_bytes()
        for p in sorted(out.glob("*/*"))
        if p.suffix in (".off", ".obj", ".ply", ".stl")
    }


def test_every_item_gets_a_status_and_a_rerun_does_no_work(manifest, tmp_path):
    out = tmp_path / "out"
    results = envelope.batch.run(manifest, out, epsilon="3%", threads=2)
    assert [r["status"] for r in results] == STATUSES
    assert all(r["ran"] for r in results)
    assert not envelope.batch.all_ok(results)
    assert "broken.off" in results[1]["message"]
    sphere_result = results[0]
    assert sphere_result["faces"][0] < sphere_result["input_faces"]
    assert sphere_result["approx_to_orig"] <= sphere_result["epsilon"][0]
    assert len(results[2]["faces"]) == 2
    summary = [json.loads(l) for l in (out / "summary.jsonl").read_text().splitlines()]
    assert [s["id"] for s in summary] == ["sphere", "broken", "cup", "missing", "plain"]
    assert (out / "plain" / "simplified.obj").exists()
    stamp = os.stat(out / "sphere" / "result.json").st_mtime_ns

    again = envelope.batch.run(manifest, out, epsilon="3%")
    assert [r["status"] for r in again] == STATUSES
    # Only the missing input (not a final status) is tried again.
    assert [r["ran"] for r in again] == [False, False, False, True, False]
    assert os.stat(out / "sphere" / "result.json").st_mtime_ns == stamp


def test_progress_cancels_and_the_next_run_finishes(manifest, tmp_path):
    out = tmp_path / "out"
    heard = []

    def stop_after_first(item):
        heard.append(item["id"])
        return False

    with pytest.raises(envelope.Cancelled):
        envelope.batch.run(manifest, out, epsilon="3%", threads=1, progress=stop_after_first)
    assert 1 <= len(heard) < 5
    results = envelope.batch.run(manifest, out, epsilon="3%", threads=1)
    assert [r["status"] for r in results] == STATUSES
    assert sum(not r["ran"] for r in results) >= 1


def test_a_bad_manifest_runs_nothing(manifest, tmp_path):
    text = manifest.read_text() + '{"id": "sphere", "input": "sphere.off"}\n'
    manifest.write_text(text)
    out = tmp_path / "out"
    with pytest.raises(ValueError, match=r"line 6: id \"sphere\" is already the id of line 1"):
        envelope.batch.run(manifest, out, epsilon="3%")
    assert not out.exists()
    with pytest.raises(envelope.InvalidArgumentError, match="engine"):
        envelope.batch.run(manifest, out, engine="spark")
    manifest.write_text('{"id": "a", "input": "sphere.off", "epsilon": "big"}\n')
    with pytest.raises(ValueError, match="line 1: `epsilon`"):
        envelope.batch.run(manifest, out)


def test_shards_make_the_same_files_as_the_whole(manifest, tmp_path):
    whole = envelope.batch.run(manifest, tmp_path / "whole", epsilon="3%")
    first = envelope.batch.run(manifest, tmp_path / "sharded", epsilon="3%", shard="1/2")
    assert [r["id"] for r in first] == ["sphere", "cup", "plain"]
    envelope.batch.run(manifest, tmp_path / "sharded", epsilon="3%", shard="2/2")
    assert meshes(tmp_path / "sharded") == meshes(tmp_path / "whole")
    assert len(meshes(tmp_path / "whole")) == 4
    assert [r["status"] for r in whole] == STATUSES
    with pytest.raises(ValueError, match="shard"):
        envelope.batch.run(manifest, tmp_path / "x", shard="3/2")


def ray_or_skip():
    try:
        import ray
    except ImportError:
        if os.environ.get("CI") == "true":
            raise
        pytest.skip("ray is not installed (CI installs it)")
    return ray


@pytest.fixture(scope="module")
def ray_cluster():
    ray = ray_or_skip()
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    yield ray
    ray.shutdown()


def test_ray_makes_the_same_files_as_the_local_engine(manifest, tmp_path, ray_cluster):
    local = envelope.batch.run(manifest, tmp_path / "local", epsilon="3%")
    remote = envelope.batch.run(
        manifest, tmp_path / "ray", epsilon="3%", engine="ray", cpus_per_task=1, max_in_flight=2
    )
    assert [r["status"] for r in remote] == [r["status"] for r in local] == STATUSES
    assert [r["key"] for r in remote] == [r["key"] for r in local]
    assert meshes(tmp_path / "ray") == meshes(tmp_path / "local")
    summary = (tmp_path / "ray" / "summary.jsonl").read_text().splitlines()
    assert [json.loads(l)["id"] for l in summary] == [r["id"] for r in local]
    # A rerun on Ray does no work for finished items either.
    again = envelope.batch.run(manifest, tmp_path / "ray", epsilon="3%", engine="ray")
    assert [r["ran"] for r in again] == [False, False, False, True, False]


def _dies_once(manifest, outdir, epsilon, item, threads):
    """A Ray task whose worker process dies the first time it runs `sphere`."""
    import os
    import pathlib

    from envelope import _envelope

    marker = pathlib.Path(outdir).parent / f"died-{item}"
    if item == "sphere" and not marker.exists():
        marker.write_text("once")
        os._exit(1)
    return _envelope.batch_run_item(manifest, outdir, epsilon, item, threads)


def test_ray_retries_an_item_whose_worker_died(manifest, tmp_path, ray_cluster, monkeypatch):
    import sys

    # Sent by value: the workers cannot import this test module.
    ray_cluster.cloudpickle.register_pickle_by_value(sys.modules[__name__])
    monkeypatch.setattr(envelope.batch, "_ray_item", _dies_once)
    results = envelope.batch.run(manifest, tmp_path / "ray", epsilon="3%", engine="ray")
    assert (tmp_path / "died-sphere").exists()
    assert [r["status"] for r in results] == STATUSES
    local = envelope.batch.run(manifest, tmp_path / "local", epsilon="3%")
    assert meshes(tmp_path / "ray") == meshes(tmp_path / "local")


def test_the_module_examples_run():
    import doctest

    result = doctest.testmod(envelope.batch)
    assert result.attempted >= 3 and result.failed == 0, result


def test_ctrl_c_stops_a_local_run_and_keeps_what_finished(manifest, tmp_path):
    import signal

    out = tmp_path / "out"

    pressed = []

    def interrupt(item):
        # One Ctrl-C, as a user presses it (a second would interrupt the test itself).
        if not pressed:
            pressed.append(item["id"])
            signal.raise_signal(signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        envelope.batch.run(manifest, out, epsilon="3%", threads=1, progress=interrupt)
    finished = [json.loads(l) for l in (out / "summary.jsonl").read_text().splitlines()]
    assert 1 <= len(finished) < 5
    results = envelope.batch.run(manifest, out, epsilon="3%", threads=1)
    assert [r["status"] for r in results] == STATUSES
