"""Throughput of the whole loop (generate -> repair -> check -> resample until clean), one core each.

    .venv/bin/python scripts/throughput.py [--samples K] [--scenes N] [--out DIR]

For each room type, the example inputs (scenes/examples/<room>_*.json) with K clean layouts each
(default 4): checked scenes per second on one thread from the command line (`shade-sim generate
--require-clean` on their folder, target/release) and from Python (`shade_sim.generate(...,
require_clean=True)` with the installed wheel, given the list of inputs, then one input at a
time). Then examples/ray_generate.py on all six inputs with N
scenes each (default 6), one Ray worker and two, and the ratio of their throughputs. Prints one
table; everything runs in this one call, so the ratios compare runs on the same machine.
"""

from __future__ import annotations

import argparse
import glob
import os
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.environ["RAYON_NUM_THREADS"] = "1"
sys.path.insert(0, os.path.join(ROOT, "examples"))

import ray_generate  # noqa: E402
import shade_sim  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=4)
    parser.add_argument("--scenes", type=int, default=6)
    parser.add_argument("--out", default=None)
    args = parser.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="shade_throughput_")
    binary = os.path.join(ROOT, "target", "release", "shade-sim")
    examples = os.path.join(ROOT, "scenes", "examples")
    print("| room | inputs × samples | CLI | Python, a list | Python, one input at a time | Python (list) / CLI |")
    print("|---|---|---:|---:|---:|---:|")
    for room in ("bedroom", "living", "dining"):
        inputs = sorted(glob.glob(os.path.join(examples, f"{room}_*.json")))
        folder = os.path.join(out, room)
        os.makedirs(folder, exist_ok=True)
        for f in inputs:
            shutil.copy(f, folder)
        start = time.perf_counter()
        subprocess.run(
            [binary, "-q", "--no-progress", "generate", "--input", folder, "--out", os.path.join(out, room + "_cli"),
             "--samples", str(args.samples), "--require-clean"],
            check=True,
        )
        cli = len(inputs) * args.samples / (time.perf_counter() - start)
        shade_sim.generate(inputs[0], seed=10_000)  # loads the model, as the CLI's start does
        start = time.perf_counter()
        kept = sum(len(k) for k in shade_sim.generate(inputs, samples=args.samples, require_clean=True))
        py = kept / (time.perf_counter() - start)
        start = time.perf_counter()
        kept = sum(len(shade_sim.generate(f, samples=args.samples, require_clean=True)) for f in inputs)
        one = kept / (time.perf_counter() - start)
        print(f"| {room} | {len(inputs)} × {args.samples} | {cli:.2f} | {py:.2f} | {one:.2f} | {py / cli:.2f} |")
    rates = {}
    for workers in (1, 2):
        r = ray_generate.run(examples, args.scenes, workers, os.path.join(out, f"ray{workers}"), require_clean=True)
        rates[workers] = r["scenes_per_second"]
        print(f"Ray, {workers} worker(s): {r['written']} scenes in {r['seconds']:.1f} s "
              f"(+ {r['setup_seconds']:.1f} s starting Ray): {r['scenes_per_second']:.2f} scenes/s")
    same = all(
        open(os.path.join(out, "ray1", n), "rb").read() == open(os.path.join(out, "ray2", n), "rb").read()
        for n in os.listdir(os.path.join(out, "ray1"))
    )
    print(f"Ray 2 workers / 1 worker: {rates[2] / rates[1]:.2f}; the same bytes: {same}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
