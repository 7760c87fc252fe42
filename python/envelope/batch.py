"""Batch runs: every item of a JSON Lines manifest, locally or on a Ray cluster.

The manifest has one JSON object per line: ``id``, ``input`` (relative to the manifest's
folder), ``epsilon`` (``"1%"``, ``"1/64%"`` or a number), and optionally ``lod`` (a list of
epsilons), ``method``, ``placement``, ``repair`` and ``format``. Item ``id``'s outputs go to
``OUTDIR/<id>/`` and ``OUTDIR/summary.jsonl`` has one line per item. These are the files of
``envelope batch MANIFEST OUTDIR`` on the command line, made by the same Rust code: the
engines only decide where each item runs.

* ``engine="local"``: ``threads / cpus_per_task`` items at a time on this machine, each on a
  pool of ``cpus_per_task`` threads.
* ``engine="ray"``: one Ray task per item, ``num_cpus=cpus_per_task``, with the item's Rust
  pool sized to match, retried when a worker is lost, at most ``max_in_flight`` at a time.
  ``ray.init()`` is called if Ray is not initialized yet: it joins the cluster named by
  ``ray_address`` or the ``RAY_ADDRESS`` variable, or starts a local one.

Every output is the same for either engine and any number of threads. A second run does
no work for items that are finished (their key, a hash of the input bytes, the parameters
and the program version, matches); a killed run resumes; one bad item never stops the
others.

Example::

    >>> import envelope, envelope.batch, json, pathlib, tempfile
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> envelope.save(d / "cup.obj", *envelope.demo())
    >>> _ = (d / "m.jsonl").write_text(json.dumps(
    ...     {"id": "cup", "input": "cup.obj", "epsilon": "1%", "placement": "subset"}) + "\\n")
    >>> [r["status"] for r in envelope.batch.run(d / "m.jsonl", d / "out")]
    ['ok']
    >>> [r["ran"] for r in envelope.batch.run(d / "m.jsonl", d / "out")]
    [False]
"""

from __future__ import annotations

import json
import os
from typing import Any, Callable, Optional, Union

from . import _envelope

__all__ = ["run", "all_ok", "STATUSES"]

#: Every status an item can have.
STATUSES = ("ok", "violated", "bad_input", "undecided", "failed")

Epsilon = Union[float, str, None]
Progress = Optional[Callable[[dict], Optional[bool]]]


def run(
    manifest: Union[str, os.PathLike],
    outdir: Union[str, os.PathLike],
    *,
    engine: str = "local",
    shard: Optional[str] = None,
    epsilon: Epsilon = None,
    threads: Optional[int] = None,
    cpus_per_task: int = 1,
    max_in_flight: Optional[int] = None,
    ray_address: Optional[str] = None,
    progress: Progress = None,
) -> list[dict]:
    """Runs the items of ``manifest`` (of ``shard`` ``"i/n"`` only, if given) into ``outdir``.

    Returns one dict per item run, in manifest order: the item's line of
    ``summary.jsonl`` (``id``, ``status``, ``faces``, ``seconds``, the certified bounds
    ``approx_to_orig`` and ``orig_to_approx``, ``message``, ...) plus ``ran`` (False when
    the result of an earlier run was reused). ``epsilon`` is the default of items that give
    none. ``progress(item)`` hears each item as it ends; returning False cancels (finished
    items are kept; the rest are run by the next call), as does Ctrl-C.

    ``cpus_per_task`` is each item's threads: the local engine runs ``threads`` (default:
    one per core) over ``cpus_per_task`` items at a time, the Ray engine gives each task
    that many CPUs. ``max_in_flight`` (default: twice the cluster's CPUs over
    ``cpus_per_task``) and ``ray_address`` are the Ray engine's.

    Raises ``envelope.InvalidArgumentError`` (a ``ValueError``) for a manifest line that
    cannot be run, naming the line and key, before any item runs; ``envelope.Cancelled``.
    """
    manifest, outdir = os.fspath(manifest), os.fspath(outdir)
    if engine == "local":
        got = _envelope.batch_run(
            manifest, outdir, epsilon, shard, threads, cpus_per_task, _relay(progress)
        )
        return [_outcome(*o) for o in got]
    if engine == "ray":
        return _run_on_ray(
            os.path.abspath(manifest),
            os.path.abspath(outdir),
            epsilon=epsilon,
            shard=shard,
            cpus_per_task=cpus_per_task,
            max_in_flight=max_in_flight,
            ray_address=ray_address,
            progress=progress,
        )
    raise _envelope.InvalidArgumentError(f"engine {engine!r}: expected 'local' or 'ray'")


