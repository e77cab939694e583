"""Fresh, checked MuJoCo scenes for a training loop.

    python examples/gym_scenes.py [INPUT.json ...] [--seed S] [--count N]

`scenes(inputs, seed)` is an endless iterator: it cycles through the inputs (default: the six
example inputs in scenes/examples/) and, for the k-th scene, generates a layout with seed `seed + k`
that passes `shade_sim.check` (resampling with new seeds inside `generate` when one does not),
yielding the scene and its MJCF world. The same inputs and seed give the same sequence, scene for
scene and byte for byte, in any process. Run as a script, it loads the first N (default 6) into
MuJoCo, replays each keyframe of their people and steps the physics, as a training loop would.
"""

from __future__ import annotations

import argparse
import glob
import itertools
import os
import sys
from dataclasses import dataclass
from typing import Iterator, Sequence

import shade_sim

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@dataclass(frozen=True)
class GymScene:
    """One scene of the stream: where it came from, the layout and its MuJoCo world."""

    index: int
    input: str
    seed: int
    scene: shade_sim.Scene
    mjcf: str


def scenes(inputs: Sequence[str], seed: int = 0, attempts: int = 8) -> Iterator[GymScene]:
    """Endless checked scenes: input `k % len(inputs)` with seed `seed + k` for the k-th. An input
    with no clean layout in `attempts` rounds is skipped for that k (its seed is not reused)."""
    if not inputs:
        raise ValueError("no inputs")
    for k in itertools.count():
        path = inputs[k % len(inputs)]
        layouts = shade_sim.generate(path, seed=seed + k, require_clean=True, attempts=attempts)
        if layouts:
            yield GymScene(k, path, seed + k, layouts[0], shade_sim.to_mjcf(layouts[0]))


def main(argv=None) -> int:
    import mujoco
    import numpy as np

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("inputs", nargs="*")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--count", type=int, default=6)
    args = parser.parse_args(argv)
    inputs = args.inputs or sorted(glob.glob(os.path.join(ROOT, "scenes", "examples", "*.json")))
    try:
        for s in itertools.islice(scenes(inputs, args.seed), args.count):
            model = mujoco.MjModel.from_xml_string(s.mjcf)
            data = mujoco.MjData(model)
            for key in range(model.nkey):
                mujoco.mj_resetDataKeyframe(model, data, key)
                mujoco.mj_step(model, data)
            assert np.isfinite(data.qpos).all()
            print(
                f"{s.index}: {os.path.basename(s.input)} seed {s.seed}: {len(s.scene.object_ids)} pieces, "
                f"{model.nbody} bodies, {model.nkey} keyframes stepped"
            )
    except (shade_sim.SceneError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
