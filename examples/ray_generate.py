"""Many layouts on many machines: (input, seed) pairs sharded over Ray tasks.

    python examples/ray_generate.py --inputs DIR --scenes N --workers W --out DIR
        [--seed S] [--require-clean] [--address auto|HOST:PORT] [--threads T]

For every input scene in DIR (sorted by name) and every k < N, one task generates the layout with
seed S + k and writes OUT/<input stem>_<k>.json. Each task calls the shade_sim package and returns
the file's bytes; the driver writes them atomically, so a scene's name and bytes depend on its
(input, k, seed) only: any number of workers, and `--workers 0` (no Ray: the same calls one
after another in this process), write the same files. A task whose worker dies is retried by Ray
(up to 3 times); a bad input is an error naming the file, not retried. Prints the throughput
(scenes written per second of generation, after the cluster has started).

Without `--address` it starts a local Ray cluster of W worker CPUs; with `--address auto` it joins
the cluster this machine is part of (`ray start --head` on one machine, `ray start
--address=HEAD:6379` on the others, each with the shade_sim wheel installed), whose CPUs then
decide how many tasks run at once. Each task takes one CPU and keeps to `--threads` threads
(default 1).
"""

from __future__ import annotations

import argparse
import glob
import os
import sys
import tempfile
import time
from typing import List, Optional, Tuple

import shade_sim

Job = Tuple[str, int, int]  # (input path, k, seed)


def jobs_for(inputs: str, scenes: int, seed: int) -> List[Job]:
    """The (input, k, seed + k) pairs of a run, inputs sorted by name."""
    files = sorted(glob.glob(os.path.join(inputs, "*.json")))
    if not files:
        raise ValueError(f"{inputs}: no .json input scenes")
    return [(f, k, seed + k) for f in files for k in range(scenes)]


def out_name(job: Job) -> str:
    stem = os.path.splitext(os.path.basename(job[0]))[0]
    return f"{stem}_{job[1]}.json"


def make_scene(job: Job, require_clean: bool, kill_first_attempt: Optional[str] = None) -> Optional[bytes]:
    """The bytes of one job's scene file (None: no clean layout). `kill_first_attempt`, a
    folder, makes the first attempt at each job exit its process (to show Ray's retries)."""
    if kill_first_attempt is not None:
        marker = os.path.join(kill_first_attempt, out_name(job) + ".attempted")
        if not os.path.exists(marker):
            open(marker, "w").close()
            os._exit(1)
    layouts = shade_sim.generate(job[0], seed=job[2], require_clean=require_clean)
    return layouts[0].to_json().encode() if layouts else None


def write_atomic(path: str, data: bytes) -> None:
    folder = os.path.dirname(path) or "."
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def run(
    inputs: str,
    scenes: int,
    workers: int,
    out: str,
    seed: int = 0,
    require_clean: bool = False,
    address: Optional[str] = None,
    threads: int = 1,
    kill_first_attempt: Optional[str] = None,
) -> dict:
    """Generates every job's scene and writes each as soon as it is back (a run of thousands keeps
    at most a batch of results in memory, and a failure leaves every file written before it
    complete); returns counts and timing."""
    todo = jobs_for(inputs, scenes, seed)
    os.makedirs(out, exist_ok=True)
    start = time.perf_counter()
    setup = 0.0
    written = 0

    def keep(job: Job, data: Optional[bytes]) -> None:
        nonlocal written
        if data is not None:
            write_atomic(os.path.join(out, out_name(job)), data)
            written += 1

    if workers == 0:
        # The same thread budget as a Ray task (read when the library first runs in parallel).
        os.environ.setdefault("RAYON_NUM_THREADS", str(threads))
        for job in todo:
            keep(job, make_scene(job, require_clean, kill_first_attempt=None))
    else:
        import ray

        env = {"RAYON_NUM_THREADS": str(threads)}
        if address is None:
            ray.init(num_cpus=workers, include_dashboard=False, log_to_driver=False, runtime_env={"env_vars": env})
        else:
            ray.init(address=address, log_to_driver=False, runtime_env={"env_vars": env})
        setup = time.perf_counter() - start
        start += setup
        if __name__ != "__main__":
            # Imported (by tests, scripts/throughput.py): send the task's code itself, as for a
            # script, so workers need only the shade_sim wheel, not this file on their path.
            ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
        try:
            task = ray.remote(num_cpus=1, max_retries=3)(make_scene)
            pending = {task.remote(job, require_clean, kill_first_attempt): job for job in todo}
            while pending:
                ready, _ = ray.wait(list(pending), num_returns=min(64, len(pending)), timeout=1.0)
                for ref in ready:
                    keep(pending.pop(ref), ray.get(ref))
        finally:
            ray.shutdown()
    elapsed = time.perf_counter() - start
    return {
        "jobs": len(todo),
        "written": written,
        "setup_seconds": setup,
        "seconds": elapsed,
        "scenes_per_second": written / elapsed,
    }


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--inputs", required=True, help="folder of input scenes (*.json)")
    parser.add_argument("--scenes", type=int, required=True, help="layouts per input")
    parser.add_argument("--workers", type=int, required=True, help="Ray workers (0: this process, no Ray)")
    parser.add_argument("--out", required=True)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--require-clean", action="store_true")
    parser.add_argument("--address", help="join a running Ray cluster (auto or HOST:PORT)")
    parser.add_argument("--threads", type=int, default=1, help="threads per task")
    parser.add_argument("--kill-first-attempt", metavar="DIR", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.scenes < 1 or args.workers < 0 or args.threads < 1:
        print("error: --scenes and --threads must be at least 1, --workers at least 0", file=sys.stderr)
        return 2
    try:
        r = run(
            args.inputs,
            args.scenes,
            args.workers,
            args.out,
            args.seed,
            args.require_clean,
            args.address,
            args.threads,
            args.kill_first_attempt,
        )
    except (shade_sim.SceneError, shade_sim.ModelError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    print(
        f"{r['written']} of {r['jobs']} scenes written to {args.out} in {r['seconds']:.1f} s with "
        f"{args.workers} workers (after {r['setup_seconds']:.1f} s starting Ray): {r['scenes_per_second']:.2f} scenes/s"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