def all_ok(results: list[dict]) -> bool:
    """Whether every item of a run is ``ok`` (the command line's exit code 0)."""
    return all(r["status"] == "ok" for r in results)


def _outcome(line: str, final: bool, ran: bool) -> dict:
    outcome = json.loads(line)
    outcome["ran"] = ran
    return outcome


def _relay(progress: Progress) -> Optional[Callable[[str, bool, bool], bool]]:
    if progress is None:
        return None
    return lambda line, final, ran: progress(_outcome(line, final, ran)) is not False


def _ray_item(manifest: str, outdir: str, epsilon: Epsilon, item: str, threads: int):
    """One Ray task: one item, on a Rust pool of ``threads`` (the task's ``num_cpus``)."""
    return _envelope.batch_run_item(manifest, outdir, epsilon, item, threads)


def _run_on_ray(
    manifest: str,
    outdir: str,
    *,
    epsilon: Epsilon,
    shard: Optional[str],
    cpus_per_task: int,
    max_in_flight: Optional[int],
    ray_address: Optional[str],
    progress: Progress,
) -> list[dict]:
    import ray

    if not isinstance(cpus_per_task, int) or cpus_per_task < 1:
        raise _envelope.InvalidArgumentError(
            f"cpus_per_task must be a positive integer, got {cpus_per_task!r}"
        )
    # Every line is checked (and the folder made) before any task starts.
    ids = _envelope.batch_items(manifest, outdir, epsilon, shard)
    if not ray.is_initialized():
        ray.init(address=ray_address, log_to_driver=False)
    if max_in_flight is None:
        cpus = int(ray.cluster_resources().get("CPU", 1))
        max_in_flight = max(1, 2 * cpus // cpus_per_task)
    task = ray.remote(num_cpus=cpus_per_task, max_retries=3)(_ray_item)

    results: dict[str, dict] = {}
    transient: list[str] = []
    waiting = iter(ids)
    running: dict[Any, str] = {}
    cancelled = False
    interrupted: Optional[KeyboardInterrupt] = None
    try:
        while True:
            while not cancelled and len(running) < max_in_flight:
                item = next(waiting, None)
                if item is None:
                    break
                ref = task.remote(manifest, outdir, epsilon, item, cpus_per_task)
                running[ref] = item
            if not running:
                break
            done, _ = ray.wait(list(running), num_returns=1)
            for ref in done:
                item = running.pop(ref)
                try:
                    line, final, ran = ray.get(ref)
                except ray.exceptions.RayError as e:
                    message = f"the Ray task failed: {e}"
                    line = _envelope.batch_lost(manifest, outdir, epsilon, item, message)
                    final, ran = False, True
                if not final:
                    transient.append(line)
                results[item] = _outcome(line, final, ran)
                if progress is not None and progress(results[item]) is False:
                    cancelled = True
    except KeyboardInterrupt as e:
        cancelled, interrupted = True, e
    if cancelled:
        for ref in running:
            ray.cancel(ref)
    _envelope.batch_summary(manifest, outdir, epsilon, transient)
    if interrupted is not None:
        raise interrupted
    if cancelled:
        raise _envelope.Cancelled("cancelled")
    return [results[i] for i in ids]
