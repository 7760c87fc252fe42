"""Objects per minute over a corpus: `envelope batch` (the CLI) against `envelope.batch.run`
with the local engine and with Ray, in one run on this machine, each into its own folder;
the outputs of the three are compared byte for byte. Then, from the measured per-object
times, the paper's 2,636-object batch on N nodes.

    python benches/batch_vs_ray.py [--quick] [--epsilon 1%] [--cpus 2] [--repeat 1]

Needs the package installed (`pip install .`), ray, and a release build of the CLI
(`cargo build --release`); the corpus comes from `bash scripts/corpus.sh`.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent


def manifest_for(corpus: pathlib.Path, epsilon: str, quick: bool, dest: pathlib.Path):
    files = sorted(
        p for p in corpus.iterdir() if p.suffix.lower() in (".off", ".obj", ".ply", ".stl")
    )
    if quick:
        # The twelve smallest files: the smoke run's few seconds.
        files = sorted(files, key=lambda p: p.stat().st_size)[:12]
    lines, seen = [], set()
    for p in files:
        stem = re.sub(r"[^A-Za-z0-9._-]", "_", p.stem).lstrip(".") or "mesh"
        ident = stem
        k = 1
        while ident in seen:
            k += 1
            ident = f"{stem}-{k}"
        seen.add(ident)
        lines.append(json.dumps({"id": ident, "input": str(p), "epsilon": epsilon}))
    dest.write_text("\n".join(lines) + "\n")
    return len(lines)


def meshes(outdir: pathlib.Path):
    return {
        str(p.relative_to(outdir)): p.read_bytes()
        for p in sorted(outdir.glob("*/*"))
        if p.suffix in (".off", ".obj", ".ply", ".stl")
    }


def summary(outdir: pathlib.Path):
    return [json.loads(l) for l in (outdir / "summary.jsonl").read_text().splitlines()]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--corpus", default=str(ROOT / ".corpus/data/meshes"))
    ap.add_argument("--epsilon", default="1%")
    ap.add_argument("--cpus", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--quick", action="store_true", help="the twelve smallest meshes")
    ap.add_argument("--repeat", type=int, default=1, help="alternating runs of each engine")
    ap.add_argument("--binary", default=str(ROOT / "target/release/envelope"))
    args = ap.parse_args()

    import envelope
    import envelope.batch
    import ray

    work = pathlib.Path(tempfile.mkdtemp(prefix="batch-bench-"))
    manifest = work / "manifest.jsonl"
    n = manifest_for(pathlib.Path(args.corpus), args.epsilon, args.quick, manifest)
    print(f"{n} objects from {args.corpus} at epsilon {args.epsilon}, {args.cpus} CPUs")

    t = time.perf_counter()
    ray.init(num_cpus=args.cpus, include_dashboard=False, log_to_driver=False)
    ray_start = time.perf_counter() - t

    def cli(out):
        subprocess.run(
            [args.binary, "--threads", str(args.cpus), "batch", str(manifest), str(out), "--quiet"],
            check=False,
            stdout=subprocess.DEVNULL,
        )

    def local(out):
        envelope.batch.run(manifest, out, threads=args.cpus)

    def on_ray(out):
        envelope.batch.run(manifest, out, engine="ray", cpus_per_task=1)

    engines = [("envelope batch (CLI)", cli), ("python, local", local), ("python, ray", on_ray)]
    times = {name: [] for name, _ in engines}
    for r in range(args.repeat):
        for name, run in engines:
            out = work / f"{re.sub(r'[^a-z]', '', name)}-{r}"
            t = time.perf_counter()
            run(out)
            times[name].append(time.perf_counter() - t)

    outs = {name: work / f"{re.sub(r'[^a-z]', '', name)}-0" for name, _ in engines}
    reference = meshes(outs["envelope batch (CLI)"])
    ok = summary(outs["envelope batch (CLI)"])
    statuses = {}
    for line in ok:
        statuses[line["status"]] = statuses.get(line["status"], 0) + 1
    print("statuses:", ", ".join(f"{v} {k}" for k, v in sorted(statuses.items())))
    print(f"ray.init: {ray_start:.1f} s (not counted below)")
    print()
    print("| engine | objects | best wall s | objects/min | ratio to CLI | outputs |")
    print("|---|---:|---:|---:|---:|---|")
    base = min(times["envelope batch (CLI)"])
    for name, _ in engines:
        best = min(times[name])
        same = "identical" if meshes(outs[name]) == reference else "DIFFERENT"
        print(
            f"| {name} | {n} | {best:.1f} | {60 * n / best:.1f} | {best / base:.2f} | {same} |"
        )

    # The paper's batch, on paper: this run's CPU time per object (the CLI's wall time times
    # its CPUs, all busy) for 2,636 objects spread over N nodes like this machine, with a
    # shared folder and no transfer costs counted.
    per_object = base * args.cpus / max(n, 1)
    print()
    print(f"per object: {per_object:.2f} CPU-seconds (CLI wall {base:.1f} s x {args.cpus} CPUs / {n})")
    print("| nodes x CPUs | 2,636 objects, estimated minutes |")
    print("|---|---:|")
    for nodes in (1, 4, 16, 64):
        cpus = nodes * args.cpus
        print(f"| {nodes} x {args.cpus} | {2636 * per_object / cpus / 60:.1f} |")
    ray.shutdown()
    different = [name for name, _ in engines[1:] if meshes(outs[name]) != reference]
    shutil.rmtree(work, ignore_errors=True)
    if different:
        sys.exit(f"{', '.join(different)} made different files than the CLI")


if __name__ == "__main__":
    main()
